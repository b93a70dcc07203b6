// Model descriptions, the model search path, detector options, and the small pieces of the
// network detectors (letterbox, class-wise NMS, the reproducible random numbers).
#include "semantics/detection/model_description.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <iostream>
#include <iterator>
#include <set>

#include "semantics/detection/class_nms.h"
#include "semantics/detection/detector_factory.h"
#include "semantics/detection/frame_rng.h"
#include "semantics/detection/letterbox.h"
#include "semantics/detection/model_search.h"
#include "slam/core/errors.h"
#include "tests/semantics/detection/detection_test_support.h"

namespace wardmap::semantics {
namespace {

namespace fs = std::filesystem;

TEST(ModelDescription, ShippedDescriptionsLoad) {
  for (const char* kind : {"yolox", "nanodet"}) {
    const ModelDescription m = load_model_description(default_model_description(kind));
    EXPECT_EQ(m.classes.size(), 80u);
    EXPECT_EQ(m.classes[0], "person");
    EXPECT_EQ(m.classes[79], "toothbrush");
    for (const char* set : {"hospital", "road", "indoor"}) EXPECT_TRUE(m.landmark_sets.count(set)) << set;
    const auto road = m.class_to_landmark("road");
    EXPECT_EQ(road[2], "vehicle");  // car
    EXPECT_EQ(road[5], "vehicle");  // bus
    EXPECT_EQ(road[7], "vehicle");  // truck
    EXPECT_EQ(road[0], "person");
    EXPECT_EQ(road[56], "");  // chair: dropped on the road
    const auto indoor = m.class_to_landmark("indoor");
    EXPECT_EQ(indoor[60], "table");                           // dining table
    EXPECT_EQ(indoor[0], "");                                 // people are not landmarks
    EXPECT_EQ(m.class_to_landmark("hospital")[57], "chair");  // couch
    EXPECT_EQ(m.class_to_landmark("coco")[60], "dining table");
    EXPECT_THROW(m.class_to_landmark("harbour"), InputError);
  }
  const ModelDescription y = load_model_description(default_model_description("yolox"));
  EXPECT_EQ(y.input.width, 416);
  EXPECT_EQ(y.input.pad_value, 114);
  const ModelDescription n = load_model_description(default_model_description("nanodet"));
  EXPECT_EQ(n.output.bins, 8);
  EXPECT_TRUE(n.input.pad_after_normalisation);
  EXPECT_EQ(n.output.box_names[2], "dis_pred_stride_32");
}

// A valid NanoDet-style description with one line replaced, written beside a copy of the class list.
std::string error_of_description(const std::string& from, const std::string& to) {
  const fs::path dir = wardmap::test::scratch_dir();
  fs::copy_file(model_descriptions_dir() / "coco80.names", dir / "coco80.names");
  std::ifstream in(default_model_description("nanodet"));
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  text.replace(text.find("landmark_sets: coco80_landmarks.yaml"), std::string::npos,
               "landmark_sets:\n  indoor:\n    dining table: table\n");
  std::ofstream(dir / "model.yaml") << text;
  try {
    load_model_description(dir / "model.yaml");
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), (dir / "model.yaml").string());
    return e.what();
  }
  return "(no error)";
}

