#include "semantics/detection/onnx_net.h"

#include <algorithm>
#include <fstream>
#include <iterator>
#include <stdexcept>

#include <spdlog/spdlog.h>

#include "semantics/detection/depthwise_layer.h"
#include "semantics/detection/pointwise_layer.h"
#include "semantics/detection/silu_layer.h"
#include "semantics/detection/small_conv_layer.h"
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

// A model file that is not there (`missing_hint` says what it is and where to get it) or is empty
// is named as such; OpenCV's message for an empty file is an assertion.
void check_model_file(const std::filesystem::path& file, const std::string& missing_hint) {
  if (!std::filesystem::is_regular_file(file)) throw InputError(file.string(), missing_hint);
  std::error_code ec;
  if (std::filesystem::file_size(file, ec) == 0 && !ec)
    throw InputError(file.string(), "empty file, not an ONNX model (an interrupted download?)");
}

}  // namespace

cv::dnn::Net load_onnx_net(const std::filesystem::path& file, const std::string& missing_hint) {
  check_model_file(file, missing_hint);
  return read_checked(file, [&] { return cv::dnn::readNetFromONNX(file.string()); });
}

cv::Mat OnnxRewrites::restore_output(const std::string& name, const cv::Mat& output) const {
  const bool transposed =
      std::find(transposed_outputs.begin(), transposed_outputs.end(), name) != transposed_outputs.end();
  return transposed ? transpose_output(output) : output;
}

cv::dnn::Net load_onnx_net(const std::filesystem::path& file, const std::string& missing_hint,
                           OnnxRewrites& rewrites, bool few_channel_convs) {
  rewrites = OnnxRewrites();
  check_model_file(file, missing_hint);
  std::ifstream in(file, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (!in && !in.eof()) throw InputError(file.string(), "cannot read the ONNX model");
  // Each rewrite reads the last one's model (or the file's bytes).
  std::optional<FoldedModel> folded_input;
  std::optional<std::string> fused, cascaded, depthwise, pointwise, small;
  std::optional<FoldedOutputs> folded_outputs;
  const std::string* model = &bytes;
  try {
    if ((folded_input = fold_space_to_depth_input(*model))) model = &folded_input->onnx;
    if ((fused = fuse_silu(*model))) model = &*fused;
    if ((cascaded = cascade_max_pools(*model))) model = &*cascaded;
    if (few_channel_convs && (depthwise = replace_depthwise_convs(*model))) model = &*depthwise;
    if (few_channel_convs && (pointwise = replace_pointwise_convs(*model))) model = &*pointwise;
    if ((small = replace_small_input_convs(*model))) model = &*small;
    if ((folded_outputs = fold_output_transposes(*model))) model = &folded_outputs->onnx;
  } catch (const std::runtime_error& ex) {
    throw InputError(file.string(), std::string("not an ONNX model: ") + ex.what());
  }
  if (model == &bytes) return net_from_bytes(bytes, file);
  try {
    if (fused) register_silu_layer();
    if (depthwise) register_depthwise_layer();
    if (pointwise) register_pointwise_layer();
    if (small) register_small_conv_layer();
    cv::dnn::Net net = on_cpu(cv::dnn::readNetFromONNX(model->data(), model->size()), file);
    if (folded_input) rewrites.input = std::move(folded_input->input);
    if (folded_outputs) rewrites.transposed_outputs = folded_outputs->outputs;
    return net;
  } catch (const cv::Exception& ex) {  // our rewrite's fault, not the user's: use the model as it is
    spdlog::warn("{}: the model as rewritten for speed (onnx_fold.h) does not load ({}); using it unchanged",
                 file.string(), ex.msg);
    return net_from_bytes(bytes, file);
  }
}

}  // namespace wardmap::semantics
