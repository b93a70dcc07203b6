#include "slam/front/orb_extractor.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "slam/front/counting_sort.h"
#include "slam/front/descriptor_distance.h"
#include "slam/front/quadtree_distribution.h"

namespace wardmap::slam {

namespace {
constexpr int kPatchSize = 31;  // rBRIEF patch (pixels)
constexpr int kHalfPatch = 15;  // orientation disc radius

// The published ORB test pattern (Rublee et al. 2011): 256 pairs of points (x0, y0, x1, y1) in a 31x31
// patch; bit i of a descriptor is I(p0) < I(p1). The values are the bit_pattern_31_ table of OpenCV's
// orb.cpp (Apache-2.0; ORB-SLAM ships the same table): descriptors must stay bit-compatible with
// cv::ORB's, which data/vocabulary was trained on.
constexpr int kBitPattern31[256 * 4] = {
    8, -3, 9, 5, 4, 2, 7, -12, -11, 9, -8, 2, 7, -12, 12, -13,
    2, -13, 2, 12, 1, -7, 1, 6, -2, -10, -2, -4, -13, -13, -11, -8,
    -13, -3, -12, -9, 10, 4, 11, 9, -13, -8, -8, -9, -11, 7, -9, 12,
    7, 7, 12, 6, -4, -5, -3, 0, -13, 2, -12, -3, -9, 0, -7, 5,
    12, -6, 12, -1, -3, 6, -2, 12, -6, -13, -4, -8, 11, -13, 12, -8,
    4, 7, 5, 1, 5, -3, 10, -3, 3, -7, 6, 12, -8, -7, -6, -2,
    -2, 11, -1, -10, -13, 12, -8, 10, -7, 3, -5, -3, -4, 2, -3, 7,
    -10, -12, -6, 11, 5, -12, 6, -7, 5, -6, 7, -1, 1, 0, 4, -5,
    9, 11, 11, -13, 4, 7, 4, 12, 2, -1, 4, 4, -4, -12, -2, 7,
    -8, -5, -7, -10, 4, 11, 9, 12, 0, -8, 1, -13, -13, -2, -8, 2,
    -3, -2, -2, 3, -6, 9, -4, -9, 8, 12, 10, 7, 0, 9, 1, 3,
    7, -5, 11, -10, -13, -6, -11, 0, 10, 7, 12, 1, -6, -3, -6, 12,
    10, -9, 12, -4, -13, 8, -8, -12, -13, 0, -8, -4, 3, 3, 7, 8,
    5, 7, 10, -7, -1, 7, 1, -12, 3, -10, 5, 6, 2, -4, 3, -10,
    -13, 0, -13, 5, -13, -7, -12, 12, -13, 3, -11, 8, -7, 12, -4, 7,
    6, -10, 12, 8, -9, -1, -7, -6, -2, -5, 0, 12, -12, 5, -7, 5,
    3, -10, 8, -13, -7, -7, -4, 5, -3, -2, -1, -7, 2, 9, 5, -11,
    -11, -13, -5, -13, -1, 6, 0, -1, 5, -3, 5, 2, -4, -13, -4, 12,
    -9, -6, -9, 6, -12, -10, -8, -4, 10, 2, 12, -3, 7, 12, 12, 12,
    -7, -13, -6, 5, -4, 9, -3, 4, 7, -1, 12, 2, -7, 6, -5, 1,
    -13, 11, -12, 5, -3, 7, -2, -6, 7, -8, 12, -7, -13, -7, -11, -12,
    1, -3, 12, 12, 2, -6, 3, 0, -4, 3, -2, -13, -1, -13, 1, 9,
    7, 1, 8, -6, 1, -1, 3, 12, 9, 1, 12, 6, -1, -9, -1, 3,
    -13, -13, -10, 5, 7, 7, 10, 12, 12, -5, 12, 9, 6, 3, 7, 11,
    5, -13, 6, 10, 2, -12, 2, 3, 3, 8, 4, -6, 2, 6, 12, -13,
    9, -12, 10, 3, -8, 4, -7, 9, -11, 12, -4, -6, 1, 12, 2, -8,
    6, -9, 7, -4, 2, 3, 3, -2, 6, 3, 11, 0, 3, -3, 8, -8,
    7, 8, 9, 3, -11, -5, -6, -4, -10, 11, -5, 10, -5, -8, -3, 12,
    -10, 5, -9, 0, 8, -1, 12, -6, 4, -6, 6, -11, -10, 12, -8, 7,
    4, -2, 6, 7, -2, 0, -2, 12, -5, -8, -5, 2, 7, -6, 10, 12,
    -9, -13, -8, -8, -5, -13, -5, -2, 8, -8, 9, -13, -9, -11, -9, 0,
    1, -8, 1, -2, 7, -4, 9, 1, -2, 1, -1, -4, 11, -6, 12, -11,
    -12, -9, -6, 4, 3, 7, 7, 12, 5, 5, 10, 8, 0, -4, 2, 8,
    -9, 12, -5, -13, 0, 7, 2, 12, -1, 2, 1, 7, 5, 11, 7, -9,
    3, 5, 6, -8, -13, -4, -8, 9, -5, 9, -3, -3, -4, -7, -3, -12,
    6, 5, 8, 0, -7, 6, -6, 12, -13, 6, -5, -2, 1, -10, 3, 10,
    4, 1, 8, -4, -2, -2, 2, -13, 2, -12, 12, 12, -2, -13, 0, -6,
    4, 1, 9, 3, -6, -10, -3, -5, -3, -13, -1, 1, 7, 5, 12, -11,
    4, -2, 5, -7, -13, 9, -9, -5, 7, 1, 8, 6, 7, -8, 7, 6,
    -7, -4, -7, 1, -8, 11, -7, -8, -13, 6, -12, -8, 2, 4, 3, 9,
    10, -5, 12, 3, -6, -5, -6, 7, 8, -3, 9, -8, 2, -12, 2, 8,
    -11, -2, -10, 3, -12, -13, -7, -9, -11, 0, -10, -5, 5, -3, 11, 8,
    -2, -13, -1, 12, -1, -8, 0, 9, -13, -11, -12, -5, -10, -2, -10, 11,
    -3, 9, -2, -13, 2, -3, 3, 2, -9, -13, -4, 0, -4, 6, -3, -10,
    -4, 12, -2, -7, -6, -11, -4, 9, 6, -3, 6, 11, -13, 11, -5, 5,
    11, 11, 12, 6, 7, -5, 12, -2, -1, 12, 0, 7, -4, -8, -3, -2,
    -7, 1, -6, 7, -13, -12, -8, -13, -7, -2, -6, -8, -8, 5, -6, -9,
    -5, -1, -4, 5, -13, 7, -8, 10, 1, 5, 5, -13, 1, 0, 10, -13,
    9, 12, 10, -1, 5, -8, 10, -9, -1, 11, 1, -13, -9, -3, -6, 2,
    -1, -10, 1, 12, -13, 1, -8, -10, 8, -11, 10, -6, 2, -13, 3, -6,
    7, -13, 12, -9, -10, -10, -5, -7, -10, -8, -8, -13, 4, -6, 8, 5,
    3, 12, 8, -13, -4, 2, -3, -3, 5, -13, 10, -12, 4, -13, 5, -1,
    -9, 9, -4, 3, 0, 3, 3, -9, -12, 1, -6, 1, 3, 2, 4, -8,
    -10, -10, -10, 9, 8, -13, 12, 12, -8, -12, -6, -5, 2, 2, 3, 7,
    10, 6, 11, -8, 6, 8, 8, -12, -7, 10, -6, 5, -3, -9, -3, 9,
    -1, -13, -1, 5, -3, -7, -3, 4, -8, -2, -8, 3, 4, 2, 12, 12,
    2, -5, 3, 11, 6, -9, 11, -13, 3, -1, 7, 12, 11, -1, 12, 4,
    -3, 0, -3, 6, 4, -11, 4, 12, 2, -4, 2, 1, -10, -6, -8, 1,
    -13, 7, -11, 1, -13, 12, -11, -13, 6, 0, 11, -13, 0, -1, 1, 4,
    -13, 3, -9, -2, -9, 8, -6, -3, -13, -6, -8, -2, 5, -9, 8, 10,
    2, 7, 3, -9, -1, -6, -1, -1, 9, 5, 11, -2, 11, -3, 12, -8,
    3, 0, 3, 5, -1, 4, 0, 10, 3, -6, 4, 5, -13, 0, -10, 5,
    5, 8, 12, 11, 8, 9, 9, -6, 7, -4, 8, -12, -10, 4, -10, 9,
    7, 3, 12, 4, 9, -7, 10, -2, 7, 0, 12, -2, -1, -6, 0, -11,
};

struct RotationPattern {
  alignas(16) float x[512];
  alignas(16) float y[512];
  RotationPattern() {
    for (int i = 0; i < 512; ++i) {
      x[i] = static_cast<float>(kBitPattern31[2 * i]);
      y[i] = static_cast<float>(kBitPattern31[2 * i + 1]);
    }
  }
};
const RotationPattern& rotation_pattern() {
  static const RotationPattern p;
  return p;
}

// Pixel offset of each pattern point rotated by (cos, sin) = (a, b), rounded as cv::ORB does
// (cvRound of x = px a - py b, y = px b + py a in single precision), relative to the centre.
void rotated_offsets(float a, float b, int step, int* offsets) {
  const RotationPattern& p = rotation_pattern();
#if defined(__SSE2__)
  if (step > 32767) {  // the multiply-add below takes the row step as a 16-bit factor
    for (int i = 0; i < 512; ++i) {
      const float x = p.x[i] * a - p.y[i] * b, y = p.x[i] * b + p.y[i] * a;
      offsets[i] = cvRound(y) * step + cvRound(x);
    }
    return;
  }
  const __m128 va = _mm_set1_ps(a), vb = _mm_set1_ps(b);
  const __m128i low16 = _mm_set1_epi32(0xffff);
  const __m128i one_step = _mm_set1_epi32(static_cast<int>((static_cast<unsigned>(step) << 16) | 1u));
  for (int i = 0; i < 512; i += 4) {
    const __m128 px = _mm_load_ps(p.x + i), py = _mm_load_ps(p.y + i);
    const __m128 x = _mm_sub_ps(_mm_mul_ps(px, va), _mm_mul_ps(py, vb));
    const __m128 y = _mm_add_ps(_mm_mul_ps(px, vb), _mm_mul_ps(py, va));
    const __m128i ix = _mm_cvtps_epi32(x), iy = _mm_cvtps_epi32(y);  // round half to even, as cvRound
    // (ix, iy) as two int16 per lane, then ix * 1 + iy * step in one multiply-add.
    const __m128i packed = _mm_or_si128(_mm_and_si128(ix, low16), _mm_slli_epi32(iy, 16));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(offsets + i), _mm_madd_epi16(packed, one_step));
  }
#else
  for (int i = 0; i < 512; ++i) {
    const float x = p.x[i] * a - p.y[i] * b, y = p.x[i] * b + p.y[i] * a;
    offsets[i] = cvRound(y) * step + cvRound(x);
  }
#endif
}

// Intensity-centroid angle for the radius-15 disc, SSE2: rows of 32 pixels (u = -15..16) weighted by
// per-row tables that are zero outside the disc. Reads one pixel right of the disc (u = 16).
struct CentroidTables {
  alignas(16) short u_weight[kHalfPatch + 1][32];  // u inside the row's half-width, else 0
  alignas(16) short v_weight[kHalfPatch + 1][32];  // v inside the row's half-width, else 0
};
int disc_half_width(int v) {
  return static_cast<int>(std::floor(std::sqrt(kHalfPatch * kHalfPatch - v * v) + 0.5));
}

const CentroidTables& centroid_tables() {
  static const CentroidTables t = [] {
    CentroidTables c{};
    for (int v = 0; v <= kHalfPatch; ++v)
      for (int k = 0; k < 32; ++k) {
        const int u = k - kHalfPatch;
        const bool inside = std::abs(u) <= disc_half_width(v);
        c.u_weight[v][k] = static_cast<short>(inside ? u : 0);
        c.v_weight[v][k] = static_cast<short>(inside ? v : 0);
      }
    return c;
  }();
  return t;
}

// Merges two lists of corners, each in raster order (by row, then column) and at distinct pixels,
// into one in raster order: a counting sort by row (a's corners before b's in each row), then a
// merge of the two parts of each row.
std::vector<cv::KeyPoint> merge_raster(const std::vector<cv::KeyPoint>& a, const std::vector<cv::KeyPoint>& b, int y0,
                                       int rows) {
  const auto row = [y0](const cv::KeyPoint& k) { return static_cast<int>(k.pt.y) - y0; };
  std::vector<int> keys(a.size() + b.size());
  for (size_t i = 0; i < a.size(); ++i) keys[i] = row(a[i]);
  for (size_t i = 0; i < b.size(); ++i) keys[a.size() + i] = row(b[i]);
  std::vector<int> start, order;
  counting_sort(keys, rows, start, order);
  std::vector<cv::KeyPoint> out(order.size());
  for (size_t p = 0; p < order.size(); ++p) {
    const size_t i = static_cast<size_t>(order[p]);
    out[p] = i < a.size() ? a[i] : b[i - a.size()];
  }
  auto by_x = [](const cv::KeyPoint& p, const cv::KeyPoint& q) { return p.pt.x < q.pt.x; };
  const auto from_a = [&a](int i) { return static_cast<size_t>(i) < a.size(); };
  for (int r = 0; r < rows; ++r) {
    const int s0 = start[static_cast<size_t>(r)], s1 = start[static_cast<size_t>(r) + 1];
    // The sort is stable, so a row's corners from a come first: the merge's middle.
    const int sm = static_cast<int>(std::partition_point(order.begin() + s0, order.begin() + s1, from_a) - order.begin());
    if (sm != s0 && sm != s1) std::inplace_merge(out.begin() + s0, out.begin() + sm, out.begin() + s1, by_x);
  }
  return out;
}

float finish_angle(int m01, int m10) {
  const float a = cv::fastAtan2(static_cast<float>(m01), static_cast<float>(m10));
  return a >= 360.f ? a - 360.f : a;
}

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

