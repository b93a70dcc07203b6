#include "sim/scene.h"

#include <algorithm>
#include <cmath>

#include "sim/object_models.h"

namespace wardmap::sim {

using Eigen::Vector2d;
using Eigen::Vector3d;

std::vector<Vector3d> Scene::box_corners(int id) const {
  const ObjectInstance& o = object(id);
  std::vector<Vector3d> c;
  for (int i = 0; i < 8; ++i) {
    const Vector3d local(((i & 1) ? 0.5 : -0.5) * o.size.x(), ((i & 2) ? 0.5 : -0.5) * o.size.y(),
                         ((i & 4) ? 0.5 : -0.5) * o.size.z());
    c.push_back(o.pose * local);
  }
  return c;
}

namespace {

// A door's footprint on its wall, kept so posters and handrails leave it free.
struct DoorZone {
  Vector2d centre, along;
  double half_width;
};

bool near_door(const std::vector<DoorZone>& doors, const Vector2d& p, double half_extent, double margin) {
  for (const DoorZone& d : doors) {
    const Vector2d r = p - d.centre;
    const double a = std::abs(r.dot(d.along));
    const double n = std::abs(r.x() * d.along.y() - r.y() * d.along.x());
    if (n < 0.3 && a < d.half_width + half_extent + margin) return true;
  }
  return false;
}

Eigen::Isometry3d frame_2d(const Vector2d& p, double z, const Vector2d& along) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  const Vector3d x(along.x(), along.y(), 0), zz = Vector3d::UnitZ();
  T.linear().col(0) = x;
  T.linear().col(1) = zz.cross(x);
  T.linear().col(2) = zz;
  T.translation() = Vector3d(p.x(), p.y(), z);
  return T;
}

class SceneBuilder {
 public:
  SceneBuilder(const Scenario& s, uint32_t seed, Scene& scene)
      : s_(s), seed_(seed), scene_(scene), tc_(scene.textures, seed) {}

  void build(const LightingOptions& lighting) {
    Rng palette = Rng::derived(seed_, hash_string("palette"));
    const cv::Scalar paints[] = {{200, 225, 235}, {200, 226, 205}, {232, 218, 198}, {222, 208, 220}};
    paint_ = paints[palette.uniform_int(0, 3)];
    add_floor_and_ceiling();
    add_objects();
    add_walls();
    apply_lighting(lighting);
  }

 private:
  void add_floor_and_ceiling() {
    const std::string kind = s_.floor_texture;
    const int floor_tex = tc_.get("floor/" + kind, true, [&](Rng& r) {
      return kind == "tiles" ? floor_tiles_texture(r) : kind == "lino" ? lino_texture(r) : plain_floor_texture(r);
    });
    const double period = kind == "tiles" ? kFloorTilesPeriod : kLinoPeriod;
    const Vector2d a = s_.floor_min, b = s_.floor_max;
    const double h = s_.ceiling_height;
    // floor in patches of at most 4 m so no triangle is huge
    const int nx = std::max(1, static_cast<int>(std::ceil((b.x() - a.x()) / 4.0)));
    const int ny = std::max(1, static_cast<int>(std::ceil((b.y() - a.y()) / 4.0)));
    const int ceil_tex = tc_.get("ceiling", true, ceiling_texture);
    for (int i = 0; i < nx; ++i)
      for (int j = 0; j < ny; ++j) {
        const double x0 = a.x() + (b.x() - a.x()) * i / nx, x1 = a.x() + (b.x() - a.x()) * (i + 1) / nx;
        const double y0 = a.y() + (b.y() - a.y()) * j / ny, y1 = a.y() + (b.y() - a.y()) * (j + 1) / ny;
        const Vector3d f[4] = {{x0, y1, 0}, {x1, y1, 0}, {x1, y0, 0}, {x0, y0, 0}};
        const Vector2d fuv[4] = {{x0 / period, -y1 / period},
                                 {x1 / period, -y1 / period},
                                 {x1 / period, -y0 / period},
                                 {x0 / period, -y0 / period}};
        add_quad_uv(scene_.triangles, f, fuv, Vector3d::UnitZ(), floor_tex, 0, false);
        const Vector3d c[4] = {{x0, y0, h}, {x1, y0, h}, {x1, y1, h}, {x0, y1, h}};
        const double cp = kCeilingPeriod;
        const Vector2d cuv[4] = {{x0 / cp, y0 / cp}, {x1 / cp, y0 / cp}, {x1 / cp, y1 / cp}, {x0 / cp, y1 / cp}};
        const size_t first = scene_.triangles.size();
        add_quad_uv(scene_.triangles, c, cuv, -Vector3d::UnitZ(), ceil_tex, 0, false);
        for (size_t k = first; k < scene_.triangles.size(); ++k) scene_.triangles[k].emissive = true;
      }
  }

