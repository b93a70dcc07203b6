// Portable random numbers: std::mt19937's raw output is fully specified by the standard, the
// std::*_distribution classes are not, so every distribution here is our own.
#pragma once

#include <cstdint>
#include <random>

namespace wardmap::sim {

class Rng {
 public:
  explicit Rng(uint32_t seed) : engine_(seed) {}
  // A stream derived from (seed, salt) that does not depend on how much this one has been used.
  static Rng derived(uint32_t seed, uint32_t salt);

  uint32_t next_u32() { return static_cast<uint32_t>(engine_()); }
  // Uniform in [0, 1) with 53 random bits.
  double uniform();
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  // Uniform integer in [lo, hi] (inclusive), unbiased by rejection.
  int uniform_int(int lo, int hi);
  // Standard normal (Box-Muller, the cosine branch only).
  double normal();
  bool chance(double p) { return uniform() < p; }

 private:
  std::mt19937 engine_;
};

// A 32-bit mix of two words (splitmix-style finaliser); used to derive seeds.
uint32_t mix_seed(uint32_t a, uint32_t b);

}  // namespace wardmap::sim