TEST(ModelDescription, ErrorsNameTheKey) {
  EXPECT_EQ(error_of_description("# NanoDet", "# NanoDet"), "(no error)");
  EXPECT_NE(error_of_description("width: 320", "width: -3").find("key 'input.width': must be in [1, 4096]"),
            std::string::npos);
  EXPECT_NE(error_of_description("width: 320", "width: wide").find("key 'input.width': expected an integer"),
            std::string::npos);
  EXPECT_NE(error_of_description("  height: 320\n", "").find("missing key 'input.height'"), std::string::npos);
  EXPECT_NE(error_of_description("decoder: nanodet", "decoder: ssd").find("key 'decoder'"), std::string::npos);
  EXPECT_NE(error_of_description("decoder: nanodet\n", "").find("missing key 'decoder'"), std::string::npos);
  EXPECT_NE(error_of_description("std: [57.375, 57.12, 58.395]", "std: [57.375, 0, 58.395]").find("key 'input.std'"),
            std::string::npos);
  EXPECT_NE(error_of_description("mean: [103.53, 116.28, 123.675]", "mean: [1, 2]").find("key 'input.mean'"),
            std::string::npos);
  EXPECT_NE(error_of_description(", dis_pred_stride_32]", "]").find("key 'output.box_names'"), std::string::npos);
  EXPECT_NE(error_of_description("bins: 8", "bins: 0").find("key 'output.bins'"), std::string::npos);
  EXPECT_NE(error_of_description("channel_order: bgr", "channel_order: hsv").find("key 'input.channel_order'"),
            std::string::npos);
  // A misspelt optional key would otherwise leave the default preprocessing in place without a word.
  EXPECT_NE(error_of_description("  pad_value: 0", "  pad_valeu: 0")
                .find(":12: key 'input.pad_valeu': not a key of section 'input' (did you mean 'input.pad_value'?)"),
            std::string::npos);
  EXPECT_NE(error_of_description("  pad_value: 0", "  pad_value: 0\n  canvas_multiple: 24")
                .find("key 'input.canvas_multiple': 24 is not a multiple of the output stride 16"),
            std::string::npos);
  EXPECT_NE(error_of_description("  pad_value: 0", "  pad_value: 0\n  canvas_multiple: -32")
                .find("key 'input.canvas_multiple': must be 0 (a fixed canvas) or in [1, 320], got -32"),
            std::string::npos);
  EXPECT_EQ(error_of_description("  pad_value: 0", "  pad_value: 0\n  canvas_multiple: 32"), "(no error)");
  EXPECT_NE(error_of_description("  bins: 8", "  bins: 8\n  bin: 8").find("key 'output.bin': not a key of section"),
            std::string::npos);
  EXPECT_NE(error_of_description("decoder: nanodet", "decoder: nanodet\ndecodr: yolox")
                .find("key 'decodr': not a known key (did you mean 'decoder'?)"),
            std::string::npos);
  EXPECT_NE(error_of_description("width: 320", "width: 324")
                .find("key 'input.width': 324 is not a multiple of the output stride 8"),
            std::string::npos);
  EXPECT_NE(error_of_description("classes: coco80.names", "classes: coco81.names")
                .find(":20: key 'classes': file not found; looked in: "),
            std::string::npos);
  const std::string e = error_of_description("classes: coco80.names", "classes: coco80.names\n# x");
  EXPECT_EQ(e, "(no error)");
  // A landmark mapping from a class the detector does not have.
  const fs::path dir = wardmap::test::scratch_dir();
  fs::copy_file(model_descriptions_dir() / "coco80.names", dir / "coco80.names");
  std::ifstream in(default_model_description("yolox"));
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  text.replace(text.find("landmark_sets: coco80_landmarks.yaml"), std::string::npos,
               "landmark_sets:\n  indoor:\n    dining tabel: table\n");
  std::ofstream(dir / "typo.yaml") << text;
  try {
    load_model_description(dir / "typo.yaml");
    FAIL() << "no error";
  } catch (const InputError& ex) {
    EXPECT_NE(std::string(ex.what()).find("key 'landmark_sets.indoor.dining tabel'"), std::string::npos) << ex.what();
  }
}

TEST(ModelDescription, ACopyElsewhereFindsTheShippedClassListAndLandmarkSets) {
  // Copied to change one value: its relative `classes` and `landmark_sets` are not beside it.
  const fs::path dir = wardmap::test::scratch_dir();
  fs::copy_file(default_model_description("yolox"), dir / "mine.yaml");
  const ModelDescription m = load_model_description(dir / "mine.yaml");
  EXPECT_EQ(m.classes.size(), 80u);
  EXPECT_EQ(m.class_to_landmark("road")[2], "vehicle");
}

