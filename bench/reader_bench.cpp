// Decode rate of each reader on the shared sequences (frames/s, reported as items_per_second).
#include <benchmark/benchmark.h>

#include "bench/bench_support.h"
#include "slam/io/sequence.h"

namespace wardmap::bench {
namespace {

void decode_sequence(benchmark::State& state, const char* sub) {
  const auto root = data_dir() / sub;
  if (!std::filesystem::exists(root)) {
    state.SkipWithError((std::string("shared sequence not found: ") + root.string()).c_str());
    return;
  }
  auto reader = slam::io::open_sequence(root);
  size_t i = 0, frames = 0;
  for (auto _ : state) {
    const slam::io::Frame f = reader->read(i);
    benchmark::DoNotOptimize(f.image.data);
    i = (i + 1) % reader->size();
    ++frames;
  }
  state.SetItemsProcessed(static_cast<int64_t>(frames));
  state.SetLabel(slam::io::to_string(reader->info().kind) + ", " + std::to_string(reader->info().width) + "x" +
                 std::to_string(reader->info().height) + (reader->info().has_depth ? " + depth" : ""));
}

void BM_ReadKitti03(benchmark::State& s) { decode_sequence(s, "kitti-odometry-03"); }
void BM_Read7ScenesRgbd(benchmark::State& s) { decode_sequence(s, "7scenes-redkitchen"); }
BENCHMARK(BM_ReadKitti03)->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK(BM_Read7ScenesRgbd)->Unit(benchmark::kMillisecond)->MinTime(2.0);

void BM_OpenSequence(benchmark::State& state) {
  const auto root = data_dir() / "7scenes-redkitchen";
  if (!std::filesystem::exists(root)) return state.SkipWithError("shared sequence not found");
  for (auto _ : state) benchmark::DoNotOptimize(slam::io::open_sequence(root)->size());
}
BENCHMARK(BM_OpenSequence)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace wardmap::bench
