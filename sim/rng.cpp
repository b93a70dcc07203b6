#include "sim/rng.h"

#include <cmath>

namespace wardmap::sim {

uint32_t mix_seed(uint32_t a, uint32_t b) {
  uint64_t z = (static_cast<uint64_t>(a) << 32) ^ b;
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  z ^= z >> 31;
  return static_cast<uint32_t>(z ^ (z >> 32));
}

Rng Rng::derived(uint32_t seed, uint32_t salt) { return Rng(mix_seed(seed, salt)); }

double Rng::uniform() {
  const uint64_t a = next_u32() >> 5;  // 27 bits
  const uint64_t b = next_u32() >> 6;  // 26 bits
  return (static_cast<double>(a) * 67108864.0 + static_cast<double>(b)) / 9007199254740992.0;
}

int Rng::uniform_int(int lo, int hi) {
  if (hi <= lo) return lo;
  const uint64_t range = static_cast<uint64_t>(static_cast<int64_t>(hi) - lo) + 1;
  const uint64_t limit = (uint64_t{1} << 32) - ((uint64_t{1} << 32) % range);
  uint64_t r;
  do {
    r = next_u32();
  } while (r >= limit);
  return static_cast<int>(static_cast<int64_t>(lo) + static_cast<int64_t>(r % range));
}

double Rng::normal() {
  double u1 = uniform();
  if (u1 < 1e-300) u1 = 1e-300;
  const double u2 = uniform();
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2);
}

}  // namespace wardmap::sim
