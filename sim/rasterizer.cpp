#include "sim/rasterizer.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace wardmap::sim {

namespace {

inline int floor_to_int(float v) {
  const int i = static_cast<int>(v);
  return i - (v < static_cast<float>(i));
}

// floor(log2(rho)) for rho^2 given, >= 0: from the float exponent of rho^2.
inline int mip_level(float rho2) {
  uint32_t bits;
  std::memcpy(&bits, &rho2, sizeof bits);
  const int e = static_cast<int>((bits >> 23) & 0xff) - 127;
  return e > 0 ? (e >> 1) : 0;
}

}  // namespace

Rasterizer::Rasterizer(const Scene& scene, const slam::PinholeCamera& camera, RenderOptions options)
    : scene_(scene), camera_(camera), options_(options) {
  for (const Texture& t : scene.textures) {
    TexInfo info;
    info.wrap = t.wrap;
    float scale = 1.0f;
    for (const cv::Mat& m : t.levels) {
      info.levels.push_back({m.data, m.cols, m.rows, static_cast<int>(m.step), scale});
      scale *= 0.5f;
    }
    textures_.push_back(info);
  }
}

namespace {
struct ClipVertex {
  Eigen::Vector3d p;
  Eigen::Vector2d uv;
};
}  // namespace

void Rasterizer::prepare(const slam::SE3& T_wc, int first, int count, bool cull) {
  items_.clear();
  const slam::SE3 T_cw = T_wc.inverse();
  const Eigen::Matrix3d R = T_cw.rotation_matrix();
  const Eigen::Vector3d& t = T_cw.translation();
  const double near = options_.near_plane;
  const double fx = camera_.fx, fy = camera_.fy, cx = camera_.cx, cy = camera_.cy;

  const auto emit = [&](int tri, const ClipVertex& a, const ClipVertex& b, const ClipVertex& c) {
    const ClipVertex* v[3] = {&a, &b, &c};
    double sx[3], sy[3], w[3];
    for (int i = 0; i < 3; ++i) {
      w[i] = 1.0 / v[i]->p.z();
      sx[i] = fx * v[i]->p.x() * w[i] + cx;
      sy[i] = fy * v[i]->p.y() * w[i] + cy;
    }
    Item it;
    it.minx = std::min({sx[0], sx[1], sx[2]});
    it.maxx = std::max({sx[0], sx[1], sx[2]});
    it.miny = std::min({sy[0], sy[1], sy[2]});
    it.maxy = std::max({sy[0], sy[1], sy[2]});
    if (it.maxx < lim_x0_ || it.minx > lim_x1_ || it.maxy < lim_y0_ || it.miny > lim_y1_) return;
    const double area = (sx[1] - sx[0]) * (sy[2] - sy[0]) - (sx[2] - sx[0]) * (sy[1] - sy[0]);
    if (!(std::abs(area) > 1e-12)) return;
    const double sign = area > 0 ? 1.0 : -1.0;
    for (int i = 0; i < 3; ++i) {
      const int j = (i + 1) % 3;
      it.ea[i] = sign * (sy[i] - sy[j]);
      it.eb[i] = sign * (sx[j] - sx[i]);
      it.ec[i] = sign * (sx[i] * sy[j] - sx[j] * sy[i]);
    }
    const auto plane = [&](const double a[3], double& A, double& B, double& C) {
      A = ((a[1] - a[0]) * (sy[2] - sy[0]) - (a[2] - a[0]) * (sy[1] - sy[0])) / area;
      B = ((a[2] - a[0]) * (sx[1] - sx[0]) - (a[1] - a[0]) * (sx[2] - sx[0])) / area;
      C = a[0] - A * sx[0] - B * sy[0];
    };
    const Triangle& T = scene_.triangles[static_cast<size_t>(tri)];
    const TexLevel& L0 = textures_[static_cast<size_t>(T.texture)].levels[0];
    double uw[3], vw[3];
    for (int i = 0; i < 3; ++i) {
      uw[i] = v[i]->uv.x() * L0.width * w[i];
      vw[i] = v[i]->uv.y() * L0.height * w[i];
    }
    plane(w, it.aw, it.bw, it.cw);
    plane(uw, it.au, it.bu, it.cu);
    plane(vw, it.av, it.bv, it.cv);
    it.zmin = std::min({v[0]->p.z(), v[1]->p.z(), v[2]->p.z()});
    it.tri = tri;
    items_.push_back(it);
  };

  for (int tri = first; tri < first + count; ++tri) {
    const Triangle& T = scene_.triangles[static_cast<size_t>(tri)];
    ClipVertex v[3];
    for (int i = 0; i < 3; ++i) {
      v[i].p = R * T.p[i].cast<double>() + t;
      v[i].uv = T.uv[i].cast<double>();
    }
    if (!T.two_sided && cull) {
      const Eigen::Vector3d n = (v[1].p - v[0].p).cross(v[2].p - v[0].p);
      if (n.dot(v[0].p) >= 0) continue;
    }
    const int inside = (v[0].p.z() >= near) + (v[1].p.z() >= near) + (v[2].p.z() >= near);
    if (inside == 0) continue;
    if (inside == 3) {
      emit(tri, v[0], v[1], v[2]);
      continue;
    }
    // Sutherland-Hodgman against z = near: at most 4 vertices
    ClipVertex poly[4];
    int n = 0;
    for (int i = 0; i < 3; ++i) {
      const ClipVertex& a = v[i];
      const ClipVertex& b = v[(i + 1) % 3];
      const bool ain = a.p.z() >= near, bin = b.p.z() >= near;
      if (ain) poly[n++] = a;
      if (ain != bin) {
        const double s = (near - a.p.z()) / (b.p.z() - a.p.z());
        ClipVertex c;
        c.p = a.p + s * (b.p - a.p);
        c.p.z() = near;
        c.uv = a.uv + s * (b.uv - a.uv);
        poly[n++] = c;
      }
    }
    for (int k = 1; k + 1 < n; ++k) emit(tri, poly[0], poly[k], poly[k + 1]);
  }
}

