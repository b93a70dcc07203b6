// EuRoC MAV: mav0/cam0/data.csv (`timestamp_ns,filename`), mav0/cam0/data/*.png, mav0/cam0/sensor.yaml,
// mav0/state_groundtruth_estimate0/data.csv (body pose T_WB; the camera pose is T_WB * T_BS).
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <limits>

#include "slam/core/errors.h"
#include "slam/io/sequence.h"
#include "slam/io/settings.h"
#include "slam/io/text_file.h"
#include "slam/io/trajectory_io.h"

namespace wardmap::slam::io {

namespace fs = std::filesystem;

namespace {

std::vector<double> yaml_numbers(const YAML::Node& node, const fs::path& file, const char* key, size_t n) {
  std::vector<double> v;
  try {
    const YAML::Node list = node["data"] ? node["data"] : node;
    for (const auto& x : list) v.push_back(x.as<double>());
  } catch (const YAML::Exception&) {
    throw InputError(file.string(), std::string("key '") + key + "': expected a list of numbers");
  }
  if (v.size() != n)
    throw InputError(file.string(), std::string("key '") + key + "': expected " + std::to_string(n) + " numbers, got " +
                                        std::to_string(v.size()));
  return v;
}

class EurocReader : public SequenceReader {
 public:
  EurocReader(const fs::path& root, const ReaderOptions& o) {
    info_.kind = DatasetKind::Euroc;
    info_.root = root;
    const fs::path mav = fs::exists(root / "mav0") ? root / "mav0" : root;
    const fs::path cam = mav / "cam0";
    const fs::path csv = cam / "data.csv";
    double previous = -std::numeric_limits<double>::infinity();
    for_each_data_line(csv, true, [&](long line, const std::vector<std::string>& tok) {
      if (tok.size() != 2) throw InputError(csv.string(), "expected 'timestamp_ns,filename'", line);
      const double t = static_cast<double>(parse_int(tok[0], csv, line, "timestamp [ns]")) * 1e-9;
      check_increasing(t, previous, csv, line);
      previous = t;
      Entry e;
      e.timestamp = t;
      e.image = cam / "data" / tok[1];
      e.listed_in = csv;
      e.line = line;
      entries_.push_back(std::move(e));
    });

    SE3 T_BS;
    const fs::path sensor = cam / "sensor.yaml";
    if (fs::exists(sensor)) {
      YAML::Node y;
      try {
        y = YAML::LoadFile(sensor.string());
      } catch (const YAML::Exception& ex) {
        throw InputError(sensor.string(), std::string("YAML error: ") + ex.what());
      }
      if (!y.IsMap() && !y.IsNull())
        throw InputError(sensor.string(), "expected keys (T_BS, intrinsics, resolution, ...), got a YAML " +
                                              std::string(y.IsSequence() ? "list" : "scalar"));
      if (y["T_BS"]) {
        const auto m = yaml_numbers(y["T_BS"], sensor, "T_BS", 16);
        Eigen::Matrix4d T;
        for (int i = 0; i < 16; ++i) T(i / 4, i % 4) = m[i];
        T_BS = checked_pose(T, sensor, 0);
      }
      if (y["intrinsics"] && y["resolution"]) {
        const auto k = yaml_numbers(y["intrinsics"], sensor, "intrinsics", 4);
        const auto r = yaml_numbers(y["resolution"], sensor, "resolution", 2);
        for (double side : r) {
          check_range(side, 1, 65535, "resolution", sensor);
          if (side != std::floor(side))
            throw InputError(sensor.string(), "key 'resolution': expected whole numbers of pixels");
        }
        PinholeCamera c;
        c.fx = k[0], c.fy = k[1], c.cx = k[2], c.cy = k[3];
        c.width = static_cast<int>(r[0]), c.height = static_cast<int>(r[1]);
        if (y["distortion_coefficients"]) {
          const auto d = yaml_numbers(y["distortion_coefficients"], sensor, "distortion_coefficients", 4);
          c.k1 = d[0], c.k2 = d[1], c.p1 = d[2], c.p2 = d[3];
        }
        if (auto err = c.validate()) throw InputError(sensor.string(), *err);
        info_.calibration = c;
        info_.calibration_source = sensor.string();
      }
      if (y["rate_hz"]) {  // else, or when it is not a positive number, the rate of the timestamps
        const double rate = y["rate_hz"].as<double>(0.0);
        if (std::isfinite(rate) && rate > 0) info_.fps = rate;
      }
    }

    const fs::path gt = mav / "state_groundtruth_estimate0" / "data.csv";
    if (fs::exists(gt)) {
      double prev = -std::numeric_limits<double>::infinity();
      for_each_data_line(gt, true, [&](long line, const std::vector<std::string>& tok) {
        if (tok.size() < 8) throw InputError(gt.string(), "expected at least 8 fields 'timestamp, p xyz, q wxyz'", line);
        const double t = static_cast<double>(parse_int(tok[0], gt, line, "timestamp [ns]")) * 1e-9;
        check_increasing(t, prev, gt, line);
        prev = t;
        double v[7];
        for (int i = 0; i < 7; ++i) v[i] = parse_double(tok[i + 1], gt, line, "pose value");
        const SE3 T_WB = checked_pose(Eigen::Quaterniond(v[3], v[4], v[5], v[6]), {v[0], v[1], v[2]}, gt, line);
        ground_truth_.push_back(t, T_WB * T_BS);
      });
      attach_ground_truth_by_time(o.max_dt);
    }
    finish_opening();
  }
};

}  // namespace

std::unique_ptr<SequenceReader> open_euroc(const fs::path& root, const ReaderOptions& o) {
  return std::make_unique<EurocReader>(root, o);
}

}  // namespace wardmap::slam::io
