// Top view of an aligned estimate over the ground truth, as a PNG a person can read: axes in metres
// with ticks, a legend, the ATE in the title.
#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace wardmap::slam::eval {

struct PlotSeries {
  std::string label;
  std::vector<Eigen::Vector3d> points;
  cv::Scalar colour;  // BGR
};

// Projects onto the two world axes along which the first series spreads most; `title` on top.
cv::Mat plot_top_view(const std::vector<PlotSeries>& series, const std::string& title, int width = 1000, int height = 800);

// Writes the PNG atomically; throws InputError when it cannot.
void save_png(const std::filesystem::path& file, const cv::Mat& image);

}  // namespace wardmap::slam::eval
