// Progress of long runs on stderr: a bar redrawn in place when stderr is a terminal, else (a log
// file, a pipe, CI) one log line every 10 s, so that a batch run shows it is alive and how far it is.
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
  bool bar_;  // a terminal: the bar
  bool log_;  // not a terminal: a log line now and then
  std::chrono::steady_clock::time_point start_, last_;
};

}  // namespace wardmap::apps