  for (int dv = 0; dv <= kHalfPatch; ++dv) circle_half_width_.push_back(disc_half_width(dv));
  centroid_tables();
  rotation_pattern();
}

cv::Point2f level_to_image(cv::Point2f p, cv::Size level, cv::Size image) {
  const float rx = static_cast<float>(image.width) / static_cast<float>(level.width);
  const float ry = static_cast<float>(image.height) / static_cast<float>(level.height);
  return {(p.x + 0.5f) * rx - 0.5f, (p.y + 0.5f) * ry - 0.5f};
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
  return finish_angle(static_cast<int>(m01), static_cast<int>(m10));
}

float OrbExtractor::centroid_angle(const cv::Mat& image, cv::Point2f pt) const {
  const int cx = static_cast<int>(std::lround(pt.x)), cy = static_cast<int>(std::lround(pt.y));
#if defined(__SSE2__)
  if (cx - kHalfPatch >= 0 && cx + kHalfPatch + 1 < image.cols && cy - kHalfPatch >= 0 &&
      cy + kHalfPatch < image.rows) {
    const CentroidTables& t = centroid_tables();
    const int step = static_cast<int>(image.step1());
    const uchar* row0 = image.ptr<uchar>(cy) + cx - kHalfPatch;
    const __m128i zero = _mm_setzero_si128();
    auto weights = [](const short* w, int k) { return _mm_load_si128(reinterpret_cast<const __m128i*>(w + k)); };
    auto load = [](const uchar* p) { return _mm_loadu_si128(reinterpret_cast<const __m128i*>(p)); };
    // v = 0: the centre row once.
    __m128i m10 = zero, m01 = zero;
    {
      const __m128i a = load(row0), b = load(row0 + 16);
      m10 = _mm_add_epi32(m10, _mm_madd_epi16(_mm_unpacklo_epi8(a, zero), weights(t.u_weight[0], 0)));
      m10 = _mm_add_epi32(m10, _mm_madd_epi16(_mm_unpackhi_epi8(a, zero), weights(t.u_weight[0], 8)));
      m10 = _mm_add_epi32(m10, _mm_madd_epi16(_mm_unpacklo_epi8(b, zero), weights(t.u_weight[0], 16)));
      m10 = _mm_add_epi32(m10, _mm_madd_epi16(_mm_unpackhi_epi8(b, zero), weights(t.u_weight[0], 24)));
    }
    for (int v = 1; v <= kHalfPatch; ++v) {
      const uchar* below = row0 + v * step;
      const uchar* above = row0 - v * step;
      const __m128i b0 = load(below), b1 = load(below + 16), a0 = load(above), a1 = load(above + 16);
      const __m128i bl[4] = {_mm_unpacklo_epi8(b0, zero), _mm_unpackhi_epi8(b0, zero), _mm_unpacklo_epi8(b1, zero),
                             _mm_unpackhi_epi8(b1, zero)};
      const __m128i al[4] = {_mm_unpacklo_epi8(a0, zero), _mm_unpackhi_epi8(a0, zero), _mm_unpacklo_epi8(a1, zero),
                             _mm_unpackhi_epi8(a1, zero)};
      for (int q = 0; q < 4; ++q) {
        m10 = _mm_add_epi32(m10, _mm_madd_epi16(_mm_add_epi16(bl[q], al[q]), weights(t.u_weight[v], 8 * q)));
        m01 = _mm_add_epi32(m01, _mm_madd_epi16(_mm_sub_epi16(bl[q], al[q]), weights(t.v_weight[v], 8 * q)));
      }
    }
    alignas(16) int s10[4], s01[4];
    _mm_store_si128(reinterpret_cast<__m128i*>(s10), m10);
    _mm_store_si128(reinterpret_cast<__m128i*>(s01), m01);
    return finish_angle(s01[0] + s01[1] + s01[2] + s01[3], s10[0] + s10[1] + s10[2] + s10[3]);
  }
#endif
  return intensity_centroid_angle(image, pt, circle_half_width_);
}

