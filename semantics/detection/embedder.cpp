#include "semantics/detection/embedder.h"

#include "semantics/detection/onnx_net.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "semantics/detection/letterbox.h"
#include "slam/core/errors.h"

namespace wardmap::semantics {

namespace {
// OSNet input (MODELS.md): RGB, 128 wide x 256 high, /255, ImageNet mean and std.
constexpr int kInputWidth = 128;
constexpr int kInputHeight = 256;
const cv::Scalar kMean(0.485, 0.456, 0.406);
const cv::Scalar kStd(0.229, 0.224, 0.225);
}  // namespace

Embedder::Embedder(const std::filesystem::path& onnx_file) {
  net_ = load_onnx_net(onnx_file, "embedding model not found (models/README.md says where to get OSNet x0.25)");
}

Eigen::VectorXf Embedder::embed(const cv::Mat& image, const Eigen::Vector4d& box) {
  const cv::Mat bgr = to_bgr8(image);
  const double x0 = std::clamp(box[0], 0.0, static_cast<double>(bgr.cols));
  const double y0 = std::clamp(box[1], 0.0, static_cast<double>(bgr.rows));
  const double x1 = std::clamp(box[2], 0.0, static_cast<double>(bgr.cols));
  const double y1 = std::clamp(box[3], 0.0, static_cast<double>(bgr.rows));
  if (x1 - x0 < kMinCropSide || y1 - y0 < kMinCropSide)
    throw std::invalid_argument("Embedder::embed: crop smaller than 2 px after clamping to the image");
  // Whole pixels covering the box.
  const int ix0 = static_cast<int>(std::floor(x0)), iy0 = static_cast<int>(std::floor(y0));
  const int ix1 = static_cast<int>(std::ceil(x1)), iy1 = static_cast<int>(std::ceil(y1));
  cv::Mat crop;
  cv::resize(bgr(cv::Rect(ix0, iy0, ix1 - ix0, iy1 - iy0)), crop, cv::Size(kInputWidth, kInputHeight), 0, 0,
             cv::INTER_LINEAR);
  cv::cvtColor(crop, crop, cv::COLOR_BGR2RGB);
  cv::Mat input;
  crop.convertTo(input, CV_32FC3, 1.0 / 255.0);
  cv::subtract(input, kMean, input);
  cv::divide(input, kStd, input);
  net_.setInput(cv::dnn::blobFromImage(input));  // 1 x 3 x 256 x 128
  const cv::Mat out = net_.forward();
  if (out.total() != static_cast<size_t>(kDimension))
    throw std::runtime_error("Embedder: expected a " + std::to_string(kDimension) + "-d output, got " +
                             std::to_string(out.total()));
  Eigen::VectorXf v = Eigen::Map<const Eigen::VectorXf>(out.ptr<float>(), kDimension);
  const float norm = v.norm();
  if (norm > 0) v /= norm;
  return v;
}

}  // namespace wardmap::semantics
