// Camera settings in ORB-SLAM3's YAML keys (existing settings files work unchanged), plus wardmap's
// own sections beside them, each read into its module's options struct with validated values.
#pragma once

#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "slam/core/camera.h"

namespace wardmap::slam::io {

struct CameraSettings {
  std::string type = "PinHole";  // Camera.type; only PinHole is supported
  PinholeCamera camera;          // Camera1.fx ... (or ORB-SLAM2's Camera.fx ...), Camera.width/height
  double fps = 30.0;             // Camera.fps
  bool rgb = true;               // Camera.RGB: 1 = RGB order, 0 = BGR
  std::optional<double> depth_map_factor;  // RGBD.DepthMapFactor (or DepthMapFactor)
};

// NOLINTNEXTLINE(bugprone-exception-escape): YAML::Node's assignment may throw
struct Settings {
  std::filesystem::path file;
  CameraSettings camera;
  YAML::Node root;  // the whole document, for the modules' own sections
  // Top-level keys that look meant to change something but are not read: a misspelling of a key
  // wardmap reads, an ORB-SLAM3 key of processing wardmap does not do (a resized image, a stereo
  // rig's second camera). Each names its key and line; a run logs them as warnings. Also the note of
  // fit_calibration_size when the images' size replaced a slightly different one, and those of
  // calibration_disagreement and depth_factor_disagreement (fit_settings_to_sequence).
  std::vector<std::string> notes;
  // A wardmap section (e.g. "tracking"); an undefined node when absent.
  YAML::Node section(const std::string& name) const { return root[name]; }
};

// A setting given on the command line (`--set KEY=VALUE`). KEY is written as in a settings file:
// dotted for wardmap's sections ("tracking.flow_extend_mono", "semantics.groups.size"), else a
// top-level key, dots included (ORB-SLAM3's "ORBextractor.nFeatures"). VALUE is YAML ("false",
// "1500", "[door, chair]"). It replaces the file's value or adds the key; it is then validated as
// the file's own keys are (a misspelt key or a wrong type is an error naming the key).
struct SettingOverride {
  std::string key;
  std::string value;
};

// Parses "KEY=VALUE"; throws InputError naming --set when there is no '=', the key or the value is
// empty, or the key is a whole section.
SettingOverride parse_setting_override(const std::string& text);

// Sets each override in a settings document (a YAML mapping), in order (the last of a key wins).
// Throws InputError naming --set for a value that is not YAML or a key whose parent is not a section.
void apply_setting_overrides(YAML::Node& root, const std::vector<SettingOverride>& overrides);

// Runs `load` (loading settings with overrides, or reading options from them). An InputError it
// throws about a key an override set ("key 'tracking.x': ...") is rethrown naming that --set rather
// than the file; any other error passes unchanged.
void blame_overrides(const std::vector<SettingOverride>& overrides, const std::function<void()>& load);

// Fits `camera`'s image size to the sequence's `width` x `height`. A size off by at most
// kCalibrationSizeTolerance of each side or kCalibrationSizeTolerancePixels, whichever is more, is
// a rounding or a crop (ORB-SLAM3's KITTI03.yaml says 1241x376 for 1242x375 images, and ORB-SLAM3
// takes the image bounds from the images): the images' size is taken, and a note saying so is
// returned. The principal point must still lie inside. Further off, the calibration is for another
// resolution: an InputError at the --set that gave Camera.width or Camera.height when one did, else
// at `source` (the settings file).
inline constexpr double kCalibrationSizeTolerance = 0.02;
inline constexpr int kCalibrationSizeTolerancePixels = 2;
// `size_keys` names the size in the messages (EuRoC's sensor.yaml: "resolution (width/height)").
std::optional<std::string> fit_calibration_size(PinholeCamera& camera, int width, int height, const std::string& source,
                                                const std::vector<SettingOverride>& overrides = {},
                                                const std::string& size_keys = "Camera.width/height");

// A note when a settings file's camera (`used`, from `used_source`) disagrees with the calibration
// the sequence itself carries (`carried`: 7-Scenes' camera-intrinsics.txt, KITTI's calib.txt,
// EuRoC's sensor.yaml, a synthetic sequence's settings.yaml): a focal length off by more than
// kCalibrationFocalTolerance of the carried one, a principal point by more than
// kCalibrationCentreTolerancePixels, or a distortion coefficient by more than
// kCalibrationDistortionTolerance. The note gives both cameras and says the settings' is used: a
// file for another camera is the usual cause, but a deliberate one (7Scenes-colour.yaml) is
// allowed. Both cameras are taken at the images' size (after fit_calibration_size).
// "fx 585.000 fy 585.000 cx 320.000 cy 240.000", with " k1 ... k3" when `with_distortion`.
std::string describe_intrinsics(const PinholeCamera& camera, bool with_distortion = false);
inline constexpr double kCalibrationFocalTolerance = 0.005;
inline constexpr double kCalibrationCentreTolerancePixels = 2.0;
inline constexpr double kCalibrationDistortionTolerance = 1e-3;
std::optional<std::string> calibration_disagreement(const PinholeCamera& used, const std::string& used_source,
                                                    const PinholeCamera& carried, const std::string& carried_source);

// A note when a settings file's RGBD.DepthMapFactor (`used`) is more than 1 % off the factor the
// sequence's format defines (`format_factor`, raw units per metre: 7-Scenes' millimetres 1000, TUM
// RGB-D's 5000). The settings' factor is used (a recording in TUM's layout may have its own), but
// a file for another dataset is the usual cause, and the first frame's depth check does not catch
// every such factor (TUM1.yaml's 5000 on 7-Scenes puts its kitchen at 0.3-0.6 m).
std::optional<std::string> depth_factor_disagreement(double used, const std::string& used_source, double format_factor,
                                                     const std::string& format);

// Loads and validates, with `overrides` set over the file's keys first; accepts OpenCV's `%YAML:1.0`
// header. Throws InputError naming the file and the key (and the line for YAML syntax errors).
Settings load_settings(const std::filesystem::path& file, const std::vector<SettingOverride>& overrides = {});

// Parses YAML text (for tests and for settings embedded in other files); `file` names it in errors.
Settings parse_settings(const std::string& text, const std::filesystem::path& file,
                        const std::vector<SettingOverride>& overrides = {});

// Reads section[key] into value when present, as the type of value; throws InputError
// "key 'section.key': expected a number, got 'abc'". Leaves value unchanged when absent.
void read_option(const YAML::Node& section, const std::string& section_name, const std::string& key, double& value,
                 const std::filesystem::path& file);
void read_option(const YAML::Node& section, const std::string& section_name, const std::string& key, int& value,
                 const std::filesystem::path& file);
void read_option(const YAML::Node& section, const std::string& section_name, const std::string& key, bool& value,
                 const std::filesystem::path& file);
void read_option(const YAML::Node& section, const std::string& section_name, const std::string& key, std::string& value,
                 const std::filesystem::path& file);
void read_option(const YAML::Node& section, const std::string& section_name, const std::string& key,
                 std::uint64_t& value, const std::filesystem::path& file);
// The options one loader reads from one wardmap section (or subsection, e.g. "semantics.groups"),
// remembering the keys it knows, so that a key it does not know (misspelt, or from another
// section) is an error rather than silently ignored.
class SectionKeys {
 public:
  SectionKeys(const YAML::Node& section, std::string name, std::filesystem::path file);
  // read_option on this section; the key becomes known.
  template <class T>
  void read(const std::string& key, T& value) {
    known_.push_back(key);
    read_option(section_, name_, key, value, file_);
  }
  // A key read some other way (a list).
  void know(const std::string& key) { known_.push_back(key); }
  // The subsection `key` (e.g. "groups" of "semantics"), which becomes a known key here; its own
  // keys are checked by its reject_unknown.
  SectionKeys section(const std::string& key) {
    known_.push_back(key);
    return SectionKeys(section_ && section_.IsMap() ? section_[key] : YAML::Node(), name_ + "." + key, file_);
  }
  const YAML::Node& node() const { return section_; }
  // Throws InputError "key 'tracking.pose_solvr': not a key of section 'tracking' (did you mean
  // 'tracking.pose_solver'?)" for the first key of the section that is not known, with its line.
  // Also rejects a section that is not a mapping. With an empty name (a whole document's top level)
  // the message is "key 'x': not a known key".
  void reject_unknown() const;

 private:
  YAML::Node section_;
  std::string name_;
  std::filesystem::path file_;
  std::vector<std::string> known_;
};

// Throws InputError "key 'section.key': must be in [lo, hi], got v".
void check_range(double value, double lo, double hi, const std::string& full_key, const std::filesystem::path& file);

// The shipped settings file (data/settings/...) that fits a dataset, when one is known: KITTI by
// image width, 7-Scenes, EuRoC, TUM fr1/2/3 by folder name. Empty when none fits.
std::string suggest_settings_name(const std::string& dataset_kind, const std::filesystem::path& root, int width);

}  // namespace wardmap::slam::io