void smooth_level(const cv::Mat& level, cv::Mat& blurred) {
  // cv::GaussianBlur(level, blurred, {7, 7}, 2, 2, BORDER_REFLECT_101) rounds differently (its 8-bit
  // fixed-point path) from what cv::ORB gets: cv::ORB blurs each level as a view into its bordered
  // pyramid, and for a view cv::GaussianBlur takes the separable filter with single-precision kernels.
  static const cv::Mat kernel = cv::getGaussianKernel(7, 2.0, CV_32F);
  cv::sepFilter2D(level, blurred, CV_8U, kernel, kernel, cv::Point(-1, -1), 0, cv::BORDER_REFLECT_101);
}

void compute_orb_descriptors(const cv::Mat& blurred, const std::vector<cv::KeyPoint>& keypoints,
                             cv::Mat& descriptors, int first_row) {
  CV_Assert(blurred.type() == CV_8UC1 && descriptors.type() == CV_8UC1 && descriptors.cols == kDescriptorBytes);
  const int step = static_cast<int>(blurred.step);
  alignas(16) int offsets[512];
  for (size_t k = 0; k < keypoints.size(); ++k) {
    const cv::KeyPoint& kp = keypoints[k];
    // As cv::ORB: the angle in radians in single precision, then its cosine and sine.
    const float angle = kp.angle * static_cast<float>(CV_PI / 180.f);
    rotated_offsets(std::cos(angle), std::sin(angle), step, offsets);
    const uchar* centre = blurred.ptr<uchar>(cvRound(kp.pt.y)) + cvRound(kp.pt.x);
    uchar* desc = descriptors.ptr<uchar>(first_row + static_cast<int>(k));
    const int* o = offsets;
    for (int i = 0; i < kDescriptorBytes; ++i, o += 16) {
      int val = 0;
      for (int bit = 0; bit < 8; ++bit) val |= (centre[o[2 * bit]] < centre[o[2 * bit + 1]]) << bit;
      desc[i] = static_cast<uchar>(val);
    }
  }
}

