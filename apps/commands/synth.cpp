#include "apps/commands/synth.h"

#include <spdlog/spdlog.h>

#include <memory>
#include <string>

#include "apps/common.h"
#include "apps/interrupt.h"
#include "apps/progress.h"
#include "sim/scenario.h"
#include "sim/sequence.h"
#include "sim/writer.h"

namespace wardmap::apps {

namespace {

struct SynthArgs {
  std::string scenario;
  std::string variant = "slow";
  uint32_t seed = 1;
  int frames = 0;
  int width = 640, height = 480;
  std::string out;
};

void run_synth(const SynthArgs& a) {
  const auto file = sim::resolve_scenario(a.scenario);
  sim::Scenario scenario = sim::load_scenario(file);
  sim::SequenceOptions options;
  options.variant = a.variant == "quick" ? sim::Variant::kQuick : sim::Variant::kSlow;
  options.seed = a.seed;
  options.max_frames = a.frames;
  options.width = a.width;
  options.height = a.height;
  sim::Sequence sequence(std::move(scenario), options);
  spdlog::info("synth: scenario '{}' ({}), variant {}, seed {}: {} frames at {}x{}, {} objects -> {}",
               sequence.scenario().name, file.string(), a.variant, a.seed, sequence.frame_count(), a.width, a.height,
               sequence.scene().objects.size(), a.out);
  Progress progress("synth", static_cast<size_t>(sequence.frame_count()), true);  // on a terminal only
  // A first Ctrl-C or SIGTERM stops after the frame in hand; write_sequence then removes its
  // partial folder, and an earlier sequence at --out is left as it was.
  const InterruptScope interrupt_scope;
  sim::write_sequence(sequence, a.out, [&progress](int done, int total) {
    progress.update(static_cast<size_t>(done));
    if (const int signal = InterruptScope::requested(); signal != 0 && done < total)
      throw Interrupted(signal, "synth interrupted (" + signal_name(signal) + ") after " + std::to_string(done) +
                                    " of " + std::to_string(total) + " frames: nothing written");
  });
  progress.finish();
  spdlog::info("synth: wrote {}", a.out);
}

std::string builtin_list() {
  std::string s;
  for (const auto& n : sim::builtin_scenarios()) s += (s.empty() ? "" : ", ") + n;
  return s.empty() ? "(none found)" : s;
}

}  // namespace

void add_synth_command(CLI::App& app) {
  auto args = std::make_shared<SynthArgs>();
  CLI::App* cmd = app.add_subcommand(
      "synth",
      "Render a synthetic hospital sequence (corridors, wards, doors, chairs, beds ...) with full ground truth: "
      "TUM RGB-D layout (rgb/, depth/, rgb.txt, depth.txt, groundtruth.txt), ORB-SLAM3 settings.yaml, "
      "objects.json, annotations.jsonl and challenges.txt.");
  cmd->add_option("--scenario", args->scenario,
                  "Built-in scenario name (" + builtin_list() + ") or the path of a scenario YAML file")
      ->required();
  cmd->add_option("--variant", args->variant,
                  "slow: the scenario's own pace; quick: the same path in about half the frames")
      ->check(CLI::IsMember({"slow", "quick"}))
      ->capture_default_str();
  cmd->add_option("--seed", args->seed,
                  "Layout details: placement jitter, appearance variants, posters and texture detail; the same "
                  "scenario and seed give byte-identical files")
      ->check(whole_number())
      ->capture_default_str();
  cmd->add_option("--frames", args->frames, "Render only the first N frames (0: the whole path)")
      ->check(whole_number())
      ->capture_default_str();
  cmd->add_option("--width", args->width, "Image width in pixels (the focal length scales with it)")
      ->check(CLI::Range(32, 8192))
      ->capture_default_str();
  cmd->add_option("--height", args->height, "Image height in pixels")
      ->check(CLI::Range(32, 8192))
      ->capture_default_str();
  cmd->add_option("--out", args->out,
                  "Output folder; written to a temporary folder beside it and renamed when complete. An earlier "
                  "synth output there is replaced")
      ->required();
  cmd->callback([args]() { run_synth(*args); });
}

}  // namespace wardmap::apps
