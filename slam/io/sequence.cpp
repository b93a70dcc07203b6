#include "slam/io/sequence.h"

#include <algorithm>
#include <cstdio>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "slam/core/errors.h"
#include "slam/io/settings.h"

namespace wardmap::slam::io {

namespace fs = std::filesystem;

std::unique_ptr<SequenceReader> open_by_kind(DatasetKind kind, const fs::path& path, const ReaderOptions& options);

std::string to_string(DatasetKind kind) {
  switch (kind) {
    case DatasetKind::TumRgbd: return "TUM RGB-D";
    case DatasetKind::Kitti: return "KITTI odometry";
    case DatasetKind::Euroc: return "EuRoC";
    case DatasetKind::SevenScenes: return "7-Scenes";
    case DatasetKind::ImageFolder: return "image folder";
    case DatasetKind::Video: return "video";
  }
  return "unknown";
}

DatasetKind parse_dataset_kind(const std::string& name) {
  if (name == "tum") return DatasetKind::TumRgbd;
  if (name == "kitti") return DatasetKind::Kitti;
  if (name == "euroc") return DatasetKind::Euroc;
  if (name == "7scenes") return DatasetKind::SevenScenes;
  if (name == "folder") return DatasetKind::ImageFolder;
  if (name == "video") return DatasetKind::Video;
  throw std::invalid_argument("unknown format '" + name + "' (allowed: tum, kitti, euroc, 7scenes, folder, video)");
}

cv::Mat load_image(const fs::path& file, bool beside_depth) {
  if (!fs::exists(file)) throw InputError(file.string(), "image file not found");
  cv::Mat img = cv::imread(file.string(), cv::IMREAD_UNCHANGED);
  if (img.empty()) throw InputError(file.string(), "cannot decode the image (corrupt or not an image)");
  if (beside_depth && img.type() == CV_16UC1)
    throw InputError(file.string(),
                     "a 16-bit single-channel image where the colour image is expected (a depth "
                     "image listed as colour?)");
  if (img.depth() == CV_16U) img.convertTo(img, CV_8U, 1.0 / 256);
  if (img.depth() != CV_8U) throw InputError(file.string(), "unsupported pixel type (expected 8 or 16 bit)");
  if (img.channels() == 4) cv::cvtColor(img, img, cv::COLOR_BGRA2BGR);
  return img;
}

cv::Mat load_depth(const fs::path& file, double factor, int invalid) {
  if (!fs::exists(file)) throw InputError(file.string(), "depth file not found");
  cv::Mat raw = cv::imread(file.string(), cv::IMREAD_ANYDEPTH);
  if (raw.empty()) throw InputError(file.string(), "cannot decode the depth image");
  if (raw.type() != CV_16UC1) throw InputError(file.string(), "depth must be a 16-bit single-channel PNG");
  cv::Mat depth;
  raw.convertTo(depth, CV_32F, 1.0 / factor);
  if (invalid >= 0) depth.setTo(0.0f, raw == invalid);
  return depth;
}

Frame SequenceReader::read(size_t i) {
  if (i >= entries_.size())
    throw std::out_of_range("frame " + std::to_string(i) + " is past the sequence's end (" +
                            std::to_string(entries_.size()) + " frames)");
  try {
    return read_entry(i);
  } catch (const InputError& e) {
    throw FrameReadError(e, i);
  }
}

Frame SequenceReader::read_entry(size_t i) {
  const Entry& e = entries_.at(i);
  Frame f;
  f.index = i;
  f.timestamp = e.timestamp;
  f.image_path = e.image;
  f.image = load_image(e.image, !e.depth.empty());
  if (f.image.cols != info_.width || f.image.rows != info_.height)
    throw InputError(e.image.string(), "image is " + std::to_string(f.image.cols) + "x" + std::to_string(f.image.rows) +
                                           ", the sequence's first image is " + std::to_string(info_.width) + "x" +
                                           std::to_string(info_.height));
  if (decode_depth_ && !e.depth.empty()) {
    f.depth = load_depth(e.depth, info_.depth_factor, info_.kind == DatasetKind::SevenScenes ? 65535 : -1);
    if (f.depth.size() != f.image.size())
      throw InputError(e.depth.string(), "depth image is " + std::to_string(f.depth.cols) + "x" +
                                             std::to_string(f.depth.rows) + ", its colour image " +
                                             e.image.filename().string() + " is " + std::to_string(f.image.cols) + "x" +
                                             std::to_string(f.image.rows) +
                                             " (registered depth of the colour image's size is needed)");
  }
  f.gt_pose = e.gt_pose;
  return f;
}

void SequenceReader::set_calibration(PinholeCamera camera, const std::string& source) {
  if (auto note = fit_calibration_size(camera, info_.width, info_.height, source)) add_note(*note);
  info_.calibration = camera;
  info_.calibration_source = source;
}

void SequenceReader::finish_opening() {
  if (entries_.empty()) throw InputError(info_.root.string(), "the sequence has no frames");
  const auto check_exists = [](const fs::path& file, const fs::path& listed_in, long line) {
    std::error_code ec;  // set when the name cannot even be looked up (too long, a folder it may not search)
    if (file.empty() || fs::exists(file, ec)) return;
    const std::string problem = ec ? "cannot be looked up: " + ec.message() : "not found";
    if (!listed_in.empty())
      throw InputError(listed_in.string(), "listed file '" + file.string() + "' " + problem, line);
    throw InputError(file.string(), "file " + problem);
  };
  for (const Entry& e : entries_) {
    check_exists(e.image, e.listed_in, e.line);
    check_exists(e.depth, e.depth_listed_in, e.depth_line);
  }
  const cv::Mat first = load_image(entries_.front().image, !entries_.front().depth.empty());
  info_.width = first.cols;
  info_.height = first.rows;
  // A calibration read before the images (EuRoC's sensor.yaml gives a resolution) fitted to them.
  if (info_.calibration)
    if (auto note = fit_calibration_size(*info_.calibration, info_.width, info_.height, info_.calibration_source, {},
                                         "resolution (width/height)"))
      add_note(*note);
  info_.has_depth = !entries_.front().depth.empty();
  update_counts();
  if (!ground_truth_.empty() && !info_.has_ground_truth) {
    char buf[256];
    std::snprintf(buf, sizeof buf, "none of the ground truth's %zu poses (%.3f-%.3f s) falls on a frame (%.3f-%.3f s)",
                  ground_truth_.size(), ground_truth_.timestamps.front(), ground_truth_.timestamps.back(),
                  entries_.front().timestamp, entries_.back().timestamp);
    info_.ground_truth_unmatched = buf;
  }
  // A motion-capture recording usually starts before the camera and stops after it (TUM's do, by
  // seconds): its poses outside the frames would count as untracked time in the tracking rate,
  // whose denominator is the sequence's duration (EVALUATION.md).
  const size_t poses = ground_truth_.size();
  const auto [before, after] = cut_ground_truth_to_frames();
  if (before + after > 0)
    add_note("ground-truth poses outside the frames left out: " + std::to_string(before) + " before the first, " +
             std::to_string(after) + " after the last (" + std::to_string(poses - before - after) + " of " +
             std::to_string(poses) + " kept)");
}

std::pair<size_t, size_t> SequenceReader::cut_ground_truth_to_frames() {
  if (entries_.empty() || ground_truth_.empty()) return {0, 0};
  const double half_period = info_.fps > 0 ? 0.5 / info_.fps : 0.0;
  const double t0 = entries_.front().timestamp - half_period, t1 = entries_.back().timestamp + half_period;
  const auto& t = ground_truth_.timestamps;  // increasing (the pose readers check it)
  const auto before = static_cast<size_t>(std::lower_bound(t.begin(), t.end(), t0) - t.begin());
  const auto after = static_cast<size_t>(t.end() - std::upper_bound(t.begin(), t.end(), t1));
  ground_truth_ = ground_truth_.within(t0, t1);
  return {before, after};
}

void SequenceReader::sort_numbered_images(NumberedImages& images, const std::string& what) {
  std::sort(images.begin(), images.end());
  for (size_t i = 1; i < images.size(); ++i)
    if (images[i].first == images[i - 1].first)
      throw InputError(images[i].second.string(),
                       "the same frame number as " + images[i - 1].second.filename().string());
  if (images.empty()) return;
  if (const size_t gaps = images.back().first - images.front().first + 1 - images.size(); gaps > 0)
    add_note(std::to_string(gaps) + " of frames " + std::to_string(images.front().first) + "-" +
             std::to_string(images.back().first) + " have no " + what);
}

void SequenceReader::update_counts() {
  info_.frame_count = entries_.size();
  const double span = entries_.back().timestamp - entries_.front().timestamp;
  if (entries_.size() > 1 && span > 0) info_.measured_fps = (entries_.size() - 1) / span;
  if (info_.fps <= 0) info_.fps = info_.measured_fps;
  info_.duration = span + (info_.fps > 0 ? 1.0 / info_.fps : 0.0);
  info_.frames_with_ground_truth =
      std::count_if(entries_.begin(), entries_.end(), [](const Entry& e) { return e.gt_pose.has_value(); });
  info_.has_ground_truth = info_.frames_with_ground_truth > 0;
}

void SequenceReader::keep_frames(size_t first, size_t count) {
  const size_t total = entries_.size();
  if (first >= total)
    throw InputError(info_.root.string(), "first frame " + std::to_string(first) +
                                              " is past the end: the sequence has " + std::to_string(total) +
                                              " frames (0-" + std::to_string(total - 1) + ")");
  const size_t last = count == 0 ? total : std::min(total, first + count);  // one past the last kept
  entries_.erase(entries_.begin() + static_cast<std::ptrdiff_t>(last), entries_.end());
  entries_.erase(entries_.begin(), entries_.begin() + static_cast<std::ptrdiff_t>(first));
  cut_ground_truth_to_frames();
  first_frame_ += first;
  update_counts();  // the nominal rate (info_.fps) stays
  add_note("frames " + std::to_string(first_frame_) + "-" + std::to_string(first_frame_ + entries_.size() - 1) +
           " of " + std::to_string(first_frame_ - first + total));
}

std::optional<size_t> nearest_within(const std::vector<double>& ts, double t, double max_dt) {
  const auto it = std::lower_bound(ts.begin(), ts.end(), t);
  std::optional<size_t> best;
  double best_dt = max_dt;
  for (auto c : {it, it == ts.begin() ? it : it - 1}) {
    if (c == ts.end()) continue;
    const double dt = std::abs(*c - t);
    if (dt <= best_dt) best_dt = dt, best = static_cast<size_t>(c - ts.begin());
  }
  return best;
}

void SequenceReader::attach_ground_truth_by_time(double max_dt) {
  for (Entry& e : entries_)
    if (const auto k = nearest_within(ground_truth_.timestamps, e.timestamp, max_dt)) e.gt_pose = ground_truth_.poses[*k];
}

static bool has_image_extension(const fs::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
  return ext == ".png" || ext == ".jpg" || ext == ".jpeg" || ext == ".bmp" || ext == ".pgm" || ext == ".ppm" ||
         ext == ".tif" || ext == ".tiff";
}

static bool has_video_extension(const fs::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
  return ext == ".mp4" || ext == ".avi" || ext == ".mkv" || ext == ".mov" || ext == ".webm" || ext == ".mpg";
}

std::string enclosing_dataset_hint(const fs::path& path) {
  // Up to three levels: KITTI's sequences/03/image_0, EuRoC's mav0/cam0/data, a TUM rgb/ folder.
  fs::path dir = fs::absolute(path).lexically_normal();
  if (!dir.has_filename()) dir = dir.parent_path();  // a trailing slash
  for (int level = 0; level < 3 && dir.has_parent_path() && dir.parent_path() != dir; ++level) {
    dir = dir.parent_path();
    try {
      const DatasetKind kind = detect_dataset_kind(dir);
      if (kind != DatasetKind::ImageFolder && kind != DatasetKind::Video)
        return "it is inside the " + to_string(kind) + " sequence " + dir.string() +
               ": give that folder to read what it holds (timestamps, calibration, depth, ground truth)";
    } catch (const InputError&) {
      // not a dataset: look one level up
    }
  }
  return "";
}

DatasetKind detect_dataset_kind(const fs::path& path) {
  if (!fs::exists(path)) throw InputError(path.string(), "no such file or folder");
  if (fs::is_regular_file(path)) {
    if (has_video_extension(path)) return DatasetKind::Video;
    const std::string hint = enclosing_dataset_hint(path);
    throw InputError(path.string(), "a file that is not a video (.mp4 .avi .mkv .mov .webm .mpg); " +
                                        (hint.empty() ? std::string("give a dataset folder") : hint));
  }
  if (fs::exists(path / "rgb.txt")) return DatasetKind::TumRgbd;
  if (fs::exists(path / "mav0") || fs::exists(path / "cam0" / "data.csv")) return DatasetKind::Euroc;
  if (fs::exists(path / "sequences") || fs::exists(path / "image_0") || fs::exists(path / "image_2"))
    return DatasetKind::Kitti;
  // 7-Scenes by its images' names, frame-NNNNNN.color.* (a stretch copied out need not start at frame 0).
  for (const auto& e : fs::directory_iterator(path)) {
    if (!e.is_regular_file() || !has_image_extension(e.path())) continue;
    const std::string name = e.path().filename().string();
    const bool seven_scenes = name.rfind("frame-", 0) == 0 &&
                              (name.find(".color.") != std::string::npos || name.find(".depth.") != std::string::npos);
    return seven_scenes ? DatasetKind::SevenScenes : DatasetKind::ImageFolder;
  }
  throw InputError(path.string(),
                   "unknown layout: expected rgb.txt (TUM RGB-D), sequences/ or image_0/ (KITTI), mav0/ (EuRoC), "
                   "frame-NNNNNN.color.* (7-Scenes), or a folder of images");
}

std::unique_ptr<SequenceReader> open_sequence(const fs::path& path, const ReaderOptions& options) {
  if (!fs::exists(path)) throw InputError(path.string(), "no such file or folder");
  const DatasetKind kind = options.kind ? *options.kind : detect_dataset_kind(path);
  std::unique_ptr<SequenceReader> reader = open_by_kind(kind, path, options);
  if (kind == DatasetKind::ImageFolder && !options.kind)
    if (const std::string hint = enclosing_dataset_hint(path); !hint.empty()) reader->add_note(hint);
  if (options.depth_factor) reader->set_depth_factor(*options.depth_factor);
  // A settings file inside the sequence folder (wardmap synth writes one) is its calibration.
  const fs::path settings = fs::is_directory(path) ? path / "settings.yaml" : fs::path();
  if (!reader->info().calibration && !settings.empty() && fs::exists(settings)) {
    const Settings s = load_settings(settings);
    reader->set_calibration(s.camera.camera, settings.string());
  }
  if (options.first_frame > 0 || options.frame_count > 0) reader->keep_frames(options.first_frame, options.frame_count);
  return reader;
}

void fit_settings_to_sequence(Settings& settings, const SequenceInfo& info, const std::vector<SettingOverride>& overrides) {
  if (auto note = fit_calibration_size(settings.camera.camera, info.width, info.height, settings.file.string(), overrides))
    settings.notes.push_back(*note);
  std::string used_source = settings.file.string();
  for (const SettingOverride& o : overrides)
    if (o.key.rfind("Camera", 0) == 0) used_source += " with --set " + o.key + "=" + o.value;
  if (info.calibration)
    if (auto note =
            calibration_disagreement(settings.camera.camera, used_source, *info.calibration, info.calibration_source))
      settings.notes.push_back(*note);
  std::error_code ec;  // a file that cannot be looked up is not the sequence's own
  if (info.has_depth && settings.camera.depth_map_factor && !fs::equivalent(settings.file, info.root / "settings.yaml", ec))
    if (auto note = depth_factor_disagreement(*settings.camera.depth_map_factor, settings.file.string(),
                                              info.depth_factor, to_string(info.kind)))
      settings.notes.push_back(*note);
}

std::unique_ptr<SequenceReader> open_by_kind(DatasetKind kind, const fs::path& path, const ReaderOptions& options) {
  switch (kind) {
    case DatasetKind::TumRgbd: return open_tum(path, options);
    case DatasetKind::Kitti: return open_kitti(path, options);
    case DatasetKind::Euroc: return open_euroc(path, options);
    case DatasetKind::SevenScenes: return open_seven_scenes(path, options);
    case DatasetKind::ImageFolder: return open_image_folder(path, options);
    case DatasetKind::Video: return open_video(path, options);
  }
  throw InputError(path.string(), "unsupported dataset kind");
}

bool is_image_file(const fs::path& p) { return has_image_extension(p); }

}  // namespace wardmap::slam::io
