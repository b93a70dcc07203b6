// Front-process speed on the shared sequences: ORB extraction per frame (7-Scenes 640x480, KITTI
// 03), and per-frame tracking with the mapper on its own thread (7-Scenes RGB-D and monocular,
// KITTI 03 monocular); and the memory the map holds over three passes forth and back.
#include <benchmark/benchmark.h>

#include <sys/resource.h>
#include <malloc.h>

#include <algorithm>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "bench/bench_support.h"
#include "slam/front/front_process.h"
#include "slam/front/orb_extractor.h"
#include "slam/io/sequence.h"
#include "slam/io/settings.h"
#include "slam/place/vocabulary.h"

namespace wardmap::bench {
namespace {

const char* kKitchen = "7scenes-redkitchen";

slam::io::Settings shipped_settings(const char* name) {
  return slam::io::load_settings(std::filesystem::path(WARDMAP_PROJECT_DIR) / "data/settings" / name);
}

// ORB extraction per frame of a shared sequence: 20 frames spread over its first 200, with its
// settings' ORB options (7-Scenes: 1000 features at 640x480; KITTI 03: 2000 at 1241x376).
void orb_extract(benchmark::State& state, const char* sequence, const char* settings_name) {
  const auto root = data_dir() / sequence;
  if (!std::filesystem::exists(root)) return state.SkipWithError("shared sequence not found");
  auto reader = slam::io::open_sequence(root);
  const slam::FrontOptions options = slam::load_front_options(shipped_settings(settings_name));
  slam::OrbExtractor extractor(options.orb);
  std::vector<cv::Mat> grey;
  for (size_t i = 0; i < 20; ++i) {
    cv::Mat image = reader->read(i * 10).image, g;
    if (image.channels() == 1) g = image;
    else cv::cvtColor(image, g, cv::COLOR_BGR2GRAY);
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

void BM_OrbExtract640x480(benchmark::State& state) { orb_extract(state, kKitchen, "7Scenes.yaml"); }
void BM_OrbExtractKitti(benchmark::State& state) { orb_extract(state, "kitti-odometry-03", "KITTI03.yaml"); }
BENCHMARK(BM_OrbExtractKitti)->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK(BM_OrbExtract640x480)->Unit(benchmark::kMillisecond)->MinTime(2.0);

// Heap in use now (MB): glibc's allocated bytes over every arena plus its mmapped blocks. Unlike the
// resident size it does not keep what earlier benchmarks of this process freed.
double heap_mb() {
  const struct mallinfo2 m = mallinfo2();
  return static_cast<double>(m.uordblks + m.hblkhd) / (1024.0 * 1024.0);
}

// One pass over a shared sequence with local mapping on its own thread (as `wardmap run` does):
// per-frame tracking time (extraction + tracking, median / p95 / max), the ratio of the median to
// the target, the median extraction time alone, keyframe rate, local BA time per keyframe,
// the largest keyframe queue seen, the keyframes made and kept, the heap the map holds at the end
// and the process's peak resident memory (frames are read as they go, so it is the SLAM's).
// The benchmark's first argument picks tracking.pose_solver: 0 = ceres (the default), 1 = lm; the
// second the optical flow (tracking.flow_extend / _mono): 0 = the settings', 1 = on for every frame (no
// time budget), 2 = off, 3 = on under the settings' time budget (tracking.flow_budget_ms / _mono).
// `passes` > 1 plays the frames forth and back (0 .. n-1, n-2 .. 0, 1 .. n-1, ...) at the sequence's
// frame rate, as a robot going up and down one corridor: the map is revisited, keyframes are made
// and culled, and the memory the map holds at the end (map_mb: the heap in use after the run, the
// front-process still alive, less before it) should follow the keyframes kept, not those made.
// `stop_frames` > 0 plays one pass with the middle frame shown that many more times, each with its
// own image noise (sigma 3, seeded), as a robot waiting at a door: stop_keyframes counts the
// keyframes made while it stands still (tracking.keyframe_still_px; a third argument 1 turns that
// rule off, for the comparison).
void run_front(benchmark::State& state, const char* sequence, const char* settings_name, bool mono, size_t max_frames,
               double target_ms, int passes = 1, size_t stop_frames = 0) {
  const auto root = data_dir() / sequence;
  if (!std::filesystem::exists(root)) return state.SkipWithError("shared sequence not found");
  const slam::io::Settings settings = shipped_settings(settings_name);
  slam::FrontOptions options = slam::load_front_options(settings);
  options.monocular = mono;
  options.mapping_thread = true;
  options.tracking.pose_solver = state.range(0) == 1 ? "lm" : "ceres";
  if (state.range(1) != 0) options.tracking.flow_extend = options.tracking.flow_extend_mono = state.range(1) != 2;
  if (state.range(1) == 1) options.tracking.flow_budget_ms = options.tracking.flow_budget_ms_mono = 0;
  if (stop_frames > 0 && state.range(2) == 1) options.tracking.keyframe_still_px = 0;
  slam::io::ReaderOptions ro;
  ro.depth_factor = settings.camera.depth_map_factor;
  auto reader = slam::io::open_sequence(root, ro);
  const size_t n = std::min<size_t>(max_frames, reader->size());
  if (passes > 1 && n < 2) return state.SkipWithError("too few frames to play back and forth");
  const size_t stop = n / 2;  // the frame shown again during a stop
  const size_t frames = passes > 1 ? static_cast<size_t>(passes) * (n - 1) + 1 : n + stop_frames;
  const double period = n > 1 ? (reader->timestamp(n - 1) - reader->timestamp(0)) / static_cast<double>(n - 1) : 0;
  cv::RNG noise_rng(1);
  const auto frame_at = [&](size_t k) {
    if (stop_frames > 0 && k > stop) {
      const bool still = k <= stop + stop_frames;
      slam::io::Frame f = reader->read(still ? stop : k - stop_frames);
      if (still) {
        cv::Mat image, noise(f.image.size(), CV_32FC(f.image.channels()));
        f.image.convertTo(image, CV_32F);
        noise_rng.fill(noise, cv::RNG::NORMAL, 0.0, 3.0);
        image += noise;
        image.convertTo(f.image, f.image.type());
      }
      f.index = k;
      f.timestamp = reader->timestamp(0) + static_cast<double>(k) * period;
      return f;
    }
    if (passes <= 1) return reader->read(k);
    const size_t cycle = 2 * (n - 1), j = k % cycle;
    slam::io::Frame f = reader->read(j < n ? j : cycle - j);
    f.index = k;
    f.timestamp = reader->timestamp(0) + static_cast<double>(k) * period;
    return f;
  };
  auto vocabulary = std::make_shared<const slam::place::Vocabulary>(
      slam::place::Vocabulary::load(std::filesystem::path(WARDMAP_PROJECT_DIR) / "data/vocabulary/orb-k10l4.bin"));
  std::vector<double> seconds, extract_seconds;
  double tracked = 0, keyframes = 0, ba_seconds = 0, mapped = 0, waited = 0, flowed = 0, stop_keyframes = 0;
  double mapping_seconds = 0;
  size_t max_queue = 0, kept = 0;
  double map_mb = 0;
  for (auto _ : state) {
    const double before_mb = heap_mb();
    slam::FrontProcess front(options, settings.camera.camera);
    front.set_vocabulary(vocabulary);
    for (size_t i = 0; i < frames; ++i) {
      const slam::FrameResult r = front.process(frame_at(i));  // r.seconds excludes reading
      seconds.push_back(r.seconds);  // without waiting for the mapper (r.wait_seconds)
      extract_seconds.push_back(r.extract_seconds);
      waited += r.wait_seconds;
      tracked += r.tracked ? 1 : 0;
      keyframes += r.keyframe ? 1 : 0;
      if (r.keyframe && i > stop && i <= stop + stop_frames) ++stop_keyframes;
      flowed += r.flow ? 1 : 0;
      max_queue = std::max(max_queue, front.mapper_queue_length());
    }
    front.finish();
    ba_seconds += front.mapper_stats().t_ba;
    mapping_seconds += front.mapper_stats().total_seconds();
    mapped += front.mapper_stats().keyframes;
    kept += front.submap().num_keyframes();
    map_mb += heap_mb() - before_mb;
  }
  auto pct = [](std::vector<double> v, double p) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : 1e3 * v[std::min(v.size() - 1, static_cast<size_t>(p * v.size()))];
  };
  state.counters["median_ms"] = pct(seconds, 0.5);
  state.counters["p95_ms"] = pct(seconds, 0.95);
  state.counters["max_ms"] = pct(seconds, 1.0);
  state.counters["median_vs_target"] = pct(seconds, 0.5) / target_ms;
  // The feature extraction inside those times (FrameResult::extract_seconds: the grey image, ORB,
  // the depth samples and the flow's pyramid): half to three quarters of them, and the part that
  // shows best how fast the host is that hour (ORB alone 4.5-4.8 ms a 7-Scenes frame on a quiet one).
  state.counters["extract_median_ms"] = pct(extract_seconds, 0.5);
  state.counters["tracked_pct"] = 100.0 * tracked / static_cast<double>(seconds.size());
  state.counters["flow_pct"] = 100.0 * flowed / static_cast<double>(seconds.size());  // frames with the flow on
  state.counters["keyframe_pct"] = 100.0 * keyframes / static_cast<double>(seconds.size());
  state.counters["keyframes_made"] = keyframes / static_cast<double>(state.iterations());
  state.counters["keyframes_kept"] = static_cast<double>(kept) / static_cast<double>(state.iterations());
  if (stop_frames > 0) {
    state.counters["stop_keyframes"] = stop_keyframes / static_cast<double>(state.iterations());
    state.counters["mapping_s"] = mapping_seconds / static_cast<double>(state.iterations());  // the mapper's work in all
  }
  state.counters["map_mb"] = map_mb / static_cast<double>(state.iterations());
  state.counters["ba_ms_per_kf"] = mapped > 0 ? 1e3 * ba_seconds / mapped : 0.0;
  state.counters["max_kf_queue"] = static_cast<double>(max_queue);
  // Time the tracker waited for a mapper still busy mapping.max_lag_frames after a keyframe, per
  // frame (offline input arrives faster than a camera's; not in the tracking times above).
  state.counters["wait_ms_per_frame"] = 1e3 * waited / static_cast<double>(seconds.size());
  struct rusage usage {};
  getrusage(RUSAGE_SELF, &usage);
  state.counters["peak_rss_mb"] = static_cast<double>(usage.ru_maxrss) / 1024.0;
  state.SetItemsProcessed(static_cast<int64_t>(seconds.size()));
}

void BM_FrontKitchenRgbd(benchmark::State& state) { run_front(state, kKitchen, "7Scenes.yaml", false, 600, 15.0); }
void BM_FrontKitchenMono(benchmark::State& state) { run_front(state, kKitchen, "7Scenes-colour.yaml", true, 600, 10.0); }
void BM_FrontKittiMono(benchmark::State& state) {
  run_front(state, "kitti-odometry-03", "KITTI03.yaml", true, 400, 15.0);
}
// Three passes forth and back: the memory a longer run holds (map_mb against keyframes_kept).
void BM_FrontKitchenRgbdBackAndForth(benchmark::State& state) {
  run_front(state, kKitchen, "7Scenes.yaml", false, 600, 15.0, 3);
}
void BM_FrontKittiMonoBackAndForth(benchmark::State& state) {
  run_front(state, "kitti-odometry-03", "KITTI03.yaml", true, 400, 15.0, 3);
}
// A 10 s stop in the middle of the kitchen (300 frames): keyframes made while standing still.
void BM_FrontKitchenRgbdStop(benchmark::State& state) { run_front(state, kKitchen, "7Scenes.yaml", false, 600, 15.0, 1, 300); }
void BM_FrontKitchenMonoStop(benchmark::State& state) {
  run_front(state, kKitchen, "7Scenes-colour.yaml", true, 600, 10.0, 1, 300);
}
BENCHMARK(BM_FrontKitchenRgbd)->ArgNames({"lm", "flow"})->Args({0, 0})->Args({1, 0})->Args({0, 1})->Args({0, 3})->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_FrontKitchenMono)->ArgNames({"lm", "flow"})->Args({0, 0})->Args({1, 0})->Args({0, 1})->Args({0, 3})->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_FrontKittiMono)->ArgNames({"lm", "flow"})->Args({0, 0})->Args({1, 0})->Args({0, 1})->Args({0, 3})->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_FrontKitchenRgbdBackAndForth)->ArgNames({"lm", "flow"})->Args({0, 0})->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_FrontKittiMonoBackAndForth)->ArgNames({"lm", "flow"})->Args({0, 0})->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_FrontKitchenRgbdStop)->ArgNames({"lm", "flow", "still_off"})->Args({0, 0, 0})->Args({0, 0, 1})->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_FrontKitchenMonoStop)->ArgNames({"lm", "flow", "still_off"})->Args({0, 0, 0})->Args({0, 0, 1})->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace
}  // namespace wardmap::bench
