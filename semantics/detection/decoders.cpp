#include "semantics/detection/decoders.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace wardmap::semantics {

namespace {

// Rows x columns of a 1 x N x C (or N x C) network output, checked against what the model should give.
void check_shape(const cv::Mat& m, int rows, int cols, const std::string& what) {
  const int n = m.dims == 3 ? m.size[1] : m.rows;
  const int c = m.dims == 3 ? m.size[2] : m.cols;
  if (m.type() != CV_32F || n != rows || c != cols)
    throw std::runtime_error("output '" + what + "' has shape " + std::to_string(n) + "x" + std::to_string(c) +
                             ", expected " + std::to_string(rows) + "x" + std::to_string(cols));
}

int best_class(const float* scores, int n) { return static_cast<int>(std::max_element(scores, scores + n) - scores); }

}  // namespace

std::vector<Candidate> decode_yolox(const cv::Mat& output, const ModelDescription& model, const cv::Size& canvas,
                                    float min_score) {
  const int num_classes = static_cast<int>(model.classes.size());
  const int row_size = 5 + num_classes;
  int total = 0;
  for (int s : model.output.strides) total += (canvas.width / s) * (canvas.height / s);
  check_shape(output, total, row_size, model.output.names.front());

  std::vector<Candidate> out;
  const float* row = output.ptr<float>();
  for (int s : model.output.strides) {
    const int gw = canvas.width / s, gh = canvas.height / s;
    for (int gy = 0; gy < gh; ++gy) {
      for (int gx = 0; gx < gw; ++gx, row += row_size) {
        const float objectness = row[4];
        if (objectness < min_score) continue;  // score = obj * cls <= obj
        const int c = best_class(row + 5, num_classes);
        const float score = objectness * row[5 + c];
        if (score < min_score) continue;
        const double cx = (row[0] + gx) * s, cy = (row[1] + gy) * s;
        const double w = std::exp(row[2]) * s, h = std::exp(row[3]) * s;
        out.push_back({cv::Rect2d(cx - 0.5 * w, cy - 0.5 * h, w, h), c, score});
      }
    }
  }
  return out;
}

std::vector<Candidate> decode_nanodet(const std::vector<cv::Mat>& class_maps, const std::vector<cv::Mat>& box_maps,
                                      const ModelDescription& model, const cv::Size& canvas, float min_score) {
  const int num_classes = static_cast<int>(model.classes.size());
  const int bins = model.output.bins;
  std::vector<Candidate> out;
  std::vector<double> soft(bins);
  for (size_t level = 0; level < model.output.strides.size(); ++level) {
    const int s = model.output.strides[level];
    const int gw = (canvas.width + s - 1) / s, gh = (canvas.height + s - 1) / s;
    check_shape(class_maps[level], gw * gh, num_classes, model.output.names[level]);
    check_shape(box_maps[level], gw * gh, 4 * bins, model.output.box_names[level]);
    const float* cls = class_maps[level].ptr<float>();
    const float* dis = box_maps[level].ptr<float>();
    for (int i = 0; i < gw * gh; ++i, cls += num_classes, dis += 4 * bins) {
      const int c = best_class(cls, num_classes);
      if (cls[c] < min_score) continue;
      const double cx = (i % gw + 0.5) * s, cy = (i / gw + 0.5) * s;
      double side[4];  // left, top, right, bottom distances in pixels
      for (int k = 0; k < 4; ++k) {
        const float* logits = dis + k * bins;
        const float top = *std::max_element(logits, logits + bins);
        double sum = 0, expectation = 0;
        for (int b = 0; b < bins; ++b) {
          soft[b] = std::exp(static_cast<double>(logits[b] - top));
          sum += soft[b];
        }
        for (int b = 0; b < bins; ++b) expectation += b * soft[b];
        side[k] = expectation / sum * s;
      }
      out.push_back({cv::Rect2d(cx - side[0], cy - side[1], side[0] + side[2], side[1] + side[3]), c, cls[c]});
    }
  }
  return out;
}

}  // namespace wardmap::semantics
