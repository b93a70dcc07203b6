// Retrieval on real photos with the shipped vocabulary (trained on synthetic renders only): the shared
// 7-Scenes redkitchen recording, a database of every 10th of the first 300 frames, queried with the
// frames half-way between (5, 15, ..., 295); the best candidate should lie within 10 frames.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <opencv2/imgproc.hpp>

#include "slam/front/orb_extractor.h"
#include "slam/io/sequence.h"
#include "slam/place/keyframe_database.h"
#include "tests/support/test_support.h"

namespace wardmap::slam::place {
namespace {

cv::Mat orb_descriptors(const OrbExtractor& extractor, const cv::Mat& image) {
  cv::Mat grey = image;
  if (image.channels() == 3) cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
  return extractor.extract(grey).descriptors;
}

TEST(PlaceRetrieval, KitchenTopCandidateWithinTenFrames) {
  WARDMAP_REQUIRE_DATA("7scenes-redkitchen");
  const auto vocabulary_file = test::source_dir() / "data/vocabulary/orb-k10l4.bin";
  ASSERT_TRUE(std::filesystem::exists(vocabulary_file)) << vocabulary_file;
  const Vocabulary vocabulary = Vocabulary::load(vocabulary_file);
  auto reader = io::open_sequence(test::shared_data_dir() / "7scenes-redkitchen");
  ASSERT_GE(reader->size(), 300u);
  const OrbExtractor extractor{OrbOptions{}};

  KeyframeDatabase db;
  for (std::size_t i = 0; i < 300; i += 10)
    db.add(i, vocabulary.transform(orb_descriptors(extractor, reader->read(i).image)));
  int queries = 0, hits = 0, top3 = 0;
  for (std::size_t q = 5; q < 300; q += 10) {
    const auto c = db.query(vocabulary.transform(orb_descriptors(extractor, reader->read(q).image)), 3);
    ++queries;
    const auto near = [q](const PlaceCandidate& x) {
      return std::llabs(static_cast<long long>(x.id) - static_cast<long long>(q)) <= 10;
    };
    if (!c.empty() && near(c[0])) ++hits;
    if (std::any_of(c.begin(), c.end(), near)) ++top3;
    if (c.empty() || !near(c[0]))
      std::printf("[ kitchen ] query %zu: best %s (score %.3f)\n", q,
                  c.empty() ? "none" : std::to_string(c[0].id).c_str(), c.empty() ? 0.0 : c[0].score);
  }
  const double rate = static_cast<double>(hits) / queries;
  std::printf("[ kitchen ] top-1 within +-10 frames: %d/%d (%.0f %%), within the top 3: %d/%d\n", hits, queries,
              100 * rate, top3, queries);
  EXPECT_GE(rate, 0.8);
}

}  // namespace
}  // namespace wardmap::slam::place