namespace {

// Calls fn(y, x_begin, x_end_inclusive) for every row span of the item inside the limits.
template <typename Item, typename Fn>
inline void for_each_span(const Item& it, int x0, int y0, int x1, int y1, Fn&& fn) {
  const int ya = std::max(y0, static_cast<int>(std::ceil(it.miny)));
  const int yb = std::min(y1, static_cast<int>(std::floor(it.maxy)));
  const double bx0 = std::max(static_cast<double>(x0), std::ceil(it.minx));
  const double bx1 = std::min(static_cast<double>(x1), std::floor(it.maxx));
  for (int y = ya; y <= yb; ++y) {
    double xl = bx0, xr = bx1;
    bool empty = false;
    for (int i = 0; i < 3; ++i) {
      const double k = it.eb[i] * y + it.ec[i], a = it.ea[i];
      if (a > 0)
        xl = std::max(xl, std::ceil(-k / a));
      else if (a < 0)
        xr = std::min(xr, std::floor(-k / a));
      else if (k < 0)
        empty = true;
    }
    if (empty || xl > xr) continue;
    fn(y, static_cast<int>(xl), static_cast<int>(xr));
  }
}

}  // namespace

void Rasterizer::visibility_pass() {
  const int W = camera_.width, H = camera_.height;
  zbuf_.assign(static_cast<size_t>(W) * H, 0.0f);
  ibuf_.assign(static_cast<size_t>(W) * H, -1);
  order_.resize(items_.size());
  for (size_t i = 0; i < order_.size(); ++i) order_[i] = static_cast<int>(i);
  std::sort(order_.begin(), order_.end(), [&](int a, int b) {
    const double za = items_[static_cast<size_t>(a)].zmin, zb = items_[static_cast<size_t>(b)].zmin;
    return za < zb || (za == zb && a < b);
  });
  for (const int idx : order_) {
    const Item& it = items_[static_cast<size_t>(idx)];
    for_each_span(it, 0, 0, W - 1, H - 1, [&](int y, int xa, int xb) {
      float* z = zbuf_.data() + static_cast<size_t>(y) * W;
      int* ib = ibuf_.data() + static_cast<size_t>(y) * W;
      const double row = it.bw * y + it.cw;
      for (int x = xa; x <= xb; ++x) {
        const float w = static_cast<float>(it.aw * x + row);
        if (w > z[x]) {
          z[x] = w;
          ib[x] = idx;
        }
      }
    });
  }
}

