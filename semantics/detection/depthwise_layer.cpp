#include "semantics/detection/depthwise_layer.h"

#include <algorithm>
#include <mutex>
#include <vector>

#include <opencv2/dnn.hpp>
#include <opencv2/dnn/layer.details.hpp>

#include "semantics/detection/conv_layer_base.h"

namespace wardmap::semantics {

// Pure arithmetic on blobs that cv::dnn's TBB workers wrote: left out of ThreadSanitizer's
// instrumentation, which cannot see TBB's synchronisation (as silu_layer.cpp's kernel;
// tests/sanitizers/tsan.supp). Copies by loop, not memcpy, whose interceptor TSan checks.
__attribute__((no_sanitize("thread"))) void depthwise_conv3x3(const float* src, float* dst, int height, int width,
                                                              const float* k, float bias, float* padded) {
  const int stride = width + 2;
  std::fill(padded, padded + stride, 0.0f);
  std::fill(padded + static_cast<size_t>(height + 1) * stride, padded + static_cast<size_t>(height + 2) * stride, 0.0f);
  for (int y = 0; y < height; ++y) {
    float* row = padded + static_cast<size_t>(y + 1) * stride;
    const float* in = src + static_cast<size_t>(y) * width;
    row[0] = 0.0f;
    for (int x = 0; x < width; ++x) row[x + 1] = in[x];
    row[width + 1] = 0.0f;
  }
  for (int y = 0; y < height; ++y) {
    const float* r0 = padded + static_cast<size_t>(y) * stride;
    const float* r1 = r0 + stride;
    const float* r2 = r1 + stride;
    float* out = dst + static_cast<size_t>(y) * width;
    for (int x = 0; x < width; ++x)  // contiguous in x: the compiler vectorises it
      out[x] = bias + k[0] * r0[x] + k[1] * r0[x + 1] + k[2] * r0[x + 2] + k[3] * r1[x] + k[4] * r1[x + 1] +
               k[5] * r1[x + 2] + k[6] * r2[x] + k[7] * r2[x + 1] + k[8] * r2[x + 2];
  }
}

namespace {

// C x 1 x 3 x 3 weights in C groups, stride 1, one pixel of padding (conv_layer_base.h).
class DepthwiseLayer : public ConvLayerBase {
 public:
  explicit DepthwiseLayer(const cv::dnn::LayerParams& params) : ConvLayerBase(params, /*depthwise=*/true) {
    CV_Assert(kernel_ == 3 && stride_ == 1 && pad_ == 1);
  }

  static cv::Ptr<cv::dnn::Layer> create(cv::dnn::LayerParams& params) {
    return cv::Ptr<cv::dnn::Layer>(new DepthwiseLayer(params));
  }

  void forward(cv::InputArrayOfArrays inputs_arr, cv::OutputArrayOfArrays outputs_arr,
               cv::OutputArrayOfArrays /*internals*/) override {
    auto [in, out] = io_blobs(inputs_arr, outputs_arr);
    const int planes = in.size[0] * out_channels_, height = in.size[2], width = in.size[3];
    const size_t plane = static_cast<size_t>(height) * width;
    const float* src = in.ptr<float>();
    float* dst = out.ptr<float>();
    // On the calling thread: a forward's 60 depthwise layers take about 1.4 ms in all, and the
    // embedder already runs one network copy per thread.
    std::vector<float> padded(static_cast<size_t>(height + 2) * (width + 2));
    for (int p = 0; p < planes; ++p) {
      const int c = p % out_channels_;
      float* out_plane = dst + static_cast<size_t>(p) * plane;
      depthwise_conv3x3(src + static_cast<size_t>(p) * plane, out_plane, height, width,
                        &weights_[9 * static_cast<size_t>(c)], bias_[static_cast<size_t>(c)], padded.data());
      if (activation_) activation_->forwardSlice(out_plane, out_plane, static_cast<int>(plane), plane, c, c + 1);
    }
  }
};

}  // namespace

void register_depthwise_layer() {
  static std::once_flag once;
  std::call_once(once, [] { cv::dnn::LayerFactory::registerLayer(kDepthwiseOpType, DepthwiseLayer::create); });
}

}  // namespace wardmap::semantics
