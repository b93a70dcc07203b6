// Pieces shared by the commands.
#pragma once

#include <CLI/CLI.hpp>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "slam/core/errors.h"
#include "slam/eval/trajectory_eval.h"
#include "slam/io/sequence.h"
#include "slam/io/settings.h"

namespace wardmap::apps {

// Checks of numeric options with a one-line message. CLI11 2.1's PositiveNumber prints its range
// as "0.000000 to 1797693...": hundreds of digits; and an unsigned option takes "-1" as 2^64 - 1.
// A number above zero (a rate, a time):
CLI::Validator positive_number();
// A whole number, digits only, at least `min` (frame counts and indices, seeds):
CLI::Validator whole_number(unsigned long long min = 0);
// A file name ending in .png (any case), for options that write a PNG whatever the name says:
CLI::Validator png_file();

// Throws InputError naming the first of `files` missing from the run folder `run`: a run folder
// without objects (a SLAM run without --objects) is told so, any other folder is asked about.
void require_run_files(const std::filesystem::path& run, const std::vector<std::string>& files);
// `given` when it is a file; when it is a folder, its `name` (a run folder's map.glb or
// trajectory.txt), checked by require_run_files.
std::filesystem::path file_or_run_file(const std::filesystem::path& given, const std::string& name);

// Throws InputError for the first given (non-empty) output file that cannot be written: a folder,
// or in a path that cannot be made (slam::io::check_output_file). Called before the work, so that a
// bad --json or --plot is not found only after it.
void check_output_files(std::initializer_list<std::pair<std::string, const char*>> files);

// How a command opens its sequences: --format, --rate, --kitti-camera, --first-frame, --frames.
struct ReaderArgs {
  std::string format;        // empty: detected from the layout
  double rate = 30.0;        // image folder, Hz
  std::string kitti_camera;  // empty: image_0 when present
  size_t first_frame = 0;    // 0-based, among the frames the reader keeps
  size_t frames = 0;         // 0: to the end
};
// Adds those options to a command.
void add_reader_options(CLI::App* cmd, ReaderArgs& args);
slam::io::ReaderOptions reader_options(const ReaderArgs& args);

// The scale drift as report.json and `wardmap eval --json` write it: null figures when not valid.
nlohmann::json scale_drift_json(const slam::eval::ScaleDriftResult& drift);

// --set KEY=VALUE, repeatable, into `texts`; `use` ends its help (what the command does with it).
void add_set_option(CLI::App* cmd, std::vector<std::string>& texts, const std::string& use);
// The --set texts parsed (slam::io::parse_setting_override), in order.
std::vector<slam::io::SettingOverride> parse_set_options(const std::vector<std::string>& texts);
// The frames a run skipped because their file does not decode or is unlike the first frame
// (FrameReadError, from SequenceReader::read once the sequence is open): the run goes on as after a
// dropped frame instead of losing what it has done. Each is warned, the first kShown in full, then
// one line per frame at debug level; report.json lists them all ("unreadable_frames").
class UnreadableFrames {
 public:
  static constexpr size_t kShown = 5;
  void add(const FrameReadError& e, double timestamp);
  bool empty() const { return list_.empty(); }
  size_t size() const { return list_.size(); }
  // [{"frame", "timestamp", "file", "problem"}, ...], in the order met.
  const nlohmann::json& to_json() const { return list_; }
  // "3 frames skipped, unreadable: frame 196 (FILE: PROBLEM) and 2 more (report.json's
  // unreadable_frames)", for report.md and the run's end.
  std::string summary() const;
  // At the run's end: the summary as a warning on `sequence`, when any frame was skipped.
  void warn_summary(const std::filesystem::path& sequence) const;

 private:
  nlohmann::json list_ = nlohmann::json::array();
};

// Logs a warning for each of the settings' notes (keys not read that look meant), each once per
// process: a SLAM run with --objects and `compare` read one file more than once.
void warn_settings_notes(const slam::io::Settings& settings);

// "; " and slam::io::enclosing_dataset_hint(sequence) when there is one, else "": for errors about a
// path given as a sequence that is a part of one (an image folder without calibration).
std::string enclosing_dataset_note(const std::filesystem::path& sequence);
// The notes as report.md lists them under its settings line ("  - note: NOTE" lines); empty
// without notes.
std::string settings_notes_text(const std::vector<std::string>& notes);

// The --set overrides of a run, for report.json ("KEY=VALUE" strings, in order) and report.md
// (", with --set KEY=VALUE, ..." after the settings file's name; empty without overrides).
nlohmann::json overrides_json(const std::vector<slam::io::SettingOverride>& overrides);
std::string overrides_text(const std::vector<slam::io::SettingOverride>& overrides);
// The same as `wardmap eval` prints it and report.md writes it: "+s +- e % a second over n windows
// of w s (+c % over the run)", or why there is none.
std::string scale_drift_text(const slam::eval::ScaleDriftResult& drift);

}  // namespace wardmap::apps
