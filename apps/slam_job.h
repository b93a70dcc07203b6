// The SLAM front-process run on a sequence (wardmap run --poses slam): tracking and local mapping,
// then the run folder's trajectory, frames, keyframes, point cloud, timings and report.
#pragma once

#include <filesystem>
#include <string>

#include "apps/semantic_job.h"

namespace wardmap::apps {

struct SlamJob {
  std::filesystem::path sequence;
  std::filesystem::path settings;  // empty: the sequence folder's settings.yaml
  std::filesystem::path out;
  std::string mode;  // "rgbd", "mono", or empty: rgbd when the sequence has depth, else mono
  bool progress = true;
  bool deterministic = false;  // local mapping on the tracking thread: identical output on reruns
  // When set, the semantic layer maps the objects on the final map's keyframes.
  const SemanticJob* objects = nullptr;
};

// Returns the tracking rate (%) when the sequence has ground truth, else -1.
double run_slam_job(const SlamJob& job);

}  // namespace wardmap::apps
