// Detectors on real photos (../shared/data/images). Asserts only what is really in each picture,
// checked by eye: bus.jpg a blue city bus and four people (one cut by the left edge);
// voc_000004_street.jpg parked cars, a dark SUV and a pickup, a traffic light, no people;
// voc_000181_livingroom.jpg four people (one only an arm) on a couch, a dark armchair, a coffee
// table with glasses, a Christmas tree, no tv; nyu_119 a bed and a framed picture; nyu_312 a long
// dining table and many chairs; nyu_358 a desk chair and three monitors (COCO's "tv").
// Every run prints its detections (label, COCO class, score, box).
#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>
#include <map>
#include <memory>
#include <opencv2/imgcodecs.hpp>

#include "semantics/detection/detector_factory.h"
#include "slam/core/errors.h"
#include "tests/semantics/detection/detection_test_support.h"

namespace wardmap::semantics {
namespace {

namespace fs = std::filesystem;

const char* model_file(const std::string& kind) {
  return kind == "yolox" ? "yolox-nano/yolox_nano_416x416.onnx" : "nanodet-m/nanodet_m_320.onnx";
}

class RealPhotos : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    WARDMAP_REQUIRE_DATA("images");
    WARDMAP_REQUIRE_MODEL(model_file(GetParam()));
  }
  bool yolox() const { return GetParam() == "yolox"; }

  std::vector<Detection> detect(const std::string& photo, const std::string& set) {
    auto& detector = detectors_[set];
    if (!detector) {
      DetectorOptions o;
      o.kind = GetParam();
      o.landmark_set = set;
      o.models_dir = wardmap::test::shared_models_dir();
      detector = make_detector(o);
    }
    const fs::path p = wardmap::test::shared_data_dir() / "images" / photo;
    const cv::Mat image = cv::imread(p.string(), cv::IMREAD_COLOR);
    EXPECT_FALSE(image.empty()) << "cannot read " << p;
    if (image.empty()) return {};
    auto dets = detector->detect(image, 0.0);
    std::cout << detector->name() << " [" << set << "] on " << photo << " (" << image.cols << "x" << image.rows
              << "): " << dets.size() << " detections\n"
              << test::describe(dets) << std::flush;
    for (const Detection& d : dets) {  // clipped to the image, well-formed
      EXPECT_GE(d.box[0], 0);
      EXPECT_GE(d.box[1], 0);
      EXPECT_LE(d.box[2], image.cols);
      EXPECT_LE(d.box[3], image.rows);
      EXPECT_LT(d.box[0], d.box[2]);
      EXPECT_LT(d.box[1], d.box[3]);
      EXPECT_GE(d.score, 0.35f);
    }
    return dets;
  }

  static std::vector<Detection> with(const std::vector<Detection>& dets, const std::string& label) {
    std::vector<Detection> out;
    std::copy_if(dets.begin(), dets.end(), std::back_inserter(out),
                 [&](const Detection& d) { return d.label == label; });
    return out;
  }
  static bool any_contains(const std::vector<Detection>& dets, double x, double y) {
    return std::any_of(dets.begin(), dets.end(), [&](const Detection& d) {
      return d.box[0] <= x && x <= d.box[2] && d.box[1] <= y && y <= d.box[3];
    });
  }

  std::map<std::string, std::unique_ptr<Detector>> detectors_;
};

TEST_P(RealPhotos, BusScene) {
  const auto dets = detect("bus.jpg", "road");
  const auto vehicles = with(dets, "vehicle");
  ASSERT_GE(vehicles.size(), 1u);
  EXPECT_EQ(vehicles.front().source_label, "bus");
  // The bus spans nearly the whole 810 px width, from above the people's heads to its wheels.
  EXPECT_LT(vehicles.front().box[0], 100);
  EXPECT_GT(vehicles.front().box[2], 700);
  EXPECT_TRUE(any_contains(vehicles, 500, 450));
  EXPECT_EQ(vehicles.size(), 1u) << "one bus, nothing else with wheels";
  const auto people = with(dets, "person");
  EXPECT_GE(people.size(), 3u);
  EXPECT_LE(people.size(), 5u);
  EXPECT_TRUE(any_contains(people, 120, 600));  // man in the light coat
  EXPECT_TRUE(any_contains(people, 290, 600));  // man in the dark jacket
}

TEST_P(RealPhotos, StreetScene) {
  const auto dets = detect("voc_000004_street.jpg", "road");
  const auto vehicles = with(dets, "vehicle");
  EXPECT_GE(vehicles.size(), yolox() ? 7u : 5u);
  EXPECT_TRUE(any_contains(vehicles, 430, 360));  // red car on the right
  EXPECT_TRUE(any_contains(vehicles, 280, 355));  // dark sedan in the middle
  EXPECT_TRUE(any_contains(vehicles, 50, 340));   // dark SUV on the left
  EXPECT_TRUE(with(dets, "person").empty()) << "there is nobody in this street";
  EXPECT_GE(with(dets, "traffic_light").size(), 1u);
}

