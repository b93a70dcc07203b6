#include "apps/progress.h"

#include <unistd.h>

#include <cstdio>

namespace wardmap::apps {

Progress::Progress(std::string what, size_t total, bool enabled)
    : what_(std::move(what)), total_(total), enabled_(enabled && ::isatty(STDERR_FILENO)),
      start_(std::chrono::steady_clock::now()), last_(start_ - std::chrono::seconds(1)) {}

void Progress::update(size_t done) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  if (done < total_ && now - last_ < std::chrono::milliseconds(100)) return;
  last_ = now;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const int width = 30, filled = total_ ? static_cast<int>(width * done / total_) : width;
  std::fprintf(stderr, "\r%s [%.*s%*s] %zu/%zu frames, %.1f fps", what_.c_str(), filled,
               "##############################", width - filled, "", done, total_, elapsed > 0 ? done / elapsed : 0.0);
  std::fflush(stderr);
}

void Progress::finish() {
  if (enabled_) std::fprintf(stderr, "\n");
}

}  // namespace wardmap::apps
