// Hamming distance between two 256-bit ORB descriptors (32-byte rows of a CV_8U matrix).
#pragma once

#include <array>
#include <cstdint>
#include <cstring>

namespace wardmap::slam::place {

constexpr int kDescriptorBytes = 32;
using Descriptor = std::array<std::uint8_t, kDescriptorBytes>;

// Bit count of a 64-bit word by the SWAR method (the build targets generic x86-64, no POPCNT).
inline int bit_count64(std::uint64_t x) {
  x = x - ((x >> 1) & 0x5555555555555555ULL);
  x = (x & 0x3333333333333333ULL) + ((x >> 2) & 0x3333333333333333ULL);
  x = (x + (x >> 4)) & 0x0f0f0f0f0f0f0f0fULL;
  return static_cast<int>((x * 0x0101010101010101ULL) >> 56);
}

inline int hamming_distance(const std::uint8_t* a, const std::uint8_t* b) {
  int d = 0;
  for (int i = 0; i < kDescriptorBytes; i += 8) {
    std::uint64_t x, y;
    std::memcpy(&x, a + i, 8);
    std::memcpy(&y, b + i, 8);
    d += bit_count64(x ^ y);
  }
  return d;
}

}  // namespace wardmap::slam::place
