// Test helper shared by the glTF writer and renderer tests: an upright object box.
#pragma once

#include <Eigen/Geometry>
#include <string>

#include "semantics/export/gltf_export.h"

namespace wardmap::test {

// An upright box turned by `yaw` about the world's z.
inline semantics::GltfObject upright_box(int id, const std::string& label, const Eigen::Vector3d& position, double yaw,
                              const Eigen::Vector3d& size, int measurements = 4) {
  semantics::GltfObject o;
  o.id = id;
  o.label = label;
  o.position = position;
  o.rotation = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ());
  o.size = size;
  o.measurements = measurements;
  return o;
}

}  // namespace wardmap::test
