// A convolution of a tensor with few input channels (one group) as one cv::dnn layer, in two
// shapes: 3 x 3 with stride 1, YOLOX's stem (12 -> 16 channels at 176 x 208 after the Focus fold),
// and 7 x 7 with stride 2, OSNet's stem (3 -> 16 channels, 256 x 128 -> 128 x 64). OpenCV 4.6 runs
// them as GEMMs of depth 108 and 147 over 16 output channels, badly shaped for it: YOLOX's 7.5 ms on
// one thread, 4.3 on two; OSNet's 1.7-2.1 ms of a 9-13 ms forward (probes, 2026-12-01). Here each
// group of 8 output channels is summed over 8 pixels at once, in registers: 3.2 ms and 0.8 ms on one
// thread. replace_small_input_convs (onnx_fold.h) gives such Conv nodes the op type
// kSmallConvOpType; the activation after one (YOLOX's SiLU, OSNet's ReLU) is fused into it.
#pragma once

#include <cstddef>
#include <vector>

namespace wardmap::semantics {

inline constexpr const char* kSmallConvOpType = "WardmapSmallInputConv";
inline constexpr int kSmallConvMaxInputs = 16;  // input channels the rewrite takes at most
inline constexpr int kSmallConvBlock = 8;       // output channels must be a multiple of this

// The (kernel, stride) pairs the layer runs: (3, 1) and (7, 2). Any padding, the same on every side.
bool small_conv_supported(int kernel, int stride);

// One convolution's sizes, and the layout of the input its kernel reads.
struct SmallConvGeometry {
  int in_channels = 0, out_channels = 0;
  int kernel = 3, stride = 1, pad = 1;
  int height = 0, width = 0;  // the input's

  int out_height() const { return (height + 2 * pad - kernel) / stride + 1; }
  int out_width() const { return (width + 2 * pad - kernel) / stride + 1; }
  // The layout: per input channel, `stride` planes, one per column phase. Plane q of channel c holds
  // the input with `pad` zeros on each side, rows of it all, columns q, q + stride, q + 2 stride ...
  // of it, each row `row_floats()` long (zero past its end), the planes one after the other.
  int layout_rows() const { return height + 2 * pad; }
  int row_floats() const { return (width + 2 * pad + stride - 1) / stride + 8; }
  size_t layout_floats() const { return static_cast<size_t>(in_channels) * stride * layout_rows() * row_floats(); }
};

// Writes the inside of `layout` (layout_floats() of them) from one batch item's input planes
// (`src`: in_channels x height x width); the zeros around it are left as they are, so the buffer can
// be zeroed once and reused for inputs of the same size.
void small_conv_layout(const float* src, SmallConvGeometry g, float* layout);

// The Cout x Cin x k x k weights in the order small_input_conv reads them: per block of
// kSmallConvBlock output channels, per input channel and tap, the block's values side by side.
std::vector<float> small_conv_pack_weights(const float* weights, const SmallConvGeometry& g);

// Output rows [row_begin, row_end) of all out_channels planes (out_height() x out_width() each, one
// after the other in `dst`): dst[o][y][x] = bias[o] + sum over c, i, j of
// weights[((o * in_channels + c) * k + i) * k + j] * src[c][stride y + i - pad][stride x + j - pad],
// src 0 outside the image. `layout`: small_conv_layout's; `packed`: small_conv_pack_weights'. g:
// small_conv_supported, out_channels a multiple of kSmallConvBlock. Uses AVX2 + FMA where the CPU
// has them.
void small_input_conv(const float* layout, SmallConvGeometry g, const float* packed, const float* bias, float* dst,
                      int row_begin, int row_end);

// Registers the layer with cv::dnn under kSmallConvOpType, once per process (thread-safe). Called
// by load_onnx_net before it reads a model replace_small_input_convs rewrote.
void register_small_conv_layer();

}  // namespace wardmap::semantics
