// The sequences feed a feature tracker: plenty of ORB corners outside the challenge segments, almost
// none where the camera faces a bare wall, and the segments really starve it.
#include <gtest/gtest.h>

#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

#include "sim/sequence.h"
#include "tests/sim/sim_test_util.h"

namespace wardmap::sim {
namespace {

struct OrbStats {
  int outside = 0, outside_rich = 0, textureless = 0, textureless_max = 0, inside = 0, inside_poor = 0;
};

OrbStats orb_over(const std::string& name, Variant variant, uint32_t seed) {
  SequenceOptions o;
  o.variant = variant;
  o.seed = seed;
  Sequence seq(testing::builtin(name), o);
  auto orb = cv::ORB::create(1000);
  OrbStats s;
  Frame f;
  cv::Mat grey;
  for (int i = 0; i < seq.frame_count(); ++i) {
    seq.render(i, f, false);
    cv::cvtColor(f.buffers.rgb, grey, cv::COLOR_BGR2GRAY);
    std::vector<cv::KeyPoint> kp;
    orb->detect(grey, kp);
    const int n = static_cast<int>(kp.size());
    const ChallengeSegment* c = seq.challenge_at(i);
    if (!c) {
      ++s.outside;
      s.outside_rich += n >= 300;
    } else {
      ++s.inside;
      s.inside_poor += n < 100;
      if (c->kind == ChallengeKind::kTextureless) {
        ++s.textureless;
        s.textureless_max = std::max(s.textureless_max, n);
      }
    }
  }
  std::printf(
      "[ %s seed %u ] outside challenges: %d/%d frames with >= 300 ORB keypoints; textureless: %d frames, "
      "max %d keypoints; inside challenges: %d/%d frames with < 100\n",
      name.c_str(), seed, s.outside_rich, s.outside, s.textureless, s.textureless_max, s.inside_poor, s.inside);
  return s;
}

TEST(Orb, CorridorLossQuick) {
  const OrbStats s = orb_over("corridor_loss", Variant::kQuick, 1);
  ASSERT_GT(s.outside, 50);
  EXPECT_GE(s.outside_rich, 0.95 * s.outside);
  ASSERT_GT(s.textureless, 10);
  EXPECT_LT(s.textureless_max, 50);
  EXPECT_GE(s.inside_poor, 0.6 * s.inside);  // dark, bare wall, whip pan and shake starve the tracker
}

TEST(Orb, WardQuickOtherSeed) {
  const OrbStats s = orb_over("ward", Variant::kQuick, 11);
  EXPECT_GE(s.outside_rich, 0.95 * s.outside);
}

}  // namespace
}  // namespace wardmap::sim