std::vector<cv::KeyPoint> OrbExtractor::detect_level(const cv::Mat& img, int level) const {
  const int border = options_.edge_threshold;
  const cv::Rect region(border, border, img.cols - 2 * border, img.rows - 2 * border);
  if (region.width <= kPatchSize || region.height <= kPatchSize) return {};
  // FAST needs 3 pixels around a candidate: detect on a slightly larger window, keep those inside.
  const cv::Rect window(region.x - 3, region.y - 3, region.width + 6, region.height + 6);

  // Per cell: the corners above iniThFAST when the cell has any, otherwise the weaker ones (above
  // minThFAST). A FAST corner's score does not depend on the detection threshold, and a corner
  // whose score is above iniThFAST is suppressed only by a neighbour with a higher score, so FAST at
  // iniThFAST finds exactly the strong corners that FAST at minThFAST with a score filter finds; the
  // weak pass then runs only over the cells without a strong corner (plus a one-pixel rim for the
  // non-maximum suppression), unless those cover most of the level.
  const int cell = options_.cell_size;
  const int ncx = std::max(1, region.width / cell), ncy = std::max(1, region.height / cell);
  const float cw = static_cast<float>(region.width) / ncx, ch = static_cast<float>(region.height) / ncy;
  auto cell_x = [&](float x) { return std::min(ncx - 1, static_cast<int>((x - region.x) / cw)); };
  auto cell_y = [&](float y) { return std::min(ncy - 1, static_cast<int>((y - region.y) / ch)); };
  auto inside = [&](const cv::KeyPoint& k) {
    return k.pt.x >= region.x && k.pt.y >= region.y && k.pt.x < region.x + region.width &&
           k.pt.y < region.y + region.height;
  };

  // (A strong threshold below minThFAST makes every minThFAST corner a strong one.)
  const int strong_threshold = std::max(options_.ini_th_fast, options_.min_th_fast);
  std::vector<cv::KeyPoint> kept;
  cv::FAST(img(window), kept, strong_threshold, true);
  std::vector<char> cell_has_strong(static_cast<size_t>(ncx * ncy), 0);
  size_t n_strong = 0;
  for (const cv::KeyPoint& k0 : kept) {
    cv::KeyPoint k = k0;
    k.pt.x += window.x;
    k.pt.y += window.y;
    if (!inside(k)) continue;
    cell_has_strong[static_cast<size_t>(cell_y(k.pt.y) * ncx + cell_x(k.pt.x))] = 1;
    kept[n_strong++] = k;
  }
  kept.resize(n_strong);
  const size_t n_empty = static_cast<size_t>(std::count(cell_has_strong.begin(), cell_has_strong.end(), 0));

  if (n_empty * 4 > cell_has_strong.size() * 3) {
    // Mostly weak cells: one FAST at minThFAST over the level costs about as much as one per run of
    // weak cells (each run's FAST also covers a rim of 4 pixels); it returns the corners in raster order.
    std::vector<cv::KeyPoint> all;
    cv::FAST(img(window), all, options_.min_th_fast, true);
    kept.clear();
    for (cv::KeyPoint& k : all) {
      k.pt.x += window.x;
      k.pt.y += window.y;
      if (!inside(k)) continue;
      if (k.response < options_.ini_th_fast &&
          cell_has_strong[static_cast<size_t>(cell_y(k.pt.y) * ncx + cell_x(k.pt.x))])
        continue;
      kept.push_back(k);
    }
  } else if (n_empty > 0) {
    // Pixel span of each cell column and row (the cell of a pixel is computed as for a keypoint).
    std::vector<int> col_first(static_cast<size_t>(ncx), -1), col_last(static_cast<size_t>(ncx), -1);
    std::vector<int> row_first(static_cast<size_t>(ncy), -1), row_last(static_cast<size_t>(ncy), -1);
    for (int x = region.x; x < region.x + region.width; ++x) {
      const size_t c = static_cast<size_t>(cell_x(static_cast<float>(x)));
      if (col_first[c] < 0) col_first[c] = x;
      col_last[c] = x;
    }
    for (int y = region.y; y < region.y + region.height; ++y) {
      const size_t c = static_cast<size_t>(cell_y(static_cast<float>(y)));
      if (row_first[c] < 0) row_first[c] = y;
      row_last[c] = y;
    }
    std::vector<cv::KeyPoint> weak, found;
    for (int iy = 0; iy < ncy; ++iy) {
      for (int ix = 0; ix < ncx; ++ix) {
        if (cell_has_strong[static_cast<size_t>(iy * ncx + ix)]) continue;
        int ix_end = ix;  // a run of cells without a strong corner, detected in one call
        while (ix_end + 1 < ncx && !cell_has_strong[static_cast<size_t>(iy * ncx + ix_end + 1)]) ++ix_end;
        const int x0 = col_first[static_cast<size_t>(ix)], x1 = col_last[static_cast<size_t>(ix_end)];
        const int y0 = row_first[static_cast<size_t>(iy)], y1 = row_last[static_cast<size_t>(iy)];
        ix = ix_end;
        if (x0 < 0 || y0 < 0) continue;
        // Candidates over the run plus a one-pixel rim (inside the region) so that non-maximum
        // suppression sees every neighbour that the whole-level detection would see.
        const int dx0 = std::max(x0 - 1, region.x), dx1 = std::min(x1 + 1, region.x + region.width - 1);
        const int dy0 = std::max(y0 - 1, region.y), dy1 = std::min(y1 + 1, region.y + region.height - 1);
        const cv::Rect sub(dx0 - 3, dy0 - 3, dx1 - dx0 + 7, dy1 - dy0 + 7);
        found.clear();
        cv::FAST(img(sub), found, options_.min_th_fast, true);
        for (cv::KeyPoint& k : found) {
          k.pt.x += sub.x;
          k.pt.y += sub.y;
          if (k.pt.x < x0 || k.pt.x > x1 || k.pt.y < y0 || k.pt.y > y1) continue;
          weak.push_back(k);
        }
      }
    }
    if (!weak.empty()) kept = merge_raster(kept, weak, region.y, region.height);
  }

  std::vector<cv::KeyPoint> spread =
      distribute_quadtree(kept, cv::Rect2f(region), features_per_level_[static_cast<size_t>(level)]);
  for (cv::KeyPoint& k : spread) {
    k.angle = centroid_angle(img, k.pt);
    k.octave = level;
  }
  return spread;
}

