// The strided-slice input stage of YOLOX-style models (YOLOX's "Focus": x[..., ::2, ::2],
// x[..., 1::2, ::2], x[..., ::2, 1::2], x[..., 1::2, 1::2] concatenated on the channels) done in C++
// instead of by cv::dnn. OpenCV 4.6 spends about 10 ms of YOLOX-nano's 50 ms at 416x416 in those
// eight Slice layers (Net::getPerfProfile, 2 threads); the same rearrangement is a copy of the input.
// The network itself is unchanged from the Concat on: its output is bit for bit the same.
// Also SiLU (x * sigmoid(x)) fused into one node that silu_layer.h runs, and other rewrites for speed
// that cv::dnn 4.6 makes worthwhile (below).
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace wardmap::semantics {

// Space-to-depth with block 2: channel block k of the output holds the input pixels of row phase
// offsets[k][0] and column phase offsets[k][1].
struct SpaceToDepth {
  int batch = 0, channels = 0, height = 0, width = 0;  // the original input, N x C x H x W
  std::vector<std::array<int, 2>> offsets;

  // N x C x H x W float -> N x (4C) x (H/2) x (W/2). H and W: the model's own or any other even
  // size (a smaller letterbox canvas). Throws std::invalid_argument for another batch or channel
  // count, or an odd side.
  cv::Mat apply(const cv::Mat& blob) const;
};

struct FoldedModel {
  std::string onnx;    // the rewritten ModelProto, for cv::dnn::readNetFromONNX(buffer)
  SpaceToDepth input;  // what to do to the original input before setInput
};

// `onnx`: the bytes of an ONNX ModelProto. When its single input feeds only chains of constant
// Slice nodes (opset >= 10: steps 2 on H and W, starts 0 or 1) that meet in one channel Concat of
// the four phases, returns the model with those nodes removed and the Concat's output as its input.
// Returns nullopt for any other graph (the model is then used as it is). Throws std::runtime_error
// when the bytes are not a protobuf message.
std::optional<FoldedModel> fold_space_to_depth_input(const std::string& onnx);

// `onnx`: the bytes of an ONNX ModelProto. Every Sigmoid whose output goes only to a Mul by the
// Sigmoid's own input (SiLU, YOLOX's activation) becomes, with that Mul, one node of op type
// kSiluOpType (silu_layer.h; register_silu_layer() before loading the result). Returns nullopt
// when the model has no such pair. Throws std::runtime_error when the bytes are not a protobuf
// message.
std::optional<std::string> fuse_silu(const std::string& onnx);

// `onnx`: the bytes of an ONNX ModelProto. Max pools of one tensor side by side, each k x k with
// stride 1 and "same" padding (YOLOX's SPP: kernels 5, 9 and 13), become a chain: each pool after
// the smallest reads the one before it, with the kernel that makes up the difference (a 5 x 5
// maximum of a 5 x 5 maximum is the 9 x 9 maximum: YOLOv5's SPPF). A maximum is exact and cv::dnn's
// pools leave the padding out, so the output is bit for bit the same, for about a third of the
// comparisons. Returns nullopt when the model has no such set. Throws std::runtime_error when the
// bytes are not a protobuf message.
std::optional<std::string> cascade_max_pools(const std::string& onnx);

// `onnx`: the bytes of an ONNX ModelProto. Each 3 x 3 depthwise Conv (constant C x 1 x 3 x 3 weights
// in C groups, an optional constant bias, stride 1, no dilation, one pixel of padding: OSNet's
// LightConv3x3) gets the op type kDepthwiseOpType (depthwise_layer.h; register_depthwise_layer()
// before loading the result), its inputs, attributes and name unchanged. The output then differs
// from the original model's by float rounding. Returns nullopt when the model has no such Conv.
// Throws std::runtime_error when the bytes are not a protobuf message.
std::optional<std::string> replace_depthwise_convs(const std::string& onnx);

// `onnx`: the bytes of an ONNX ModelProto. Each 1 x 1 Conv of one group (constant Cout x Cin x 1 x 1
// weights, at most kPointwiseMaxInputs input channels, Cout a multiple of kPointwiseBlock, an
// optional constant bias, stride 1, no dilation, no padding: 92 of OSNet x0.25's) gets the op type
// kPointwiseOpType (pointwise_layer.h; register_pointwise_layer() before loading the result), its
// inputs, attributes and name unchanged. The output then differs from the original model's by float
// rounding. Returns nullopt when the model has no such Conv. Throws std::runtime_error when the bytes
// are not a protobuf message.
std::optional<std::string> replace_pointwise_convs(const std::string& onnx);

// `onnx`: the bytes of an ONNX ModelProto. Each Conv of one group with at most kSmallConvMaxInputs
// input channels, a multiple of kSmallConvBlock output channels and a kernel and stride the layer
// runs (small_conv_supported: 3 x 3 with stride 1, YOLOX's stem after the Focus fold, 12 -> 16
// channels; 7 x 7 with stride 2, OSNet's, 3 -> 16), with constant weights, an optional constant bias,
// no dilation and the same padding on every side, gets the op type kSmallConvOpType
// (small_conv_layer.h; register_small_conv_layer() before loading the result), its inputs,
// attributes and name unchanged. The output then differs from the original model's by float
// rounding. Returns nullopt when the model has no such Conv. Throws std::runtime_error when the
// bytes are not a protobuf message.
std::optional<std::string> replace_small_input_convs(const std::string& onnx);

struct FoldedOutputs {
  std::string onnx;                  // the rewritten ModelProto
  std::vector<std::string> outputs;  // the graph outputs that now come out B x C x N instead of B x N x C
};

// `onnx`: the bytes of an ONNX ModelProto. Each graph output made by a Transpose with perm (0, 2, 1)
// (YOLOX's last node, 1 x 85 x N -> 1 x N x 85) from a tensor that nothing else reads loses that
// Transpose: the tensor before it takes the output's name. OpenCV 4.6's Permute layer takes about
// 2 ms for YOLOX-nano's output; transpose_output() puts it back in a fraction of that, bit for
// bit. Returns nullopt when the model has no such output. Throws std::runtime_error when the
// bytes are not a protobuf message.
std::optional<FoldedOutputs> fold_output_transposes(const std::string& onnx);

// A B x C x N float output of a model that fold_output_transposes rewrote, as B x N x C (the
// original model's output). Throws std::invalid_argument for another shape or type.
cv::Mat transpose_output(const cv::Mat& output);

}  // namespace wardmap::semantics
