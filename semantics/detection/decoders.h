// Decoding of the raw network outputs into candidate boxes in network-input pixels (MODELS.md).
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "semantics/detection/model_description.h"

namespace wardmap::semantics {

struct Candidate {
  cv::Rect2d box;  // network-input pixels (x, y, width, height)
  int class_id = 0;
  float score = 0;
};

// YOLOX: rows [tx, ty, tw, th, obj, classes...] over strides in order, x fastest within a stride;
// cx = (tx + gx) s, cy = (ty + gy) s, w = exp(tw) s, h = exp(th) s, score = obj * max(cls).
// Keeps candidates with score >= min_score. `canvas`: the network input's W x H (Letterbox::canvas).
std::vector<Candidate> decode_yolox(const cv::Mat& output, const ModelDescription& model, const cv::Size& canvas,
                                    float min_score);

// NanoDet (GFL head): per stride a class map (N x C, sigmoided) and a distance map (N x 4 * bins);
// each side is the expectation of a softmax over bins, times the stride, measured from the centre
// ((x + 0.5) s, (y + 0.5) s); sides in the order left, top, right, bottom.
std::vector<Candidate> decode_nanodet(const std::vector<cv::Mat>& class_maps, const std::vector<cv::Mat>& box_maps,
                                      const ModelDescription& model, const cv::Size& canvas, float min_score);

}  // namespace wardmap::semantics
