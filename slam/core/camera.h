// Pinhole camera with radial-tangential (OpenCV / ORB-SLAM3 "PinHole") distortion.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>

namespace wardmap::slam {

struct PinholeCamera {
  double fx = 0, fy = 0, cx = 0, cy = 0;
  double k1 = 0, k2 = 0, p1 = 0, p2 = 0, k3 = 0;
  int width = 0, height = 0;

  bool has_distortion() const { return k1 != 0 || k2 != 0 || p1 != 0 || p2 != 0 || k3 != 0; }
  // Empty when valid, else a sentence naming the offending parameter; with `parameter`, also its
  // name: "fx", "fy", "size", "cx", "cy" or "distortion".
  std::optional<std::string> validate(std::string* parameter = nullptr) const;

  // Camera-frame point (z > 0) to distorted pixel.
  Eigen::Vector2d project(const Eigen::Vector3d& p_cam) const;
  // Jacobian of project() with respect to p_cam.
  Eigen::Matrix<double, 2, 3> project_jacobian(const Eigen::Vector3d& p_cam) const;
  // Distorted pixel to the undistorted normalised ray (x, y, 1).
  Eigen::Vector3d unproject(const Eigen::Vector2d& pixel) const;
  // Distorted pixel to the pixel an ideal pinhole camera with the same fx, fy, cx, cy would see.
  Eigen::Vector2d undistort_point(const Eigen::Vector2d& pixel) const;
  // Apply / remove the distortion on normalised coordinates.
  Eigen::Vector2d distort_normalized(const Eigen::Vector2d& xn) const;
  Eigen::Vector2d undistort_normalized(const Eigen::Vector2d& xd) const;
  bool in_image(const Eigen::Vector2d& pixel, double border = 0) const {
    return pixel.x() >= border && pixel.y() >= border && pixel.x() < width - border && pixel.y() < height - border;
  }
};

}  // namespace wardmap::slam
