// Loading an ONNX model into cv::dnn on the CPU, with errors that name the file.
#pragma once

#include <filesystem>
#include <opencv2/dnn.hpp>
#include <optional>
#include <string>
#include <vector>

#include "semantics/detection/onnx_fold.h"

namespace wardmap::semantics {

// Throws InputError(file, missing_hint) when the file is absent, InputError(file, ...) when OpenCV
// cannot load it.
cv::dnn::Net load_onnx_net(const std::filesystem::path& file, const std::string& missing_hint);

// What load_onnx_net's rewrites ask of the caller: the input rearranged before Net::setInput
// (a strided-slice input stage folded out of the graph), outputs transposed back after forward.
struct OnnxRewrites {
  std::optional<SpaceToDepth> input;  // empty: the input blob as it is
  std::vector<std::string> transposed_outputs;  // fold_output_transposes: these come out B x C x N

  cv::Mat prepare_input(const cv::Mat& blob) const { return input ? input->apply(blob) : blob; }
  // The output `name` as the original model gives it.
  cv::Mat restore_output(const std::string& name, const cv::Mat& output) const;
};

// The same, with the model rewritten for speed when it allows (onnx_fold.h): a strided-slice input
// stage folded out of the graph, SiLU activations fused into one layer each (fuse_silu,
// silu_layer.h; the outputs then differ from the original model's by float rounding), max pools
// side by side on one tensor (SPP) chained, outputs' final Transposes left to the caller, and
// convolutions of few input channels (YOLOX's 3 x 3 stem, OSNet's 7 x 7 one) run by
// small_conv_layer.h (replace_small_input_convs; float rounding). When `few_channel_convs` (the
// embedder's), also 3 x 3 depthwise convolutions (depthwise_layer.h, replace_depthwise_convs) and
// 1 x 1 convolutions (pointwise_layer.h, replace_pointwise_convs), float rounding again: OSNet
// x0.25's forward 13.9 -> 10.0 ms on one thread with the first (2026-12-01), while YOLOX-nano's
// larger depthwise planes gain 1-3 % (49.0 -> 47.6 ms) for outputs 2e-4 off, and its wider 1 x 1
// convolutions run well in cv::dnn. `rewrites` says what the caller must do about them; it is left
// empty when the model is loaded as it is.
cv::dnn::Net load_onnx_net(const std::filesystem::path& file, const std::string& missing_hint,
                           OnnxRewrites& rewrites, bool few_channel_convs = false);

}  // namespace wardmap::semantics
