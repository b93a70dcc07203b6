// OSNet x0.25 embeddings on crops of bus.jpg (boxes from YOLOX's detections, checked by eye).
#include "semantics/detection/embedder.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <iostream>
#include <opencv2/imgcodecs.hpp>

#include "semantics/detection/model_search.h"
#include "slam/core/errors.h"
#include "tests/semantics/detection/detection_test_support.h"

namespace wardmap::semantics {
namespace {

constexpr const char* kOsnet = "osnet-x0_25/osnet_x0_25_msmt17.onnx";

class EmbedderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    WARDMAP_REQUIRE_DATA("images/bus.jpg");
    WARDMAP_REQUIRE_MODEL(kOsnet);
    image_ = cv::imread((wardmap::test::shared_data_dir() / "images" / "bus.jpg").string());
    ASSERT_FALSE(image_.empty());
  }
  cv::Mat image_;
  const Eigen::Vector4d bus_{14, 231, 801, 733};
  const Eigen::Vector4d man_coat_{50, 395, 216, 898};   // man in the light coat
  const Eigen::Vector4d man_dark_{220, 402, 347, 855};  // man in the dark jacket
};

TEST_F(EmbedderTest, UnitLength512AndSameCropGivesCosineOne) {
  Embedder e(find_embedder_file(wardmap::test::shared_models_dir()));
  const Eigen::VectorXf a = e.embed(image_, man_coat_);
  const Eigen::VectorXf b = e.embed(image_, man_coat_);
  ASSERT_EQ(a.size(), Embedder::kDimension);
  EXPECT_NEAR(a.norm(), 1.0f, 1e-5f);
  EXPECT_GE(a.minCoeff(), 0.0f);  // ends in BN + ReLU
  EXPECT_NEAR(cosine(a, b), 1.0f, 1e-5f);
}

TEST_F(EmbedderTest, ShiftedBoxesOfOneObjectAgreeDifferentObjectsLess) {
  Embedder e(find_embedder_file(wardmap::test::shared_models_dir()));
  const Eigen::Vector4d shift_coat(man_coat_ + Eigen::Vector4d(8, 20, 8, 20));  // ~5 % of the box
  const Eigen::Vector4d shift_dark(man_dark_ + Eigen::Vector4d(-6, -15, -6, -15));
  const Eigen::Vector4d shift_bus(bus_ + Eigen::Vector4d(30, 15, 10, -10));
  const float same_coat = cosine(e.embed(image_, man_coat_), e.embed(image_, shift_coat));
  const float same_dark = cosine(e.embed(image_, man_dark_), e.embed(image_, shift_dark));
  const float same_bus = cosine(e.embed(image_, bus_), e.embed(image_, shift_bus));
  const float bus_vs_person = cosine(e.embed(image_, bus_), e.embed(image_, man_coat_));
  const float person_vs_person = cosine(e.embed(image_, man_coat_), e.embed(image_, man_dark_));
  std::cout << "cosine: coat shifted " << same_coat << ", dark jacket shifted " << same_dark << ", bus shifted "
            << same_bus << ", bus vs person " << bus_vs_person << ", person vs other person " << person_vs_person
            << "\n";
  EXPECT_GT(same_coat, 0.8f);
  EXPECT_GT(same_dark, 0.8f);
  EXPECT_GT(same_bus, 0.8f);
  EXPECT_LT(bus_vs_person, 0.7f);
  EXPECT_LT(bus_vs_person, std::min({same_coat, same_dark, same_bus}) - 0.2f);
  EXPECT_LT(person_vs_person, std::min(same_coat, same_dark));
}

