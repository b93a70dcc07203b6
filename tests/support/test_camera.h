// The camera the unit tests share: 640x480, fx = fy = 500 unless given, principal point at the image centre, no
// distortion.
#pragma once

#include "slam/core/camera.h"

namespace wardmap::test {

inline slam::PinholeCamera vga_camera(double focal = 500) {
  slam::PinholeCamera c;
  c.fx = c.fy = focal;
  c.cx = 319.5;
  c.cy = 239.5;
  c.width = 640;
  c.height = 480;
  return c;
}

}  // namespace wardmap::test
