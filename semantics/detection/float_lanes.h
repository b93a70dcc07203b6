// GCC / Clang vector extensions for the hand-written cv::dnn layers (silu_layer.h,
// small_conv_layer.h, pointwise_layer.h): W floats (or int32) in one register; Load reads and
// writes W floats at any float-aligned address.
#pragma once

#include <cstdint>

namespace wardmap::semantics {

template <int W>
struct Lanes {
  typedef float F __attribute__((vector_size(4 * W)));
  typedef std::int32_t I __attribute__((vector_size(4 * W)));
  typedef float Load __attribute__((vector_size(4 * W), aligned(4), may_alias));
};

}  // namespace wardmap::semantics
