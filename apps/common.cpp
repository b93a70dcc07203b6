#include "apps/common.h"

namespace wardmap::apps {

void add_reader_options(CLI::App* cmd, std::string& format, double& rate, std::string& kitti_camera) {
  cmd->add_option("--format", format, "Dataset kind instead of detecting it from the layout")
      ->check(CLI::IsMember({"tum", "kitti", "euroc", "7scenes", "folder", "video"}));
  cmd->add_option("--rate", rate, "Frame rate of an image folder (Hz)")->capture_default_str()->check(CLI::PositiveNumber);
  cmd->add_option("--kitti-camera", kitti_camera, "KITTI camera folder: image_0 (default) or image_2")
      ->check(CLI::IsMember({"image_0", "image_2"}));
}

slam::io::ReaderOptions reader_options(const std::string& format, double rate, const std::string& kitti_camera) {
  slam::io::ReaderOptions o;
  if (!format.empty()) o.kind = slam::io::parse_dataset_kind(format);
  o.rate = rate;
  o.kitti_camera = kitti_camera;
  return o;
}

}  // namespace wardmap::apps
