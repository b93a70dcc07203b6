// Decodes a sequence's frames on a thread of its own, a few frames ahead of the one being tracked,
// so that an offline run does not wait for the PNG decoder between frames (the decode of a 640x480
// colour + depth pair costs about as much as tracking it). Frames come out in order, each exactly
// as SequenceReader::read gives it; a read error is thrown by next() at the frame it concerns, as a
// direct read would. After a FrameReadError (one frame that does not decode) the next call gives the
// next frame; after any other error every later call throws it again. With `ahead` = 0 there is no thread: next()
// reads on the caller's (for threaded runs, whose tracker and mapper already keep both cores busy).
#pragma once

#include <cstddef>
#include <exception>
#include <optional>
#include <thread>

#include "slam/front/bounded_queue.h"
#include "slam/io/sequence.h"

namespace wardmap::apps {

class FramePrefetcher {
 public:
  // Reads frames 0 .. reader.size() - 1, at most `ahead` decoded and waiting (0: read in next()). The
  // reader must outlive this object and must not be read from elsewhere meanwhile.
  explicit FramePrefetcher(slam::io::SequenceReader& reader, size_t ahead = 2);
  ~FramePrefetcher();  // stops the reading thread (frames not taken are dropped)
  FramePrefetcher(const FramePrefetcher&) = delete;
  FramePrefetcher& operator=(const FramePrefetcher&) = delete;

  // The next frame, in order; throws the read's error at that frame (a FrameReadError skips the
  // frame); std::out_of_range past the end.
  slam::io::Frame next();

 private:
  struct Item {
    std::optional<slam::io::Frame> frame;
    std::exception_ptr error;
    bool fatal = false;  // an error other than FrameReadError: nothing is read after it
  };
  Item read_item(size_t i);  // reader_.read(i), its error kept
  void run();

  slam::io::SequenceReader& reader_;
  bool threaded_;
  slam::BoundedQueue<Item> queue_;
  size_t taken_ = 0;
  std::exception_ptr error_;  // a read that failed, not a FrameReadError: thrown again by every later next()
  std::thread thread_;
};

}  // namespace wardmap::apps
