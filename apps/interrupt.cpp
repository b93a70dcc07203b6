#include "apps/interrupt.h"

#include <atomic>
#include <csignal>

namespace wardmap::apps {

namespace {

std::atomic<int> g_requested{0};
static_assert(std::atomic<int>::is_always_lock_free, "the signal handler needs a lock-free flag");

struct sigaction g_previous_int, g_previous_term;

extern "C" void on_signal(int sig) {
  int expected = 0;
  if (g_requested.compare_exchange_strong(expected, sig)) return;  // first: finish the frame, write, stop
  // Second: end now, as the default action does (and with its exit status).
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}

}  // namespace

InterruptScope::InterruptScope() {
  g_requested.store(0);
  struct sigaction sa = {};
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESTART;  // reads and sleeps go on; the run loop checks the flag
  sigaction(SIGINT, &sa, &g_previous_int);
  sigaction(SIGTERM, &sa, &g_previous_term);
}

InterruptScope::~InterruptScope() {
  sigaction(SIGINT, &g_previous_int, nullptr);
  sigaction(SIGTERM, &g_previous_term, nullptr);
}

int InterruptScope::requested() { return g_requested.load(); }

std::string signal_name(int signal) {
  if (signal == SIGINT) return "SIGINT";
  if (signal == SIGTERM) return "SIGTERM";
  return "signal " + std::to_string(signal);
}

}  // namespace wardmap::apps
