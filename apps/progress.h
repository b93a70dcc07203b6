// A progress bar on stderr for long runs (only when stderr is a terminal or when asked).
#pragma once

#include <chrono>
#include <cstddef>
#include <string>

namespace wardmap::apps {

class Progress {
 public:
  Progress(std::string what, size_t total, bool enabled);
  void update(size_t done);
  void finish();

 private:
  std::string what_;
  size_t total_;
  bool enabled_;
  std::chrono::steady_clock::time_point start_, last_;
};

}  // namespace wardmap::apps
