// Input preparation for the letterbox detectors (MODELS.md): aspect-preserving resize into the
// top-left corner of the network canvas, padding, per-channel normalisation, NCHW blob.
#pragma once

#include <opencv2/core.hpp>

#include "semantics/detection/model_description.h"

namespace wardmap::semantics {

// BGR 8-bit view of an image: grey and BGRA are converted, 16-bit is scaled down; a BGR 8-bit
// image is returned as is (no copy). Throws std::invalid_argument for other types and empty images.
cv::Mat to_bgr8(const cv::Mat& image);

struct Letterbox {
  cv::Mat blob;        // 1 x 3 x H x W float
  double scale = 1.0;  // r: network pixels per image pixel; image box = network box / r
  cv::Size canvas;     // W x H: the model's input size, or less (InputSpec::canvas_multiple)
};

// The canvas for an image resized to `resized`: the model's width x height; when
// spec.canvas_multiple (N) is set, a side the image does not fill is cut to the smallest multiple of
// N that holds the image and N pixels of padding after it.
cv::Size letterbox_canvas(const cv::Size& resized, const InputSpec& spec);

// r = min(W / w, H / h); image resized by r into the canvas corner (0, 0); the rest is padded.
Letterbox make_letterbox(const cv::Mat& bgr, const InputSpec& spec);

}  // namespace wardmap::semantics
