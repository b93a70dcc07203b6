#include "semantics/detection/pointwise_layer.h"

#include <mutex>
#include <opencv2/dnn.hpp>
#include <opencv2/dnn/layer.details.hpp>

#include "semantics/detection/conv_layer_base.h"
#include "semantics/detection/float_lanes.h"

namespace wardmap::semantics {

namespace {

// kPointwiseBlock output channels x V vectors of L pixels from pixel p on, the sums in registers.
// Pure arithmetic on blobs that cv::dnn's TBB workers wrote: left out of ThreadSanitizer's
// instrumentation (as silu_layer.cpp's kernel).
template <int L, int V>
__attribute__((always_inline, no_sanitize("thread"))) inline void block(const float* src, int in_channels, size_t plane,
                                                                        const float* weights, const float* bias,
                                                                        float* dst, size_t p) {
  using F = typename Lanes<L>::F;
  using Load = typename Lanes<L>::Load;
  F acc[kPointwiseBlock][V];
  for (int j = 0; j < kPointwiseBlock; ++j)
    for (int k = 0; k < V; ++k) acc[j][k] = F{} + bias[j];
  for (int c = 0; c < in_channels; ++c) {
    F v[V];
    for (int k = 0; k < V; ++k) v[k] = *reinterpret_cast<const Load*>(src + c * plane + p + k * L);
    for (int j = 0; j < kPointwiseBlock; ++j) {
      const float w = weights[j * in_channels + c];
      for (int k = 0; k < V; ++k) acc[j][k] += v[k] * w;
    }
  }
  for (int j = 0; j < kPointwiseBlock; ++j)
    for (int k = 0; k < V; ++k) *reinterpret_cast<Load*>(dst + j * plane + p + k * L) = acc[j][k];
}

template <int L>
__attribute__((always_inline, no_sanitize("thread"))) inline void pointwise(const float* src, int in_channels,
                                                                            int out_channels, size_t plane,
                                                                            const float* weights, const float* bias,
                                                                            float* dst) {
  for (int o = 0; o < out_channels; o += kPointwiseBlock) {
    const float* w = weights + static_cast<size_t>(o) * in_channels;
    float* out = dst + o * plane;
    size_t p = 0;
    for (; p + 3 * L <= plane; p += 3 * L) block<L, 3>(src, in_channels, plane, w, bias + o, out, p);
    for (; p + L <= plane; p += L) block<L, 1>(src, in_channels, plane, w, bias + o, out, p);
    for (; p < plane; ++p)  // fewer than L pixels left
      for (int j = 0; j < kPointwiseBlock; ++j) {
        float sum = bias[o + j];
        for (int c = 0; c < in_channels; ++c) sum += src[c * plane + p] * w[j * in_channels + c];
        out[j * plane + p] = sum;
      }
  }
}

#ifdef WARDMAP_X86_SIMD
__attribute__((target("avx2,fma"), no_sanitize("thread"))) void pointwise_8(const float* src, int in_channels,
                                                                            int out_channels, size_t plane,
                                                                            const float* weights, const float* bias,
                                                                            float* dst) {
  pointwise<8>(src, in_channels, out_channels, plane, weights, bias, dst);
}
#endif

// Cout x Cin x 1 x 1 weights in one group, stride 1, no padding (conv_layer_base.h).
class PointwiseLayer : public ConvLayerBase {
 public:
  explicit PointwiseLayer(const cv::dnn::LayerParams& params) : ConvLayerBase(params, /*depthwise=*/false) {
    CV_Assert(kernel_ == 1 && stride_ == 1 && pad_ == 0 && out_channels_ % kPointwiseBlock == 0);
  }

  static cv::Ptr<cv::dnn::Layer> create(cv::dnn::LayerParams& params) {
    return cv::Ptr<cv::dnn::Layer>(new PointwiseLayer(params));
  }

  void forward(cv::InputArrayOfArrays inputs_arr, cv::OutputArrayOfArrays outputs_arr,
               cv::OutputArrayOfArrays /*internals*/) override {
    auto [in, out] = io_blobs(inputs_arr, outputs_arr);
    const size_t plane = static_cast<size_t>(in.size[2]) * in.size[3];
    // On the calling thread, as depthwise_layer.h's: the embedder runs one network copy per thread.
    for (int n = 0; n < in.size[0]; ++n) {
      float* dst = out.ptr<float>() + static_cast<size_t>(n) * out_channels_ * plane;
      pointwise_conv(in.ptr<float>() + static_cast<size_t>(n) * in_channels_ * plane, in_channels_, out_channels_,
                     plane, weights_.data(), bias_.data(), dst);
      if (activation_) activation_->forwardSlice(dst, dst, static_cast<int>(plane), plane, 0, out_channels_);
    }
  }
};

}  // namespace

__attribute__((no_sanitize("thread"))) void pointwise_conv(const float* src, int in_channels, int out_channels,
                                                           size_t plane, const float* weights, const float* bias,
                                                           float* dst) {
#ifdef WARDMAP_X86_SIMD
  if (cpu_has_avx2_fma()) return pointwise_8(src, in_channels, out_channels, plane, weights, bias, dst);
#endif
  pointwise<4>(src, in_channels, out_channels, plane, weights, bias, dst);
}

void register_pointwise_layer() {
  static std::once_flag once;
  std::call_once(once, [] { cv::dnn::LayerFactory::registerLayer(kPointwiseOpType, PointwiseLayer::create); });
}

}  // namespace wardmap::semantics
