// Triangles of the scene and the few primitives everything is built from (quads, boxes, cylinders).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

namespace wardmap::sim {

struct Triangle {
  Eigen::Vector3f p[3];   // world coordinates
  Eigen::Vector2f uv[3];  // texture coordinates; 1.0 = one texture width / height
  int texture = 0;
  int instance = 0;  // object id, 0 = building structure
  float shade = 1.0f;
  bool two_sided = false;
  bool emissive = false;  // lighting leaves shade as set (light panels, signs)

  Eigen::Vector3f normal() const { return (p[1] - p[0]).cross(p[2] - p[0]).normalized(); }
};

// What a face shows: a texture and how many times it repeats across the face.
struct FaceMaterial {
  int texture = 0;
  float u_repeat = 1.0f, v_repeat = 1.0f;
};

// Box faces by outward local axis. Textures are upright when seen from outside (v down = -z;
// top and bottom faces have v along -y).
struct BoxMaterials {
  FaceMaterial front, back, side, top, bottom;  // +y, -y, +-x, +z, -z
  static BoxMaterials all(const FaceMaterial& m) { return {m, m, m, m, m}; }
};

// Quad with corners in texture order: top-left, top-right, bottom-right, bottom-left (uv (0,0),
// (1,0), (1,1), (0,1) scaled by the material). Its front side faces `outward`.
void add_quad(std::vector<Triangle>& out, const Eigen::Vector3d corners[4], const Eigen::Vector3d& outward,
              const FaceMaterial& m, int instance, bool two_sided);
// Quad with explicit texture coordinates per corner.
void add_quad_uv(std::vector<Triangle>& out, const Eigen::Vector3d corners[4], const Eigen::Vector2d uvs[4],
                 const Eigen::Vector3d& outward, int texture, int instance, bool two_sided);
// Box centred at pose.translation() with half extents along the pose's axes.
void add_box(std::vector<Triangle>& out, const Eigen::Isometry3d& pose, const Eigen::Vector3d& half,
             const BoxMaterials& m, int instance);
// Closed cylinder along the pose's z axis, centred at pose.translation().
void add_cylinder(std::vector<Triangle>& out, const Eigen::Isometry3d& pose, double radius, double half_length,
                  int segments, const FaceMaterial& side, const FaceMaterial& caps, int instance);

}  // namespace wardmap::sim
