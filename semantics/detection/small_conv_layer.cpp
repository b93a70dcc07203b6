#include "semantics/detection/small_conv_layer.h"

#include <algorithm>
#include <cstddef>
#include <mutex>
#include <opencv2/core/utility.hpp>
#include <opencv2/dnn.hpp>
#include <opencv2/dnn/layer.details.hpp>
#include <vector>

#include "semantics/detection/conv_layer_base.h"
#include "semantics/detection/float_lanes.h"

namespace wardmap::semantics {

namespace {

// small_input_conv with L pixels a vector, for one (K, S): 8 output channels x L pixels of sums in
// registers, each input vector read once per tap. Pure arithmetic on blobs that cv::dnn's TBB
// workers wrote: left out of ThreadSanitizer's instrumentation (as silu_layer.cpp's kernel).
template <int L, int K, int S>
__attribute__((always_inline, no_sanitize("thread"))) inline void conv_rows(const float* layout, SmallConvGeometry g,
                                                                            const float* packed, const float* bias,
                                                                            float* dst, int row_begin, int row_end) {
  using F = typename Lanes<L>::F;
  using Load = typename Lanes<L>::Load;
  const int row = g.row_floats(), out_width = g.out_width();
  const size_t phase_plane = static_cast<size_t>(g.layout_rows()) * row;
  const size_t plane = static_cast<size_t>(g.out_height()) * out_width;
  const size_t per_block = static_cast<size_t>(g.in_channels) * K * K * kSmallConvBlock;
  for (int o0 = 0; o0 < g.out_channels; o0 += kSmallConvBlock)
    for (int y = row_begin; y < row_end; ++y)
      for (int x = 0; x < out_width; x += L) {
        F acc[kSmallConvBlock];
        for (int j = 0; j < kSmallConvBlock; ++j) acc[j] = F{} + bias[o0 + j];
        const float* w = packed + (o0 / kSmallConvBlock) * per_block;
        for (int c = 0; c < g.in_channels; ++c)
          for (int i = 0; i < K; ++i) {
            // Input row S y + i of channel c; tap t reads column phase t % S from column x + t / S.
            const float* in =
                layout + static_cast<size_t>(c) * S * phase_plane + static_cast<size_t>(S * y + i) * row + x;
            for (int t = 0; t < K; ++t, w += kSmallConvBlock) {
              const F v = *reinterpret_cast<const Load*>(in + (t % S) * phase_plane + t / S);
              for (int j = 0; j < kSmallConvBlock; ++j) acc[j] += v * w[j];
            }
          }
        for (int j = 0; j < kSmallConvBlock; ++j) {
          float* out = dst + (o0 + j) * plane + static_cast<size_t>(y) * out_width + x;
          if (x + L <= out_width) {
            *reinterpret_cast<Load*>(out) = acc[j];
          } else {
            for (int k = 0; k < out_width - x; ++k) out[k] = acc[j][k];
          }
        }
      }
}

// The supported shapes (small_conv_supported) with L lanes.
template <int L>
__attribute__((always_inline, no_sanitize("thread"))) inline void conv_rows_any(const float* layout,
                                                                                SmallConvGeometry g,
                                                                                const float* packed, const float* bias,
                                                                                float* dst, int row_begin,
                                                                                int row_end) {
  if (g.kernel == 3 && g.stride == 1)
    conv_rows<L, 3, 1>(layout, g, packed, bias, dst, row_begin, row_end);
  else
    conv_rows<L, 7, 2>(layout, g, packed, bias, dst, row_begin, row_end);
}

#ifdef WARDMAP_X86_SIMD
__attribute__((target("avx2,fma"), no_sanitize("thread"))) void conv_rows_8(const float* layout, SmallConvGeometry g,
                                                                            const float* packed, const float* bias,
                                                                            float* dst, int row_begin, int row_end) {
  conv_rows_any<8>(layout, g, packed, bias, dst, row_begin, row_end);
}
#endif

// Cout x Cin x k x k weights in one group, a supported kernel and stride (conv_layer_base.h).
class SmallConvLayer : public ConvLayerBase {
 public:
  explicit SmallConvLayer(const cv::dnn::LayerParams& params) : ConvLayerBase(params, /*depthwise=*/false) {
    CV_Assert(out_channels_ % kSmallConvBlock == 0 && small_conv_supported(kernel_, stride_));
    packed_ = small_conv_pack_weights(weights_.data(), geometry(0, 0));
  }

  static cv::Ptr<cv::dnn::Layer> create(cv::dnn::LayerParams& params) {
    return cv::Ptr<cv::dnn::Layer>(new SmallConvLayer(params));
  }

  void forward(cv::InputArrayOfArrays inputs_arr, cv::OutputArrayOfArrays outputs_arr,
               cv::OutputArrayOfArrays /*internals*/) override {
    auto [in, out] = io_blobs(inputs_arr, outputs_arr);
    const SmallConvGeometry g = geometry(in.size[2], in.size[3]);
    // The zero-bordered input layout is kept between forwards (a network copy runs one forward at a
    // time): YOLOX's stem needs 1.9 MB, allocated and zeroed once per input size, not per frame.
    if (layout_size_ != cv::Size(g.width, g.height)) {
      layout_.assign(g.layout_floats(), 0.0f);
      layout_size_ = cv::Size(g.width, g.height);
    }
    const size_t in_item = static_cast<size_t>(in_channels_) * g.height * g.width;
    const size_t out_item = static_cast<size_t>(out_channels_) * g.out_height() * g.out_width();
    for (int n = 0; n < in.size[0]; ++n) {
      small_conv_layout(in.ptr<float>() + n * in_item, g, layout_.data());
      Rows rows(g, layout_.data(), packed_.data(), bias_.data(), activation_.get(), out.ptr<float>() + n * out_item);
      cv::parallel_for_(cv::Range(0, g.out_height()), rows, 8);
    }
  }

