// The annotations back-end on hand-written and generated annotations.jsonl files.
#include "semantics/detection/annotations_detector.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "semantics/detection/detector_factory.h"
#include "slam/core/errors.h"
#include "tests/semantics/detection/detection_test_support.h"

namespace wardmap::semantics {
namespace {

namespace fs = std::filesystem;

// Three frames at 30 Hz; the bed in frame 2 is 5 % visible (never reported), the chair in frame 3 is
// 20 % visible (a likelier miss).
const char* kThreeFrames =
    R"({"timestamp": 0.0, "objects": [{"id": 3, "class": "door", "box": [100, 50, 180, 300], "visible": 0.83}, {"id": 7, "class": "chair", "box": [300.5, 200, 360, 310.25], "visible": 1.0}]}
{"timestamp": 0.033333, "objects": [{"id": 3, "class": "door", "box": [110, 52, 190, 302], "visible": 0.9}, {"id": 9, "class": "bed", "box": [400, 250, 630, 470], "visible": 0.05}]}

{"timestamp": 0.066667, "objects": [{"id": 7, "class": "chair", "box": [320, 210, 380, 320], "visible": 0.2}, {"id": 11, "class": "iv_pole", "box": [500, 40, 530, 400], "visible": 0.6}]}
)";

fs::path write_file(const fs::path& dir, const std::string& text) {
  const fs::path file = dir / "annotations.jsonl";
  std::ofstream(file) << text;
  return file;
}

const cv::Mat kImage(480, 640, CV_8UC3, cv::Scalar::all(0));

std::vector<Detection> run(AnnotationsDetector& d, double t) { return d.detect(kImage, t); }

bool same(const std::vector<Detection>& a, const std::vector<Detection>& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    if (a[i].box != b[i].box || a[i].label != b[i].label || a[i].score != b[i].score ||
        a[i].gt_instance != b[i].gt_instance)
      return false;
  return true;
}

TEST(AnnotationsDetector, NoiseFreeReproducesTheAnnotations) {
  AnnotationsDetector d(write_file(wardmap::test::scratch_dir(), kThreeFrames), AnnotationNoise::none());
  EXPECT_EQ(d.num_frames(), 3u);
  const auto f1 = run(d, 0.0);
  std::cout << "frame 1:\n" << test::describe(f1);
  ASSERT_EQ(f1.size(), 2u);
  EXPECT_EQ(f1[0].box, Eigen::Vector4d(100, 50, 180, 300));
  EXPECT_EQ(f1[0].label, "door");
  EXPECT_EQ(f1[0].source_label, "door");
  EXPECT_EQ(f1[0].gt_instance, 3);
  EXPECT_EQ(f1[1].box, Eigen::Vector4d(300.5, 200, 360, 310.25));
  EXPECT_EQ(f1[1].gt_instance, 7);
  EXPECT_FLOAT_EQ(f1[1].score, 0.5f + 0.45f);  // score_base + gain * visible

  const auto f2 = run(d, 0.03338);  // within 1e-4 s of 0.033333
  ASSERT_EQ(f2.size(), 1u) << "the 5 % visible bed is below min_visible";
  EXPECT_EQ(f2[0].box, Eigen::Vector4d(110, 52, 190, 302));

  const auto f3 = run(d, 0.066667);
  ASSERT_EQ(f3.size(), 2u);
  EXPECT_EQ(f3[0].label, "chair");
  EXPECT_EQ(f3[1].label, "iv_pole");
  EXPECT_EQ(f3[1].gt_instance, 11);

  EXPECT_TRUE(run(d, 0.0335).empty()) << "2e-4 s away is no frame";
  EXPECT_TRUE(run(d, 5.0).empty());
}

TEST(AnnotationsDetector, DefaultNoiseIsDeterministicPerSeedAndOrderFree) {
  const fs::path file = write_file(wardmap::test::scratch_dir(), kThreeFrames);
  const double times[] = {0.0, 0.033333, 0.066667};
  AnnotationNoise noise;  // defaults
  noise.seed = 42;
  AnnotationsDetector forward(file, noise), backward(file, noise);
  std::vector<std::vector<Detection>> a(3), b(3);
  for (int i = 0; i < 3; ++i) a[i] = run(forward, times[i]);
  for (int i = 2; i >= 0; --i) b[i] = run(backward, times[i]);
  for (int i = 0; i < 3; ++i) {
    std::cout << "seed 42, frame " << i + 1 << ":\n" << test::describe(a[i]);
    EXPECT_TRUE(same(a[i], b[i])) << "frame " << i;
    EXPECT_TRUE(same(a[i], run(forward, times[i]))) << "frame " << i << " again";
  }
  // Jitter moves the boxes off the exact annotation.
  ASSERT_FALSE(a[0].empty());
  EXPECT_NE(a[0][0].box, Eigen::Vector4d(100, 50, 180, 300));

  noise.seed = 43;
  AnnotationsDetector other(file, noise);
  int differing = 0;
  for (int i = 0; i < 3; ++i) differing += same(a[i], run(other, times[i])) ? 0 : 1;
  EXPECT_EQ(differing, 3);
}

// Rates of the noise model over many frames of five fully visible objects.
TEST(AnnotationsDetector, NoiseRatesMatchTheOptions) {
  const int frames = 4000;
  std::string text;
  for (int i = 0; i < frames; ++i) {
    text += "{\"timestamp\": " + std::to_string(i / 30.0) + ", \"objects\": [";
    for (int k = 0; k < 5; ++k)
      text += std::string(k ? ", " : "") + "{\"id\": " + std::to_string(k) + ", \"class\": \"chair\", \"box\": [" +
              std::to_string(40 + 110 * k) + ", 100, " + std::to_string(140 + 110 * k) + ", 300], \"visible\": 1.0}";
    text += "]}\n";
  }
  AnnotationNoise noise;
  AnnotationsDetector d(write_file(wardmap::test::scratch_dir(), text), noise);
  int reported = 0, false_positives = 0, confused = 0;
  double sum_sq = 0;
  int jitter_samples = 0;
  for (int i = 0; i < frames; ++i) {
    for (const Detection& det : d.detect(kImage, i / 30.0)) {
      if (det.gt_instance < 0) {
        ++false_positives;
        continue;
      }
      ++reported;
      if (det.label != "chair") ++confused;
      const double dx = (det.box[0] - (40 + 110 * det.gt_instance)) / 100.0;  // box width 100
      sum_sq += dx * dx;
      ++jitter_samples;
    }
  }
  const double miss_rate = 1.0 - reported / (5.0 * frames);
  const double jitter = std::sqrt(sum_sq / jitter_samples);
  std::cout << "miss rate " << miss_rate << ", false positives per frame " << false_positives / double(frames)
            << ", confusion rate " << confused / double(reported) << ", jitter std " << jitter << "\n";
  EXPECT_NEAR(miss_rate, noise.miss_probability, 0.01);
  EXPECT_NEAR(false_positives / double(frames), noise.false_positives_per_frame, 0.015);
  EXPECT_NEAR(confused / double(reported), noise.confusion_probability, 0.004);
  EXPECT_NEAR(jitter, noise.box_jitter, 0.002);
}

TEST(AnnotationsDetector, LowVisibilityIsMissedMoreOften) {
  std::string text;
  for (int i = 0; i < 2000; ++i)
    text += "{\"timestamp\": " + std::to_string(i * 0.1) +
            ", \"objects\": [{\"id\": 1, \"class\": \"door\", \"box\": [10, 10, 60, 200], \"visible\": 0.2}]}\n";
  AnnotationNoise noise;
  noise.false_positives_per_frame = 0;
  AnnotationsDetector d(write_file(wardmap::test::scratch_dir(), text), noise);
  int reported = 0;
  for (int i = 0; i < 2000; ++i) reported += static_cast<int>(d.detect(kImage, i * 0.1).size());
  const double expected = (1 - noise.miss_probability) * (1 - noise.low_visible_miss_probability);
  EXPECT_NEAR(reported / 2000.0, expected, 0.03);
}

std::string error_of(const std::string& text, const fs::path& dir) {
  const fs::path file = write_file(dir, text);
  try {
    AnnotationsDetector d(file, AnnotationNoise::none());
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), file.string());
    return e.what();
  }
  return "(no error)";
}

