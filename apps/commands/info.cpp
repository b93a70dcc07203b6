// wardmap info <dataset>: what a sequence holds.
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>

#include "apps/commands/commands.h"
#include "apps/common.h"
#include "apps/slam_job.h"
#include "semantics/detection/detector_options.h"
#include "semantics/options.h"
#include "slam/core/errors.h"
#include "slam/front/front_options.h"
#include "slam/io/sequence.h"
#include "slam/io/settings.h"
#include "slam/io/text_file.h"

namespace wardmap::apps {

namespace fs = std::filesystem;

namespace {

struct InfoArgs {
  std::string path, settings, json;
  std::vector<std::string> set;  // --set KEY=VALUE
  ReaderArgs reader;
};

// A settings file read as `wardmap run` reads it: the camera, the front-process's keys and the
// semantics and detection sections, each validated (an error names the file or the --set).
slam::io::Settings check_settings(const fs::path& file, const std::vector<slam::io::SettingOverride>& overrides) {
  slam::io::Settings settings;
  slam::io::blame_overrides(overrides, [&] {
    settings = slam::io::load_settings(file, overrides);
    slam::load_front_options(settings);
    semantics::load_semantic_options(settings.section("semantics"), file);
    semantics::detector_options_from_yaml(settings.section("detection"), file);
  });
  return settings;
}

void run_info(const InfoArgs& a) {
  check_output_files({{a.json, "--json"}});
  const auto reader = slam::io::open_sequence(a.path, reader_options(a.reader));
  const auto& in = reader->info();
  const std::string suggestion = slam::io::suggest_settings_name(slam::io::to_string(in.kind), in.root, in.width);

  // --set alone is checked against the file a SLAM run would read.
  const auto overrides = parse_set_options(a.set);
  fs::path settings_file = a.settings;
  if (settings_file.empty() && !overrides.empty()) {
    settings_file = default_settings(in);
    if (settings_file.empty())
      throw InputError("--set", "no settings file to set it in: the sequence has no settings.yaml and no shipped one "
                                "fits; give --settings");
  }
  std::optional<slam::io::Settings> settings;
  if (!settings_file.empty()) {
    settings = check_settings(settings_file, overrides);
    slam::io::fit_settings_to_sequence(*settings, in, overrides);
  }

  std::string calib;
  if (in.calibration) {
    calib = slam::io::describe_intrinsics(*in.calibration) + " (from " + in.calibration_source + ")";
  } else if (settings) {
    calib = "from " + settings_file.string();
  } else {
    calib = "none in the dataset";
    if (!suggestion.empty()) calib += "; shipped settings: data/settings/" + suggestion;
  }

  std::printf("kind:          %s\n", slam::io::to_string(in.kind).c_str());
  std::printf("path:          %s\n", in.root.c_str());
  std::printf("frames:        %zu\n", in.frame_count);
  std::printf("duration:      %.2f s at %.2f Hz", in.duration, in.fps);
  if (in.measured_fps > 0 && std::abs(in.measured_fps - in.fps) > 0.01 * in.fps)
    std::printf(" nominal (%.2f Hz from the timestamps)", in.measured_fps);
  std::printf("\n");
  std::printf("resolution:    %dx%d\n", in.width, in.height);
  std::printf("calibration:   %s\n", calib.c_str());
  if (in.has_depth) std::printf("depth:         yes (factor %g per metre)\n", in.depth_factor);
  else std::printf("depth:         no\n");
  if (in.has_ground_truth)
    std::printf("ground truth:  yes (%zu of %zu frames, %zu poses)\n", in.frames_with_ground_truth, in.frame_count,
                reader->ground_truth().size());
  else if (!in.ground_truth_unmatched.empty())
    std::printf("ground truth:  no (%s)\n", in.ground_truth_unmatched.c_str());
  else std::printf("ground truth:  no\n");
  if (!in.notes.empty()) std::printf("notes:         %s\n", in.notes.c_str());
  if (settings) {
    std::printf("settings:      %s%s: valid (camera, tracking, mapping, semantics, detection)%s\n",
                settings_file.c_str(), overrides_text(overrides).c_str(),
                settings->notes.empty() ? "" : ", with notes:");
    for (const std::string& note : settings->notes) std::printf("               %s\n", note.c_str());
  }

  if (!a.json.empty()) {
    nlohmann::json j = {{"kind", slam::io::to_string(in.kind)}, {"path", in.root.string()}, {"frames", in.frame_count},
                        {"duration", in.duration}, {"fps", in.fps}, {"measured_fps", in.measured_fps}, {"width", in.width}, {"height", in.height},
                        {"depth", in.has_depth}, {"ground_truth", in.has_ground_truth},
                        {"frames_with_ground_truth", in.frames_with_ground_truth}, {"calibration", calib},
                        {"suggested_settings", suggestion}};
    if (!in.ground_truth_unmatched.empty()) j["ground_truth_unmatched"] = in.ground_truth_unmatched;
    if (!in.notes.empty()) j["notes"] = in.notes;
    if (settings) {
      j["settings"] = settings_file.string();
      j["settings_overrides"] = overrides_json(overrides);
      j["settings_notes"] = settings->notes;
    }
    slam::io::write_file_atomic(a.json, j.dump(2) + "\n");
  }
}

}  // namespace

void add_info_command(CLI::App& app) {
  auto args = std::make_shared<InfoArgs>();
  auto* cmd = app.add_subcommand("info", "Describe a sequence: kind, frames, duration, resolution, calibration, depth, ground truth");
  cmd->add_option("dataset", args->path, "Sequence folder (TUM RGB-D, KITTI, EuRoC, 7-Scenes, images) or video file")->required();
  add_reader_options(cmd, args->reader);
  cmd->add_option("--settings", args->settings,
                  "Also read this settings YAML as `wardmap run` would, and validate it against the sequence: the\n"
                  "camera (its size against the images'), and the tracking, mapping, semantics and detection keys");
  add_set_option(cmd, args->set,
                 "Checked with the rest; without --settings, over the file a SLAM run would read (the sequence's\n"
                 "settings.yaml, else the shipped one for its dataset)");
  cmd->add_option("--json", args->json, "Also write the description as JSON to this file");
  cmd->callback([args] { run_info(*args); });
}

}  // namespace wardmap::apps
