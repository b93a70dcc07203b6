// Microsoft 7-Scenes: frame-NNNNNN.color.(jpg|png), frame-NNNNNN.depth.png (uint16 mm, 65535 invalid),
// frame-NNNNNN.pose.txt (4x4 camera-to-world); 30 Hz, frame N has timestamp N / 30 s.
#include <cstdio>

#include "slam/core/errors.h"
#include "slam/io/sequence.h"
#include "slam/io/text_file.h"
#include "slam/io/trajectory_io.h"

namespace wardmap::slam::io {

namespace fs = std::filesystem;

namespace {

Eigen::Matrix4d read_matrix4(const fs::path& file) {
  std::vector<double> v;
  long last_line = 0;
  for_each_data_line(file, false, [&](long line, const std::vector<std::string>& tok) {
    last_line = line;
    for (const auto& t : tok) v.push_back(parse_double(t, file, line, "matrix entry"));
  });
  if (v.size() != 16) throw InputError(file.string(), "expected a 4x4 matrix (16 numbers), got " + std::to_string(v.size()), last_line);
  Eigen::Matrix4d T;
  for (int i = 0; i < 16; ++i) T(i / 4, i % 4) = v[i];
  return T;
}

class SevenScenesReader : public SequenceReader {
 public:
  explicit SevenScenesReader(const fs::path& root) {
    info_.kind = DatasetKind::SevenScenes;
    info_.root = root;
    info_.fps = 30.0;
    info_.depth_factor = 1000.0;  // millimetres; ReaderOptions::depth_factor overrides it (open_sequence)
    // Frame N is frame-NNNNNN: found by name, so a missing number is a gap (reported), not the end.
    NumberedImages colour;
    for (const auto& f : fs::directory_iterator(root)) {
      int n = -1, used = 0;
      const std::string name = f.path().filename().string();
      if (std::sscanf(name.c_str(), "frame-%d.color.%n", &n, &used) == 1 && used > 0 && n >= 0 &&
          (name.substr(static_cast<size_t>(used)) == "png" || name.substr(static_cast<size_t>(used)) == "jpg"))
        colour.emplace_back(static_cast<size_t>(n), f.path());
    }
    sort_numbered_images(colour, "colour image");
    size_t without_pose = 0;
    char stem[64];
    for (const auto& [n, path] : colour) {
      std::snprintf(stem, sizeof stem, "frame-%06zu.", n);
      Entry e;
      e.timestamp = n / info_.fps;
      e.image = path;
      if (const fs::path d = root / (std::string(stem) + "depth.png"); fs::exists(d)) e.depth = d;
      if (const fs::path p = root / (std::string(stem) + "pose.txt"); fs::exists(p)) {
        e.gt_pose = checked_pose(read_matrix4(p), p, 0);
        ground_truth_.push_back(e.timestamp, *e.gt_pose);
      } else {
        ++without_pose;
      }
      entries_.push_back(std::move(e));
    }
    if (without_pose && without_pose < colour.size())
      add_note(std::to_string(without_pose) + " frames without pose.txt");
    finish_opening();
    // Frames without depth in a sequence that has it elsewhere would silently change the mode.
    for (const Entry& e : entries_)
      if (e.depth.empty() != entries_.front().depth.empty())
        throw InputError(e.image.string(), "depth image missing for this frame while other frames have one");
    const fs::path intr = root / "camera-intrinsics.txt";
    if (fs::exists(intr)) {
      std::vector<double> k;
      for_each_data_line(intr, false, [&](long line, const std::vector<std::string>& tok) {
        for (const auto& t : tok) k.push_back(parse_double(t, intr, line, "intrinsic"));
      });
      if (k.size() != 9) throw InputError(intr.string(), "expected a 3x3 matrix (9 numbers), got " + std::to_string(k.size()));
      PinholeCamera c;
      c.fx = k[0], c.cx = k[2], c.fy = k[4], c.cy = k[5];
      c.width = info_.width, c.height = info_.height;
      if (auto err = c.validate()) throw InputError(intr.string(), *err);
      info_.calibration = c;
      info_.calibration_source = intr.string();
    }
  }
};

}  // namespace

std::unique_ptr<SequenceReader> open_seven_scenes(const fs::path& root, const ReaderOptions& /*options*/) {
  return std::make_unique<SevenScenesReader>(root);
}

}  // namespace wardmap::slam::io
