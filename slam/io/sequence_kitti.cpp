// KITTI odometry: sequences/XX/image_0|image_2/NNNNNN.png, times.txt, optional calib.txt, and
// poses/XX.txt (row-major 3x4 camera-to-world of the left grey camera, one line per frame).
#include <algorithm>
#include <limits>

#include "slam/core/errors.h"
#include "slam/io/sequence.h"
#include "slam/io/text_file.h"
#include "slam/io/trajectory_io.h"

namespace wardmap::slam::io {

namespace fs = std::filesystem;

namespace {

// The sequence folder (the one holding image_0/) for a dataset root or a sequence folder.
fs::path find_sequence_folder(const fs::path& root) {
  if (fs::exists(root / "image_0") || fs::exists(root / "image_2")) return root;
  const fs::path seqs = root / "sequences";
  std::vector<fs::path> found;
  if (fs::is_directory(seqs))
    for (const auto& e : fs::directory_iterator(seqs))
      if (e.is_directory()) found.push_back(e.path());
  if (found.empty()) throw InputError(root.string(), "KITTI layout: no sequences/XX folder with image_0/ or image_2/");
  if (found.size() > 1)
    throw InputError(root.string(), "KITTI layout: " + std::to_string(found.size()) +
                                        " sequences found; give one sequence folder, e.g. " + found.front().string());
  return found.front();
}

PinholeCamera read_calib(const fs::path& file, const std::string& key, int width, int height) {
  PinholeCamera cam;
  bool found = false;
  for_each_data_line(file, false, [&](long line, const std::vector<std::string>& tok) {
    if (tok.empty() || tok[0] != key + ":") return;
    if (tok.size() != 13) throw InputError(file.string(), key + ": expected 12 numbers, got " + std::to_string(tok.size() - 1), line);
    double P[12];
    for (int i = 0; i < 12; ++i) P[i] = parse_double(tok[i + 1], file, line, key.c_str());
    cam.fx = P[0];
    cam.cx = P[2];
    cam.fy = P[5];
    cam.cy = P[6];
    found = true;
  });
  if (!found) throw InputError(file.string(), "no '" + key + ":' line (the projection matrix of this camera)");
  cam.width = width;
  cam.height = height;
  if (auto err = cam.validate()) throw InputError(file.string(), key + ": " + *err);
  return cam;
}

// A KITTI image's frame number: its file name without extension, all digits (000123.png).
size_t frame_number(const fs::path& image) {
  const std::string stem = image.stem().string();
  if (stem.empty() || stem.size() > 9 ||
      !std::all_of(stem.begin(), stem.end(), [](char c) { return c >= '0' && c <= '9'; }))
    throw InputError(image.string(),
                     "KITTI images are named by their frame number (000123.png); give another layout with --format");
  return std::stoul(stem);
}

class KittiReader : public SequenceReader {
 public:
  KittiReader(const fs::path& root, const ReaderOptions& o) {
    info_.kind = DatasetKind::Kitti;
    info_.root = root;
    const fs::path seq = find_sequence_folder(root);
    std::string cam = o.kitti_camera;
    if (cam.empty()) cam = fs::exists(seq / "image_0") ? "image_0" : "image_2";
    if (cam != "image_0" && cam != "image_2") throw InputError(seq.string(), "camera must be image_0 or image_2, got '" + cam + "'");
    const fs::path img_dir = seq / cam;
    if (!fs::is_directory(img_dir)) throw InputError(img_dir.string(), "image folder not found");
    // Frame n is image n's file name (000123.png), not its rank: a missing image must not shift the
    // timestamps and poses of the frames after it.
    NumberedImages images;
    for (const auto& e : fs::directory_iterator(img_dir))
      if (e.is_regular_file() && e.path().extension() == ".png") images.emplace_back(frame_number(e.path()), e.path());
    if (images.empty()) throw InputError(img_dir.string(), "no .png images");
    sort_numbered_images(images, "image (" + img_dir.string() + ")");

    std::vector<double> times;
    const fs::path times_file = seq / "times.txt";
    if (fs::exists(times_file)) {
      double previous = -std::numeric_limits<double>::infinity();
      for_each_data_line(times_file, false, [&](long line, const std::vector<std::string>& tok) {
        if (tok.size() != 1) throw InputError(times_file.string(), "expected one timestamp per line", line);
        const double t = parse_double(tok[0], times_file, line, "timestamp");
        check_increasing(t, previous, times_file, line);
        previous = t;
        times.push_back(t);
      });
      if (times.size() <= images.back().first)
        throw InputError(times_file.string(), "has " + std::to_string(times.size()) +
                                                  " timestamps, and the images go up to " +
                                                  images.back().second.filename().string());
    }
    info_.fps = 10.0;
    for (const auto& [n, path] : images) {
      Entry e;
      e.timestamp = times.empty() ? static_cast<double>(n) / info_.fps : times[n];
      e.image = path;
      entries_.push_back(std::move(e));
    }

    // poses/XX.txt beside sequences/ (dataset root), or next to a lone sequence folder.
    const std::string id = seq.filename().string();
    for (const fs::path& p : {seq.parent_path().parent_path() / "poses" / (id + ".txt"), seq / "poses.txt",
                              root / "poses" / (id + ".txt")}) {
      if (!fs::exists(p)) continue;
      const Trajectory poses = read_trajectory(p, PoseFormat::Kitti);
      for (size_t i = 0; i < entries_.size() && images[i].first < poses.size(); ++i) {
        entries_[i].gt_pose = poses.poses[images[i].first];
        ground_truth_.push_back(entries_[i].timestamp, poses.poses[images[i].first]);
      }
      if (poses.size() <= images.back().first) {
        add_note(p.string() + " has " + std::to_string(poses.size()) + " poses, for frames 0-" +
                 std::to_string(images.back().first));
      }
      break;
    }
    finish_opening();
    const fs::path calib = seq / "calib.txt";
    if (fs::exists(calib)) {
      info_.calibration = read_calib(calib, cam == "image_0" ? "P0" : "P2", info_.width, info_.height);
      info_.calibration_source = calib.string();
    }
  }
};

}  // namespace

std::unique_ptr<SequenceReader> open_kitti(const fs::path& root, const ReaderOptions& o) {
  return std::make_unique<KittiReader>(root, o);
}

}  // namespace wardmap::slam::io
