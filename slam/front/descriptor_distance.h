// Hamming distance between two 256-bit ORB descriptors.
#pragma once

#include <cstdint>
#include <cstring>

namespace wardmap::slam {

constexpr int kDescriptorBytes = 32;  // an ORB (rBRIEF) descriptor: 256 bits

// Bit count of a 64-bit word without relying on the POPCNT instruction (the build targets generic x86-64).
inline int popcount64(std::uint64_t x) {
  x = x - ((x >> 1) & 0x5555555555555555ULL);
  x = (x & 0x3333333333333333ULL) + ((x >> 2) & 0x3333333333333333ULL);
  x = (x + (x >> 4)) & 0x0f0f0f0f0f0f0f0fULL;
  return static_cast<int>((x * 0x0101010101010101ULL) >> 56);
}

inline int descriptor_distance(const unsigned char* a, const unsigned char* b) {
  int d = 0;
  for (int i = 0; i < kDescriptorBytes / 8; ++i) {
    std::uint64_t x, y;
    std::memcpy(&x, a + 8 * i, 8);
    std::memcpy(&y, b + 8 * i, 8);
    d += popcount64(x ^ y);
  }
  return d;
}

// RUMI Formula 1: keypoint p of the query frame matches map point P when D(d(p), d(P)) < Th_d.
// wardmap keeps ORB-SLAM's inclusive thresholds (th_high 100 for projection searches, th_low 50
// elsewhere), so Th_d = th + 1.
inline bool descriptor_matches(int distance, int th) { return distance <= th; }

}  // namespace wardmap::slam
