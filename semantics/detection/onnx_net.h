// Loading an ONNX model into cv::dnn on the CPU, with errors that name the file.
#pragma once

#include <filesystem>
#include <opencv2/dnn.hpp>
#include <optional>
#include <string>

#include "semantics/detection/onnx_fold.h"

namespace wardmap::semantics {

// Throws InputError(file, missing_hint) when the file is absent, InputError(file, ...) when OpenCV
// cannot load it.
cv::dnn::Net load_onnx_net(const std::filesystem::path& file, const std::string& missing_hint);

// The same, with a strided-slice input stage folded out of the graph (onnx_fold.h) when the model
// has one: `folded` then says how to rearrange the input blob before Net::setInput; it is left
// empty when the model is loaded without it. SiLU activations are fused into one layer each
// (fuse_silu, silu_layer.h); the outputs then differ from the original model's by float rounding.
// Max pools side by side on one tensor (SPP) are chained (cascade_max_pools: the same output).
cv::dnn::Net load_onnx_net(const std::filesystem::path& file, const std::string& missing_hint,
                           std::optional<SpaceToDepth>& folded);

}  // namespace wardmap::semantics
