#include "slam/eval/trajectory_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "slam/core/errors.h"
#include "slam/io/text_file.h"

namespace wardmap::slam::eval {

namespace {

// A round tick spacing giving about `target` ticks over `range`.
double nice_step(double range, int target) {
  const double raw = range / target;
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (raw <= m * mag) return m * mag;
  return 10 * mag;
}

std::string tick_label(double v, double step) {
  char buf[32];
  const int decimals = step >= 1 ? 0 : static_cast<int>(std::ceil(-std::log10(step)));
  std::snprintf(buf, sizeof buf, "%.*f", decimals, std::abs(v) < 1e-12 ? 0.0 : v);
  return buf;
}

}  // namespace

cv::Mat plot_top_view(const std::vector<PlotSeries>& series, const std::string& title, int width, int height) {
  cv::Mat img(height, width, CV_8UC3, cv::Scalar(255, 255, 255));
  const int left = 90, right = 30, top = 60, bottom = 70;
  const char* axis_names[3] = {"x", "y", "z"};
  // Axes: the two of largest spread in the reference (first) series.
  int ax = 0, ay = 2;
  if (!series.empty() && !series[0].points.empty()) {
    Eigen::Vector3d lo = series[0].points[0], hi = lo;
    for (const auto& p : series[0].points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    const Eigen::Vector3d ext = hi - lo;
    int smallest = 0;
    for (int k = 1; k < 3; ++k)
      if (ext(k) < ext(smallest)) smallest = k;
    ax = smallest == 0 ? 1 : 0;
    ay = smallest == 2 ? 1 : 2;
  }
  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
  for (const auto& s : series)
    for (const auto& p : s.points) {
      x0 = std::min(x0, p(ax)), x1 = std::max(x1, p(ax));
      y0 = std::min(y0, p(ay)), y1 = std::max(y1, p(ay));
    }
  if (x0 > x1) x0 = -1, x1 = 1, y0 = -1, y1 = 1;
  // Equal scale on both axes, with a margin.
  const double pw = width - left - right, ph = height - top - bottom;
  double span = std::max({(x1 - x0) / pw, (y1 - y0) / ph, 1e-6 / std::min(pw, ph)}) * 1.08;
  const double cxm = 0.5 * (x0 + x1), cym = 0.5 * (y0 + y1);
  x0 = cxm - 0.5 * span * pw, x1 = cxm + 0.5 * span * pw;
  y0 = cym - 0.5 * span * ph, y1 = cym + 0.5 * span * ph;
  auto to_px = [&](double x, double y) {
    return cv::Point2d(left + (x - x0) / span, top + ph - (y - y0) / span);  // y grows upwards
  };
  const cv::Scalar grid(225, 225, 225), ink(40, 40, 40);
  const int font = cv::FONT_HERSHEY_SIMPLEX;
  const double step = nice_step(std::max(x1 - x0, y1 - y0), 8);
  for (double x = std::ceil(x0 / step) * step; x <= x1; x += step) {
    const cv::Point2d a = to_px(x, y0), b = to_px(x, y1);
    cv::line(img, a, b, grid, 1, cv::LINE_AA);
    const std::string l = tick_label(x, step);
    cv::putText(img, l, cv::Point(static_cast<int>(a.x) - 4 * static_cast<int>(l.size()), top + static_cast<int>(ph) + 20),
                font, 0.45, ink, 1, cv::LINE_AA);
  }
  for (double y = std::ceil(y0 / step) * step; y <= y1; y += step) {
    const cv::Point2d a = to_px(x0, y), b = to_px(x1, y);
    cv::line(img, a, b, grid, 1, cv::LINE_AA);
    cv::putText(img, tick_label(y, step), cv::Point(left - 60, static_cast<int>(a.y) + 5), font, 0.45, ink, 1, cv::LINE_AA);
  }
  cv::rectangle(img, cv::Point(left, top), cv::Point(left + static_cast<int>(pw), top + static_cast<int>(ph)), ink, 1);
  cv::putText(img, std::string(axis_names[ax]) + " [m]", cv::Point(left + static_cast<int>(pw) / 2 - 20, height - 20), font,
              0.6, ink, 1, cv::LINE_AA);
  cv::putText(img, std::string(axis_names[ay]) + " [m]", cv::Point(10, top - 12), font, 0.6, ink, 1, cv::LINE_AA);
  cv::putText(img, title, cv::Point(left, 32), font, 0.65, ink, 1, cv::LINE_AA);

  int legend_y = top + 22;
  for (const auto& s : series) {
    std::vector<cv::Point> poly;
    poly.reserve(s.points.size());
    for (const auto& p : s.points) poly.push_back(to_px(p(ax), p(ay)));
    if (poly.size() > 1) cv::polylines(img, poly, false, s.colour, 2, cv::LINE_AA);
    if (!poly.empty()) cv::circle(img, poly.front(), 5, s.colour, cv::FILLED, cv::LINE_AA);  // start
    const int lx = left + static_cast<int>(pw) - 290;
    cv::line(img, cv::Point(lx, legend_y - 5), cv::Point(lx + 30, legend_y - 5), s.colour, 3, cv::LINE_AA);
    cv::putText(img, s.label, cv::Point(lx + 40, legend_y), font, 0.5, ink, 1, cv::LINE_AA);
    legend_y += 22;
  }
  cv::putText(img, "dot = start", cv::Point(left + static_cast<int>(pw) - 250, legend_y), font, 0.45, cv::Scalar(120, 120, 120),
              1, cv::LINE_AA);
  return img;
}

void save_png(const std::filesystem::path& file, const cv::Mat& image) {
  std::vector<uchar> buf;
  if (!cv::imencode(".png", image, buf)) throw InputError(file.string(), "cannot encode the PNG");
  if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path());
  io::write_file_atomic(file, std::string(buf.begin(), buf.end()));
}

}  // namespace wardmap::slam::eval
