// Writes a Sequence in the TUM RGB-D layout plus wardmap's ground truth (../shared/docs/FORMATS.md):
// rgb/, depth/, rgb.txt, depth.txt, groundtruth.txt, settings.yaml, objects.json, annotations.jsonl,
// challenges.txt. Everything goes to a temporary folder beside `out` that is renamed at the end.
#pragma once

#include <filesystem>
#include <functional>
#include <string>

#include "sim/sequence.h"

namespace wardmap::sim {

using ProgressFn = std::function<void(int done, int total)>;

constexpr double kDepthFactor = 5000.0;

// Throws wardmap::InputError when `out` exists and is neither empty nor an earlier synth output
// (which is replaced), or when it cannot be written.
void write_sequence(Sequence& sequence, const std::filesystem::path& out, const ProgressFn& progress = {});

// File contents, exposed for tests.
std::string settings_yaml(const Sequence& sequence);
std::string objects_json(const Scene& scene);
std::string annotation_line(double timestamp, const std::vector<Annotation>& annotations);
// Timestamps as written everywhere: 6 decimals.
std::string format_timestamp(double t);
// Metres to the uint16 depth PNG (factor 5000, 0 = invalid or beyond 13.1 m).
cv::Mat depth_to_png16(const cv::Mat& depth_m);

}  // namespace wardmap::sim
