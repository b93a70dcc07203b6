// SiLU (x * sigmoid(x), YOLOX's activation) as one cv::dnn layer with a vectorised kernel.
// OpenCV 4.6 runs an exported SiLU as two layers, a Sigmoid (a scalar exp per element) and an
// elementwise Mul: about 14 ms of YOLOX-nano's 35 ms at 416x352 on 2 threads (Net::getPerfProfile).
// fuse_silu (onnx_fold.h) rewrites each such pair as one node of type kSiluOpType; this layer, an
// ActivationLayer, is then fused into the convolution before it and runs while its output is still
// in the cache.
#pragma once

#include <cstddef>

namespace wardmap::semantics {

inline constexpr const char* kSiluOpType = "WardmapSiLU";

// dst[i] = src[i] * sigmoid(src[i]) = src[i] / (1 + exp(-src[i])), exp from Cephes' expf
// polynomial: within 1e-6 relative of std::exp's (a test checks it). src and dst may be the same.
// Uses AVX2 + FMA where the CPU has them (8 lanes), else 4-lane vectors.
void silu(const float* src, float* dst, std::size_t n);
// The 4-lane kernel alone (what a CPU without AVX2 runs), for tests.
void silu_4lanes(const float* src, float* dst, std::size_t n);

// Registers the layer with cv::dnn under kSiluOpType, once per process (thread-safe). Called by
// load_onnx_net before it reads a model fuse_silu rewrote.
void register_silu_layer();

}  // namespace wardmap::semantics
