// Object map files (FORMATS.md): objects.json (estimated or true objects) and measurements.jsonl.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "semantics/object_association.h"
#include "semantics/object_measurement.h"

namespace wardmap::semantics {

struct TrueObject {
  int id = -1;
  std::string label;
  ObjectPose pose;
};

// objects.json: {"objects": [{"id", "class", "position", "rotation_xyzw", "size", "measurements"}]}
std::string format_objects_json(const std::vector<ObjectLandmark>& landmarks);
// measurements.jsonl: one line per measurement {"keyframe", "timestamp", "class", "box", "score",
// "track", "group", "landmark"} (+ "gt_instance" when known, "position" when placed).
std::string format_measurements_jsonl(const std::vector<ObjectMeasurement>& measurements, const AssociationResult& result);

// Reads an objects.json (a synthetic sequence's truth or a run's output); throws InputError naming
// the file and the offending entry.
std::vector<TrueObject> read_objects_json(const std::filesystem::path& file);

struct MeasurementRecord {
  int keyframe = -1;
  double timestamp = 0;
  std::string label;
  Eigen::Vector4d box = Eigen::Vector4d::Zero();
  float score = 0;
  int track = -1, group = -1, landmark = -1, gt_instance = -1;
};
std::vector<MeasurementRecord> read_measurements_jsonl(const std::filesystem::path& file);

}  // namespace wardmap::semantics
