// Frames rendered per second by the sim rasteriser at 640x480 on one core (RGB + depth + instances,
// no annotations, no challenge effects), and the same with annotations.
#include <benchmark/benchmark.h>

#include "sim/scenario.h"
#include "sim/sequence.h"

namespace {

using wardmap::sim::Frame;
using wardmap::sim::Sequence;
using wardmap::sim::SequenceOptions;

void render_frames(benchmark::State& state, const std::string& name, bool annotate) {
  SequenceOptions o;
  o.width = 640;
  o.height = 480;
  Sequence seq(wardmap::sim::load_scenario(wardmap::sim::resolve_scenario(name)), o);
  Frame f;
  int i = 0;
  for (auto _ : state) {
    int frame = i++ % seq.frame_count();
    while (seq.challenge_at(frame)) frame = i++ % seq.frame_count();  // plain frames only
    seq.render(frame, f, annotate);
    benchmark::DoNotOptimize(f.buffers.rgb.data);
  }
  state.counters["frames_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

void BM_SimRender_AisleStraight(benchmark::State& s) { render_frames(s, "aisle_straight", false); }
void BM_SimRender_Ward(benchmark::State& s) { render_frames(s, "ward", false); }
void BM_SimRender_CorridorLoss(benchmark::State& s) { render_frames(s, "corridor_loss", false); }
void BM_SimRenderAnnotated_Ward(benchmark::State& s) { render_frames(s, "ward", true); }

BENCHMARK(BM_SimRender_AisleStraight)->Unit(benchmark::kMillisecond)->MinTime(3.0);
BENCHMARK(BM_SimRender_Ward)->Unit(benchmark::kMillisecond)->MinTime(3.0);
BENCHMARK(BM_SimRender_CorridorLoss)->Unit(benchmark::kMillisecond)->MinTime(3.0);
BENCHMARK(BM_SimRenderAnnotated_Ward)->Unit(benchmark::kMillisecond)->MinTime(3.0);

}  // namespace

BENCHMARK_MAIN();
