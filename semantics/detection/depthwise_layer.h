// A 3 x 3 depthwise convolution (stride 1, one pixel of zero padding) as one cv::dnn layer.
// OSNet's LightConv3x3 blocks run 60 of them. OpenCV 4.6 takes 140-150 us for each 24-channel one at
// 32 x 16 (110 k multiply-adds), 6.4 of OSNet x0.25's 16.3 ms a crop on one thread
// (Net::getPerfProfile); the same arithmetic over a zero-padded copy of each plane takes a few us.
// replace_depthwise_convs (onnx_fold.h) gives such Conv nodes the op type kDepthwiseOpType; the
// activation after one (OSNet's ReLU) is fused into it.
#pragma once

namespace wardmap::semantics {

inline constexpr const char* kDepthwiseOpType = "WardmapDepthwiseConv3x3";

// One plane: dst[y][x] = bias + sum over i, j in {0, 1, 2} of k[3 i + j] * src[y + i - 1][x + j - 1],
// src taken as 0 outside its `height` x `width`. `padded`: scratch of (height + 2) x (width + 2)
// floats. src and dst must not overlap.
void depthwise_conv3x3(const float* src, float* dst, int height, int width, const float* k, float bias, float* padded);

// Registers the layer with cv::dnn under kDepthwiseOpType, once per process (thread-safe). Called
// by load_onnx_net before it reads a model replace_depthwise_convs rewrote.
void register_depthwise_layer();

}  // namespace wardmap::semantics
