#include "semantics/detection/onnx_net.h"

#include <fstream>
#include <iterator>
#include <stdexcept>

#include <spdlog/spdlog.h>

#include "semantics/detection/silu_layer.h"
#include "slam/core/errors.h"

namespace wardmap::semantics {

namespace {

cv::dnn::Net on_cpu(cv::dnn::Net net, const std::filesystem::path& file) {
  if (net.empty()) throw InputError(file.string(), "cannot load the ONNX model (empty network)");
  net.setPreferableBackend(cv::dnn::DNN_BACKEND_OPENCV);
  net.setPreferableTarget(cv::dnn::DNN_TARGET_CPU);
  return net;
}

// Runs a cv::dnn ONNX reader; OpenCV's errors become an InputError naming the file.
template <typename Read>
cv::dnn::Net read_checked(const std::filesystem::path& file, Read read) {
  try {
    return on_cpu(read(), file);
  } catch (const cv::Exception& ex) {
    throw InputError(file.string(), "cannot load the ONNX model: " + ex.msg);
  }
}

// The model's bytes, already read.
cv::dnn::Net net_from_bytes(const std::string& bytes, const std::filesystem::path& file) {
  return read_checked(file, [&] { return cv::dnn::readNetFromONNX(bytes.data(), bytes.size()); });
}

}  // namespace

cv::dnn::Net load_onnx_net(const std::filesystem::path& file, const std::string& missing_hint) {
  if (!std::filesystem::is_regular_file(file)) throw InputError(file.string(), missing_hint);
  return read_checked(file, [&] { return cv::dnn::readNetFromONNX(file.string()); });
}

cv::dnn::Net load_onnx_net(const std::filesystem::path& file, const std::string& missing_hint,
                           std::optional<SpaceToDepth>& folded) {
  folded.reset();
  if (!std::filesystem::is_regular_file(file)) throw InputError(file.string(), missing_hint);
  std::ifstream in(file, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (!in && !in.eof()) throw InputError(file.string(), "cannot read the ONNX model");
  std::optional<FoldedModel> folded_input;
  std::optional<std::string> fused, cascaded;
  try {
    folded_input = fold_space_to_depth_input(bytes);
    const std::string& unfolded = folded_input ? folded_input->onnx : bytes;
    fused = fuse_silu(unfolded);
    cascaded = cascade_max_pools(fused ? *fused : unfolded);
  } catch (const std::runtime_error& ex) {
    throw InputError(file.string(), std::string("not an ONNX model: ") + ex.what());
  }
  if (!folded_input && !fused && !cascaded) return net_from_bytes(bytes, file);
  const std::string& rewritten = cascaded ? *cascaded : fused ? *fused : folded_input->onnx;
  try {
    if (fused) register_silu_layer();
    cv::dnn::Net net = on_cpu(cv::dnn::readNetFromONNX(rewritten.data(), rewritten.size()), file);
    if (folded_input) folded = std::move(folded_input->input);
    return net;
  } catch (const cv::Exception& ex) {  // our rewrite's fault, not the user's: use the model as it is
    spdlog::warn("{}: the model with its input stage folded, its SiLUs fused or its max pools chained does not load ({}); using it unchanged",
                 file.string(), ex.msg);
    return net_from_bytes(bytes, file);
  }
}

}  // namespace wardmap::semantics
