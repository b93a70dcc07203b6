// The ORB extractor against a reference: the straightforward extractor it replaced (wardmap a788096),
// kept here verbatim in substance. FAST at minThFAST over each whole level with the per-cell
// iniThFAST filter, a quadtree whose nodes hold vectors of members, the scalar intensity centroid,
// and cv::ORB::compute (on each level, with the keypoints' angles) for the descriptors. The
// extractor must give the same keypoints (every field), in the same order, with the same
// descriptors, whatever the image.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <opencv2/features2d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "slam/front/orb_extractor.h"
#include "slam/front/quadtree_distribution.h"
#include "tests/slam/front/test_images.h"
#include "tests/support/test_support.h"

namespace wardmap::slam {
namespace {

constexpr int kPatchSize = 31;

// ---- the reference (the former implementation) ----

struct RefNode {
  cv::Rect2f box;
  std::vector<int> members;
  bool leaf() const { return members.size() <= 1 || box.width < 2.0f || box.height < 2.0f; }
};

void ref_split(const RefNode& n, const std::vector<cv::KeyPoint>& kps, std::vector<RefNode>& out) {
  const float hw = n.box.width / 2, hh = n.box.height / 2;
  RefNode c[4];
  for (int i = 0; i < 4; ++i) c[i].box = cv::Rect2f(n.box.x + (i % 2) * hw, n.box.y + (i / 2) * hh, hw, hh);
  for (int m : n.members) {
    const cv::Point2f& p = kps[static_cast<size_t>(m)].pt;
    const int ix = p.x >= n.box.x + hw ? 1 : 0;
    const int iy = p.y >= n.box.y + hh ? 1 : 0;
    c[iy * 2 + ix].members.push_back(m);
  }
  for (auto& ch : c)
    if (!ch.members.empty()) out.push_back(std::move(ch));
}

std::vector<cv::KeyPoint> ref_quadtree(const std::vector<cv::KeyPoint>& kps, const cv::Rect2f& region, int target) {
  if (kps.empty() || target <= 0) return {};
  const int n_init = std::max(1, static_cast<int>(std::lround(region.width / std::max(region.height, 1.0f))));
  const float w = region.width / n_init;
  std::vector<RefNode> nodes(static_cast<size_t>(n_init));
  for (int i = 0; i < n_init; ++i) nodes[static_cast<size_t>(i)].box = cv::Rect2f(region.x + i * w, region.y, w, region.height);
  for (int k = 0; k < static_cast<int>(kps.size()); ++k) {
    const int i = std::clamp(static_cast<int>((kps[static_cast<size_t>(k)].pt.x - region.x) / w), 0, n_init - 1);
    nodes[static_cast<size_t>(i)].members.push_back(k);
  }
  nodes.erase(std::remove_if(nodes.begin(), nodes.end(), [](const RefNode& n) { return n.members.empty(); }),
              nodes.end());
  while (static_cast<int>(nodes.size()) < target) {
    std::stable_sort(nodes.begin(), nodes.end(),
                     [](const RefNode& a, const RefNode& b) { return a.members.size() > b.members.size(); });
    std::vector<RefNode> next;
    bool any_split = false;
    size_t i = 0;
    for (; i < nodes.size(); ++i) {
      const int remaining_count = static_cast<int>(next.size() + (nodes.size() - i));
      if (remaining_count >= target) break;
      if (nodes[i].leaf()) {
        next.push_back(std::move(nodes[i]));
        continue;
      }
      ref_split(nodes[i], kps, next);
      any_split = true;
    }
    for (; i < nodes.size(); ++i) next.push_back(std::move(nodes[i]));
    nodes.swap(next);
    if (!any_split) break;
  }
  std::vector<cv::KeyPoint> out;
  for (const RefNode& n : nodes) {
    int best = n.members.front();
    for (int m : n.members)
      if (kps[static_cast<size_t>(m)].response > kps[static_cast<size_t>(best)].response) best = m;
    out.push_back(kps[static_cast<size_t>(best)]);
  }
  return out;
}

OrbFeatures reference_extract(const OrbOptions& o, const cv::Mat& grey) {
  const ScalePyramid pyramid(o.scale_factor, o.n_levels);
  std::vector<int> per_level_target;
  {
    const double inv = 1.0 / o.scale_factor;
    double per_level = o.n_features * (1 - inv) / (1 - std::pow(inv, o.n_levels));
    int sum = 0;
    for (int l = 0; l < o.n_levels - 1; ++l) {
      per_level_target.push_back(static_cast<int>(std::lround(per_level)));
      sum += per_level_target.back();
      per_level *= inv;
    }
    per_level_target.push_back(std::max(o.n_features - sum, 0));
  }
  std::vector<int> half_width;
  for (int dv = 0; dv <= 15; ++dv) half_width.push_back(static_cast<int>(std::floor(std::sqrt(225 - dv * dv) + 0.5)));
  cv::Ptr<cv::ORB> orb = cv::ORB::create(std::numeric_limits<int>::max() / 2, static_cast<float>(o.scale_factor), 1,
                                         o.edge_threshold, 0, 2, cv::ORB::HARRIS_SCORE, kPatchSize, o.min_th_fast);
  std::vector<cv::Mat> levels(static_cast<size_t>(o.n_levels));
  levels[0] = grey;
  for (int l = 1; l < o.n_levels; ++l) {
    const cv::Size sz(static_cast<int>(std::lround(grey.cols * pyramid.inv_scale[static_cast<size_t>(l)])),
                      static_cast<int>(std::lround(grey.rows * pyramid.inv_scale[static_cast<size_t>(l)])));
    cv::resize(levels[static_cast<size_t>(l) - 1], levels[static_cast<size_t>(l)], sz, 0, 0, cv::INTER_LINEAR);
  }
  OrbFeatures out;
  std::vector<cv::Mat> descriptors;
  for (int l = 0; l < o.n_levels; ++l) {
    const cv::Mat& img = levels[static_cast<size_t>(l)];
    const int border = o.edge_threshold;
    const cv::Rect region(border, border, img.cols - 2 * border, img.rows - 2 * border);
    if (region.width <= kPatchSize || region.height <= kPatchSize) continue;
    const cv::Rect window(region.x - 3, region.y - 3, region.width + 6, region.height + 6);
    std::vector<cv::KeyPoint> all;
    cv::FAST(img(window), all, o.min_th_fast, true);
    const int ncx = std::max(1, region.width / o.cell_size), ncy = std::max(1, region.height / o.cell_size);
    const float cw = static_cast<float>(region.width) / ncx, ch = static_cast<float>(region.height) / ncy;
    std::vector<char> strong(static_cast<size_t>(ncx * ncy), 0);
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
      if (k.response >= o.ini_th_fast) strong[static_cast<size_t>(cell_of[i])] = 1;
    }
    std::vector<cv::KeyPoint> kept;
    for (size_t i = 0; i < all.size(); ++i) {
      if (cell_of[i] < 0) continue;
      if (strong[static_cast<size_t>(cell_of[i])] && all[i].response < o.ini_th_fast) continue;
      kept.push_back(all[i]);
    }
    std::vector<cv::KeyPoint> kps = ref_quadtree(kept, cv::Rect2f(region), per_level_target[static_cast<size_t>(l)]);
    if (kps.empty()) continue;
    for (size_t i = 0; i < kps.size(); ++i) {
      kps[i].angle = intensity_centroid_angle(img, kps[i].pt, half_width);
      kps[i].class_id = static_cast<int>(i);
      kps[i].octave = 0;
      kps[i].size = static_cast<float>(kPatchSize);
    }
    cv::Mat desc;
    orb->compute(img, kps, desc);
    const float s = static_cast<float>(pyramid.scale[static_cast<size_t>(l)]);
    // Level-0 pixels through the ratio of the sizes cv::resize was given (wardmap 2026-11: the
    // former extractor used scale_factor^l here, up to 1.4 px off at level 7).
    const float rx = static_cast<float>(grey.cols) / static_cast<float>(img.cols);
    const float ry = static_cast<float>(grey.rows) / static_cast<float>(img.rows);
    for (cv::KeyPoint& k : kps) {
      k.pt.x = (k.pt.x + 0.5f) * rx - 0.5f;
      k.pt.y = (k.pt.y + 0.5f) * ry - 0.5f;
      k.octave = l;
      k.size = kPatchSize * s;
      k.class_id = static_cast<int>(out.keypoints.size());
      out.keypoints.push_back(k);
    }
    descriptors.push_back(desc);
  }
  if (out.keypoints.empty())
    out.descriptors = cv::Mat(0, 32, CV_8U);
  else
    cv::vconcat(descriptors, out.descriptors);
  return out;
}

// ---- comparisons ----

void expect_identical(const OrbFeatures& want, const OrbFeatures& got, const std::string& what) {
  ASSERT_EQ(want.keypoints.size(), got.keypoints.size()) << what;
  ASSERT_EQ(want.descriptors.rows, got.descriptors.rows) << what;
  ASSERT_EQ(got.descriptors.cols, 32) << what;
  ASSERT_EQ(got.descriptors.type(), CV_8U) << what;
  int differing_keypoints = 0, differing_descriptors = 0;
  for (size_t i = 0; i < want.keypoints.size(); ++i) {
    const cv::KeyPoint &a = want.keypoints[i], &b = got.keypoints[i];
    // Exact float equality on purpose: the output must be the same bit for bit.
    const bool same = a.pt.x == b.pt.x && a.pt.y == b.pt.y && a.size == b.size && a.angle == b.angle &&
                      a.response == b.response && a.octave == b.octave && a.class_id == b.class_id;
    if (!same && differing_keypoints++ < 3)
      ADD_FAILURE() << what << ": keypoint " << i << " (" << a.pt << " oct " << a.octave << " angle " << a.angle
                    << ") vs (" << b.pt << " oct " << b.octave << " angle " << b.angle << ")";
    if (cv::norm(want.descriptors.row(static_cast<int>(i)), got.descriptors.row(static_cast<int>(i)), cv::NORM_HAMMING) !=
            0 &&
        differing_descriptors++ < 3)
      ADD_FAILURE() << what << ": descriptor " << i << " differs";
  }
  EXPECT_EQ(differing_keypoints, 0) << what;
  EXPECT_EQ(differing_descriptors, 0) << what;
}

// A textured image with flat, low-contrast areas: many FAST cells have no corner above iniThFAST,
// so both the per-run weak detection and the whole-level one are exercised.
cv::Mat patchy_image(int width, int height, unsigned seed, double textured_fraction) {
  cv::Mat img = test::textured_image(width, height, seed);
  cv::RNG rng(seed + 1);
  cv::Mat flat(height, width, CV_8UC1);
  rng.fill(flat, cv::RNG::UNIFORM, 118, 132);
  cv::GaussianBlur(flat, flat, cv::Size(3, 3), 0.8);
  // Blocks of texture on the low-contrast background.
  cv::Mat out = flat.clone();
  const int bw = std::max(8, width / 12), bh = std::max(8, height / 8);
  for (int y = 0; y < height; y += bh)
    for (int x = 0; x < width; x += bw)
      if (rng.uniform(0.0, 1.0) < textured_fraction) {
        const cv::Rect r = cv::Rect(x, y, bw, bh) & cv::Rect(0, 0, width, height);
        img(r).copyTo(out(r));
      }
  return out;
}

TEST(OrbReference, SameKeypointsAndDescriptorsAsTheFormerExtractor) {
  struct Case {
    std::string name;
    cv::Mat image;
    int n_features;
  };
  std::vector<Case> cases = {
      {"textured 640x480", test::textured_image(), 1000},
      {"textured 640x480, 2000 features", test::textured_image(640, 480, 11), 2000},
      {"textured 1242x375", test::textured_image(1242, 375, 5), 2000},
      {"patchy 640x480 (half textured)", patchy_image(640, 480, 3, 0.5), 1000},
      {"patchy 640x480 (mostly flat)", patchy_image(640, 480, 4, 0.15), 1000},
      {"patchy 1242x375 (mostly textured)", patchy_image(1242, 375, 8, 0.8), 2000},
      {"flat 320x240", patchy_image(320, 240, 9, 0.0), 500},
      {"small 100x80", test::textured_image(100, 80, 2), 200},
  };
  // Real frames when the shared data is there (KITTI 03, 7-Scenes, photos).
  const auto data = test::shared_data_dir();
  if (!data.empty()) {
    const std::vector<std::pair<std::string, int>> files = {
        {"kitti-odometry-03/sequences/03/image_0/000000.png", 2000},
        {"kitti-odometry-03/sequences/03/image_0/000200.png", 2000},
        {"7scenes-redkitchen/frame-000000.color.jpg", 1000},
        {"7scenes-redkitchen/frame-000300.color.jpg", 2000},
        {"images/nyu_119.png", 1000},
    };
    for (const auto& [file, n] : files) {
      const cv::Mat img = cv::imread((data / file).string(), cv::IMREAD_GRAYSCALE);
      if (!img.empty()) cases.push_back({file, img, n});
    }
  }
  for (const Case& c : cases) {
    OrbOptions o;
    o.n_features = c.n_features;
    const OrbExtractor extractor(o);
    expect_identical(reference_extract(o, c.image), extractor.extract(c.image), c.name);
  }
}

TEST(OrbReference, OtherOptionsToo) {
  const cv::Mat img = patchy_image(640, 480, 21, 0.6);
  OrbOptions a;
  a.n_features = 1500;
  a.scale_factor = 1.3;
  a.n_levels = 6;
  a.ini_th_fast = 25;
  a.min_th_fast = 5;
  a.cell_size = 40;
  OrbOptions b;
  b.cell_size = 17;
  b.edge_threshold = 25;
  b.n_levels = 10;
  OrbOptions c;  // iniThFAST below minThFAST: every corner is a strong one
  c.ini_th_fast = 9;
  c.min_th_fast = 12;
  for (const OrbOptions& o : {a, b, c}) expect_identical(reference_extract(o, img), OrbExtractor(o).extract(img), "options");
}

TEST(OrbReference, DescriptorsEqualCvOrbForAnyAngleAndPosition) {
  const cv::Mat img = test::textured_image(400, 300, 13);
  cv::RNG rng(17);
  std::vector<cv::KeyPoint> kps;
  for (int i = 0; i < 3000; ++i) {
    cv::KeyPoint k(cv::Point2f(static_cast<float>(rng.uniform(19, 400 - 19)), static_cast<float>(rng.uniform(19, 300 - 19))),
                   static_cast<float>(kPatchSize), rng.uniform(0.f, 360.f));
    if (i % 10 == 0) k.angle = static_cast<float>(rng.uniform(0, 8) * 45);  // axis-aligned and diagonal
    k.octave = 0;
    kps.push_back(k);
  }
  std::vector<cv::KeyPoint> for_orb = kps;
  cv::Mat want;
  cv::ORB::create(std::numeric_limits<int>::max() / 2, 1.2f, 1, 19, 0, 2, cv::ORB::HARRIS_SCORE, kPatchSize, 7)
      ->compute(img, for_orb, want);
  ASSERT_EQ(for_orb.size(), kps.size());
  cv::Mat blurred, got(static_cast<int>(kps.size()), 32, CV_8U);
  smooth_level(img, blurred);
  compute_orb_descriptors(blurred, kps, got);
  EXPECT_EQ(cv::norm(want, got, cv::NORM_HAMMING), 0.0);
}

TEST(OrbReference, QuadtreeMatchesTheFormerOne) {
  cv::RNG rng(5);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<cv::KeyPoint> kps;
    const int n = rng.uniform(1, 4000);
    const float w = static_cast<float>(rng.uniform(50, 1300)), h = static_cast<float>(rng.uniform(50, 500));
    for (int i = 0; i < n; ++i) {
      // Integer positions (as FAST gives), with clusters and repeated responses (ties).
      const bool cluster = i % 3 == 0;
      const float x = std::floor(cluster ? rng.uniform(0.f, w / 8) : rng.uniform(0.f, w));
      const float y = std::floor(cluster ? rng.uniform(0.f, h / 8) : rng.uniform(0.f, h));
      kps.emplace_back(cv::Point2f(x, y), 7.f, -1.f, static_cast<float>(rng.uniform(7, 60)));
    }
    const cv::Rect2f region(0, 0, w, h);
    for (int target : {1, 7, 100, 433, 5000}) {
      const auto want = ref_quadtree(kps, region, target);
      const auto got = distribute_quadtree(kps, region, target);
      ASSERT_EQ(want.size(), got.size()) << "trial " << trial << " target " << target;
      for (size_t i = 0; i < want.size(); ++i) {
        ASSERT_EQ(want[i].pt, got[i].pt) << "trial " << trial << " target " << target << " node " << i;
        ASSERT_EQ(want[i].response, got[i].response);
      }
    }
  }
}

// Fixed figures of the former extractor on the synthetic image (default options): a tripwire for
// changes in OpenCV or in the reference above as much as in the extractor.
TEST(OrbReference, FixedFiguresOnTheTexturedImage) {
  const OrbFeatures f = OrbExtractor(OrbOptions{}).extract(test::textured_image());
  uint64_t hash = 1469598103934665603ull;  // FNV-1a over keypoint positions, levels, angles and descriptors
  auto mix = [&](const void* p, size_t n) {
    const auto* b = static_cast<const unsigned char*>(p);
    for (size_t i = 0; i < n; ++i) hash = (hash ^ b[i]) * 1099511628211ull;
  };
  for (const cv::KeyPoint& k : f.keypoints) {
    mix(&k.pt, sizeof(k.pt));
    mix(&k.angle, sizeof(k.angle));
    mix(&k.octave, sizeof(k.octave));
  }
  mix(f.descriptors.data, f.descriptors.total());
  EXPECT_EQ(f.keypoints.size(), 1008u);
  EXPECT_EQ(hash, 1490758853094130240ull);  // since level positions use the level sizes (2026-11)
}

}  // namespace
}  // namespace wardmap::slam
