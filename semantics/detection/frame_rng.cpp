#include "semantics/detection/frame_rng.h"

#include <cmath>

namespace wardmap::semantics {

namespace {

// SplitMix64 finaliser: spreads nearby inputs (consecutive timestamps, seeds 1 and 2) over all bits.
std::uint64_t mix(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

constexpr double kTwoPi = 6.283185307179586476925286766559;
constexpr double kMicrosecondsPerSecond = 1e6;

}  // namespace

FrameRng::FrameRng(std::uint64_t seed, double timestamp) {
  const auto micros = static_cast<std::int64_t>(std::llround(timestamp * kMicrosecondsPerSecond));
  engine_.seed(mix(mix(seed) ^ static_cast<std::uint64_t>(micros)));
}

double FrameRng::uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }

double FrameRng::uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }

double FrameRng::normal() {
  const double u1 = 1.0 - uniform();  // (0, 1]: log stays finite
  const double u2 = uniform();
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(kTwoPi * u2);
}

int FrameRng::poisson(double mean) {
  if (mean <= 0) return 0;
  const double limit = std::exp(-mean);
  int k = 0;
  double product = uniform();
  while (product > limit) {
    ++k;
    product *= uniform();
  }
  return k;
}

int FrameRng::index(int n) {
  const int i = static_cast<int>(uniform() * n);
  return i < n ? i : n - 1;
}

}  // namespace wardmap::semantics
