// Reproducible random numbers for the annotations back-end. std::mt19937_64's raw output is fixed
// by the standard, but std:: distributions are not (libstdc++ and libc++ differ), so the uniform,
// normal and Poisson draws here are computed from the raw 64-bit words by formulas written out
// below. Each frame gets its own generator, seeded from (seed, timestamp), so a frame's noise does
// not depend on which frames were processed before it.
#pragma once

#include <cstdint>
#include <random>

namespace wardmap::semantics {

class FrameRng {
 public:
  // The timestamp enters at microsecond resolution.
  FrameRng(std::uint64_t seed, double timestamp);

  double uniform();                      // [0, 1), 53 random bits
  double uniform(double lo, double hi);  // [lo, hi)
  bool bernoulli(double p) { return uniform() < p; }
  double normal();           // N(0, 1), Box-Muller (both uniforms drawn each call)
  int poisson(double mean);  // Knuth's product of uniforms (small means)
  int index(int n);          // uniform in [0, n)

 private:
  std::mt19937_64 engine_;
};

}  // namespace wardmap::semantics
