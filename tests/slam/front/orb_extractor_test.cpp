#include "slam/front/orb_extractor.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "slam/front/quadtree_distribution.h"
#include "tests/slam/front/test_images.h"

namespace wardmap::slam {

TEST(QuadtreeDistribution, KeepsTheStrongestPerLeafAndSpreads) {
  cv::RNG rng(3);
  std::vector<cv::KeyPoint> kps;
  // A dense cluster in one corner plus a sparse spread elsewhere.
  for (int i = 0; i < 2000; ++i)
    kps.emplace_back(cv::Point2f(rng.uniform(0.f, 50.f), rng.uniform(0.f, 50.f)), 7.f, -1.f, rng.uniform(0.f, 100.f));
  for (int i = 0; i < 300; ++i)
    kps.emplace_back(cv::Point2f(rng.uniform(0.f, 400.f), rng.uniform(0.f, 300.f)), 7.f, -1.f, rng.uniform(0.f, 100.f));
  const auto out = distribute_quadtree(kps, cv::Rect2f(0, 0, 400, 300), 200);
  EXPECT_GE(out.size(), 200u);
  EXPECT_LE(out.size(), 203u);
  int in_cluster = 0;
  for (const auto& k : out) in_cluster += (k.pt.x < 50 && k.pt.y < 50) ? 1 : 0;
  EXPECT_LT(in_cluster, 100) << "the dense cluster must not take most of the budget";
}

TEST(OrbExtractor, FillsTheImageWithAboutNFeatures) {
  OrbOptions o;
  OrbExtractor ex(o);
  const cv::Mat img = test::textured_image();
  const OrbFeatures f = ex.extract(img);
  EXPECT_GE(f.keypoints.size(), 850u);
  EXPECT_LE(f.keypoints.size(), 1100u);
  ASSERT_EQ(f.descriptors.rows, static_cast<int>(f.keypoints.size()));
  EXPECT_EQ(f.descriptors.cols, 32);
  // Every cell of a 4x4 partition of the image holds keypoints; several levels are used.
  int cells[4][4] = {};
  std::vector<int> per_level(o.n_levels, 0);
  for (const auto& k : f.keypoints) {
    ++cells[std::min(3, static_cast<int>(k.pt.y / 120))][std::min(3, static_cast<int>(k.pt.x / 160))];
    ASSERT_GE(k.octave, 0);
    ASSERT_LT(k.octave, o.n_levels);
    ++per_level[static_cast<size_t>(k.octave)];
    EXPECT_GE(k.angle, 0.f);
    EXPECT_LT(k.angle, 360.f);
    EXPECT_GE(k.pt.x, o.edge_threshold - 1);
    EXPECT_LT(k.pt.x, 640 - o.edge_threshold + 1);
  }
  for (auto& row : cells)
    for (int c : row) EXPECT_GE(c, 20);
  EXPECT_GT(per_level[0], per_level[4]);
  EXPECT_GT(per_level[4], 0);
}

// A keypoint found at a pixel of a pyramid level must be reported at the level-0 position that pixel
// was sampled from. Resizing an image whose value is its own x (or y) coordinate gives, at each level
// pixel, exactly that position (bilinear interpolation of a linear ramp), whatever the rounding of
// the level sizes.
TEST(OrbExtractor, LevelPixelsMapToTheImagePositionsTheyWereSampledFrom) {
  for (const cv::Size size : {cv::Size(640, 480), cv::Size(1242, 375)}) {
    cv::Mat xs(size, CV_32F), ys(size, CV_32F);
    for (int v = 0; v < size.height; ++v)
      for (int u = 0; u < size.width; ++u) {
        xs.at<float>(v, u) = static_cast<float>(u);
        ys.at<float>(v, u) = static_cast<float>(v);
      }
    const OrbExtractor extractor{OrbOptions{}};
    const std::vector<cv::Mat> px = extractor.build_pyramid(xs), py = extractor.build_pyramid(ys);
    ASSERT_EQ(px.size(), 8u);
    double worst = 0;
    for (size_t l = 1; l < px.size(); ++l) {
      // Away from the border, where cv::resize clamps its samples.
      for (int v = 2; v < px[l].rows - 2; ++v)
        for (int u = 2; u < px[l].cols - 2; ++u) {
          const cv::Point2f p = level_to_image(cv::Point2f(static_cast<float>(u), static_cast<float>(v)),
                                               px[l].size(), size);
          worst = std::max({worst, static_cast<double>(std::abs(p.x - px[l].at<float>(v, u))),
                            static_cast<double>(std::abs(p.y - py[l].at<float>(v, u)))});
        }
    }
    EXPECT_LT(worst, 0.01) << size << ": largest gap between a level pixel's mapped and sampled position (px)";
  }
}

TEST(OrbExtractor, IntensityCentroidPointsTowardsTheBrightSide) {
  cv::Mat img(64, 64, CV_8UC1);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) img.at<uchar>(y, x) = static_cast<uchar>(2 * x);  // brighter to the right
  std::vector<int> half_width;
  for (int v = 0; v <= 15; ++v) half_width.push_back(static_cast<int>(std::floor(std::sqrt(225.0 - v * v) + 0.5)));
  const float right = intensity_centroid_angle(img, cv::Point2f(32, 32), half_width);
  EXPECT_TRUE(right < 1.0f || right > 359.0f) << right;
  cv::Mat down;
  cv::rotate(img, down, cv::ROTATE_90_CLOCKWISE);  // brighter towards +y
  EXPECT_NEAR(intensity_centroid_angle(down, cv::Point2f(32, 32), half_width), 90.0f, 1.0f);
}

TEST(OrbExtractor, DescriptorsAreStableUnderSmallRotation) {
  OrbExtractor ex(OrbOptions{});
  const cv::Mat img = test::textured_image();
  cv::Mat rotated;
  const cv::Mat R = cv::getRotationMatrix2D(cv::Point2f(320, 240), 20.0, 1.0);
  cv::warpAffine(img, rotated, R, img.size(), cv::INTER_LINEAR, cv::BORDER_REFLECT);
  const OrbFeatures a = ex.extract(img), b = ex.extract(rotated);
  // Keypoints found at the rotated position have an angle about 20 degrees smaller (image y down).
  int compared = 0, consistent = 0;
  for (const auto& ka : a.keypoints) {
    const cv::Point2f pb(
        static_cast<float>(R.at<double>(0, 0) * ka.pt.x + R.at<double>(0, 1) * ka.pt.y + R.at<double>(0, 2)),
        static_cast<float>(R.at<double>(1, 0) * ka.pt.x + R.at<double>(1, 1) * ka.pt.y + R.at<double>(1, 2)));
    for (const auto& kb : b.keypoints) {
      if (kb.octave != ka.octave || cv::norm(kb.pt - pb) > 1.5) continue;
      ++compared;
      float d = std::fmod(ka.angle - kb.angle + 720.f, 360.f);
      if (std::abs(d - 20.f) < 15.f) ++consistent;
      break;
    }
  }
  ASSERT_GT(compared, 100);
  EXPECT_GT(consistent, 0.7 * compared);
}

}  // namespace wardmap::slam