TEST_F(EmbedderTest, BoxesAreClampedDegenerateCropsThrow) {
  Embedder e(find_embedder_file(wardmap::test::shared_models_dir()));
  const Eigen::Vector4d beyond(-50, 300, 900, 1200);  // clamped to the image
  EXPECT_EQ(e.embed(image_, beyond).size(), Embedder::kDimension);
  EXPECT_THROW(e.embed(image_, Eigen::Vector4d(100, 100, 101, 300)), std::invalid_argument);  // 1 px wide
  EXPECT_THROW(e.embed(image_, Eigen::Vector4d(900, 100, 950, 300)), std::invalid_argument);  // off the image
  EXPECT_THROW(e.embed(cv::Mat(), bus_), std::invalid_argument);
}

TEST_F(EmbedderTest, AllBoxesAtOnceGiveWhatOneByOneGives) {
  const std::vector<Eigen::Vector4d> boxes = {bus_, man_coat_, Eigen::Vector4d(100, 100, 101, 300), man_dark_,
                                              Eigen::Vector4d(-50, 300, 900, 1200)};
  for (int threads : {1, 2, 3}) {
    Embedder e(find_embedder_file(wardmap::test::shared_models_dir()), threads);
    EXPECT_EQ(e.threads(), threads);
    for (int round = 0; round < 2; ++round) {
      const std::vector<Eigen::VectorXf> all = e.embed_all(image_, boxes);
      ASSERT_EQ(all.size(), boxes.size());
      for (size_t i = 0; i < boxes.size(); ++i) {
        if (i == 2) {
          EXPECT_EQ(all[i].size(), 0) << "a 1 px wide crop has nothing to describe";
          continue;
        }
        const Eigen::VectorXf one = e.embed(image_, boxes[i]);
        ASSERT_EQ(all[i].size(), Embedder::kDimension);
        EXPECT_LE((all[i] - one).cwiseAbs().maxCoeff(), 1e-6f) << "box " << i << ", " << threads << " threads";
      }
    }
    EXPECT_TRUE(e.embed_all(image_, {}).empty());
    EXPECT_THROW(e.embed_all(cv::Mat(), {bus_}), std::invalid_argument);
  }
  EXPECT_THROW(Embedder(find_embedder_file(wardmap::test::shared_models_dir()), 0), std::invalid_argument);
}

TEST(EmbedderFile, MissingFileNamesIt) {
  try {
    Embedder e("/nonexistent/osnet.onnx");
    FAIL() << "no error";
  } catch (const InputError& ex) {
    EXPECT_NE(std::string(ex.what()).find("/nonexistent/osnet.onnx"), std::string::npos) << ex.what();
  }
}

TEST(EmbedderFile, NotAnOnnxFileNamesIt) {
  const auto file = wardmap::test::scratch_dir() / "broken.onnx";
  std::ofstream(file) << "not a model";
  try {
    Embedder e(file);
    FAIL() << "no error";
  } catch (const InputError& ex) {
    EXPECT_NE(std::string(ex.what()).find(file.string()), std::string::npos) << ex.what();
  }
}

TEST(EmbedderFile, EmptyFileNamesIt) {
  const auto file = wardmap::test::scratch_dir() / "empty.onnx";
  std::ofstream{file};
  try {
    Embedder e(file);
    FAIL() << "no error";
  } catch (const InputError& ex) {
    EXPECT_EQ(ex.file(), file.string());
    EXPECT_NE(std::string(ex.what()).find("empty file"), std::string::npos) << ex.what();
  }
}

TEST(EmbedderFile, AnotherNetworkIsRefusedAtLoad) {
  // YOLOX is fully convolutional: cv::dnn runs it on OSNet's input, and its output is no embedding.
  WARDMAP_REQUIRE_MODEL("yolox-nano/yolox_nano_416x416.onnx");
  const auto file = wardmap::test::shared_models_dir() / "yolox-nano/yolox_nano_416x416.onnx";
  try {
    Embedder e(file);
    FAIL() << "no error";
  } catch (const InputError& ex) {
    EXPECT_EQ(ex.file(), file.string());
    EXPECT_NE(std::string(ex.what()).find("expected a 512-d output"), std::string::npos) << ex.what();
  }
}

}  // namespace
}  // namespace wardmap::semantics