  void add_objects() {
    int next_id = 1;
    Rng rooms = Rng::derived(seed_, hash_string("room_numbers"));
    int room_number = rooms.uniform_int(1, 40) * 10;
    for (size_t i = 0; i < s_.objects.size(); ++i) {
      const ObjectSpec& spec = s_.objects[i];
      Rng rng = Rng::derived(seed_, 1000 + static_cast<uint32_t>(i));
      const int variant = spec.variant >= 0 ? spec.variant : rng.uniform_int(0, variant_count(spec.cls) - 1);
      const double yaw0 = spec.yaw_deg * M_PI / 180.0;
      const Vector2d along(std::cos(yaw0), std::sin(yaw0));
      const bool door = spec.cls == ObjectClass::kDoor;
      for (int k = 0; k < spec.count; ++k) {
        double dx = 0, dy = 0, dyaw = 0;
        if (spec.jitter) {
          dx = rng.uniform(-1, 1) * s_.position_jitter;
          if (!door) {
            dy = rng.uniform(-1, 1) * s_.position_jitter;
            dyaw = rng.uniform(-1, 1) * s_.yaw_jitter_deg * M_PI / 180.0;
          }
        }
        const Vector2d across(-along.y(), along.x());
        const Vector2d base = spec.at + along * (spec.spacing * k + dx) + across * dy;
        const int id = next_id++;
        add_object(spec.cls, variant, id, base, spec.elevation, yaw0 + dyaw);
        if (door) {
          add_door_fittings(base, yaw0, room_number);
          room_number += rooms.uniform_int(1, 2);
        }
      }
    }
  }

  void add_object(ObjectClass cls, int variant, int id, const Vector2d& base, double elevation, double yaw) {
    std::vector<Triangle> local = build_object_local(cls, variant, tc_, id);
    Eigen::Vector3f lo = local[0].p[0], hi = local[0].p[0];
    for (const Triangle& t : local)
      for (const auto& p : t.p) {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
      }
    const Eigen::Matrix3d R = Eigen::AngleAxisd(yaw, Vector3d::UnitZ()).toRotationMatrix();
    const Vector3d origin(base.x(), base.y(), elevation);
    ObjectInstance o;
    o.id = id;
    o.cls = cls;
    o.variant = variant;
    o.size = (hi - lo).cast<double>();
    o.pose = slam::SE3(R, origin + R * (0.5 * (lo + hi)).cast<double>());
    o.first_triangle = static_cast<int>(scene_.triangles.size());
    o.triangle_count = static_cast<int>(local.size());
    for (Triangle& t : local) {
      for (auto& p : t.p) p = (origin + R * p.cast<double>()).cast<float>();
      scene_.triangles.push_back(t);
    }
    scene_.objects.push_back(o);
    if (cls == ObjectClass::kDoor) doors_.push_back({base, Vector2d(std::cos(yaw), std::sin(yaw)), 0.5});
  }

