// Loading an ONNX model into cv::dnn on the CPU, with errors that name the file.
#pragma once

#include <filesystem>
#include <opencv2/dnn.hpp>
#include <string>

namespace wardmap::semantics {

// Throws InputError(file, missing_hint) when the file is absent, InputError(file, ...) when OpenCV
// cannot load it.
cv::dnn::Net load_onnx_net(const std::filesystem::path& file, const std::string& missing_hint);

}  // namespace wardmap::semantics
