// Pieces shared by the commands.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "slam/io/sequence.h"

namespace wardmap::apps {

// --format, --rate, --kitti-camera on a command.
void add_reader_options(CLI::App* cmd, std::string& format, double& rate, std::string& kitti_camera);
slam::io::ReaderOptions reader_options(const std::string& format, double rate, const std::string& kitti_camera);

}  // namespace wardmap::apps