TEST(ModelSearch, MissingModelNamesEveryPlaceSearched) {
  const fs::path dir = wardmap::test::scratch_dir();
  try {
    find_model_file("yolox-nano/missing.onnx", dir);
    FAIL() << "no error";
  } catch (const InputError& e) {
    const std::string what = e.what();
    std::cout << what << "\n";
    EXPECT_EQ(e.file(), "yolox-nano/missing.onnx");
    EXPECT_NE(what.find((dir / "yolox-nano/missing.onnx").string()), std::string::npos) << what;
    for (const fs::path& place : model_search_path(dir))
      EXPECT_NE(what.find((place / "yolox-nano/missing.onnx").string()), std::string::npos) << place;
    EXPECT_NE(what.find("WARDMAP_MODELS"), std::string::npos);
  }
  ASSERT_GE(model_search_path(dir).size(), 2u);
  EXPECT_EQ(model_search_path(dir).front(), dir);
  EXPECT_EQ(model_search_path().back().filename(), "models");
}

TEST(ModelSearch, MissingModelsFolderIsAnError) {
  const fs::path absent = wardmap::test::scratch_dir() / "absent";
  try {
    find_model_file("yolox-nano/yolox_nano_416x416.onnx", absent);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), absent.string());
    EXPECT_NE(std::string(e.what()).find("models folder not found"), std::string::npos) << e.what();
  }
  EXPECT_THROW(find_embedder_file(absent), InputError);
}

TEST(ModelSearch, AFolderWhereTheModelShouldBeIsAnError) {
  // Not a reason to go on to the next place of the search path and take its copy without a word.
  const fs::path dir = wardmap::test::scratch_dir();
  fs::create_directories(dir / "yolox-nano" / "yolox_nano_416x416.onnx");
  try {
    find_model_file("yolox-nano/yolox_nano_416x416.onnx", dir);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), (dir / "yolox-nano" / "yolox_nano_416x416.onnx").string());
    EXPECT_NE(std::string(e.what()).find("not a regular file"), std::string::npos) << e.what();
  }
}

TEST(ModelSearch, FactoryReportsMissingWeights) {
  const fs::path dir = wardmap::test::scratch_dir();
  std::ifstream in(default_model_description("yolox"));
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  text.replace(text.find("yolox-nano/yolox_nano_416x416.onnx"), 34, "yolox-nano/not_there_416.onnx");
  text.replace(text.find("coco80_landmarks.yaml"), 21, (model_descriptions_dir() / "coco80_landmarks.yaml").string());
  fs::copy_file(model_descriptions_dir() / "coco80.names", dir / "coco80.names");
  std::ofstream(dir / "yolox.yaml") << text;
  DetectorOptions o;
  o.model_description = dir / "yolox.yaml";
  o.models_dir = dir;
  try {
    make_detector(o);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find((dir / "yolox-nano/not_there_416.onnx").string()), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("looked in"), std::string::npos) << e.what();
  }
}

