// What wardmap's convolution layers share (depthwise_layer.h, small_conv_layer.h): constant weights
// Cout x Cin/groups x k x k (blobs[0], as cv::dnn's ONNX reader hands a custom layer its constant
// inputs) and an optional bias of Cout (blobs[1]); the stride and the padding (the same on every
// side), from the node's attributes as cv::dnn's ONNX reader turns them into layer parameters
// ("stride", "pad"; 1 and 0 when absent); the output shape (N x Cout x H' x W' of an N x Cin x H x W
// input, H' = (H + 2 pad - k) / stride + 1); and the activation cv::dnn fuses into it.
#pragma once

#include <algorithm>
#include <utility>
#include <vector>

#include <opencv2/dnn.hpp>
#include <opencv2/dnn/all_layers.hpp>

namespace wardmap::semantics {

class ConvLayerBase : public cv::dnn::Layer {
 public:
  bool getMemoryShapes(const std::vector<cv::dnn::MatShape>& inputs, int /*required_outputs*/,
                       std::vector<cv::dnn::MatShape>& outputs,
                       std::vector<cv::dnn::MatShape>& /*internals*/) const override {
    CV_Assert(inputs.size() == 1 && inputs[0].size() == 4 && inputs[0][1] == in_channels_ &&
              inputs[0][2] + 2 * pad_ >= kernel_ && inputs[0][3] + 2 * pad_ >= kernel_);
    outputs = inputs;
    outputs[0][1] = out_channels_;
    outputs[0][2] = out_size(inputs[0][2]);
    outputs[0][3] = out_size(inputs[0][3]);
    return false;  // not in place: each output reads its input's neighbours
  }

  bool setActivation(const cv::Ptr<cv::dnn::ActivationLayer>& layer) override {
    activation_ = layer;
    return !activation_.empty();
  }

 protected:
  // `depthwise`: one input channel per group (Cin = Cout), else one group.
  ConvLayerBase(const cv::dnn::LayerParams& params, bool depthwise) {
    setParamsFrom(params);
    CV_Assert(!blobs.empty() && blobs.size() <= 2 && blobs[0].type() == CV_32F && blobs[0].dims == 4 &&
              blobs[0].size[2] == blobs[0].size[3] && blobs[0].isContinuous() && (!depthwise || blobs[0].size[1] == 1));
    out_channels_ = blobs[0].size[0];
    in_channels_ = depthwise ? out_channels_ : blobs[0].size[1];
    kernel_ = blobs[0].size[2];
    stride_ = same_values(params, "stride", 1);
    pad_ = same_values(params, "pad", 0);
    CV_Assert(stride_ >= 1 && pad_ >= 0 && same_values(params, "kernel_size", kernel_) == kernel_);
    weights_.assign(blobs[0].ptr<float>(), blobs[0].ptr<float>() + blobs[0].total());
    bias_.assign(static_cast<size_t>(out_channels_), 0.0f);
    if (blobs.size() == 2) {
      CV_Assert(blobs[1].type() == CV_32F && blobs[1].total() == bias_.size() && blobs[1].isContinuous());
      std::copy(blobs[1].ptr<float>(), blobs[1].ptr<float>() + out_channels_, bias_.begin());
    }
  }

  // The value of a parameter that holds one value per axis or side (cv::dnn's ONNX reader makes
  // "pads" a list of 4), all of them the same; `fallback` when absent.
  static int same_values(const cv::dnn::LayerParams& params, const char* key, int fallback) {
    if (!params.has(key)) return fallback;
    const cv::dnn::DictValue& v = params.get(key);
    CV_Assert(v.size() >= 1);
    for (int i = 1; i < v.size(); ++i) CV_Assert(v.get<int>(i) == v.get<int>(0));
    return v.get<int>(0);
  }

  int out_size(int in) const { return (in + 2 * pad_ - kernel_) / stride_ + 1; }

  // forward()'s one input and one output blob (headers on cv::dnn's data), checked against the
  // layer: an N x Cin x H x W float input, an N x Cout x H' x W' output, both continuous.
  std::pair<cv::Mat, cv::Mat> io_blobs(cv::InputArrayOfArrays inputs_arr, cv::OutputArrayOfArrays outputs_arr) const {
    std::vector<cv::Mat> inputs, outputs;
    inputs_arr.getMatVector(inputs);
    outputs_arr.getMatVector(outputs);
    CV_Assert(inputs.size() == 1 && outputs.size() == 1);
    const cv::Mat& in = inputs[0];
    const cv::Mat& out = outputs[0];
    CV_Assert(in.type() == CV_32F && out.type() == CV_32F && in.dims == 4 && out.dims == 4 && in.isContinuous() &&
              out.isContinuous() && in.size[1] == in_channels_ && out.size[1] == out_channels_ &&
              in.size[0] == out.size[0] && out.size[2] == out_size(in.size[2]) && out.size[3] == out_size(in.size[3]));
    return {in, out};
  }

  int in_channels_ = 0, out_channels_ = 0, kernel_ = 0, stride_ = 1, pad_ = 0;
  std::vector<float> weights_, bias_;
  cv::Ptr<cv::dnn::ActivationLayer> activation_;
};

}  // namespace wardmap::semantics
