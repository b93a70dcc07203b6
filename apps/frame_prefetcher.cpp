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

void FramePrefetcher::run() {
  for (size_t i = 0; i < reader_.size(); ++i) {
    Item item;
    bool fatal = false;
    try {
      item.frame = reader_.read(i);
    } catch (const FrameReadError&) {
      item.error = std::current_exception();  // this frame only: the next ones are read
    } catch (...) {
      item.error = std::current_exception();
      fatal = true;
    }
    if (!queue_.push(std::move(item)) || fatal) break;  // closed, or nothing after that error
  }
  queue_.close();  // what is queued can still be taken
}

slam::io::Frame FramePrefetcher::next() {
  if (taken_ >= reader_.size())
    throw std::out_of_range("FramePrefetcher::next: all " + std::to_string(reader_.size()) + " frames were taken");
  if (error_) std::rethrow_exception(error_);  // the frame that failed fails again, as a direct read
  if (!threaded_) {
    try {
      return reader_.read(taken_++);
    } catch (const FrameReadError&) {
      throw;  // this frame only: the next call reads the next one
    } catch (...) {
      --taken_;
      error_ = std::current_exception();
      throw;
    }
  }
  std::optional<Item> item = queue_.pop();
  if (!item) throw std::logic_error("FramePrefetcher::next: the reading thread stopped early");
  if (item->error) {
    try {
      std::rethrow_exception(item->error);
    } catch (const FrameReadError&) {
      ++taken_;
      throw;
    } catch (...) {
      error_ = item->error;
      throw;
    }
  }
  ++taken_;
  return std::move(*item->frame);
}

}  // namespace wardmap::apps
