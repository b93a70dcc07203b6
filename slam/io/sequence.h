// Sequence readers: every dataset is opened as a list of frame entries (timestamp, image path,
// optional depth path, optional ground-truth pose); images are decoded only when a frame is read,
// so a sequence is never held in memory.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <opencv2/core.hpp>

#include "slam/core/camera.h"
#include "slam/core/trajectory.h"
#include "slam/io/settings.h"

namespace wardmap::slam::io {

enum class DatasetKind { TumRgbd, Kitti, Euroc, SevenScenes, ImageFolder, Video };

std::string to_string(DatasetKind kind);
// "tum" | "kitti" | "euroc" | "7scenes" | "folder" | "video"; throws std::invalid_argument otherwise.
DatasetKind parse_dataset_kind(const std::string& name);

struct Frame {
  size_t index = 0;
  double timestamp = 0;
  cv::Mat image;                 // as stored: 8-bit grey or BGR
  cv::Mat depth;                 // CV_32F metres, 0 = invalid; empty when the sequence has no depth
  std::optional<SE3> gt_pose;    // camera-to-world, when the dataset has ground truth for this frame
  std::filesystem::path image_path;
};

struct SequenceInfo {
  DatasetKind kind = DatasetKind::ImageFolder;
  std::filesystem::path root;
  size_t frame_count = 0;
  double fps = 0;                // nominal frame rate
  double measured_fps = 0;       // (frames - 1) / (last - first timestamp)
  double duration = 0;           // last - first timestamp + one frame period, seconds
  int width = 0, height = 0;
  std::optional<PinholeCamera> calibration;  // when the dataset itself carries one
  std::string calibration_source;            // file it came from
  bool has_depth = false;
  double depth_factor = 0;       // raw depth units per metre
  bool has_ground_truth = false;
  size_t frames_with_ground_truth = 0;
  // Set when the dataset has a ground-truth file none of whose poses falls on a frame: why there is
  // no evaluation (the pose and frame time spans), for `wardmap info` and a warning from `run`.
  std::string ground_truth_unmatched;
  std::string notes;             // e.g. frames dropped by RGB/depth association
};

struct ReaderOptions {
  std::optional<DatasetKind> kind;   // --format; detected from the layout when absent
  double max_dt = 0.02;              // TUM rgb/depth and ground-truth association window (s)
  double rate = 30.0;                // image folder: frames per second
  std::string kitti_camera;          // "image_0" | "image_2"; empty: image_0 if present
  std::optional<double> depth_factor;  // overrides the dataset's default
  // A stretch of the sequence: frames from first_frame (0-based, among the frames the reader keeps:
  // TUM colour frames without depth are dropped first), at most frame_count of them (0: to the
  // end). See SequenceReader::keep_frames.
  size_t first_frame = 0;
  size_t frame_count = 0;
};

class SequenceReader {
 public:
  virtual ~SequenceReader() = default;
  const SequenceInfo& info() const { return info_; }
  size_t size() const { return entries_.size(); }
  double timestamp(size_t i) const { return entries_.at(i).timestamp; }
  // Ground-truth pose of frame i without decoding it.
  const std::optional<SE3>& gt_pose(size_t i) const { return entries_.at(i).gt_pose; }
  // Decodes frame i; throws FrameReadError (slam/core/errors.h), naming the file, when it cannot be
  // decoded or is unlike the sequence's first frame; std::out_of_range past the end.
  Frame read(size_t i);
  // Whether read() decodes the depth images (default true). A monocular run does not use them, and
  // decoding a 16-bit PNG costs about as much as the colour image; Frame::depth is then empty.
  void set_decode_depth(bool decode) { decode_depth_ = decode; }
  // Raw depth units per metre, overriding the dataset's default: ReaderOptions::depth_factor when the
  // calibration is known before opening, or later. Ignored when the sequence has no depth.
  void set_depth_factor(double units_per_metre) {
    if (info_.has_depth) info_.depth_factor = units_per_metre;
  }
  // The ground-truth trajectory as the dataset gives it (may be denser than the frames), within the
  // frames' time span: poses recorded before the first frame or after the last are left out.
  const Trajectory& ground_truth() const { return ground_truth_; }
  // Calibration found beside the dataset (a settings.yaml in its folder), fitted to the images' size
  // (fit_calibration_size; a note when it differed a little).
  void set_calibration(PinholeCamera camera, const std::string& source);
  // Appends to info_.notes ("; " between notes).
  void add_note(const std::string& note) { info_.notes += (info_.notes.empty() ? "" : "; ") + note; }
  // Keeps `count` frames from frame `first` (0: to the end), renumbered from 0 with their own
  // timestamps, and the ground truth within their time span (half a frame period either side), so
  // that a run and its evaluation see the stretch alone. Throws InputError naming the sequence when
  // `first` is past its last frame.
  void keep_frames(size_t first, size_t count);
  // The dataset's index of frame 0 (non-zero after keep_frames).
  size_t first_frame() const { return first_frame_; }

