// Front-process speed on the shared 7-Scenes redkitchen RGB-D recording: ORB extraction per
// 640x480 frame, and tracking per frame (median, p95 as counters; inline mapping reported apart).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "bench/bench_support.h"
#include "slam/front/front_process.h"
#include "slam/front/orb_extractor.h"
#include "slam/io/sequence.h"
#include "slam/io/settings.h"

namespace wardmap::bench {
namespace {

const char* kKitchen = "7scenes-redkitchen";

std::filesystem::path settings_file() {
  return std::filesystem::path(WARDMAP_PROJECT_DIR) / "data/settings/7Scenes.yaml";
}

void BM_OrbExtract640x480(benchmark::State& state) {
  const auto root = data_dir() / kKitchen;
  if (!std::filesystem::exists(root)) return state.SkipWithError("shared sequence not found");
  auto reader = slam::io::open_sequence(root);
  const slam::FrontOptions options = slam::load_front_options(slam::io::load_settings(settings_file()));
  slam::OrbExtractor extractor(options.orb);
  std::vector<cv::Mat> grey;
  for (size_t i = 0; i < 20; ++i) {
    cv::Mat g;
    cv::cvtColor(reader->read(i * 10).image, g, cv::COLOR_BGR2GRAY);
    grey.push_back(g);
  }
  size_t i = 0, n = 0;
  for (auto _ : state) {
    const slam::OrbFeatures f = extractor.extract(grey[i]);
    benchmark::DoNotOptimize(f.keypoints.data());
    n += f.keypoints.size();
    i = (i + 1) % grey.size();
  }
  state.counters["keypoints"] = benchmark::Counter(static_cast<double>(n), benchmark::Counter::kAvgIterations);
}
BENCHMARK(BM_OrbExtract640x480)->Unit(benchmark::kMillisecond)->MinTime(2.0);

// The first 300 frames tracked once per iteration; per-frame figures as counters.
void BM_FrontProcessKitchenRgbd(benchmark::State& state) {
  const auto root = data_dir() / kKitchen;
  if (!std::filesystem::exists(root)) return state.SkipWithError("shared sequence not found");
  const slam::io::Settings settings = slam::io::load_settings(settings_file());
  const slam::FrontOptions options = slam::load_front_options(settings);
  slam::io::ReaderOptions ro;
  ro.depth_factor = settings.camera.depth_map_factor;
  auto reader = slam::io::open_sequence(root, ro);
  const size_t n = std::min<size_t>(300, reader->size());
  std::vector<slam::io::Frame> frames;
  for (size_t i = 0; i < n; ++i) frames.push_back(reader->read(i));
  std::vector<double> total, tracking;
  double tracked = 0;
  for (auto _ : state) {
    slam::FrontProcess front(options, settings.camera.camera);
    for (const auto& f : frames) {
      const slam::FrameResult r = front.process(f);
      total.push_back(r.seconds);
      tracking.push_back(r.seconds - r.mapping_seconds);
      tracked += r.tracked ? 1 : 0;
    }
  }
  auto pct = [](std::vector<double> v, double p) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : 1e3 * v[std::min(v.size() - 1, static_cast<size_t>(p * v.size()))];
  };
  state.counters["median_ms"] = pct(total, 0.5);
  state.counters["p95_ms"] = pct(total, 0.95);
  state.counters["tracking_median_ms"] = pct(tracking, 0.5);
  state.counters["tracked_pct"] = 100.0 * tracked / static_cast<double>(total.size());
  state.SetItemsProcessed(static_cast<int64_t>(total.size()));
}
BENCHMARK(BM_FrontProcessKitchenRgbd)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace
}  // namespace wardmap::bench
