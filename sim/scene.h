// The scene: every triangle (building and objects), the textures, and the ground-truth objects.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "sim/mesh.h"
#include "sim/scenario.h"
#include "sim/textures.h"
#include "slam/core/se3.h"

namespace wardmap::sim {

struct ObjectInstance {
  int id = 0;  // > 0, also its value in the instance buffer
  ObjectClass cls = ObjectClass::kChair;
  int variant = 0;
  slam::SE3 pose;                                  // box frame to world; the box centre is pose.translation()
  Eigen::Vector3d size = Eigen::Vector3d::Zero();  // box extents along the box's own x, y, z
  int first_triangle = 0, triangle_count = 0;      // its triangles in Scene::triangles
};

struct Scene {
  std::vector<Triangle> triangles;
  std::vector<Texture> textures;
  std::vector<ObjectInstance> objects;  // objects[i].id == i + 1

  const ObjectInstance& object(int id) const { return objects.at(static_cast<size_t>(id - 1)); }
  // The 8 corners of an object's box in world coordinates.
  std::vector<Eigen::Vector3d> box_corners(int id) const;
};

// Light direction and model: shade = ambient + diffuse * |n . L|, per triangle (flat).
struct LightingOptions {
  Eigen::Vector3d direction = Eigen::Vector3d(0.35, 0.25, 0.9);  // towards the light, normalised on use
  double ambient = 0.62;
  double diffuse = 0.38;
  double ceiling_shade = 0.97;  // ceiling and light panels (emissive)
};

// Build the scene of a scenario; the seed jitters placement, picks appearance variants and draws
// the textures (posters, tiles, speckle).
Scene build_scene(const Scenario& scenario, uint32_t seed, const LightingOptions& lighting = {});

}  // namespace wardmap::sim
