#include "slam/front/orb_extractor.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>

#include "slam/front/quadtree_distribution.h"

namespace wardmap::slam {

namespace {
constexpr int kPatchSize = 31;  // rBRIEF patch (pixels)
constexpr int kHalfPatch = 15;  // orientation disc radius
}  // namespace

OrbExtractor::OrbExtractor(const OrbOptions& options)
    : options_(options), pyramid_(options.scale_factor, options.n_levels) {
  // Geometric share of nFeatures per level (finer levels get more).
  const double inv = 1.0 / options.scale_factor;
  const int L = options.n_levels;
  double per_level = options.n_features * (1 - inv) / (1 - std::pow(inv, L));
  int sum = 0;
  for (int l = 0; l < L - 1; ++l) {
    features_per_level_.push_back(static_cast<int>(std::lround(per_level)));
    sum += features_per_level_.back();
    per_level *= inv;
  }
  features_per_level_.push_back(std::max(options.n_features - sum, 0));

  for (int dv = 0; dv <= kHalfPatch; ++dv)
    circle_half_width_.push_back(static_cast<int>(std::floor(std::sqrt(kHalfPatch * kHalfPatch - dv * dv) + 0.5)));

  // Descriptors are computed level by level on this extractor's own pyramid (one level per call), so
  // cv::ORB neither rebuilds the pyramid nor resizes: about half its cost.
  descriptor_ = cv::ORB::create(std::numeric_limits<int>::max() / 2, static_cast<float>(options.scale_factor), 1,
                                options.edge_threshold, 0, 2, cv::ORB::HARRIS_SCORE, kPatchSize, options.min_th_fast);
}

std::vector<cv::Mat> OrbExtractor::build_pyramid(const cv::Mat& grey) const {
  std::vector<cv::Mat> levels(options_.n_levels);
  levels[0] = grey;
  for (int l = 1; l < options_.n_levels; ++l) {
    const cv::Size sz(static_cast<int>(std::lround(grey.cols * pyramid_.inv_scale[l])),
                      static_cast<int>(std::lround(grey.rows * pyramid_.inv_scale[l])));
    cv::resize(levels[l - 1], levels[l], sz, 0, 0, cv::INTER_LINEAR);
  }
  return levels;
}

float intensity_centroid_angle(const cv::Mat& image, cv::Point2f pt, const std::vector<int>& half_width) {
  const int r = static_cast<int>(half_width.size()) - 1;
  const int cx = static_cast<int>(std::lround(pt.x)), cy = static_cast<int>(std::lround(pt.y));
  long m01 = 0, m10 = 0;
  const uchar* centre = image.ptr<uchar>(cy) + cx;
  for (int u = -r; u <= r; ++u) m10 += u * centre[u];
  const int step = static_cast<int>(image.step1());
  for (int v = 1; v <= r; ++v) {
    long v_sum = 0;
    const int d = half_width[v];
    for (int u = -d; u <= d; ++u) {
      const int below = centre[u + v * step], above = centre[u - v * step];
      v_sum += below - above;
      m10 += u * (below + above);
    }
    m01 += v * v_sum;
  }
  float a = cv::fastAtan2(static_cast<float>(m01), static_cast<float>(m10));
  return a >= 360.f ? a - 360.f : a;
}

std::vector<cv::KeyPoint> OrbExtractor::detect_level(const cv::Mat& img, int level) const {
  const int border = options_.edge_threshold;
  const cv::Rect region(border, border, img.cols - 2 * border, img.rows - 2 * border);
  if (region.width <= kPatchSize || region.height <= kPatchSize) return {};
  // FAST needs 3 pixels around a candidate: detect on a slightly larger window, keep those inside.
  const cv::Rect window(region.x - 3, region.y - 3, region.width + 6, region.height + 6);
  std::vector<cv::KeyPoint> all;
  cv::FAST(img(window), all, options_.min_th_fast, true);

  // Per cell: the corners above iniThFAST when the cell has any, otherwise the weaker ones.
  const int cell = options_.cell_size;
  const int ncx = std::max(1, region.width / cell), ncy = std::max(1, region.height / cell);
  const float cw = static_cast<float>(region.width) / ncx, ch = static_cast<float>(region.height) / ncy;
  std::vector<char> cell_has_strong(static_cast<size_t>(ncx * ncy), 0);
  std::vector<int> cell_of(all.size(), -1);
  for (size_t i = 0; i < all.size(); ++i) {
    cv::KeyPoint& k = all[i];
    k.pt.x += window.x;
    k.pt.y += window.y;
    if (k.pt.x < region.x || k.pt.y < region.y || k.pt.x >= region.x + region.width ||
        k.pt.y >= region.y + region.height)
      continue;
    const int ix = std::min(ncx - 1, static_cast<int>((k.pt.x - region.x) / cw));
    const int iy = std::min(ncy - 1, static_cast<int>((k.pt.y - region.y) / ch));
    cell_of[i] = iy * ncx + ix;
    if (k.response >= options_.ini_th_fast) cell_has_strong[static_cast<size_t>(cell_of[i])] = 1;
  }
  std::vector<cv::KeyPoint> kept;
  kept.reserve(all.size());
  for (size_t i = 0; i < all.size(); ++i) {
    if (cell_of[i] < 0) continue;
    if (cell_has_strong[static_cast<size_t>(cell_of[i])] && all[i].response < options_.ini_th_fast) continue;
    kept.push_back(all[i]);
  }
  std::vector<cv::KeyPoint> spread =
      distribute_quadtree(kept, cv::Rect2f(region), features_per_level_[static_cast<size_t>(level)]);
  const float size = static_cast<float>(kPatchSize * pyramid_.scale[static_cast<size_t>(level)]);
  for (cv::KeyPoint& k : spread) {
    k.angle = intensity_centroid_angle(img, k.pt, circle_half_width_);
    k.octave = level;
    k.size = size;
  }
  return spread;
}

OrbFeatures OrbExtractor::extract(const cv::Mat& grey) const {
  CV_Assert(grey.type() == CV_8UC1);
  const std::vector<cv::Mat> levels = build_pyramid(grey);
  OrbFeatures out;
  std::vector<cv::Mat> descriptors;
  for (int l = 0; l < options_.n_levels; ++l) {
    std::vector<cv::KeyPoint> kps = detect_level(levels[static_cast<size_t>(l)], l);
    if (kps.empty()) continue;
    // cv::ORB (one level) keeps the given angles; it may drop keypoints near the border, so the
    // survivors are re-identified by class_id. It reads octave 0 and the patch size at level scale.
    for (size_t i = 0; i < kps.size(); ++i) {
      kps[i].class_id = static_cast<int>(i);
      kps[i].octave = 0;
      kps[i].size = static_cast<float>(kPatchSize);
    }
    cv::Mat desc;
    descriptor_->compute(levels[static_cast<size_t>(l)], kps, desc);
    const float s = static_cast<float>(pyramid_.scale[static_cast<size_t>(l)]);
    for (cv::KeyPoint& k : kps) {
      // To level-0 pixels; cv::resize maps pixel centres, so x0 = (x_l + 0.5) s - 0.5.
      k.pt.x = (k.pt.x + 0.5f) * s - 0.5f;
      k.pt.y = (k.pt.y + 0.5f) * s - 0.5f;
      k.octave = l;
      k.size = kPatchSize * s;
      k.class_id = static_cast<int>(out.keypoints.size());
      out.keypoints.push_back(k);
    }
    descriptors.push_back(desc);
  }
  if (out.keypoints.empty()) {
    out.descriptors = cv::Mat(0, 32, CV_8U);
    return out;
  }
  cv::vconcat(descriptors, out.descriptors);
  return out;
}

}  // namespace wardmap::slam