 private:
  SmallConvGeometry geometry(int height, int width) const {
    SmallConvGeometry g;
    g.in_channels = in_channels_;
    g.out_channels = out_channels_;
    g.kernel = kernel_;
    g.stride = stride_;
    g.pad = pad_;
    g.height = height;
    g.width = width;
    return g;
  }

  std::vector<float> packed_;  // small_conv_pack_weights
  std::vector<float> layout_;  // small_conv_layout's buffer
  cv::Size layout_size_;       // the input width and height layout_ was made for

  // Output rows on cv::dnn's threads. Its body reads the buffers its caller wrote, through TBB's
  // synchronisation, which ThreadSanitizer cannot see: left out of its instrumentation, and given
  // plain values and pointers (taken on the calling thread), since the inline accessors it would
  // otherwise call are instrumented.
  class Rows : public cv::ParallelLoopBody {
   public:
    Rows(const SmallConvGeometry& g, const float* layout, const float* packed, const float* bias,
         const cv::dnn::ActivationLayer* activation, float* dst)
        : g_(g), layout_(layout), packed_(packed), bias_(bias), activation_(activation), dst_(dst) {}
    __attribute__((no_sanitize("thread"))) void operator()(const cv::Range& r) const override {
      const SmallConvGeometry g = g_;
      small_input_conv(layout_, g, packed_, bias_, dst_, r.start, r.end);
      if (activation_) {
        const int width = g.out_width();  // of the copy on this thread's stack
        const size_t plane = static_cast<size_t>(g.out_height()) * width;
        float* first = dst_ + static_cast<size_t>(r.start) * width;
        activation_->forwardSlice(first, first, (r.end - r.start) * width, plane, 0, g.out_channels);
      }
    }

   private:
    SmallConvGeometry g_;
    const float* layout_;
    const float* packed_;
    const float* bias_;
    const cv::dnn::ActivationLayer* activation_;
    float* dst_;
  };
};

}  // namespace

bool small_conv_supported(int kernel, int stride) {
  return (kernel == 3 && stride == 1) || (kernel == 7 && stride == 2);
}

// Pure copying into a buffer its caller owns, of a blob cv::dnn's TBB workers wrote: left out of
// ThreadSanitizer's instrumentation, by loop rather than memcpy (whose interceptor TSan checks).
__attribute__((no_sanitize("thread"))) void small_conv_layout(const float* src, SmallConvGeometry g, float* layout) {
  const int row = g.row_floats();
  const size_t phase_plane = static_cast<size_t>(g.layout_rows()) * row;
  for (int c = 0; c < g.in_channels; ++c)
    for (int y = 0; y < g.height; ++y) {
      const float* in = src + (static_cast<size_t>(c) * g.height + y) * g.width;
      float* rows = layout + static_cast<size_t>(c) * g.stride * phase_plane + static_cast<size_t>(y + g.pad) * row;
      // Column phase q holds the padded input's columns q, q + stride ...: the input's columns from
      // x0 = (q - pad) mod stride on, every stride-th, at (x0 + pad) / stride on.
      for (int q = 0; q < g.stride; ++q) {
        const int x0 = ((q - g.pad) % g.stride + g.stride) % g.stride;
        float* out = rows + static_cast<size_t>(q) * phase_plane + (x0 + g.pad) / g.stride;
        for (int x = x0; x < g.width; x += g.stride) *out++ = in[x];
      }
    }
}

std::vector<float> small_conv_pack_weights(const float* weights, const SmallConvGeometry& g) {
  const size_t taps = static_cast<size_t>(g.kernel) * g.kernel;
  std::vector<float> packed(static_cast<size_t>(g.out_channels) * g.in_channels * taps);
  size_t k = 0;
  for (int o0 = 0; o0 < g.out_channels; o0 += kSmallConvBlock)
    for (int c = 0; c < g.in_channels; ++c)
      for (size_t t = 0; t < taps; ++t)
        for (int j = 0; j < kSmallConvBlock; ++j)
          packed[k++] = weights[(static_cast<size_t>(o0 + j) * g.in_channels + c) * taps + t];
  return packed;
}

__attribute__((no_sanitize("thread"))) void small_input_conv(const float* layout, SmallConvGeometry g,
                                                             const float* packed, const float* bias, float* dst,
                                                             int row_begin, int row_end) {
#ifdef WARDMAP_X86_SIMD
  if (cpu_has_avx2_fma()) return conv_rows_8(layout, g, packed, bias, dst, row_begin, row_end);
#endif
  conv_rows_any<4>(layout, g, packed, bias, dst, row_begin, row_end);
}

void register_small_conv_layer() {
  static std::once_flag once;
  std::call_once(once, [] { cv::dnn::LayerFactory::registerLayer(kSmallConvOpType, SmallConvLayer::create); });
}

}  // namespace wardmap::semantics
