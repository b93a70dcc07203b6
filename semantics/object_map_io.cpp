#include "semantics/object_map_io.h"

#include <fstream>
#include <nlohmann/json.hpp>

#include "slam/core/errors.h"

namespace wardmap::semantics {

namespace fs = std::filesystem;
using nlohmann::json;

std::string format_objects_json(const std::vector<ObjectLandmark>& landmarks) {
  json objs = json::array();
  for (const auto& l : landmarks) {
    const auto& q = l.pose.pose.rotation();
    const auto& t = l.pose.pose.translation();
    objs.push_back({{"id", l.id},
                    {"class", l.label},
                    {"position", {t.x(), t.y(), t.z()}},
                    {"rotation_xyzw", {q.x(), q.y(), q.z(), q.w()}},
                    {"size", {l.pose.size.x(), l.pose.size.y(), l.pose.size.z()}},
                    {"measurements", l.measurements.size()}});
  }
  return json{{"objects", objs}}.dump(2) + "\n";
}

std::string format_measurements_jsonl(const std::vector<ObjectMeasurement>& ms, const AssociationResult& r) {
  std::string out;
  for (const auto& m : ms) {
    json j = {{"keyframe", m.keyframe},
              {"timestamp", m.timestamp},
              {"class", m.label},
              {"box", {m.box(0), m.box(1), m.box(2), m.box(3)}},
              {"score", m.score},
              {"track", r.track_of.empty() ? -1 : r.track_of[m.id]},
              {"group", r.group_of.empty() ? -1 : r.group_of[m.id]},
              {"landmark", r.landmark_of.empty() ? -1 : r.landmark_of[m.id]}};
    if (m.gt_instance >= 0) j["gt_instance"] = m.gt_instance;
    if (m.pose) {
      const auto& t = m.pose->pose.translation();
      j["position"] = {t.x(), t.y(), t.z()};
    }
    out += j.dump() + "\n";
  }
  return out;
}

namespace {

Eigen::VectorXd numbers(const json& j, size_t n, const fs::path& file, const std::string& what) {
  if (!j.is_array() || j.size() != n) throw InputError(file.string(), what + ": expected " + std::to_string(n) + " numbers");
  Eigen::VectorXd v(n);
  for (size_t i = 0; i < n; ++i) {
    if (!j[i].is_number()) throw InputError(file.string(), what + ": expected numbers");
    v(i) = j[i].get<double>();
  }
  return v;
}

}  // namespace

std::vector<TrueObject> read_objects_json(const fs::path& file) {
  std::ifstream in(file);
  if (!in) throw InputError(file.string(), "cannot open");
  json doc;
  try {
    doc = json::parse(in);
  } catch (const json::exception& e) {  // parse_error, or out_of_range for a number too large
    throw InputError(file.string(), std::string("JSON syntax error: ") + e.what());
  }
  if (!doc.contains("objects") || !doc["objects"].is_array()) throw InputError(file.string(), "expected {\"objects\": [...]}");
  std::vector<TrueObject> out;
  for (size_t i = 0; i < doc["objects"].size(); ++i) {
    const json& o = doc["objects"][i];
    const std::string where = "objects[" + std::to_string(i) + "]";
    if (!o.contains("id") || !o["id"].is_number_integer()) throw InputError(file.string(), where + ".id: expected an integer");
    if (!o.contains("class") || !o["class"].is_string()) throw InputError(file.string(), where + ".class: expected a string");
    TrueObject t;
    t.id = o["id"].get<int>();
    t.label = o["class"].get<std::string>();
    const Eigen::VectorXd p = numbers(o.value("position", json()), 3, file, where + ".position");
    const Eigen::VectorXd q = numbers(o.value("rotation_xyzw", json()), 4, file, where + ".rotation_xyzw");
    const Eigen::VectorXd s = numbers(o.value("size", json()), 3, file, where + ".size");
    t.pose.pose = slam::SE3(Eigen::Quaterniond(q(3), q(0), q(1), q(2)), p);
    t.pose.size = s;
    out.push_back(t);
  }
  return out;
}

std::vector<MeasurementRecord> read_measurements_jsonl(const fs::path& file) {
  std::ifstream in(file);
  if (!in) throw InputError(file.string(), "cannot open");
  std::vector<MeasurementRecord> out;
  std::string line;
  long n = 0;
  while (std::getline(in, line)) {
    ++n;
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    try {
      const json j = json::parse(line);
      MeasurementRecord r;
      r.keyframe = j.at("keyframe").get<int>();
      r.timestamp = j.at("timestamp").get<double>();
      r.label = j.at("class").get<std::string>();
      const auto& b = j.at("box");
      r.box = Eigen::Vector4d(b.at(0).get<double>(), b.at(1).get<double>(), b.at(2).get<double>(), b.at(3).get<double>());
      r.score = j.value("score", 0.0f);
      r.track = j.value("track", -1);
      r.group = j.value("group", -1);
      r.landmark = j.value("landmark", -1);
      r.gt_instance = j.value("gt_instance", -1);
      out.push_back(r);
    } catch (const json::exception& e) {
      throw InputError(file.string(), std::string("malformed measurement: ") + e.what(), n);
    }
  }
  return out;
}

}  // namespace wardmap::semantics
