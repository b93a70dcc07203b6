// A 1 x 1 convolution (one group, stride 1, no padding) of few input channels as one cv::dnn
// layer. OSNet x0.25 runs 92 of them from 16, 24 or 32 channels (to a multiple of 4), on planes of
// 64 x 32 down to 16 x 8. OpenCV 4.6 takes 80-140 us for a 16 -> 16 one at 64 x 32 (524 k
// multiply-adds), and 4.1 of the 12-13 ms of a crop for the 92 on one thread
// (Net::getPerfProfile, 2026-12-01). Summing 4 output channels x 24 pixels in registers takes 1.9
// ms for them. From 64 channels and more it is no faster than cv::dnn, which keeps those.
// replace_pointwise_convs (onnx_fold.h) gives such Conv nodes the op type kPointwiseOpType; an
// activation after one is fused into it.
#pragma once

#include <cstddef>

namespace wardmap::semantics {

inline constexpr const char* kPointwiseOpType = "WardmapPointwiseConv";
inline constexpr int kPointwiseBlock = 4;       // output channels must be a multiple of this
inline constexpr int kPointwiseMaxInputs = 32;  // input channels the rewrite takes at most

// dst[o][p] = bias[o] + sum over c of weights[o * in_channels + c] * src[c][p], for the
// out_channels planes of `plane` values each (src: in_channels planes). out_channels: a multiple of
// kPointwiseBlock. src and dst must not overlap. Uses AVX2 + FMA where the CPU has them.
void pointwise_conv(const float* src, int in_channels, int out_channels, size_t plane, const float* weights,
                    const float* bias, float* dst);

// Registers the layer with cv::dnn under kPointwiseOpType, once per process (thread-safe). Called
// by load_onnx_net before it reads a model replace_pointwise_convs rewrote.
void register_pointwise_layer();

}  // namespace wardmap::semantics
