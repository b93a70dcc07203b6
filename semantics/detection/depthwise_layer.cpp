#include "semantics/detection/depthwise_layer.h"

#include <algorithm>
#include <mutex>
#include <vector>

#include <opencv2/dnn.hpp>
#include <opencv2/dnn/all_layers.hpp>
#include <opencv2/dnn/layer.details.hpp>

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

// blobs[0]: the weights, C x 1 x 3 x 3; blobs[1] (optional): the bias, C values. Input and output
// N x C x H x W floats.
class DepthwiseLayer : public cv::dnn::Layer {
 public:
  explicit DepthwiseLayer(const cv::dnn::LayerParams& params) {
    setParamsFrom(params);
    CV_Assert(!blobs.empty() && blobs[0].type() == CV_32F && blobs[0].dims == 4 && blobs[0].size[1] == 1 &&
              blobs[0].size[2] == 3 && blobs[0].size[3] == 3 && blobs[0].isContinuous());
    channels_ = blobs[0].size[0];
    weights_.assign(blobs[0].ptr<float>(), blobs[0].ptr<float>() + 9 * channels_);
    bias_.assign(static_cast<size_t>(channels_), 0.0f);
    if (blobs.size() > 1) {
      CV_Assert(blobs[1].type() == CV_32F && blobs[1].total() == static_cast<size_t>(channels_) &&
                blobs[1].isContinuous());
      std::copy(blobs[1].ptr<float>(), blobs[1].ptr<float>() + channels_, bias_.begin());
    }
  }

  static cv::Ptr<cv::dnn::Layer> create(cv::dnn::LayerParams& params) {
    return cv::Ptr<cv::dnn::Layer>(new DepthwiseLayer(params));
  }

  bool getMemoryShapes(const std::vector<cv::dnn::MatShape>& inputs, int /*required_outputs*/,
                       std::vector<cv::dnn::MatShape>& outputs,
                       std::vector<cv::dnn::MatShape>& /*internals*/) const override {
    CV_Assert(inputs.size() == 1 && inputs[0].size() == 4 && inputs[0][1] == channels_);
    outputs = inputs;
    return false;  // not in place: each output reads its input's neighbours
  }

  bool setActivation(const cv::Ptr<cv::dnn::ActivationLayer>& layer) override {
    activation_ = layer;
    return !activation_.empty();
  }

  void forward(cv::InputArrayOfArrays inputs_arr, cv::OutputArrayOfArrays outputs_arr,
               cv::OutputArrayOfArrays /*internals*/) override {
    std::vector<cv::Mat> inputs, outputs;
    inputs_arr.getMatVector(inputs);
    outputs_arr.getMatVector(outputs);
    CV_Assert(inputs.size() == 1 && outputs.size() == 1);
    const cv::Mat& in = inputs[0];
    cv::Mat& out = outputs[0];
    CV_Assert(in.type() == CV_32F && out.type() == CV_32F && in.dims == 4 && in.isContinuous() &&
              out.isContinuous() && in.size == out.size && in.size[1] == channels_);
    const int planes = in.size[0] * channels_, height = in.size[2], width = in.size[3];
    const size_t plane = static_cast<size_t>(height) * width;
    const float* src = in.ptr<float>();
    float* dst = out.ptr<float>();
    // On the calling thread: a forward's 60 depthwise layers take about 1.4 ms in all, and the
    // embedder already runs one network copy per thread.
    std::vector<float> padded(static_cast<size_t>(height + 2) * (width + 2));
    for (int p = 0; p < planes; ++p) {
      const int c = p % channels_;
      float* out_plane = dst + static_cast<size_t>(p) * plane;
      depthwise_conv3x3(src + static_cast<size_t>(p) * plane, out_plane, height, width,
                        &weights_[9 * static_cast<size_t>(c)], bias_[static_cast<size_t>(c)], padded.data());
      if (activation_) activation_->forwardSlice(out_plane, out_plane, static_cast<int>(plane), plane, c, c + 1);
    }
  }

 private:
  int channels_ = 0;
  std::vector<float> weights_, bias_;
  cv::Ptr<cv::dnn::ActivationLayer> activation_;
};

}  // namespace

void register_depthwise_layer() {
  static std::once_flag once;
  std::call_once(once, [] { cv::dnn::LayerFactory::registerLayer(kDepthwiseOpType, DepthwiseLayer::create); });
}

}  // namespace wardmap::semantics
