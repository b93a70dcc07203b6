// The object map as a binary glTF 2.0 file (map.glb, ../shared/docs/FORMATS.md): one box per object
// in its class colour, the camera trajectory as a line strip, the sparse map points as points. Meant
// for viewers (three.js, Blender, the Khronos sample viewer) and checked by the Khronos validator.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <filesystem>
#include <string>
#include <vector>

namespace wardmap::semantics {

// One mapped object: an oriented box.
struct GltfObject {
  int id = 0;
  std::string label;                                             // landmark class ("door", "chair", ...)
  Eigen::Vector3d position = Eigen::Vector3d::Zero();            // box centre in the world frame
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();  // object-to-world
  Eigen::Vector3d size = Eigen::Vector3d::Ones();                // full extent along the object's own x, y, z
  int measurements = 0;                                          // how many measurements support it
};

struct GltfMapContent {
  std::vector<GltfObject> objects;
  std::vector<Eigen::Vector3d> trajectory;        // camera positions in order (a line strip); may be empty
  std::vector<Eigen::Vector3d> points;            // sparse map points; may be empty
  Eigen::Vector3d up = Eigen::Vector3d::UnitZ();  // the world's up; a root node rotates it onto glTF's +Y
};

// Writes `content` as a binary glTF 2.0 file. The file appears whole or not at all (written to a
// temporary name beside it, then renamed). Throws wardmap::InputError naming the file on bad
// content (non-finite numbers, a zero rotation or up vector, negative sizes) or a write failure.
void write_map_glb(const std::filesystem::path& file, const GltfMapContent& content);

// The display colour (RGBA, 0-1) of a landmark class: a fixed table for the known classes, a
// colour derived from a hash of the name (stable across runs and platforms) for the others.
Eigen::Vector4f class_colour(const std::string& label);

}  // namespace wardmap::semantics