 protected:
  // read()'s work for one layout (i is in range); throws InputError.
  virtual Frame read_entry(size_t i);

  struct Entry {
    double timestamp = 0;
    std::filesystem::path image, depth;
    std::optional<SE3> gt_pose;
    std::filesystem::path listed_in;  // index file naming this frame (rgb.txt, data.csv), if any
    long line = 0;                    // its line there
    std::filesystem::path depth_listed_in;  // and the one naming its depth image (depth.txt)
    long depth_line = 0;
  };
  // Checks that every listed image and depth file exists (naming the index file and line when one
  // lists it), fills info_.width/height from the first image, duration, counts, and
  // info_.ground_truth_unmatched. Call last.
  void finish_opening();
  // Images named by their frame number (KITTI's 000123.png, 7-Scenes' frame-000123.color.png),
  // sorted here by number: two with one number are an error; the numbers missing between the first
  // and the last are noted ("3 of frames 0-99 have no <what>"), not taken for the end.
  using NumberedImages = std::vector<std::pair<size_t, std::filesystem::path>>;
  void sort_numbered_images(NumberedImages& images, const std::string& what);
  // frame_count, fps, duration and the ground-truth counts of info_ from entries_.
  void update_counts();
  // Attaches to each entry the ground-truth pose closest in time within max_dt.
  void attach_ground_truth_by_time(double max_dt);
  // Keeps the ground-truth poses within the frames' time span (half a frame period either side);
  // returns how many lay before and after it.
  std::pair<size_t, size_t> cut_ground_truth_to_frames();

  SequenceInfo info_;
  std::vector<Entry> entries_;
  bool decode_depth_ = true;
  Trajectory ground_truth_;
  size_t first_frame_ = 0;
};

// Opens a sequence, detecting its kind from the folder layout unless options.kind is set.
// Throws InputError (unknown layout, malformed index files, missing files) naming the file.
std::unique_ptr<SequenceReader> open_sequence(const std::filesystem::path& path, const ReaderOptions& options = {});
DatasetKind detect_dataset_kind(const std::filesystem::path& path);
// When `path` (a file, an image folder) lies up to three levels inside a folder of a dataset layout
// (KITTI's sequences/03/image_0, a TUM sequence's rgb/ or rgb.txt, a 7-Scenes frame): "it is inside
// the <kind> sequence <folder>: give that folder, ...", for the errors and notes that a path meant as
// that sequence gets; else "".
std::string enclosing_dataset_hint(const std::filesystem::path& path);

// The checks of a settings file against the sequence it is used on, their notes joining
// `settings.notes` (a run warns about them and records them): fit_calibration_size at the file (or
// the --set that gave the size); calibration_disagreement against the calibration the sequence
// carries, when it carries one (a --set Camera* named beside the file; a synthetic sequence's
// settings.yaml, also its calibration, agrees with itself unless such a --set changes it); and
// depth_factor_disagreement against the depth factor of the sequence's format, unless the file is
// the sequence's own settings.yaml.
void fit_settings_to_sequence(Settings& settings, const SequenceInfo& info, const std::vector<SettingOverride>& overrides);

// One per layout (sequence_*.cpp).
std::unique_ptr<SequenceReader> open_tum(const std::filesystem::path& root, const ReaderOptions& o);
std::unique_ptr<SequenceReader> open_kitti(const std::filesystem::path& root, const ReaderOptions& o);
std::unique_ptr<SequenceReader> open_euroc(const std::filesystem::path& root, const ReaderOptions& o);
std::unique_ptr<SequenceReader> open_seven_scenes(const std::filesystem::path& root, const ReaderOptions& o);
std::unique_ptr<SequenceReader> open_image_folder(const std::filesystem::path& root, const ReaderOptions& o);
std::unique_ptr<SequenceReader> open_video(const std::filesystem::path& file, const ReaderOptions& o);

// Index of the value of `sorted` closest to t, when within max_dt (TUM's association rule).
std::optional<size_t> nearest_within(const std::vector<double>& sorted, double t, double max_dt);

// Shared by the readers: a readable image (8-bit, grey or BGR) or an InputError naming it. With
// `beside_depth` (a colour image of an RGB-D frame), a 16-bit single-channel image is an error: it
// is a depth image, read as dim grey otherwise.
cv::Mat load_image(const std::filesystem::path& file, bool beside_depth = false);
// uint16 depth PNG to metres (0 = invalid); `invalid` raw values (e.g. 65535) are zeroed too.
cv::Mat load_depth(const std::filesystem::path& file, double factor, int invalid = -1);

}  // namespace wardmap::slam::io
