#include "sim/mesh.h"

#include <cmath>

namespace wardmap::sim {

namespace {
void push(std::vector<Triangle>& out, const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
          const Eigen::Vector2d& ta, const Eigen::Vector2d& tb, const Eigen::Vector2d& tc,
          const Eigen::Vector3d& outward, int texture, int instance, bool two_sided) {
  Triangle t;
  const bool flip = (b - a).cross(c - a).dot(outward) < 0;
  t.p[0] = a.cast<float>();
  t.p[1] = (flip ? c : b).cast<float>();
  t.p[2] = (flip ? b : c).cast<float>();
  t.uv[0] = ta.cast<float>();
  t.uv[1] = (flip ? tc : tb).cast<float>();
  t.uv[2] = (flip ? tb : tc).cast<float>();
  t.texture = texture;
  t.instance = instance;
  t.two_sided = two_sided;
  out.push_back(t);
}
}  // namespace

void add_quad_uv(std::vector<Triangle>& out, const Eigen::Vector3d corners[4], const Eigen::Vector2d uvs[4],
                 const Eigen::Vector3d& outward, int texture, int instance, bool two_sided) {
  push(out, corners[0], corners[1], corners[2], uvs[0], uvs[1], uvs[2], outward, texture, instance, two_sided);
  push(out, corners[0], corners[2], corners[3], uvs[0], uvs[2], uvs[3], outward, texture, instance, two_sided);
}

void add_quad(std::vector<Triangle>& out, const Eigen::Vector3d corners[4], const Eigen::Vector3d& outward,
              const FaceMaterial& m, int instance, bool two_sided) {
  const Eigen::Vector2d uvs[4] = {{0, 0}, {m.u_repeat, 0}, {m.u_repeat, m.v_repeat}, {0, m.v_repeat}};
  add_quad_uv(out, corners, uvs, outward, m.texture, instance, two_sided);
}

void add_box(std::vector<Triangle>& out, const Eigen::Isometry3d& pose, const Eigen::Vector3d& half,
             const BoxMaterials& m, int instance) {
  const Eigen::Matrix3d R = pose.linear();
  const Eigen::Vector3d c = pose.translation();
  struct Face {
    Eigen::Vector3d n, right, down;
    const FaceMaterial* mat;
  };
  const Eigen::Vector3d X = Eigen::Vector3d::UnitX(), Y = Eigen::Vector3d::UnitY(), Z = Eigen::Vector3d::UnitZ();
  // right = z x n for the side faces (upright when seen from outside)
  const Face faces[6] = {{Y, -X, -Z, &m.front}, {-Y, X, -Z, &m.back}, {X, Y, -Z, &m.side},
                         {-X, -Y, -Z, &m.side}, {Z, X, -Y, &m.top},   {-Z, X, Y, &m.bottom}};
  for (const Face& f : faces) {
    const double hn = std::abs(f.n.dot(half)), hr = std::abs(f.right.dot(half)), hd = std::abs(f.down.dot(half));
    const Eigen::Vector3d fc = f.n * hn, U = f.right * hr, V = f.down * hd;
    const Eigen::Vector3d local[4] = {fc - U - V, fc + U - V, fc + U + V, fc - U + V};
    Eigen::Vector3d world[4];
    for (int i = 0; i < 4; ++i) world[i] = c + R * local[i];
    add_quad(out, world, R * f.n, *f.mat, instance, false);
  }
}

void add_cylinder(std::vector<Triangle>& out, const Eigen::Isometry3d& pose, double radius, double half_length,
                  int segments, const FaceMaterial& side, const FaceMaterial& caps, int instance) {
  const Eigen::Matrix3d R = pose.linear();
  const Eigen::Vector3d c = pose.translation(), axis = R.col(2);
  const auto ring = [&](int i, double z) {
    const double a = 2.0 * M_PI * i / segments;
    return Eigen::Vector3d(c + R * Eigen::Vector3d(radius * std::cos(a), radius * std::sin(a), z));
  };
  for (int i = 0; i < segments; ++i) {
    const double a = 2.0 * M_PI * (i + 0.5) / segments;
    const Eigen::Vector3d n = R * Eigen::Vector3d(std::cos(a), std::sin(a), 0);
    const Eigen::Vector3d q[4] = {ring(i, half_length), ring(i + 1, half_length), ring(i + 1, -half_length),
                                  ring(i, -half_length)};
    const double u0 = side.u_repeat * i / segments, u1 = side.u_repeat * (i + 1) / segments;
    const Eigen::Vector2d uv[4] = {{u0, 0}, {u1, 0}, {u1, side.v_repeat}, {u0, side.v_repeat}};
    add_quad_uv(out, q, uv, n, side.texture, instance, false);
    for (int s = -1; s <= 1; s += 2) {
      const Eigen::Vector3d centre = c + axis * (s * half_length);
      const Eigen::Vector2d tc(0.5 * caps.u_repeat, 0.5 * caps.v_repeat);
      const double a0 = 2.0 * M_PI * i / segments, a1 = 2.0 * M_PI * (i + 1) / segments;
      const Eigen::Vector2d t0(tc.x() * (1 + std::cos(a0)), tc.y() * (1 + std::sin(a0)));
      const Eigen::Vector2d t1(tc.x() * (1 + std::cos(a1)), tc.y() * (1 + std::sin(a1)));
      const Eigen::Vector3d p0 = ring(i, s * half_length), p1 = ring(i + 1, s * half_length);
      push(out, centre, p0, p1, tc, t0, t1, axis * s, caps.texture, instance, false);  // one piece of the cap fan
    }
  }
}

}  // namespace wardmap::sim