std::vector<cv::KeyPoint> OrbExtractor::extract_level(const cv::Mat& level_image, int level, cv::Mat& descriptors) const {
  std::vector<cv::KeyPoint> kps = detect_level(level_image, level);
  // rBRIEF samples up to 18 pixels from the keypoint: keep those edge_threshold inside the level
  // (as cv::ORB's border filter; the detection region already guarantees it).
  const float b = static_cast<float>(options_.edge_threshold);
  kps.erase(std::remove_if(kps.begin(), kps.end(),
                           [&](const cv::KeyPoint& k) {
                             return !(k.pt.x >= b && k.pt.y >= b && k.pt.x < level_image.cols - b &&
                                      k.pt.y < level_image.rows - b);
                           }),
            kps.end());
  descriptors.create(static_cast<int>(kps.size()), kDescriptorBytes, CV_8U);
  if (kps.empty()) return kps;
  cv::Mat blurred;
  smooth_level(level_image, blurred);
  compute_orb_descriptors(blurred, kps, descriptors);
  return kps;
}

OrbFeatures OrbExtractor::extract(const cv::Mat& grey) const {
  CV_Assert(grey.type() == CV_8UC1);
  const std::vector<cv::Mat> levels = build_pyramid(grey);
  const size_t L = levels.size();
  std::vector<std::vector<cv::KeyPoint>> per_level(L);
  std::vector<cv::Mat> level_descriptors(L);
  // Levels are independent, but run one after the other: the tracking thread gets one core (the
  // mapper has the other), and the output cannot depend on a thread count.
  for (size_t l = 0; l < L; ++l) per_level[l] = extract_level(levels[l], static_cast<int>(l), level_descriptors[l]);

  size_t total = 0;
  for (const auto& kps : per_level) total += kps.size();
  OrbFeatures out;
  out.keypoints.reserve(total);
  out.descriptors.create(static_cast<int>(total), kDescriptorBytes, CV_8U);
  for (size_t l = 0; l < L; ++l) {
    std::vector<cv::KeyPoint>& kps = per_level[l];
    if (kps.empty()) continue;
    level_descriptors[l].copyTo(out.descriptors.rowRange(static_cast<int>(out.keypoints.size()),
                                                         static_cast<int>(out.keypoints.size() + kps.size())));
    const float s = static_cast<float>(pyramid_.scale[l]);
    for (cv::KeyPoint& k : kps) {
      k.pt = level_to_image(k.pt, levels[l].size(), grey.size());
      k.size = kPatchSize * s;
      k.class_id = static_cast<int>(out.keypoints.size());
      out.keypoints.push_back(k);
    }
  }
  return out;
}

}  // namespace wardmap::slam
