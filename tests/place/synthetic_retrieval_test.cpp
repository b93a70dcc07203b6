// Retrieval on simulator renders with the shipped vocabulary: a ward rendered with a seed the
// vocabulary was not trained on (its layout details and textures differ), a database of every 10th
// frame, queried with the frames 2 later; the keyframe closest in time must rank in the top 3
// wherever neither frame is inside a challenge segment (dark, bare wall, whip pan ...).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <opencv2/imgproc.hpp>

#include "sim/sequence.h"
#include "slam/front/orb_extractor.h"
#include "slam/place/keyframe_database.h"
#include "tests/support/test_support.h"

namespace wardmap::slam::place {
namespace {

TEST(PlaceRetrieval, SyntheticWardFindsTheKeyframeTwoFramesBefore) {
  const auto vocabulary_file = test::source_dir() / "data/vocabulary/orb-k10l4.bin";
  ASSERT_TRUE(std::filesystem::exists(vocabulary_file)) << vocabulary_file;
  const Vocabulary vocabulary = Vocabulary::load(vocabulary_file);
  sim::SequenceOptions so;
  so.seed = 3;  // the shipped vocabulary was trained on seed 7
  so.max_frames = 200;
  sim::Sequence seq(sim::load_scenario(test::source_dir() / "data/scenarios/ward.yaml"), so);
  const OrbExtractor extractor{OrbOptions{}};
  sim::Frame frame;
  cv::Mat grey;
  const auto bag = [&](int i) {
    seq.render(i, frame, false);
    cv::cvtColor(frame.buffers.rgb, grey, cv::COLOR_BGR2GRAY);
    return vocabulary.transform(extractor.extract(grey).descriptors);
  };

  KeyframeDatabase db;
  for (int i = 0; i < seq.frame_count(); i += 10) db.add(static_cast<std::uint64_t>(i), bag(i));
  int checked = 0, found = 0, skipped = 0;
  for (int q = 12; q < seq.frame_count(); q += 10) {
    const int expected = q - 2;
    if (seq.challenge_at(q) || seq.challenge_at(expected)) {
      ++skipped;
      continue;
    }
    const auto c = db.query(bag(q), 3);
    ++checked;
    const bool ok = std::any_of(c.begin(), c.end(),
                                [&](const PlaceCandidate& x) { return x.id == static_cast<std::uint64_t>(expected); });
    found += ok;
    EXPECT_TRUE(ok) << "query frame " << q << ": keyframe " << expected << " not in the top 3 (best "
                    << (c.empty() ? -1 : static_cast<long long>(c[0].id)) << ")";
  }
  std::printf(
      "[ ward seed 3 ] keyframe 2 frames before in the top 3: %d/%d queries (%d in challenge segments skipped)\n",
      found, checked, skipped);
  EXPECT_GE(checked, 10);
}

}  // namespace
}  // namespace wardmap::slam::place
