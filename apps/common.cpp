#include "apps/common.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <set>

#include "slam/core/errors.h"
#include "slam/io/text_file.h"

namespace wardmap::apps {

CLI::Validator positive_number() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        if (text.empty() || *end != '\0') return "expected a number, got '" + text + "'";
        if (!(v > 0) || !std::isfinite(v)) return "must be a number above 0, got " + text;
        return {};
      },
      "POSITIVE");
}

CLI::Validator png_file() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        std::string ext = std::filesystem::path(text).extension().string();
        std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
        if (ext != ".png") return "writes a PNG: give a file name ending in .png, got '" + text + "'";
        return {};
      },
      "FILE.png");
}

CLI::Validator whole_number(unsigned long long min) {
  return CLI::Validator(
      [min](std::string& text) -> std::string {
        const bool digits = !text.empty() && text.size() <= 19 &&
                            std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
        if (!digits || std::stoull(text) < min)
          return "expected a whole number" + (min ? " from " + std::to_string(min) : std::string()) + ", got '" + text +
                 "'";
        return {};
      },
      min ? ">=" + std::to_string(min) : "");
}

void require_run_files(const std::filesystem::path& run, const std::vector<std::string>& files) {
  for (const std::string& f : files) {
    if (std::filesystem::exists(run / f)) continue;
    const bool slam_run =
        std::filesystem::exists(run / "trajectory.txt") && std::filesystem::exists(run / "frames.csv");
    throw InputError((run / f).string(), slam_run ? "not found: the run was made without objects (wardmap run SEQ "
                                                    "--objects, or --poses gt)"
                                                  : "not found: is this a wardmap run folder?");
  }
}

std::filesystem::path file_or_run_file(const std::filesystem::path& given, const std::string& name) {
  if (!std::filesystem::is_directory(given)) return given;
  require_run_files(given, {name});
  return given / name;
}

void check_output_files(std::initializer_list<std::pair<std::string, const char*>> files) {
  for (const auto& [file, option] : files)
    if (!file.empty()) slam::io::check_output_file(file, option);
}

void add_reader_options(CLI::App* cmd, ReaderArgs& args) {
  cmd->add_option("--format", args.format, "Dataset kind instead of detecting it from the layout")
      ->check(CLI::IsMember({"tum", "kitti", "euroc", "7scenes", "folder", "video"}));
  cmd->add_option("--rate", args.rate, "Frame rate of an image folder (Hz)")
      ->capture_default_str()
      ->check(positive_number());
  cmd->add_option("--kitti-camera", args.kitti_camera, "KITTI camera folder: image_0 (default) or image_2")
      ->check(CLI::IsMember({"image_0", "image_2"}));
  cmd->add_option("--first-frame", args.first_frame,
                  "Start at this frame (0-based, among the frames `wardmap info` counts: a TUM colour frame without "
                  "depth is not one); the frames keep their timestamps, and the ground truth is cut to the stretch")
      ->check(whole_number());
  cmd->add_option("--frames", args.frames, "Use at most this many frames (from --first-frame; default: to the end)")
      ->check(whole_number(1));
}

slam::io::ReaderOptions reader_options(const ReaderArgs& args) {
  slam::io::ReaderOptions o;
  if (!args.format.empty()) o.kind = slam::io::parse_dataset_kind(args.format);
  o.rate = args.rate;
  o.kitti_camera = args.kitti_camera;
  o.first_frame = args.first_frame;
  o.frame_count = args.frames;
  return o;
}

nlohmann::json scale_drift_json(const slam::eval::ScaleDriftResult& drift) {
  nlohmann::json j = {{"window_s", drift.window_seconds}, {"windows", drift.ratios.size()}};
  j["slope_percent_per_s"] = drift.valid ? nlohmann::json(drift.slope_percent_per_second) : nlohmann::json();
  j["slope_se_percent_per_s"] = drift.valid ? nlohmann::json(drift.slope_se_percent_per_second) : nlohmann::json();
  j["change_percent"] = drift.valid ? nlohmann::json(drift.change_percent) : nlohmann::json();
  return j;
}

