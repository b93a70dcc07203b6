// GCC / Clang vector extensions for the hand-written cv::dnn layers (silu_layer.h,
// small_conv_layer.h, pointwise_layer.h): W floats (or int32) in one register; Load reads and
// writes W floats at any float-aligned address. On x86 (WARDMAP_X86_SIMD) each layer also has an
// 8-lane kernel built for AVX2 + FMA, run when cpu_has_avx2_fma().
#pragma once

#include <cstdint>

namespace wardmap::semantics {

template <int W>
struct Lanes {
  typedef float F __attribute__((vector_size(4 * W)));
  typedef std::int32_t I __attribute__((vector_size(4 * W)));
  typedef float Load __attribute__((vector_size(4 * W), aligned(4), may_alias));
};

#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
#define WARDMAP_X86_SIMD 1
// Whether this CPU has AVX2 and FMA (asked once).
inline bool cpu_has_avx2_fma() {
  static const bool has = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  return has;
}
#endif

}  // namespace wardmap::semantics