TEST(DetectorOptions, ValidateAndYamlNameTheKey) {
  DetectorOptions o;
  EXPECT_FALSE(o.validate());
  o.kind = "ssd";
  EXPECT_NE(o.validate()->find("'kind'"), std::string::npos);
  o = DetectorOptions();
  o.nms_iou = 1.5;
  EXPECT_NE(o.validate()->find("'nms_iou' must be in [0, 1]"), std::string::npos);
  EXPECT_THROW(make_detector(o), InputError);
  o = DetectorOptions();
  o.embedding_threads = 0;
  EXPECT_NE(o.validate()->find("'embedding_threads' must be in [1, 8]"), std::string::npos);

  const YAML::Node node = YAML::Load(
      "kind: annotations\nscore_threshold: 0.5\nlandmark_set: hospital\nannotations: {seed: 7, box_jitter: 0.1}\n");
  const DetectorOptions loaded = detector_options_from_yaml(node, "s.yaml");
  EXPECT_EQ(loaded.kind, "annotations");
  EXPECT_EQ(loaded.landmark_set, "hospital");
  EXPECT_EQ(loaded.noise.seed, 7u);
  EXPECT_DOUBLE_EQ(loaded.noise.box_jitter, 0.1);
  EXPECT_DOUBLE_EQ(loaded.noise.miss_probability, 0.05);
  auto error = [](const std::string& yaml) -> std::string {
    try {
      detector_options_from_yaml(YAML::Load(yaml), "s.yaml");
    } catch (const InputError& e) {
      return e.what();
    }
    return "(no error)";
  };
  EXPECT_NE(error("nms_iou: high").find("s.yaml:1: key 'detection.nms_iou': expected a number"), std::string::npos);
  EXPECT_NE(error("annotations: {miss_probability: 2}").find("key 'detection.annotations.miss_probability' must be"),
            std::string::npos);
  EXPECT_NE(error("landmark_set: harbour").find("key 'detection.landmark_set'"), std::string::npos);
  // A misspelt key, in the section or in its annotations subsection, is an error with its line and
  // the nearest known key, not a silently kept default.
  EXPECT_NE(error("kind: annotations\nscore_treshold: 0.5\n")
                .find("s.yaml:2: key 'detection.score_treshold': not a key of section 'detection' (did you mean "
                      "'detection.score_threshold'?)"),
            std::string::npos);
  EXPECT_NE(error("annotations:\n  miss_probabilty: 0.2\n")
                .find("s.yaml:2: key 'detection.annotations.miss_probabilty': not a key of section "
                      "'detection.annotations' (did you mean 'detection.annotations.miss_probability'?)"),
            std::string::npos);
  EXPECT_NE(error("annotations: {seed: -3}").find("key 'detection.annotations.seed': expected a non-negative integer"),
            std::string::npos);
  EXPECT_NE(error("- yolox").find("key 'detection': expected a section"), std::string::npos);
  EXPECT_EQ(detector_options_from_yaml(YAML::Load("models_dir: /opt/models"), "s.yaml").models_dir, "/opt/models");
  EXPECT_EQ(detector_options_from_yaml(YAML::Load("embedding_threads: 1"), "s.yaml").embedding_threads, 1);
  EXPECT_EQ(DetectorOptions().embedding_threads, 2);
}

TEST(Letterbox, TopLeftWithPadding) {
  InputSpec spec;
  spec.width = 416;
  spec.height = 416;
  spec.pad_value = 114;
  const cv::Mat image(50, 100, CV_8UC3, cv::Scalar(10, 20, 30));
  const Letterbox lb = make_letterbox(image, spec);
  EXPECT_DOUBLE_EQ(lb.scale, 4.16);
  ASSERT_EQ(lb.blob.size[1], 3);
  ASSERT_EQ(lb.blob.size[2], 416);
  auto at = [&](int c, int y, int x) { return lb.blob.ptr<float>(0, c)[y * 416 + x]; };
  EXPECT_FLOAT_EQ(at(0, 10, 10), 10);  // B channel first, raw values
  EXPECT_FLOAT_EQ(at(2, 200, 400), 30);
  EXPECT_FLOAT_EQ(at(1, 300, 10), 114);  // below the image: padding

  spec.mean = {100, 100, 100};
  spec.std = {2, 2, 2};
  spec.pad_value = 0;
  spec.pad_after_normalisation = true;
  spec.channel_order = "rgb";
  const Letterbox n = make_letterbox(image, spec);
  auto at_n = [&](int c, int y, int x) { return n.blob.ptr<float>(0, c)[y * 416 + x]; };
  EXPECT_FLOAT_EQ(at_n(0, 10, 10), (30 - 100) / 2.0f);  // R first after the swap
  EXPECT_FLOAT_EQ(at_n(0, 300, 10), 0);
}

