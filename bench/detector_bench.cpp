// Latency of the network back-ends on one real photo (bus.jpg, 810x1080): YOLOX-nano and NanoDet-m
// per frame (letterbox + forward + decode + NMS), OSNet x0.25 per crop; YOLOX-nano also on a
// 7-Scenes frame (640x480) and a KITTI 03 frame (1241x376), whose letterbox canvases are cut to
// 416x352 and 416x160 (input.canvas_multiple). Skipped when ../shared/models or the images are
// missing. OpenCV's default thread count.
#include <benchmark/benchmark.h>

#include <memory>
#include <opencv2/imgcodecs.hpp>

#include "bench/bench_support.h"
#include "semantics/detection/detector_factory.h"
#include "semantics/detection/embedder.h"
#include "semantics/detection/model_search.h"

namespace wardmap::bench {
namespace {

cv::Mat bus_photo() { return cv::imread((data_dir() / "images" / "bus.jpg").string(), cv::IMREAD_COLOR); }

void run_detector(benchmark::State& state, const char* kind, const std::string& image_file = "images/bus.jpg",
                  const char* landmark_set = "road") {
  const cv::Mat image = cv::imread((data_dir() / image_file).string(), cv::IMREAD_COLOR);
  if (image.empty()) return state.SkipWithError(("../shared/data/" + image_file + " not found").c_str());
  std::unique_ptr<semantics::Detector> detector;
  try {
    semantics::DetectorOptions options;
    options.kind = kind;
    options.landmark_set = landmark_set;
    detector = semantics::make_detector(options);
  } catch (const std::exception& e) {
    return state.SkipWithError(e.what());
  }
  detector->detect(image, 0.0);  // warm-up: first forward allocates
  size_t detections = 0;
  for (auto _ : state) detections = detector->detect(image, 0.0).size();
  state.SetLabel(detector->name() + ", " + std::to_string(image.cols) + "x" + std::to_string(image.rows) + ", " +
                 std::to_string(detections) + " detections");
}

void BM_DetectYoloxNano(benchmark::State& s) { run_detector(s, "yolox"); }
void BM_DetectNanodetM(benchmark::State& s) { run_detector(s, "nanodet"); }
BENCHMARK(BM_DetectYoloxNano)->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK(BM_DetectNanodetM)->Unit(benchmark::kMillisecond)->MinTime(2.0);
void BM_DetectYoloxNano7Scenes(benchmark::State& s) { run_detector(s, "yolox", "7scenes-redkitchen/frame-000000.color.jpg", "indoor"); }
void BM_DetectYoloxNanoKitti(benchmark::State& s) { run_detector(s, "yolox", "kitti-odometry-03/sequences/03/image_0/000000.png"); }
BENCHMARK(BM_DetectYoloxNano7Scenes)->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK(BM_DetectYoloxNanoKitti)->Unit(benchmark::kMillisecond)->MinTime(2.0);

void BM_EmbedOsnetCrop(benchmark::State& state) {
  const cv::Mat image = bus_photo();
  if (image.empty()) return state.SkipWithError("../shared/data/images/bus.jpg not found");
  std::unique_ptr<semantics::Embedder> embedder;
  try {
    embedder = std::make_unique<semantics::Embedder>(semantics::find_embedder_file());
  } catch (const std::exception& e) {
    return state.SkipWithError(e.what());
  }
  const Eigen::Vector4d person(50, 395, 216, 898);
  embedder->embed(image, person);
  for (auto _ : state) benchmark::DoNotOptimize(embedder->embed(image, person).data());
  state.SetLabel("OSNet x0.25, one 166x503 crop");
}
BENCHMARK(BM_EmbedOsnetCrop)->Unit(benchmark::kMillisecond)->MinTime(2.0);

}  // namespace
}  // namespace wardmap::bench