void add_set_option(CLI::App* cmd, std::vector<std::string>& texts, const std::string& use) {
  cmd->add_option("--set", texts,
                  "KEY=VALUE: a setting over the settings file's (repeat for more), its key as the file writes it:\n"
                  "dotted in wardmap's sections (--set tracking.flow_extend_mono=false --set semantics.groups.size=6)\n"
                  "or ORB-SLAM3's (--set ORBextractor.nFeatures=1500); the value is YAML and is checked as the\n"
                  "file's would be. " + use)
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
}

std::vector<slam::io::SettingOverride> parse_set_options(const std::vector<std::string>& texts) {
  std::vector<slam::io::SettingOverride> overrides;
  for (const std::string& text : texts) overrides.push_back(slam::io::parse_setting_override(text));
  return overrides;
}

nlohmann::json overrides_json(const std::vector<slam::io::SettingOverride>& overrides) {
  nlohmann::json j = nlohmann::json::array();
  for (const auto& o : overrides) j.push_back(o.key + "=" + o.value);
  return j;
}

std::string overrides_text(const std::vector<slam::io::SettingOverride>& overrides) {
  std::string s;
  for (const auto& o : overrides) s += (s.empty() ? ", with --set " : ", ") + o.key + "=" + o.value;
  return s;
}

std::string scale_drift_text(const slam::eval::ScaleDriftResult& drift) {
  char buf[160];
  if (drift.valid)
    std::snprintf(buf, sizeof buf, "%+.3f +- %.3f %% a second over %zu windows of %.0f s (%+.2f %% over the run)",
                  drift.slope_percent_per_second, drift.slope_se_percent_per_second, drift.ratios.size(),
                  drift.window_seconds, drift.change_percent);
  else
    std::snprintf(buf, sizeof buf, "n/a (needs timestamps and 3 windows of %.0f s that move)", drift.window_seconds);
  return buf;
}

std::string settings_notes_text(const std::vector<std::string>& notes) {
  std::string text;
  for (const std::string& note : notes) text += "  - note: " + note + "\n";
  return text;
}

std::string enclosing_dataset_note(const std::filesystem::path& sequence) {
  const std::string hint = slam::io::enclosing_dataset_hint(sequence);
  return hint.empty() ? hint : "; " + hint;
}

void warn_settings_notes(const slam::io::Settings& settings) {
  static std::mutex mutex;
  static std::set<std::string> warned;
  const std::lock_guard<std::mutex> lock(mutex);
  for (const std::string& note : settings.notes)
    if (warned.insert(note).second) spdlog::warn("{}", note);
}

void UnreadableFrames::add(const FrameReadError& e, double timestamp) {
  list_.push_back({{"frame", e.frame()}, {"timestamp", timestamp}, {"file", e.file()}, {"problem", e.problem()}});
  if (list_.size() <= kShown)
    spdlog::warn("frame {} skipped: {}{}", e.frame(), e.what(),
                 list_.size() == kShown ? " (further unreadable frames are counted at the end of the run)" : "");
  else
    spdlog::debug("frame {} skipped: {}", e.frame(), e.what());
}

void UnreadableFrames::warn_summary(const std::filesystem::path& sequence) const {
  if (!list_.empty()) spdlog::warn("{}: {}; the run went on without them", sequence.string(), summary());
}

std::string UnreadableFrames::summary() const {
  if (list_.empty()) return "no frame skipped";
  const nlohmann::json& first = list_.front();
  std::string s = std::to_string(list_.size()) + (list_.size() == 1 ? " frame" : " frames") +
                  " skipped, unreadable: frame " + std::to_string(first["frame"].get<size_t>()) + " (" +
                  first["file"].get<std::string>() + ": " + first["problem"].get<std::string>() + ")";
  if (list_.size() > 1) s += " and " + std::to_string(list_.size() - 1) + " more (report.json's unreadable_frames)";
  return s;
}

}  // namespace wardmap::apps
