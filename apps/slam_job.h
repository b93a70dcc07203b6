// The SLAM front-process run on a sequence (wardmap run --poses slam): tracking and local mapping,
// then the run folder's trajectory, frames, keyframes, point cloud, timings and report.
#pragma once

#include <filesystem>
#include <string>

#include "apps/semantic_job.h"
#include "slam/io/sequence.h"

namespace wardmap::apps {

struct SlamJob {
  std::filesystem::path sequence;
  std::filesystem::path settings;  // empty: default_settings(the sequence's info)
  std::filesystem::path out;
  std::string mode;  // "rgbd", "mono", or empty: rgbd when the sequence has depth, else mono
  bool progress = true;
  bool deterministic = false;        // local mapping on the tracking thread: identical output on reruns
  std::filesystem::path vocabulary;  // empty: $WARDMAP_VOCABULARY, then data/vocabulary/orb-k10l4.bin
  // When set, the semantic layer maps the objects on the final map's keyframes.
  const SemanticJob* objects = nullptr;
  // Feed the frames no faster than their timestamps, as a live camera would, so that the mapper
  // thread has the time it would have live (offline input otherwise arrives 3-8x faster). Threaded only.
  bool realtime = false;
  slam::io::ReaderOptions reader{};  // --format, --first-frame, --frames, ...
  std::vector<slam::io::SettingOverride> settings_overrides{};  // --set KEY=VALUE, over the settings file's keys
};

// The place-recognition vocabulary: `given`, else $WARDMAP_VOCABULARY, else the project's shipped one;
// empty when none is found. Throws InputError when a named file is missing.
std::filesystem::path find_vocabulary(const std::filesystem::path& given);

// Settings for a run given no --settings: the sequence's own settings.yaml (wardmap synth writes one),
// else the shipped data/settings/ file that fits its dataset (as `wardmap info` suggests: KITTI by
// image width, 7-Scenes, EuRoC, TUM by freiburg1/2/3 in its name); empty when neither.
std::filesystem::path default_settings(const slam::io::SequenceInfo& info);

// Returns the tracking rate (%) when the sequence has ground truth, else -1.
double run_slam_job(const SlamJob& job);

}  // namespace wardmap::apps