TEST(AnnotationsDetector, MalformedLinesNameFileAndLine) {
  const fs::path dir = wardmap::test::scratch_dir();
  const std::string file = (dir / "annotations.jsonl").string();
  const std::string first = R"({"timestamp": 0.0, "objects": []})";
  std::string e = error_of(first + "\n{\"timestamp\": 0.1, \"objects\": [\n", dir);
  EXPECT_NE(e.find(file + ":2:"), std::string::npos) << e;
  EXPECT_NE(e.find("malformed JSON"), std::string::npos) << e;
  e = error_of(first + "\n\n" + R"({"timestamp": 0.1, "objects": [{"id": 1, "class": "door", "visible": 1}]})", dir);
  EXPECT_NE(e.find(file + ":3:"), std::string::npos) << e;
  EXPECT_NE(e.find("'box'"), std::string::npos) << e;
  e = error_of(R"({"objects": []})", dir);
  EXPECT_NE(e.find(":1:"), std::string::npos) << e;
  EXPECT_NE(e.find("'timestamp'"), std::string::npos) << e;
  e = error_of(first + "\n" + R"({"timestamp": 0.00005, "objects": []})", dir);
  EXPECT_NE(e.find(":2:"), std::string::npos) << e;
  EXPECT_NE(e.find("repeats"), std::string::npos) << e;
  e = error_of(R"({"timestamp": 0, "objects": [{"id": 1, "class": "door", "box": [0, 0, 5, 5], "visible": 2}]})", dir);
  EXPECT_NE(e.find("'visible'"), std::string::npos) << e;
  // A number too large for a double (nlohmann's out_of_range, not a parse_error; found by fuzz_annotations).
  e = error_of(first + "\n" + R"({"timestamp": 4e347, "objects": []})", dir);
  EXPECT_NE(e.find(file + ":2: malformed JSON"), std::string::npos) << e;
  EXPECT_NE(e.find("number overflow"), std::string::npos) << e;
}

TEST(AnnotationsDetector, FactoryReadsTheSequenceFolder) {
  const fs::path dir = wardmap::test::scratch_dir();
  write_file(dir, kThreeFrames);
  DetectorOptions o;
  o.kind = "annotations";
  o.noise = AnnotationNoise::none();
  auto d = make_detector(o, dir);
  EXPECT_EQ(d->name(), "annotations");
  EXPECT_EQ(d->detect(cv::Mat(), 0.0).size(), 2u);  // no image: nothing clipped
  try {
    make_detector(o, dir / "missing");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("missing/annotations.jsonl"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace wardmap::semantics
