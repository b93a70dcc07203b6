// wardmap info <dataset>: what a sequence holds.
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>

#include "apps/commands/commands.h"
#include "apps/common.h"
#include "slam/core/errors.h"
#include "slam/io/sequence.h"
#include "slam/io/settings.h"
#include "slam/io/text_file.h"

namespace wardmap::apps {

namespace fs = std::filesystem;

namespace {

struct InfoArgs {
  std::string path, settings, json;
  ReaderArgs reader;
};

void run_info(const InfoArgs& a) {
  const auto reader = slam::io::open_sequence(a.path, reader_options(a.reader));
  const auto& in = reader->info();
  const std::string suggestion = slam::io::suggest_settings_name(slam::io::to_string(in.kind), in.root, in.width);

  std::optional<slam::io::Settings> settings;
  if (!a.settings.empty()) {
    settings = slam::io::load_settings(a.settings);
    const auto& c = settings->camera.camera;
    if (c.width != in.width || c.height != in.height)
      throw InputError(a.settings, "Camera.width/height " + std::to_string(c.width) + "x" + std::to_string(c.height) +
                                       " do not match the sequence's images " + std::to_string(in.width) + "x" +
                                       std::to_string(in.height));
  }

  std::string calib;
  if (in.calibration) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "fx %.3f fy %.3f cx %.3f cy %.3f (from %s)", in.calibration->fx, in.calibration->fy,
                  in.calibration->cx, in.calibration->cy, in.calibration_source.c_str());
    calib = buf;
  } else if (settings) {
    calib = "from " + a.settings;
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
  else std::printf("ground truth:  no\n");
  if (!in.notes.empty()) std::printf("notes:         %s\n", in.notes.c_str());

  if (!a.json.empty()) {
    nlohmann::json j = {{"kind", slam::io::to_string(in.kind)}, {"path", in.root.string()}, {"frames", in.frame_count},
                        {"duration", in.duration}, {"fps", in.fps}, {"measured_fps", in.measured_fps}, {"width", in.width}, {"height", in.height},
                        {"depth", in.has_depth}, {"ground_truth", in.has_ground_truth},
                        {"frames_with_ground_truth", in.frames_with_ground_truth}, {"calibration", calib},
                        {"suggested_settings", suggestion}};
    slam::io::write_file_atomic(a.json, j.dump(2) + "\n");
  }
}

}  // namespace

void add_info_command(CLI::App& app) {
  auto args = std::make_shared<InfoArgs>();
  auto* cmd = app.add_subcommand("info", "Describe a sequence: kind, frames, duration, resolution, calibration, depth, ground truth");
  cmd->add_option("dataset", args->path, "Sequence folder (TUM RGB-D, KITTI, EuRoC, 7-Scenes, images) or video file")->required();
  add_reader_options(cmd, args->reader);
  cmd->add_option("--settings", args->settings, "Also load and validate this settings YAML against the sequence");
  cmd->add_option("--json", args->json, "Also write the description as JSON to this file");
  cmd->callback([args] { run_info(*args); });
}

}  // namespace wardmap::apps
