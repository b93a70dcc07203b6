#include "semantics/detection/onnx_net.h"

#include "slam/core/errors.h"

namespace wardmap::semantics {

cv::dnn::Net load_onnx_net(const std::filesystem::path& file, const std::string& missing_hint) {
  if (!std::filesystem::is_regular_file(file)) throw InputError(file.string(), missing_hint);
  cv::dnn::Net net;
  try {
    net = cv::dnn::readNetFromONNX(file.string());
  } catch (const cv::Exception& ex) {
    throw InputError(file.string(), "cannot load the ONNX model: " + ex.msg);
  }
  if (net.empty()) throw InputError(file.string(), "cannot load the ONNX model (empty network)");
  net.setPreferableBackend(cv::dnn::DNN_BACKEND_OPENCV);
  net.setPreferableTarget(cv::dnn::DNN_TARGET_CPU);
  return net;
}

}  // namespace wardmap::semantics