  void add_door_fittings(const Vector2d& base, double yaw, int number) {
    const Vector2d along(std::cos(yaw), std::sin(yaw));
    const int frame_tex =
        tc_.get("door_frame", true, [](Rng& r) { return metal_texture(r, cv::Scalar(225, 225, 222)); });
    const auto M = BoxMaterials::all(FaceMaterial{frame_tex, 1, 1});
    auto T = [&](double x, double y, double z) {
      Eigen::Isometry3d F = frame_2d(base, 0, along);
      F.translation() += F.linear() * Vector3d(x, y, z);
      return F;
    };
    add_box(scene_.triangles, T(-0.48, 0.013, 1.055), Vector3d(0.03, 0.012, 1.055), M, 0);
    add_box(scene_.triangles, T(0.48, 0.013, 1.055), Vector3d(0.03, 0.012, 1.055), M, 0);
    add_box(scene_.triangles, T(0, 0.013, 2.08), Vector3d(0.51, 0.012, 0.03), M, 0);
    const double h = s_.ceiling_height;
    if (h >= 2.45) {
      const int sign = tc_.get("room_sign/" + std::to_string(number), false, [&](Rng& r) {
        return sign_texture(r, "ROOM " + std::to_string(number), cv::Scalar(120, 60, 20), cv::Scalar(250, 250, 250));
      });
      const double zc = std::min(2.28, h - 0.12);
      const Eigen::Isometry3d F = frame_2d(base, 0, along);
      const Vector3d c = F * Vector3d(0, 0.008, zc), r = -F.linear().col(0), up = Vector3d::UnitZ();
      const Vector3d q[4] = {c - r * 0.28 + up * 0.07, c + r * 0.28 + up * 0.07, c + r * 0.28 - up * 0.07,
                             c - r * 0.28 - up * 0.07};
      add_quad(scene_.triangles, q, F.linear().col(1), FaceMaterial{sign, 1, 1}, 0, false);
    }
  }

  void add_walls() {
    const double h = s_.ceiling_height;
    for (size_t i = 0; i < s_.walls.size(); ++i) {
      const WallSpec& w = s_.walls[i];
      const int tex = tc_.get("wall/" + w.texture, true, [&](Rng& r) { return wall_texture(r, w.texture, paint_, h); });
      Rng rng = Rng::derived(seed_, 5000 + static_cast<uint32_t>(i));
      const Vector2d d = (w.to - w.from).normalized();
      const Vector2d n(-d.y(), d.x());
      const double len = (w.to - w.from).norm(), u0 = rng.uniform(0, 1);
      const Vector3d q[4] = {
          {w.from.x(), w.from.y(), h}, {w.to.x(), w.to.y(), h}, {w.to.x(), w.to.y(), 0}, {w.from.x(), w.from.y(), 0}};
      const Vector2d uv[4] = {{u0, 0}, {u0 + len / kWallPeriod, 0}, {u0 + len / kWallPeriod, 1}, {u0, 1}};
      add_quad_uv(scene_.triangles, q, uv, Vector3d(n.x(), n.y(), 0), tex, 0, true);
      for (int side = -1; side <= 1; side += 2) {
        add_posters(w, static_cast<int>(i), side, rng);
        if (w.handrail) add_handrail(w, side);
      }
    }
  }

