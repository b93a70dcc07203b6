#include "semantics/detection/small_conv_layer.h"

#include <algorithm>
#include <cstddef>
#include <mutex>
#include <vector>

#include <opencv2/core/utility.hpp>
#include <opencv2/dnn.hpp>
#include <opencv2/dnn/layer.details.hpp>

#include "semantics/detection/conv3x3_layer.h"

namespace wardmap::semantics {

namespace {

// L floats in one register (GCC / Clang vector extensions); Load reads and writes them at any
// float-aligned address.
template <int L>
struct Lanes {
  typedef float F __attribute__((vector_size(4 * L)));
  typedef float Load __attribute__((vector_size(4 * L), aligned(4), may_alias));
};

// small_input_conv3x3 with L pixels a vector: 8 output channels x L pixels of sums in registers,
// each input value read once per tap. Pure arithmetic on blobs that cv::dnn's TBB workers wrote:
// left out of ThreadSanitizer's instrumentation (as silu_layer.cpp's kernel).
template <int L>
__attribute__((always_inline, no_sanitize("thread"))) inline void conv_rows(const float* padded, int in_channels,
                                                                            int out_channels, int height, int width,
                                                                            int stride, const float* weights,
                                                                            const float* bias, float* dst, int row_begin,
                                                                            int row_end) {
  using F = typename Lanes<L>::F;
  using Load = typename Lanes<L>::Load;
  const size_t padded_plane = static_cast<size_t>(height + 2) * stride;
  const size_t plane = static_cast<size_t>(height) * width;
  const size_t per_output = static_cast<size_t>(in_channels) * 9;
  for (int o0 = 0; o0 < out_channels; o0 += kSmallConvBlock)
    for (int y = row_begin; y < row_end; ++y)
      for (int x = 0; x < width; x += L) {
        F acc[kSmallConvBlock];
        for (int j = 0; j < kSmallConvBlock; ++j) acc[j] = F{} + bias[o0 + j];
        for (int c = 0; c < in_channels; ++c) {
          const float* in = padded + c * padded_plane + static_cast<size_t>(y) * stride + x;
          const float* w = weights + static_cast<size_t>(o0) * per_output + static_cast<size_t>(c) * 9;
          for (int t = 0; t < 9; ++t) {
            const F v = *reinterpret_cast<const Load*>(in + (t / 3) * stride + t % 3);
            for (int j = 0; j < kSmallConvBlock; ++j) acc[j] += v * w[j * per_output + t];
          }
        }
        for (int j = 0; j < kSmallConvBlock; ++j) {
          float* out = dst + (o0 + j) * plane + static_cast<size_t>(y) * width + x;
          if (x + L <= width) {
            *reinterpret_cast<Load*>(out) = acc[j];
          } else {
            for (int k = 0; k < width - x; ++k) out[k] = acc[j][k];
          }
        }
      }
}

#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
#define WARDMAP_SMALL_CONV_AVX2 1
__attribute__((target("avx2,fma"), no_sanitize("thread"))) void conv_rows_8(const float* padded, int in_channels,
                                                                              int out_channels, int height, int width,
                                                                              int stride, const float* weights,
                                                                              const float* bias, float* dst,
                                                                              int row_begin, int row_end) {
  conv_rows<8>(padded, in_channels, out_channels, height, width, stride, weights, bias, dst, row_begin, row_end);
}
#endif

// The input planes of one batch item into the inside of `padded`: planes of height + 2 rows, rows
// `stride` long, the plane starting one row and one column in. The border (and each row's tail)
// is left as it is: zero, written once when the buffer was made.
__attribute__((no_sanitize("thread"))) void copy_into_border(const float* src, int channels, int height, int width,
                                                             int stride, float* padded) {
  for (int c = 0; c < channels; ++c)
    for (int y = 0; y < height; ++y) {
      const float* in = src + (static_cast<size_t>(c) * height + y) * width;
      float* row = padded + (static_cast<size_t>(c) * (height + 2) + y + 1) * stride + 1;
      for (int x = 0; x < width; ++x) row[x] = in[x];
    }
}

// Cout x Cin x 3 x 3 weights in one group (conv3x3_layer.h).
class SmallConvLayer : public Conv3x3Layer {
 public:
  explicit SmallConvLayer(const cv::dnn::LayerParams& params) : Conv3x3Layer(params, /*depthwise=*/false) {
    CV_Assert(out_channels_ % kSmallConvBlock == 0);
  }

