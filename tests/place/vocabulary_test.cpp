// The vocabulary tree: k-majority clustering (majority centres, Hamming assignment), training on
// clustered random descriptors, tf-idf bags of words, the L1 score, and the file (round trip, bad files).
#include <gtest/gtest.h>

#include <fstream>
#include <random>

#include "slam/core/errors.h"
#include "slam/place/vocabulary_training.h"
#include "tests/support/test_support.h"

namespace wardmap::slam::place {
namespace {

Descriptor bits(std::initializer_list<int> set) {
  Descriptor d{};
  for (int b : set) d[b / 8] |= static_cast<std::uint8_t>(1u << (b % 8));
  return d;
}

Descriptor random_descriptor(std::mt19937& rng) {
  Descriptor d;
  for (auto& byte : d) byte = static_cast<std::uint8_t>(rng() & 0xff);
  return d;
}

Descriptor flip(Descriptor d, int n, std::mt19937& rng) {
  for (int i = 0; i < n; ++i) {
    const int b = static_cast<int>(rng() % 256);
    d[b / 8] ^= static_cast<std::uint8_t>(1u << (b % 8));
  }
  return d;
}

cv::Mat to_mat(const std::vector<Descriptor>& ds) {
  cv::Mat m(static_cast<int>(ds.size()), kDescriptorBytes, CV_8U);
  for (int r = 0; r < m.rows; ++r) std::memcpy(m.ptr(r), ds[r].data(), kDescriptorBytes);
  return m;
}

// Images made of noisy copies of "landmark" descriptors: image i sees landmarks [i, i + 40) of 200.
std::vector<cv::Mat> clustered_images(int images, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::vector<Descriptor> landmarks(200);
  for (auto& l : landmarks) l = random_descriptor(rng);
  std::vector<cv::Mat> out;
  for (int i = 0; i < images; ++i) {
    std::vector<Descriptor> ds;
    for (int j = 0; j < 40; ++j)
      for (int copy = 0; copy < 3; ++copy) ds.push_back(flip(landmarks[(i * 4 + j) % 200], 6, rng));
    out.push_back(to_mat(ds));
  }
  return out;
}

PlaceOptions small_options() {
  PlaceOptions o;
  o.branching = 4;
  o.levels = 3;
  return o;
}

TEST(KMajority, CentreIsTheBitwiseMajority) {
  // Bit 0 in 3 of 4, bit 9 in 2 of 4 (a tie: not set), bit 255 in 4 of 4, bit 100 in 1 of 4.
  const std::vector<Descriptor> points = {bits({0, 9, 255}), bits({0, 9, 255, 100}), bits({0, 255}), bits({255})};
  EXPECT_EQ(majority_centre(points, {0, 1, 2, 3}), bits({0, 255}));
  EXPECT_EQ(majority_centre(points, {0, 1, 2}), bits({0, 9, 255}));  // bit 9 in 2 of 3
  EXPECT_EQ(majority_centre(points, {3}), bits({255}));
}

TEST(KMajority, AssignsToTheNearestCentreInHammingDistance) {
  const std::vector<Descriptor> centres = {bits({}), bits({0, 1, 2, 3, 4, 5, 6, 7}), bits({200, 201, 202})};
  EXPECT_EQ(nearest_centre(bits({1}).data(), centres), 0);              // 1 vs 7 vs 4
  EXPECT_EQ(nearest_centre(bits({0, 1, 2, 3, 4}).data(), centres), 1);  // 5 vs 3 vs 8
  EXPECT_EQ(nearest_centre(bits({200, 201}).data(), centres), 2);       // 2 vs 10 vs 1
  EXPECT_EQ(nearest_centre(bits({0, 1, 2, 3}).data(), centres), 0);     // 4 vs 4 vs 7: tie to the lower index
}

TEST(KMajority, RecoversTwoNoisyClusters) {
  std::mt19937 rng(3);
  const Descriptor a = random_descriptor(rng), b = random_descriptor(rng);
  std::vector<Descriptor> points;
  for (int i = 0; i < 30; ++i) points.push_back(flip(i % 2 ? a : b, 8, rng));
  std::mt19937 seed_rng(1);
  const Clustering c = k_majority(points, 2, 20, seed_rng);
  ASSERT_EQ(c.centres.size(), 2u);
  for (int i = 0; i < 30; ++i) EXPECT_EQ(c.assignment[i], c.assignment[i % 2]) << "point " << i;
  EXPECT_NE(c.assignment[0], c.assignment[1]);
  // The majority of 15 copies with 8 random flips each is the original.
  EXPECT_EQ(c.centres[c.assignment[1]], a);
  EXPECT_EQ(c.centres[c.assignment[0]], b);
}

TEST(KMajority, FewerDistinctPointsThanKGiveOneCentreEach) {
  std::mt19937 rng(5);
  const Descriptor a = random_descriptor(rng), b = random_descriptor(rng);
  const Clustering c = k_majority({a, b, a, a, b}, 10, 10, rng);
  ASSERT_EQ(c.centres.size(), 2u);
  EXPECT_EQ(c.assignment, (std::vector<int>{0, 1, 0, 0, 1}));
}

TEST(Vocabulary, TrainingBuildsABoundedTreeWithIdfWeights) {
  const auto images = clustered_images(40, 11);
  const Vocabulary v = train_vocabulary(images, small_options(), 1);
  EXPECT_EQ(v.branching(), 4);
  EXPECT_EQ(v.levels(), 3);
  EXPECT_EQ(v.training_images(), 40u);
  EXPECT_LE(v.word_count(), 64u);
  EXPECT_GT(v.word_count(), 40u);  // 200 well-separated landmarks fill most of the 64 leaves
  for (NodeId n = 0; n < v.node_count(); ++n) EXPECT_LE(v.depth(n), 3);
  for (WordId w = 0; w < v.word_count(); ++w) {
    EXPECT_GE(v.idf(w), 0.0);
    EXPECT_LE(v.idf(w), std::log(40.0) + 1e-6);
  }
}

TEST(Vocabulary, TransformGivesASortedL1NormalisedBag) {
  const auto images = clustered_images(40, 11);
  const Vocabulary v = train_vocabulary(images, small_options(), 1);
  const BowVector bow = v.transform(images[7]);
  ASSERT_FALSE(bow.empty());
  double sum = 0;
  for (std::size_t i = 0; i < bow.size(); ++i) {
    EXPECT_GT(bow[i].second, 0.0);
    if (i > 0) {
      EXPECT_LT(bow[i - 1].first, bow[i].first);
    }
    sum += bow[i].second;
  }
  EXPECT_NEAR(sum, 1.0, 1e-9);
  EXPECT_NEAR(l1_score(bow, bow), 1.0, 1e-9);
  // Image 8 shares 36 of image 7's 40 landmarks, image 30 none.
  EXPECT_GT(l1_score(bow, v.transform(images[8])), l1_score(bow, v.transform(images[30])));
  EXPECT_TRUE(v.transform(cv::Mat()).empty());
  EXPECT_THROW(v.transform(cv::Mat(3, 16, CV_8U, cv::Scalar(0))), std::invalid_argument);
}

TEST(Vocabulary, DirectIndexGroupsEveryFeatureUnderOneNode) {
  const auto images = clustered_images(20, 4);
  const Vocabulary v = train_vocabulary(images, small_options(), 1);
  FeatureVector direct;
  v.transform(images[3], &direct, 1);
  std::size_t features = 0;
  for (const auto& [node, rows] : direct) {
    EXPECT_EQ(v.depth(node), 1);
    features += rows.size();
  }
  EXPECT_EQ(features, static_cast<std::size_t>(images[3].rows));
}

TEST(Vocabulary, L1ScoreKnownAnswer) {
  const BowVector a = {{1, 0.5}, {2, 0.5}}, b = {{2, 0.5}, {3, 0.5}}, c = {{1, 0.25}, {2, 0.75}};
  EXPECT_NEAR(l1_score(a, b), 0.5, 1e-12);   // 1 - 0.5 (0.5 + 0 + 0.5)
  EXPECT_NEAR(l1_score(a, c), 0.75, 1e-12);  // 1 - 0.5 (0.25 + 0.25)
  EXPECT_NEAR(l1_score(a, {}), 0.0, 1e-12);
  EXPECT_NEAR(l1_score(a, b), l1_score(b, a), 1e-12);
}

TEST(Vocabulary, SameSeedSameVocabulary) {
  const auto images = clustered_images(20, 4);
  EXPECT_EQ(train_vocabulary(images, small_options(), 9).to_bytes(),
            train_vocabulary(images, small_options(), 9).to_bytes());
}

TEST(Vocabulary, InvalidOptionsNameTheKey) {
  PlaceOptions o;
  o.branching = 1;
  try {
    train_vocabulary(clustered_images(2, 1), o, 1);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("place.branching"), std::string::npos) << e.what();
  }
  o = {};
  o.levels = 9;
  EXPECT_THROW(o.validate(), std::invalid_argument);
  o = {};
  o.min_common_ratio = 1.5;
  EXPECT_THROW(o.validate(), std::invalid_argument);
}

TEST(VocabularyFile, SaveLoadRoundTripGivesIdenticalBags) {
  const auto images = clustered_images(30, 2);
  const Vocabulary v = train_vocabulary(images, small_options(), 3);
  const auto file = test::scratch_dir() / "voc.bin";
  v.save(file);
  const Vocabulary w = Vocabulary::load(file);
  EXPECT_EQ(w.branching(), v.branching());
  EXPECT_EQ(w.levels(), v.levels());
  EXPECT_EQ(w.word_count(), v.word_count());
  EXPECT_EQ(w.node_count(), v.node_count());
  EXPECT_EQ(w.training_images(), v.training_images());
  EXPECT_EQ(w.to_bytes(), v.to_bytes());
  for (const auto& image : images) EXPECT_EQ(w.transform(image), v.transform(image));
  EXPECT_EQ(std::filesystem::file_size(file), v.to_bytes().size());
}

void expect_input_error(const std::filesystem::path& file, const std::string& problem) {
  try {
    Vocabulary::load(file);
    FAIL() << "no exception for " << file;
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), file.string());
    EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(problem), std::string::npos) << e.what();
  }
}