void Rasterizer::shade_pass(cv::Mat& rgb) {
  const int W = camera_.width, H = camera_.height;
  rgb.create(H, W, CV_8UC3);
  const double falloff = options_.falloff;
  for (int y = 0; y < H; ++y) {
    uint8_t* out = rgb.ptr<uint8_t>(y);
    const int* ib = ibuf_.data() + static_cast<size_t>(y) * W;
    int last = -2;
    const Item* it = nullptr;
    const TexInfo* tex = nullptr;
    float shade = 0;
    double roww = 0, rowu = 0, rowv = 0;
    for (int x = 0; x < W; ++x) {
      const int idx = ib[x];
      if (idx < 0) {
        out[3 * x] = out[3 * x + 1] = out[3 * x + 2] = 0;
        continue;
      }
      if (idx != last) {
        last = idx;
        it = &items_[static_cast<size_t>(idx)];
        const Triangle& T = scene_.triangles[static_cast<size_t>(it->tri)];
        tex = &textures_[static_cast<size_t>(T.texture)];
        shade = T.shade;
        roww = it->bw * y + it->cw;
        rowu = it->bu * y + it->cu;
        rowv = it->bv * y + it->cv;
      }
      const double w = it->aw * x + roww;
      const double z = 1.0 / w;
      const double u = (it->au * x + rowu) * z, v = (it->av * x + rowv) * z;
      const double dudx = (it->au - u * it->aw) * z, dvdx = (it->av - v * it->aw) * z;
      const double dudy = (it->bu - u * it->bw) * z, dvdy = (it->bv - v * it->bw) * z;
      const float rho2 = static_cast<float>(std::max(dudx * dudx + dvdx * dvdx, dudy * dudy + dvdy * dvdy));
      const int level = std::min(mip_level(rho2), static_cast<int>(tex->levels.size()) - 1);
      const TexLevel& L = tex->levels[static_cast<size_t>(level)];
      const float fu = static_cast<float>(u) * L.scale - 0.5f, fv = static_cast<float>(v) * L.scale - 0.5f;
      int x0 = floor_to_int(fu), y0 = floor_to_int(fv);
      const float ax = fu - static_cast<float>(x0), ay = fv - static_cast<float>(y0);
      int x1 = x0 + 1, y1 = y0 + 1;
      if (tex->wrap) {
        x0 &= L.width - 1;
        x1 &= L.width - 1;
        y0 &= L.height - 1;
        y1 &= L.height - 1;
      } else {
        x0 = std::clamp(x0, 0, L.width - 1);
        x1 = std::clamp(x1, 0, L.width - 1);
        y0 = std::clamp(y0, 0, L.height - 1);
        y1 = std::clamp(y1, 0, L.height - 1);
      }
      const uint8_t* r0 = L.data + static_cast<size_t>(y0) * L.step;
      const uint8_t* r1 = L.data + static_cast<size_t>(y1) * L.step;
      const uint8_t *p00 = r0 + 3 * x0, *p01 = r0 + 3 * x1, *p10 = r1 + 3 * x0, *p11 = r1 + 3 * x1;
      const float f = shade / static_cast<float>(1.0 + falloff * z * z);
      for (int c = 0; c < 3; ++c) {
        const float top = p00[c] + (static_cast<float>(p01[c]) - p00[c]) * ax;
        const float bot = p10[c] + (static_cast<float>(p11[c]) - p10[c]) * ax;
        const float val = (top + (bot - top) * ay) * f + 0.5f;
        out[3 * x + c] = static_cast<uint8_t>(std::min(val, 255.0f));
      }
    }
  }
}

void Rasterizer::render(const slam::SE3& T_wc, RenderBuffers& out) {
  const int W = camera_.width, H = camera_.height;
  lim_x0_ = 0, lim_y0_ = 0, lim_x1_ = W - 1, lim_y1_ = H - 1;
  prepare(T_wc, 0, static_cast<int>(scene_.triangles.size()), true);
  visibility_pass();
  shade_pass(out.rgb);
  out.depth.create(H, W, CV_32F);
  out.instance.create(H, W, CV_32S);
  if (options_.triangle_ids) out.triangle.create(H, W, CV_32S);
  for (int y = 0; y < H; ++y) {
    float* d = out.depth.ptr<float>(y);
    int* ins = out.instance.ptr<int>(y);
    int* tr = options_.triangle_ids ? out.triangle.ptr<int>(y) : nullptr;
    const float* z = zbuf_.data() + static_cast<size_t>(y) * W;
    const int* ib = ibuf_.data() + static_cast<size_t>(y) * W;
    for (int x = 0; x < W; ++x) {
      if (ib[x] < 0) {
        d[x] = 0.0f;
        ins[x] = 0;
        if (tr) tr[x] = -1;
        continue;
      }
      const int tri = items_[static_cast<size_t>(ib[x])].tri;
      d[x] = 1.0f / z[x];
      ins[x] = scene_.triangles[static_cast<size_t>(tri)].instance;
      if (tr) tr[x] = tri;
    }
  }
}

void Rasterizer::render_colour(const slam::SE3& T_wc, cv::Mat& out) {
  lim_x0_ = 0, lim_y0_ = 0, lim_x1_ = camera_.width - 1, lim_y1_ = camera_.height - 1;
  prepare(T_wc, 0, static_cast<int>(scene_.triangles.size()), true);
  visibility_pass();
  shade_pass(out);
}

long Rasterizer::object_coverage(const slam::SE3& T_wc, int object_id, int margin_x, int margin_y) {
  const ObjectInstance& o = scene_.object(object_id);
  lim_x0_ = -margin_x, lim_y0_ = -margin_y;
  lim_x1_ = camera_.width - 1 + margin_x, lim_y1_ = camera_.height - 1 + margin_y;
  prepare(T_wc, o.first_triangle, o.triangle_count, true);
  const int CW = camera_.width + 2 * margin_x, CH = camera_.height + 2 * margin_y;
  if (stamp_.size() != static_cast<size_t>(CW) * CH) {
    stamp_.assign(static_cast<size_t>(CW) * CH, 0);
    stamp_value_ = 0;
  }
  if (++stamp_value_ == 0) {
    std::fill(stamp_.begin(), stamp_.end(), 0);
    stamp_value_ = 1;
  }
  long covered = 0;
  for (const Item& it : items_) {
    for_each_span(it, lim_x0_, lim_y0_, lim_x1_, lim_y1_, [&](int y, int xa, int xb) {
      uint32_t* s = stamp_.data() + static_cast<size_t>(y + margin_y) * CW + margin_x;
      for (int x = xa; x <= xb; ++x) {
        if (s[x] != stamp_value_) {
          s[x] = stamp_value_;
          ++covered;
        }
      }
    });
  }
  return covered;
}

}  // namespace wardmap::sim
