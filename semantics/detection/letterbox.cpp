#include "semantics/detection/letterbox.h"

#include <algorithm>
#include <cmath>
#include <opencv2/dnn.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace wardmap::semantics {

cv::Mat to_bgr8(const cv::Mat& image) {
  if (image.empty()) throw std::invalid_argument("detector: empty image");
  cv::Mat eight = image;
  if (image.depth() == CV_16U)
    image.convertTo(eight, CV_8U, 1.0 / 257.0);
  else if (image.depth() != CV_8U)
    throw std::invalid_argument("detector: expected an 8-bit or 16-bit image");
  cv::Mat bgr;
  switch (eight.channels()) {
    case 1:
      cv::cvtColor(eight, bgr, cv::COLOR_GRAY2BGR);
      return bgr;
    case 3:
      return eight;
    case 4:
      cv::cvtColor(eight, bgr, cv::COLOR_BGRA2BGR);
      return bgr;
    default:
      throw std::invalid_argument("detector: expected 1, 3 or 4 channels");
  }
}

cv::Size letterbox_canvas(const cv::Size& resized, const InputSpec& spec) {
  const int m = spec.canvas_multiple;
  if (m <= 0) return {spec.width, spec.height};
  // At least m pixels of padding stay after the image: the network then sees where the image ends
  // as on the full canvas (without them boxes that reach the image's bottom, such as tables, were
  // regressed past it and all clipped to the border).
  const auto fit = [m](int side, int limit) {
    return side >= limit ? limit : std::min(limit, (side + 2 * m - 1) / m * m);
  };
  return {fit(resized.width, spec.width), fit(resized.height, spec.height)};
}

Letterbox make_letterbox(const cv::Mat& bgr, const InputSpec& spec) {
  Letterbox lb;
  lb.scale = std::min(static_cast<double>(spec.width) / bgr.cols, static_cast<double>(spec.height) / bgr.rows);
  const int w = std::clamp(static_cast<int>(std::lround(bgr.cols * lb.scale)), 1, spec.width);
  const int h = std::clamp(static_cast<int>(std::lround(bgr.rows * lb.scale)), 1, spec.height);
  cv::Mat resized;
  cv::resize(bgr, resized, cv::Size(w, h), 0, 0, cv::INTER_LINEAR);

  // Work in the network's channel order so mean/std apply as written in the description.
  if (spec.channel_order == "rgb") cv::cvtColor(resized, resized, cv::COLOR_BGR2RGB);
  cv::Mat normalised;
  resized.convertTo(normalised, CV_32FC3);
  const cv::Scalar mean(spec.mean[0], spec.mean[1], spec.mean[2]);
  const cv::Scalar inv_std(1.0 / spec.std[0], 1.0 / spec.std[1], 1.0 / spec.std[2]);
  cv::subtract(normalised, mean, normalised);
  cv::multiply(normalised, inv_std, normalised);

  cv::Scalar pad = cv::Scalar::all(spec.pad_value);
  if (!spec.pad_after_normalisation) {  // the pad is a pixel value: normalise it like the pixels
    for (int c = 0; c < 3; ++c) pad[c] = (spec.pad_value - spec.mean[c]) / spec.std[c];
  }
  lb.canvas = letterbox_canvas({w, h}, spec);
  cv::Mat canvas(lb.canvas, CV_32FC3, pad);
  normalised.copyTo(canvas(cv::Rect(0, 0, w, h)));
  lb.blob = cv::dnn::blobFromImage(canvas);  // HWC -> NCHW, no scaling, no swap
  return lb;
}

}  // namespace wardmap::semantics