  static cv::Ptr<cv::dnn::Layer> create(cv::dnn::LayerParams& params) {
    return cv::Ptr<cv::dnn::Layer>(new SmallConvLayer(params));
  }

  void forward(cv::InputArrayOfArrays inputs_arr, cv::OutputArrayOfArrays outputs_arr,
               cv::OutputArrayOfArrays /*internals*/) override {
    auto [in, out] = io_blobs(inputs_arr, outputs_arr);
    const int height = in.size[2], width = in.size[3];
    const int stride = width + 2 + 8;
    // The zero-bordered input buffer is kept between forwards (a network copy runs one forward at a
    // time): YOLOX's stem needs 1.9 MB, allocated and zeroed once per input size, not per frame.
    if (padded_size_ != cv::Size(width, height)) {
      padded_.assign(static_cast<size_t>(in_channels_) * (height + 2) * stride, 0.0f);
      padded_size_ = cv::Size(width, height);
    }
    for (int n = 0; n < in.size[0]; ++n) {
      copy_into_border(in.ptr<float>() + static_cast<size_t>(n) * in_channels_ * height * width, in_channels_, height,
                       width, stride, padded_.data());
      Rows rows(*this, padded_.data(), height, width, stride,
                out.ptr<float>() + static_cast<size_t>(n) * out_channels_ * height * width);
      cv::parallel_for_(cv::Range(0, height), rows, 8);
    }
  }

 private:
  std::vector<float> padded_;
  cv::Size padded_size_;  // the input width and height padded_ was made for

  // Output rows on cv::dnn's threads. Its body reads the buffers its caller wrote, through TBB's
  // synchronisation, which ThreadSanitizer cannot see: left out of its instrumentation, and given
  // plain values and pointers (taken on the calling thread), since the inline accessors it would
  // otherwise call are instrumented.
  class Rows : public cv::ParallelLoopBody {
   public:
    Rows(const SmallConvLayer& layer, const float* padded, int height, int width, int stride, float* dst)
        : padded_(padded), weights_(layer.weights_.data()), bias_(layer.bias_.data()),
          activation_(layer.activation_.get()), in_channels_(layer.in_channels_),
          out_channels_(layer.out_channels_), height_(height), width_(width), stride_(stride), dst_(dst) {}
    __attribute__((no_sanitize("thread"))) void operator()(const cv::Range& r) const override {
      small_input_conv3x3(padded_, in_channels_, out_channels_, height_, width_, stride_, weights_, bias_, dst_,
                          r.start, r.end);
      if (activation_) {
        const size_t plane = static_cast<size_t>(height_) * width_;
        float* first = dst_ + static_cast<size_t>(r.start) * width_;
        activation_->forwardSlice(first, first, (r.end - r.start) * width_, plane, 0, out_channels_);
      }
    }

   private:
    const float* padded_;
    const float* weights_;
    const float* bias_;
    const cv::dnn::ActivationLayer* activation_;
    int in_channels_, out_channels_, height_, width_, stride_;
    float* dst_;
  };

};

}  // namespace

__attribute__((no_sanitize("thread"))) void small_input_conv3x3(const float* padded, int in_channels,
                                                                int out_channels, int height, int width,
                                                                int padded_stride, const float* weights,
                                                                const float* bias, float* dst, int row_begin,
                                                                int row_end) {
#ifdef WARDMAP_SMALL_CONV_AVX2
  static const bool avx2 = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  if (avx2)
    return conv_rows_8(padded, in_channels, out_channels, height, width, padded_stride, weights, bias, dst, row_begin,
                       row_end);
#endif
  conv_rows<4>(padded, in_channels, out_channels, height, width, padded_stride, weights, bias, dst, row_begin, row_end);
}

void register_small_conv_layer() {
  static std::once_flag once;
  std::call_once(once, [] { cv::dnn::LayerFactory::registerLayer(kSmallConvOpType, SmallConvLayer::create); });
}

}  // namespace wardmap::semantics
