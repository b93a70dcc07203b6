#include "apps/progress.h"

#include <spdlog/spdlog.h>
#include <unistd.h>

#include <cstdio>

namespace wardmap::apps {

namespace {
constexpr auto kBarPeriod = std::chrono::milliseconds(100);
constexpr auto kLogPeriod = std::chrono::seconds(10);
}  // namespace

Progress::Progress(std::string what, size_t total, bool enabled)
    : what_(std::move(what)), total_(total), bar_(enabled && ::isatty(STDERR_FILENO)), log_(enabled && !bar_),
      start_(std::chrono::steady_clock::now()), last_(start_ - kBarPeriod) {}

void Progress::update(size_t done) {
  if (!bar_ && !log_) return;
  const auto now = std::chrono::steady_clock::now();
  if (log_) {
    // The first line after 10 s: short runs stay quiet.
    if (done >= total_ || now - (last_ < start_ ? start_ : last_) < kLogPeriod) return;
    last_ = now;
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    const double rate = elapsed > 0 ? done / elapsed : 0.0;
    spdlog::info("{}: {} of {} frames ({:.0f} %), {:.1f} frames/s, about {:.0f} s left", what_, done, total_,
                 total_ ? 100.0 * done / total_ : 100.0, rate, rate > 0 ? (total_ - done) / rate : 0.0);
    return;
  }
  if (done < total_ && now - last_ < kBarPeriod) return;
  last_ = now;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const int width = 30, filled = total_ ? static_cast<int>(width * done / total_) : width;
  std::fprintf(stderr, "\r%s [%.*s%*s] %zu/%zu frames, %.1f fps", what_.c_str(), filled,
               "##############################", width - filled, "", done, total_, elapsed > 0 ? done / elapsed : 0.0);
  std::fflush(stderr);
}

void Progress::finish() {
  if (bar_) std::fprintf(stderr, "\n");
}

}  // namespace wardmap::apps