TEST_P(RealPhotos, LivingRoom) {
  const auto indoor = detect("voc_000181_livingroom.jpg", "indoor");
  EXPECT_TRUE(with(indoor, "tv").empty()) << "there is no tv in this room";
  EXPECT_TRUE(with(indoor, "person").empty()) << "people are not indoor landmarks";
  if (yolox()) {
    EXPECT_TRUE(any_contains(with(indoor, "cup"), 355, 330));    // the glass in front
    EXPECT_TRUE(any_contains(with(indoor, "table"), 400, 340));  // the coffee table
    EXPECT_GE(with(indoor, "chair").size(), 1u);                 // the dark armchair
  }
  const auto raw = detect("voc_000181_livingroom.jpg", "coco");
  const auto people = with(raw, "person");
  EXPECT_GE(people.size(), yolox() ? 3u : 2u);
  EXPECT_TRUE(any_contains(people, 80, 220));  // man in the red sweater
}

TEST_P(RealPhotos, Bedroom) {
  const auto dets = detect("nyu_119.png", "indoor");
  const auto beds = with(dets, "bed");
  ASSERT_EQ(beds.size(), 1u);
  EXPECT_TRUE(any_contains(beds, 280, 300));
  EXPECT_LT(beds.front().box[0], 80);
  EXPECT_GT(beds.front().box[2], 460);
  if (yolox()) {
    EXPECT_EQ(dets.size(), 1u) << "only the bed (the picture is not a landmark class)";
  }
}

TEST_P(RealPhotos, DiningRoom) {
  const auto dets = detect("nyu_312.png", "indoor");
  const auto tables = with(dets, "table");
  ASSERT_GE(tables.size(), 1u);
  EXPECT_TRUE(any_contains(tables, 320, 330));
  EXPECT_EQ(tables.front().source_label, "dining table");
  EXPECT_GE(with(dets, "chair").size(), 3u);
  EXPECT_TRUE(any_contains(with(dets, "chair"), 550, 250));  // the chair at the head of the table
}

TEST_P(RealPhotos, Office) {
  const auto dets = detect("nyu_358.png", "indoor");
  const auto chairs = with(dets, "chair");
  EXPECT_TRUE(any_contains(chairs, 300, 330));  // the wooden desk chair
  const auto screens = with(dets, "tv");
  EXPECT_GE(screens.size(), 1u);
  EXPECT_TRUE(any_contains(screens, 180, 200));  // the left monitor
}

TEST_P(RealPhotos, GreyImagesAreAccepted) {
  const fs::path p = wardmap::test::shared_data_dir() / "images" / "nyu_119.png";
  const cv::Mat grey = cv::imread(p.string(), cv::IMREAD_GRAYSCALE);
  ASSERT_FALSE(grey.empty());
  DetectorOptions o;
  o.kind = GetParam();
  o.models_dir = wardmap::test::shared_models_dir();
  const auto dets = make_detector(o)->detect(grey, 0.0);
  std::cout << "grey nyu_119.png:\n" << test::describe(dets);
  EXPECT_TRUE(any_contains(with(dets, "bed"), 280, 300));
}

INSTANTIATE_TEST_SUITE_P(Detectors, RealPhotos, ::testing::Values("yolox", "nanodet"),
                         [](const auto& info) { return info.param; });

TEST(DetectorFile, AnotherModelsWeightsAreRefusedAtLoad) {
  // OSNet's weights where YOLOX's should be: the network runs on YOLOX's input, but its output is
  // not YOLOX's. Refused when the detector is made, naming the weights and the description.
  WARDMAP_REQUIRE_MODEL("osnet-x0_25/osnet_x0_25_msmt17.onnx");
  const fs::path dir = wardmap::test::scratch_dir();
  fs::create_directories(dir / "yolox-nano");
  fs::copy_file(wardmap::test::shared_models_dir() / "osnet-x0_25/osnet_x0_25_msmt17.onnx", dir / model_file("yolox"),
                fs::copy_options::overwrite_existing);
  DetectorOptions o;
  o.kind = "yolox";
  o.models_dir = dir;
  try {
    make_detector(o);
    FAIL() << "no error";
  } catch (const InputError& ex) {
    EXPECT_EQ(ex.file(), (dir / model_file("yolox")).string());
    const std::string what = ex.what();
    EXPECT_NE(what.find("has shape 1x512, expected 3549x85"), std::string::npos) << what;
    EXPECT_NE(what.find("yolox-nano.yaml"), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace wardmap::semantics