// canvas_multiple: the side the image leaves partly empty is cut to the smallest multiple holding it
// and that many pixels of padding.
TEST(Letterbox, CanvasCutToTheImage) {
  InputSpec spec;
  spec.width = 416;
  spec.height = 416;
  spec.pad_value = 114;
  spec.canvas_multiple = 32;
  EXPECT_EQ(letterbox_canvas({416, 312}, spec), cv::Size(416, 352));  // 640x480
  EXPECT_EQ(letterbox_canvas({416, 126}, spec), cv::Size(416, 160));  // KITTI 1241x376
  EXPECT_EQ(letterbox_canvas({312, 416}, spec), cv::Size(352, 416));  // portrait
  EXPECT_EQ(letterbox_canvas({416, 384}, spec), cv::Size(416, 416));  // no smaller multiple holds 32 more
  EXPECT_EQ(letterbox_canvas({416, 416}, spec), cv::Size(416, 416));
  spec.canvas_multiple = 0;
  EXPECT_EQ(letterbox_canvas({416, 126}, spec), cv::Size(416, 416));

  spec.canvas_multiple = 32;
  const cv::Mat image(480, 640, CV_8UC3, cv::Scalar(10, 20, 30));
  const Letterbox lb = make_letterbox(image, spec);
  EXPECT_EQ(lb.canvas, cv::Size(416, 352));
  ASSERT_EQ(lb.blob.size[2], 352);
  ASSERT_EQ(lb.blob.size[3], 416);
  EXPECT_DOUBLE_EQ(lb.scale, 0.65);
  auto at = [&](int c, int y, int x) { return lb.blob.ptr<float>(0, c)[y * 416 + x]; };
  EXPECT_FLOAT_EQ(at(0, 311, 415), 10);   // the image's last row
  EXPECT_FLOAT_EQ(at(0, 312, 0), 114);    // the 40 rows of padding below it
  EXPECT_FLOAT_EQ(at(2, 351, 415), 114);
}

TEST(ClassWiseNms, SuppressesWithinAGroupOnly) {
  const std::vector<cv::Rect2d> boxes{{10, 10, 100, 100}, {12, 12, 100, 100}, {11, 11, 100, 100}, {300, 10, 50, 50}};
  const std::vector<float> scores{0.9f, 0.8f, 0.7f, 0.6f};
  const std::vector<int> groups{0, 0, 1, 0};
  const std::vector<int> keep = class_wise_nms(boxes, scores, groups, 0.45f);
  EXPECT_EQ(keep, (std::vector<int>{0, 2, 3}));
  EXPECT_TRUE(class_wise_nms({}, {}, {}, 0.45f).empty());
}

TEST(FrameRng, ReproducibleAndWellDistributed) {
  FrameRng a(5, 1.25), b(5, 1.25), c(6, 1.25), d(5, 1.2500001);
  const double first = a.uniform();
  EXPECT_EQ(first, b.uniform());
  EXPECT_NE(first, c.uniform());
  EXPECT_EQ(first, d.uniform()) << "timestamps enter at microsecond resolution";
  FrameRng r(1, 0.0);
  const int n = 200000;
  double sum = 0, sum_sq = 0, sum_u = 0, sum_p = 0;
  for (int i = 0; i < n; ++i) {
    const double u = r.uniform();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    sum_u += u;
    const double z = r.normal();
    sum += z;
    sum_sq += z * z;
    sum_p += r.poisson(0.5);
  }
  EXPECT_NEAR(sum_u / n, 0.5, 0.005);
  EXPECT_NEAR(sum / n, 0.0, 0.01);
  EXPECT_NEAR(sum_sq / n, 1.0, 0.02);
  EXPECT_NEAR(sum_p / n, 0.5, 0.01);
  std::set<int> seen;
  for (int i = 0; i < 1000; ++i) seen.insert(r.index(6));
  EXPECT_EQ(seen, (std::set<int>{0, 1, 2, 3, 4, 5}));
}

}  // namespace
}  // namespace wardmap::semantics