void write(const std::filesystem::path& file, const std::string& bytes) {
  std::ofstream(file, std::ios::binary) << bytes;
}

TEST(VocabularyFile, BadFilesThrowInputErrorNamingTheFileAndProblem) {
  const std::string bytes = train_vocabulary(clustered_images(10, 2), small_options(), 3).to_bytes();
  const auto dir = test::scratch_dir();
  write(dir / "truncated.bin", bytes.substr(0, bytes.size() - 100));
  expect_input_error(dir / "truncated.bin", "truncated");
  write(dir / "header.bin", bytes.substr(0, 20));
  expect_input_error(dir / "header.bin", "truncated");
  write(dir / "empty.bin", "");
  expect_input_error(dir / "empty.bin", "truncated");
  write(dir / "magic.bin", "PK\x03\x04" + bytes.substr(4));
  expect_input_error(dir / "magic.bin", "not a wardmap vocabulary");
  std::string flipped = bytes;
  flipped[bytes.size() / 2] ^= 0x10;
  write(dir / "flipped.bin", flipped);
  expect_input_error(dir / "flipped.bin", "checksum");
  write(dir / "trailing.bin", bytes + "x");
  expect_input_error(dir / "trailing.bin", "unexpected bytes");
  std::string version = bytes;
  version[8] = 7;
  write(dir / "version.bin", version);
  expect_input_error(dir / "version.bin", "version 7");
  expect_input_error(dir / "missing.bin", "cannot open");
}

TEST(VocabularyFile, ShippedVocabularyLoads) {
  const auto file = test::source_dir() / "data/vocabulary/orb-k10l4.bin";
  if (!std::filesystem::exists(file)) GTEST_SKIP() << file << " not found";
  const Vocabulary v = Vocabulary::load(file);
  EXPECT_EQ(v.branching(), 10);
  EXPECT_EQ(v.levels(), 4);
  EXPECT_GT(v.word_count(), 5000u);
  EXPECT_LT(std::filesystem::file_size(file), 1u << 20);
}

}  // namespace
}  // namespace wardmap::slam::place
