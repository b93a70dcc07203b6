#include "sim/object_models.h"

#include <cmath>
#include <opencv2/imgproc.hpp>

namespace wardmap::sim {

using Eigen::Isometry3d;
using Eigen::Vector3d;

uint32_t hash_string(const std::string& s) {
  uint32_t h = 2166136261u;
  for (unsigned char c : s) h = (h ^ c) * 16777619u;
  return h;
}

int TextureCache::get(const std::string& key, bool wrap, const std::function<cv::Mat(Rng&)>& make) {
  const auto it = ids_.find(key);
  if (it != ids_.end()) return it->second;
  Rng rng = Rng::derived(seed_, hash_string(key));
  textures_.push_back(make_texture(make(rng), wrap));
  const int id = static_cast<int>(textures_.size()) - 1;
  ids_[key] = id;
  return id;
}

namespace {

Isometry3d at(double x, double y, double z) {
  Isometry3d T = Isometry3d::Identity();
  T.translation() = Vector3d(x, y, z);
  return T;
}
Isometry3d at_rot(double x, double y, double z, const Eigen::Matrix3d& R) {
  Isometry3d T = at(x, y, z);
  T.linear() = R;
  return T;
}
const Eigen::Matrix3d kAxisX = Eigen::AngleAxisd(M_PI / 2, Vector3d::UnitY()).toRotationMatrix();  // local z -> x

FaceMaterial tex(int id, float ur = 1.f, float vr = 1.f) { return FaceMaterial{id, ur, vr}; }

cv::Mat wheel_texture(Rng& rng) {
  cv::Mat m(128, 128, CV_8UC3, cv::Scalar(40, 40, 40));
  cv::circle(m, {64, 64}, 54, cv::Scalar(170, 170, 175), cv::FILLED, cv::LINE_AA);
  cv::circle(m, {64, 64}, 46, cv::Scalar(90, 90, 95), cv::FILLED, cv::LINE_AA);
  for (int i = 0; i < 12; ++i) {
    const double a = i * M_PI / 6 + rng.uniform(-0.02, 0.02);
    cv::line(m, {64, 64}, {64 + static_cast<int>(46 * std::cos(a)), 64 + static_cast<int>(46 * std::sin(a))},
             cv::Scalar(210, 210, 210), 2, cv::LINE_AA);
  }
  cv::circle(m, {64, 64}, 9, cv::Scalar(220, 220, 220), cv::FILLED, cv::LINE_AA);
  return m;
}

std::vector<Triangle> door(int v, TextureCache& tc, int id) {
  std::vector<Triangle> t;
  const int face = tc.get("door/" + std::to_string(v), false, [v](Rng& r) { return door_texture(r, v, ""); });
  const int edge = tc.get("door_edge", true, [](Rng&) { return solid_texture(cv::Scalar(60, 65, 70)); });
  // back face 2 mm in front of the wall plane (y = 0), 4 cm thick
  add_box(t, at(0, 0.022, 1.025), Vector3d(0.45, 0.02, 1.025), {tex(face), tex(face), tex(edge), tex(edge), tex(edge)},
          id);
  return t;
}

std::vector<Triangle> chair(int v, TextureCache& tc, int id) {
  std::vector<Triangle> t;
  const cv::Scalar colours[] = {{150, 80, 30}, {120, 130, 40}, {40, 110, 210}};
  const int fabric =
      tc.get("chair_fabric/" + std::to_string(v), true, [&](Rng& r) { return fabric_texture(r, colours[v % 3]); });
  const int metal = tc.get("metal_dark", true, [](Rng& r) { return metal_texture(r, cv::Scalar(70, 70, 75)); });
  const auto F = BoxMaterials::all(tex(fabric, 2, 2)), M = BoxMaterials::all(tex(metal));
  add_box(t, at(0, 0.01, 0.45), Vector3d(0.25, 0.24, 0.03), F, id);       // seat
  add_box(t, at(0, -0.225, 0.665), Vector3d(0.25, 0.025, 0.185), F, id);  // back
  for (int sx = -1; sx <= 1; sx += 2)
    for (int sy = -1; sy <= 1; sy += 2)
      add_box(t, at(sx * 0.225, sy * 0.215, 0.21), Vector3d(0.018, 0.018, 0.21), M, id);
  if (v == 1) {
    for (int sx = -1; sx <= 1; sx += 2) {
      add_box(t, at(sx * 0.235, 0.0, 0.64), Vector3d(0.02, 0.2, 0.015), M, id);
      add_box(t, at(sx * 0.235, 0.17, 0.555), Vector3d(0.012, 0.012, 0.07), M, id);
    }
  }
  return t;
}

std::vector<Triangle> bed(int v, TextureCache& tc, int id) {
  std::vector<Triangle> t;
  const int metal = tc.get("metal_light", true, [](Rng& r) { return metal_texture(r, cv::Scalar(190, 190, 185)); });
  const int sheet = tc.get("sheet", true, [](Rng& r) { return sheet_texture(r, cv::Scalar(245, 240, 235)); });
  const cv::Scalar blankets[] = {{170, 120, 60}, {90, 160, 120}};
  const int blanket =
      tc.get("blanket/" + std::to_string(v), true, [&](Rng& r) { return fabric_texture(r, blankets[v % 2]); });
  const int board =
      v == 0 ? tc.get("bed_board_wood", true,
                      [](Rng& r) { return wood_texture(r, cv::Scalar(90, 140, 185), 256, 256, false); })
             : tc.get("bed_board_grey", true, [](Rng& r) { return metal_texture(r, cv::Scalar(150, 155, 160)); });
  const auto M = BoxMaterials::all(tex(metal));
  add_box(t, at(0, 0, 0.42), Vector3d(0.48, 1.0, 0.07), M, id);                                        // frame
  add_box(t, at(0, 0.02, 0.56), Vector3d(0.45, 0.95, 0.07), BoxMaterials::all(tex(sheet, 1, 3)), id);  // mattress
  add_box(t, at(0, 0.3, 0.64), Vector3d(0.46, 0.62, 0.012), BoxMaterials::all(tex(blanket, 3, 4)), id);
  add_box(t, at(0, -0.72, 0.665), Vector3d(0.3, 0.15, 0.04), BoxMaterials::all(tex(sheet)), id);  // pillow
  add_box(t, at(0, -1.02, 0.5), Vector3d(0.5, 0.025, 0.45), BoxMaterials::all(tex(board)), id);   // headboard
  add_box(t, at(0, 1.02, 0.42), Vector3d(0.5, 0.025, 0.32), BoxMaterials::all(tex(board)), id);   // footboard
  for (int sx = -1; sx <= 1; sx += 2)
    for (int sy = -1; sy <= 1; sy += 2) add_box(t, at(sx * 0.42, sy * 0.88, 0.18), Vector3d(0.03, 0.03, 0.18), M, id);
  // side rails
  for (int sx = -1; sx <= 1; sx += 2) add_box(t, at(sx * 0.485, -0.35, 0.72), Vector3d(0.012, 0.45, 0.03), M, id);
  return t;
}

std::vector<Triangle> cabinet(int v, TextureCache& tc, int id) {
  std::vector<Triangle> t;
  const int front =
      tc.get("cabinet_front/" + std::to_string(v), false, [v](Rng& r) { return cabinet_front_texture(r, v); });
  const cv::Scalar sides[] = {{180, 205, 215}, {215, 215, 215}, {70, 115, 160}};
  const int side =
      tc.get("cabinet_side/" + std::to_string(v), true, [&](Rng& r) { return metal_texture(r, sides[v % 3]); });
  const int top =
      tc.get("laminate", true, [](Rng& r) { return wood_texture(r, cv::Scalar(150, 170, 185), 256, 256, false); });
  add_box(t, at(0, 0, 0.4), Vector3d(0.25, 0.225, 0.4), {tex(front), tex(side), tex(side), tex(top), tex(side)}, id);
  return t;
}

std::vector<Triangle> wheelchair(int v, TextureCache& tc, int id) {
  std::vector<Triangle> t;
  const int frame = tc.get("wheelchair_frame/" + std::to_string(v), true, [v](Rng& r) {
    return metal_texture(r, v == 0 ? cv::Scalar(180, 180, 180) : cv::Scalar(60, 40, 160));
  });
  const int seat = tc.get("wheelchair_seat", true, [](Rng& r) { return fabric_texture(r, cv::Scalar(45, 40, 40)); });
  const int tyre = tc.get("tyre", true, [](Rng&) { return solid_texture(cv::Scalar(35, 35, 35)); });
  const int wheel = tc.get("wheel", false, wheel_texture);
  const auto M = BoxMaterials::all(tex(frame)), S = BoxMaterials::all(tex(seat));
  for (int sx = -1; sx <= 1; sx += 2) {
    add_cylinder(t, at_rot(sx * 0.30, -0.12, 0.30, kAxisX), 0.30, 0.02, 16, tex(tyre), tex(wheel), id);
    add_cylinder(t, at_rot(sx * 0.24, 0.38, 0.08, kAxisX), 0.08, 0.015, 10, tex(tyre), tex(wheel), id);
    add_box(t, at(sx * 0.24, -0.24, 0.70), Vector3d(0.015, 0.015, 0.22), M, id);   // back posts
    add_box(t, at(sx * 0.24, -0.31, 0.915), Vector3d(0.015, 0.08, 0.015), M, id);  // push handles
    add_box(t, at(sx * 0.25, 0.0, 0.68), Vector3d(0.02, 0.18, 0.015), M, id);      // armrests
    add_box(t, at(sx * 0.16, 0.36, 0.30), Vector3d(0.012, 0.012, 0.2), M, id);     // footrest struts
    add_box(t, at(sx * 0.24, 0.12, 0.34), Vector3d(0.015, 0.28, 0.015), M, id);    // lower frame
  }
  add_box(t, at(0, 0.02, 0.50), Vector3d(0.22, 0.22, 0.03), S, id);
  add_box(t, at(0, -0.23, 0.72), Vector3d(0.22, 0.015, 0.19), S, id);
  add_box(t, at(0, 0.45, 0.12), Vector3d(0.17, 0.06, 0.01), M, id);
  return t;
}

std::vector<Triangle> iv_pole(int v, TextureCache& tc, int id) {
  std::vector<Triangle> t;
  const int metal = tc.get("metal_chrome", true, [](Rng& r) { return metal_texture(r, cv::Scalar(200, 200, 205)); });
  const int dark = tc.get("metal_dark", true, [](Rng& r) { return metal_texture(r, cv::Scalar(70, 70, 75)); });
  const int bag = tc.get("iv_bag", false, [](Rng& r) {
    cv::Mat m(128, 64, CV_8UC3, cv::Scalar(235, 230, 215));
    cv::rectangle(m, cv::Rect(8, 30, 48, 50), cv::Scalar(250, 250, 250), cv::FILLED);
    cv::rectangle(m, cv::Rect(8, 30, 48, 12), cv::Scalar(60, 60, 200), cv::FILLED);
    for (int y = 48; y < 76; y += 6)
      cv::rectangle(m, cv::Rect(12, y, r.uniform_int(15, 40), 3), cv::Scalar(40, 40, 40), cv::FILLED);
    return m;
  });
  const auto M = BoxMaterials::all(tex(metal)), D = BoxMaterials::all(tex(dark));
  add_box(t, at(0, 0, 0.06), Vector3d(0.27, 0.02, 0.015), M, id);
  add_box(t, at(0, 0, 0.06), Vector3d(0.02, 0.27, 0.015), M, id);
  for (int i = 0; i < 4; ++i) {
    const double a = i * M_PI / 2;
    add_box(t, at(0.25 * std::cos(a), 0.25 * std::sin(a), 0.0225), Vector3d(0.02, 0.02, 0.0225), D, id);
  }
  add_cylinder(t, at(0, 0, 0.995), 0.02, 0.92, 8, tex(metal), tex(metal), id);
  add_box(t, at(0, 0, 1.9), Vector3d(0.16, 0.015, 0.015), M, id);
  add_box(t, at(0.12, 0, 1.72), Vector3d(0.06, 0.02, 0.1), {tex(bag), tex(bag), tex(bag), tex(bag), tex(bag)}, id);
  if (v == 1) {
    const int pump = tc.get("iv_pump", false, [](Rng& r) {
      cv::Mat m(128, 128, CV_8UC3, cv::Scalar(225, 225, 220));
      cv::rectangle(m, cv::Rect(14, 14, 100, 40), cv::Scalar(40, 60, 30), cv::FILLED);
      for (int i = 0; i < 3; ++i)
        cv::rectangle(m, cv::Rect(20 + 30 * i, 24, r.uniform_int(10, 24), 18), cv::Scalar(80, 230, 120), cv::FILLED);
      for (int i = 0; i < 6; ++i)
        cv::rectangle(m, cv::Rect(16 + 17 * i, 76, 12, 12), cv::Scalar(60, 60, 60), cv::FILLED);
      return m;
    });
    add_box(t, at(0, 0.07, 1.1), Vector3d(0.09, 0.05, 0.1), {tex(pump), tex(dark), tex(dark), tex(dark), tex(dark)},
            id);
  }
  return t;
}

}  // namespace

std::vector<Triangle> build_object_local(ObjectClass cls, int variant, TextureCache& textures, int instance) {
  switch (cls) {
    case ObjectClass::kDoor:
      return door(variant, textures, instance);
    case ObjectClass::kChair:
      return chair(variant, textures, instance);
    case ObjectClass::kBed:
      return bed(variant, textures, instance);
    case ObjectClass::kCabinet:
      return cabinet(variant, textures, instance);
    case ObjectClass::kWheelchair:
      return wheelchair(variant, textures, instance);
    case ObjectClass::kIvPole:
      return iv_pole(variant, textures, instance);
  }
  return {};
}

}  // namespace wardmap::sim
