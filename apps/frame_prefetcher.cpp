#include "apps/frame_prefetcher.h"

#include <stdexcept>
#include <string>
#include <utility>

#include "slam/core/errors.h"

namespace wardmap::apps {

FramePrefetcher::FramePrefetcher(slam::io::SequenceReader& reader, size_t ahead)
    : reader_(reader), threaded_(ahead > 0), queue_(threaded_ ? ahead : 1) {
  if (threaded_) thread_ = std::thread([this] { run(); });
}

FramePrefetcher::~FramePrefetcher() {
  if (!threaded_) return;
  queue_.close();  // a push waiting for room returns false, and the thread ends
  thread_.join();
}

FramePrefetcher::Item FramePrefetcher::read_item(size_t i) {
  Item item;
  try {
    item.frame = reader_.read(i);
  } catch (const FrameReadError&) {
    item.error = std::current_exception();  // this frame only: the next ones are read
  } catch (...) {
    item.error = std::current_exception();
    item.fatal = true;
  }
  return item;
}

void FramePrefetcher::run() {
  for (size_t i = 0; i < reader_.size(); ++i) {
    Item item = read_item(i);
    const bool fatal = item.fatal;
    if (!queue_.push(std::move(item)) || fatal) break;  // closed, or nothing after that error
  }
  queue_.close();  // what is queued can still be taken
}

slam::io::Frame FramePrefetcher::next() {
  if (taken_ >= reader_.size())
    throw std::out_of_range("FramePrefetcher::next: all " + std::to_string(reader_.size()) + " frames were taken");
  if (error_) std::rethrow_exception(error_);  // the frame that failed fails again, as a direct read
  Item item;
  if (!threaded_) {
    item = read_item(taken_);
  } else {
    std::optional<Item> queued = queue_.pop();
    if (!queued) throw std::logic_error("FramePrefetcher::next: the reading thread stopped early");
    item = std::move(*queued);
  }
  if (item.fatal) std::rethrow_exception(error_ = item.error);
  ++taken_;  // a FrameReadError skips its frame: the next call gives the next one
  if (item.error) std::rethrow_exception(item.error);
  return std::move(*item.frame);
}

}  // namespace wardmap::apps
