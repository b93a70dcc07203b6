// Place-recognition speed with the shipped vocabulary (data/vocabulary/orb-k10l4.bin): the bag of
// words of 1000 ORB descriptors, and a query on a 500-keyframe database: frames 0-499 of the shared
// 7-Scenes redkitchen recording queried with frames 500, 505, ..., or bags of random descriptors.
#include <benchmark/benchmark.h>

#include <opencv2/imgproc.hpp>
#include <random>
#include <vector>

#include "bench/bench_support.h"
#include "slam/front/orb_extractor.h"
#include "slam/io/sequence.h"
#include "slam/place/keyframe_database.h"

namespace wardmap::bench {
namespace {

using slam::place::BowVector;
using slam::place::KeyframeDatabase;
using slam::place::Vocabulary;

const Vocabulary* shipped_vocabulary() {
  static const Vocabulary* v = [] {
    const auto file = std::filesystem::path(WARDMAP_PROJECT_DIR) / "data/vocabulary/orb-k10l4.bin";
    return std::filesystem::exists(file) ? new Vocabulary(Vocabulary::load(file)) : nullptr;
  }();
  return v;
}

cv::Mat random_descriptors(int n, std::mt19937& rng) {
  cv::Mat m(n, 32, CV_8U);
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < 32; ++c) m.at<std::uint8_t>(r, c) = static_cast<std::uint8_t>(rng() & 0xff);
  return m;
}

void BM_PlaceTransform1000(benchmark::State& state) {
  const Vocabulary* v = shipped_vocabulary();
  if (!v) return state.SkipWithError("data/vocabulary/orb-k10l4.bin not found");
  std::mt19937 rng(1);
  const cv::Mat d = random_descriptors(1000, rng);
  for (auto _ : state) {
    const BowVector bow = v->transform(d);
    benchmark::DoNotOptimize(bow.data());
  }
}
BENCHMARK(BM_PlaceTransform1000)->Unit(benchmark::kMicrosecond);

// Query time on 500 keyframes; queries are other bags of the same source.
void run_queries(benchmark::State& state, const std::vector<BowVector>& keyframes,
                 const std::vector<BowVector>& queries) {
  if (queries.empty()) return state.SkipWithError("no query images");
  KeyframeDatabase db;
  for (std::size_t i = 0; i < keyframes.size(); ++i) db.add(i, keyframes[i]);
  std::size_t i = 0, candidates = 0;
  for (auto _ : state) {
    const auto c = db.query(queries[i], 10);
    benchmark::DoNotOptimize(c.data());
    candidates += c.size();
    i = (i + 1) % queries.size();
  }
  state.counters["candidates"] =
      benchmark::Counter(static_cast<double>(candidates), benchmark::Counter::kAvgIterations);
}

void BM_PlaceQuery500Random(benchmark::State& state) {
  const Vocabulary* v = shipped_vocabulary();
  if (!v) return state.SkipWithError("data/vocabulary/orb-k10l4.bin not found");
  std::mt19937 rng(2);
  std::vector<BowVector> keyframes, queries;
  for (int i = 0; i < 500; ++i) keyframes.push_back(v->transform(random_descriptors(1000, rng)));
  for (int i = 0; i < 20; ++i) queries.push_back(v->transform(random_descriptors(1000, rng)));
  run_queries(state, keyframes, queries);
}
BENCHMARK(BM_PlaceQuery500Random)->Unit(benchmark::kMicrosecond);

void BM_PlaceQuery500Kitchen(benchmark::State& state) {
  const Vocabulary* v = shipped_vocabulary();
  if (!v) return state.SkipWithError("data/vocabulary/orb-k10l4.bin not found");
  const auto root = data_dir() / "7scenes-redkitchen";
  if (!std::filesystem::exists(root)) return state.SkipWithError("shared sequence not found");
  auto reader = slam::io::open_sequence(root);
  if (reader->size() < 520) return state.SkipWithError("sequence shorter than 520 frames");
  const slam::OrbExtractor extractor{slam::OrbOptions{}};
  std::vector<BowVector> keyframes, queries;
  cv::Mat grey;
  for (std::size_t i = 0; i < reader->size() && queries.size() < 20; i += i < 500 ? 1 : 5) {
    cv::cvtColor(reader->read(i).image, grey, cv::COLOR_BGR2GRAY);
    (i < 500 ? keyframes : queries).push_back(v->transform(extractor.extract(grey).descriptors));
  }
  run_queries(state, keyframes, queries);
}
BENCHMARK(BM_PlaceQuery500Kitchen)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace wardmap::bench