  void add_posters(const WallSpec& w, int wall, int side, Rng& rng) {
    const Vector2d d = (w.to - w.from).normalized();
    const Vector2d n = Vector2d(-d.y(), d.x()) * side;
    const double len = (w.to - w.from).norm(), h = s_.ceiling_height;
    std::vector<std::pair<double, double>> taken;
    for (int p = 0; p < w.posters; ++p) {
      for (int attempt = 0; attempt < 25; ++attempt) {
        const bool landscape = rng.chance(0.3);
        const double width = landscape ? rng.uniform(0.6, 1.0) : rng.uniform(0.4, 0.65);
        const double height = landscape ? width * rng.uniform(0.55, 0.7) : width * rng.uniform(1.25, 1.45);
        if (width + 0.2 > len) break;
        const double u = rng.uniform(width / 2 + 0.1, len - width / 2 - 0.1);
        const double zc = std::clamp(rng.uniform(1.35, 1.6), 1.0 + height / 2, h - 0.3 - height / 2);
        const Vector2d c2 = w.from + d * u;
        bool clash = near_door(doors_, c2, width / 2, 0.15);
        for (const auto& [a, b] : taken) clash = clash || (u + width / 2 + 0.15 > a && u - width / 2 - 0.15 < b);
        if (clash) continue;
        taken.emplace_back(u - width / 2, u + width / 2);
        const int tw = landscape ? 512 : 256, th = landscape ? 256 : 512;
        const std::string key = "poster/" + std::to_string(wall) + "/" + std::to_string(side) + "/" + std::to_string(p);
        const int tex = tc_.get(key, false, [&](Rng& r) { return poster_texture(r, tw, th); });
        const Vector3d c(c2.x() + n.x() * 0.008, c2.y() + n.y() * 0.008, zc);
        const Vector3d right(-n.y(), n.x(), 0), up = Vector3d::UnitZ();  // right = z x n
        const Vector3d q[4] = {c - right * (width / 2) + up * (height / 2), c + right * (width / 2) + up * (height / 2),
                               c + right * (width / 2) - up * (height / 2),
                               c - right * (width / 2) - up * (height / 2)};
        add_quad(scene_.triangles, q, Vector3d(n.x(), n.y(), 0), FaceMaterial{tex, 1, 1}, 0, false);
        break;
      }
    }
  }

  void add_handrail(const WallSpec& w, int side) {
    const Vector2d d = (w.to - w.from).normalized();
    const Vector2d n = Vector2d(-d.y(), d.x()) * side;
    const double len = (w.to - w.from).norm();
    const int tex =
        tc_.get("handrail", true, [](Rng& r) { return wood_texture(r, cv::Scalar(70, 120, 170), 128, 128, false); });
    const int bracket_tex =
        tc_.get("metal_chrome", true, [](Rng& r) { return metal_texture(r, cv::Scalar(200, 200, 205)); });
    // free stretches between doors
    const double step = 0.05;
    double start = -1;
    for (double u = 0.1; u <= len - 0.1 + 1e-9; u += step) {
      const bool blocked = near_door(doors_, w.from + d * u, 0, 0.15);
      if (!blocked && start < 0) start = u;
      const bool end_here = start >= 0 && (blocked || u + step > len - 0.1 + 1e-9);
      if (end_here) {
        const double stop = blocked ? u - step : u;
        if (stop - start > 0.3) {
          const Vector2d mid = w.from + d * (0.5 * (start + stop));
          const Vector2d c = mid + n * 0.085;
          add_box(scene_.triangles, frame_2d(c, 0.9, d), Vector3d(0.5 * (stop - start), 0.025, 0.025),
                  BoxMaterials::all(FaceMaterial{tex, static_cast<float>((stop - start) / 0.5), 1}), 0);
          for (double b = start + 0.15; b < stop; b += 1.2) {
            const Vector2d bc = w.from + d * b + n * 0.035;
            add_box(scene_.triangles, frame_2d(bc, 0.87, d), Vector3d(0.012, 0.035, 0.012),
                    BoxMaterials::all(FaceMaterial{bracket_tex, 1, 1}), 0);
          }
        }
        start = -1;
      }
    }
  }

  void apply_lighting(const LightingOptions& l) {
    const Eigen::Vector3f L = l.direction.normalized().cast<float>();
    for (Triangle& t : scene_.triangles) {
      if (t.emissive) {
        t.shade = static_cast<float>(l.ceiling_shade);
        continue;
      }
      const float c = t.normal().dot(L);
      const float k = t.two_sided ? std::abs(c) : std::max(0.0f, c);
      t.shade = static_cast<float>(l.ambient) + static_cast<float>(l.diffuse) * k;
    }
  }

  const Scenario& s_;
  uint32_t seed_;
  Scene& scene_;
  TextureCache tc_;
  cv::Scalar paint_;
  std::vector<DoorZone> doors_;
};

}  // namespace

Scene build_scene(const Scenario& scenario, uint32_t seed, const LightingOptions& lighting) {
  Scene scene;
  SceneBuilder(scenario, seed, scene).build(lighting);
  return scene;
}

}  // namespace wardmap::sim
