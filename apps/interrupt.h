// Ctrl-C (SIGINT) or SIGTERM during a long run: the first asks the run to stop after the frame it is
// on and to write what it has (the map of the frames so far); a second one ends the process at once,
// as the default action would. Outside an InterruptScope both signals keep their default action.
#pragma once

#include <stdexcept>
#include <string>

namespace wardmap::apps {

// One scope at a time (the handlers and the request are process-wide).
class InterruptScope {
 public:
  InterruptScope();   // installs the handlers (SIGINT, SIGTERM) and clears any earlier request
  ~InterruptScope();  // restores the previous handlers
  InterruptScope(const InterruptScope&) = delete;
  InterruptScope& operator=(const InterruptScope&) = delete;

  // The signal that asked the run to stop (SIGINT or SIGTERM), or 0.
  static int requested();
};

// "SIGINT" / "SIGTERM" (or "signal N").
std::string signal_name(int signal);

// Thrown once an interrupted run has written its outputs: the CLI exits with 128 + signal.
class Interrupted : public std::runtime_error {
 public:
  explicit Interrupted(int signal, const std::string& what) : std::runtime_error(what), signal_(signal) {}
  int signal() const { return signal_; }

 private:
  int signal_;
};

}  // namespace wardmap::apps
