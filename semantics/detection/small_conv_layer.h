// A 3 x 3 convolution (stride 1, one pixel of zero padding, one group) of a tensor with few input
// channels as one cv::dnn layer: YOLOX's stem, 12 -> 16 channels at 176 x 208 after the Focus
// fold. OpenCV 4.6 runs it as a GEMM of depth 108 over 16 output channels, badly shaped for it:
// 7.5 ms on one thread, 4.3 on two (a probe, 2026-12-01), about a fifth of YOLOX-nano's forward.
// Here each group of 8 output channels is summed over 8 pixels at once, in registers: 3.2 ms on
// one thread. replace_small_input_convs (onnx_fold.h) gives such Conv nodes the op type
// kSmallConvOpType; the activation after one (YOLOX's SiLU) is fused into it.
#pragma once

namespace wardmap::semantics {

inline constexpr const char* kSmallConvOpType = "WardmapSmallInputConv3x3";
inline constexpr int kSmallConvMaxInputs = 16;  // input channels the rewrite takes at most
inline constexpr int kSmallConvBlock = 8;       // output channels must be a multiple of this

// Output rows [row_begin, row_end) of all `out_channels` planes (height x width each, one after the
// other in `dst`): dst[o][y][x] = bias[o] + sum over c, i, j of
// weights[((o * in_channels + c) * 3 + i) * 3 + j] * src[c][y + i - 1][x + j - 1], src 0 outside
// the image. `padded`: the input planes with a border of one zero pixel, each row `padded_stride`
// floats (at least width + 2 + 8, the rest zero as well), each plane height + 2 rows.
// out_channels: a multiple of kSmallConvBlock. Uses AVX2 + FMA where the CPU has them.
void small_input_conv3x3(const float* padded, int in_channels, int out_channels, int height, int width,
                         int padded_stride, const float* weights, const float* bias, float* dst, int row_begin,
                         int row_end);

// Registers the layer with cv::dnn under kSmallConvOpType, once per process (thread-safe). Called
// by load_onnx_net before it reads a model replace_small_input_convs rewrote.
void register_small_conv_layer();

}  // namespace wardmap::semantics
