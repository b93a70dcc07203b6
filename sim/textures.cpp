#include "sim/textures.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace wardmap::sim {

namespace {

bool is_pow2(int v) { return v > 0 && (v & (v - 1)) == 0; }

uchar clamp8(int v) { return static_cast<uchar>(std::clamp(v, 0, 255)); }

cv::Scalar jitter_colour(Rng& rng, const cv::Scalar& c, int amount) {
  const int d = rng.uniform_int(-amount, amount);
  return cv::Scalar(std::clamp(c[0] + d + rng.uniform_int(-2, 2), 0.0, 255.0),
                    std::clamp(c[1] + d + rng.uniform_int(-2, 2), 0.0, 255.0),
                    std::clamp(c[2] + d + rng.uniform_int(-2, 2), 0.0, 255.0));
}

// Grey per-texel noise in [-amount, amount].
void add_noise(cv::Mat& m, Rng& rng, int amount) {
  if (amount <= 0) return;
  for (int y = 0; y < m.rows; ++y) {
    auto* p = m.ptr<uchar>(y);
    for (int x = 0; x < m.cols; ++x) {
      const int d = rng.uniform_int(-amount, amount);
      for (int c = 0; c < 3; ++c) p[3 * x + c] = clamp8(p[3 * x + c] + d);
    }
  }
}

// Small dots brighter or darker than what is under them (what FAST sees as corners).
void add_speckle(cv::Mat& m, Rng& rng, int count, int contrast, int max_radius) {
  for (int i = 0; i < count; ++i) {
    const cv::Point c(rng.uniform_int(0, m.cols - 1), rng.uniform_int(0, m.rows - 1));
    const int r = rng.uniform_int(1, max_radius);
    const cv::Vec3b under = m.at<cv::Vec3b>(c);
    const int d = (rng.chance(0.7) ? -1 : 1) * rng.uniform_int(contrast / 2, contrast);
    cv::circle(m, c, r, cv::Scalar(clamp8(under[0] + d), clamp8(under[1] + d), clamp8(under[2] + d)), cv::FILLED,
               cv::LINE_8);
  }
}

const char* kWords[] = {"WARD",     "EXIT",   "HAND",     "HYGIENE", "PLEASE",   "WASH",     "HANDS",  "NO",
                        "ENTRY",    "STAFF",  "ONLY",     "X-RAY",   "WAITING",  "ROOM",     "NURSE",  "STATION",
                        "OXYGEN",   "IN USE", "VISITORS", "QUIET",   "PHARMACY", "LIFT",     "STAIRS", "FIRE",
                        "ASSEMBLY", "POINT",  "CAUTION",  "WET",     "FLOOR",    "ONCOLOGY", "CARDIO", "MRI"};
constexpr int kWordCount = sizeof(kWords) / sizeof(kWords[0]);

void put_text_fit(cv::Mat& m, const std::string& text, const cv::Rect& box, const cv::Scalar& colour, int thickness) {
  int base = 0;
  const cv::Size s1 = cv::getTextSize(text, cv::FONT_HERSHEY_SIMPLEX, 1.0, thickness, &base);
  const double scale = std::min(box.width * 0.9 / std::max(1, s1.width), box.height * 0.8 / std::max(1, s1.height));
  const cv::Size s = cv::getTextSize(text, cv::FONT_HERSHEY_SIMPLEX, scale, thickness, &base);
  const cv::Point org(box.x + (box.width - s.width) / 2, box.y + (box.height + s.height) / 2);
  cv::putText(m, text, org, cv::FONT_HERSHEY_SIMPLEX, scale, colour, thickness, cv::LINE_AA);
}

// Rows of short dark blocks that read as print from a distance.
void add_print(cv::Mat& m, Rng& rng, const cv::Rect& area, const cv::Scalar& ink, int line_h) {
  for (int y = area.y; y + line_h <= area.y + area.height; y += line_h * 2) {
    int x = area.x;
    const int end = area.x + area.width - rng.uniform_int(0, area.width / 4);
    while (x < end) {
      const int w = rng.uniform_int(line_h, line_h * 5);
      if (x + w > end) break;
      cv::rectangle(m, cv::Rect(x, y, w, line_h), ink, cv::FILLED);
      x += w + rng.uniform_int(line_h / 2 + 1, line_h);
    }
  }
}

}  // namespace

Texture make_texture(const cv::Mat& level0, bool wrap) {
  if (level0.type() != CV_8UC3 || !is_pow2(level0.cols) || !is_pow2(level0.rows))
    throw std::logic_error("make_texture: needs CV_8UC3 with power-of-two sides");
  Texture t;
  t.wrap = wrap;
  t.levels.push_back(level0.clone());
  while (t.levels.back().cols >= 8 && t.levels.back().rows >= 8) {
    const cv::Mat& a = t.levels.back();
    cv::Mat b(a.rows / 2, a.cols / 2, CV_8UC3);
    for (int y = 0; y < b.rows; ++y) {
      const uchar* r0 = a.ptr<uchar>(2 * y);
      const uchar* r1 = a.ptr<uchar>(2 * y + 1);
      uchar* o = b.ptr<uchar>(y);
      for (int x = 0; x < b.cols * 3; ++x) {
        const int c = x % 3, px = x / 3;
        const int s = r0[6 * px + c] + r0[6 * px + 3 + c] + r1[6 * px + c] + r1[6 * px + 3 + c];
        o[x] = static_cast<uchar>((s + 2) / 4);
      }
    }
    t.levels.push_back(b);
  }
  return t;
}

cv::Mat floor_tiles_texture(Rng& rng) {
  const int n = 1024, tile = n / 8;
  cv::Mat m(n, n, CV_8UC3);
  const cv::Scalar base = jitter_colour(rng, cv::Scalar(185, 195, 200), 10);
  const cv::Scalar accent = rng.chance(0.5) ? cv::Scalar(150, 120, 95) : cv::Scalar(120, 140, 150);
  for (int ty = 0; ty < 8; ++ty)
    for (int tx = 0; tx < 8; ++tx) {
      const cv::Scalar c = rng.chance(0.18) ? jitter_colour(rng, accent, 12) : jitter_colour(rng, base, 16);
      cv::rectangle(m, cv::Rect(tx * tile, ty * tile, tile, tile), c, cv::FILLED);
    }
  add_speckle(m, rng, 9000, 70, 2);
  add_noise(m, rng, 3);
  const cv::Scalar grout(105, 110, 115);
  for (int i = 0; i < 8; ++i) {
    cv::rectangle(m, cv::Rect(i * tile, 0, 3, n), grout, cv::FILLED);
    cv::rectangle(m, cv::Rect(0, i * tile, n, 3), grout, cv::FILLED);
  }
  return m;
}

cv::Mat lino_texture(Rng& rng) {
  const int n = 512;
  cv::Mat m(n, n, CV_8UC3, jitter_colour(rng, cv::Scalar(160, 170, 150), 15));
  add_speckle(m, rng, 7000, 80, 2);
  add_noise(m, rng, 4);
  return m;
}

cv::Mat plain_floor_texture(Rng& rng) {
  cv::Mat m(64, 64, CV_8UC3, jitter_colour(rng, cv::Scalar(150, 160, 165), 10));
  return m;
}

cv::Mat wall_texture(Rng& rng, const std::string& kind, const cv::Scalar& base_bgr, double ceiling_height) {
  const int w = 512, h = 512;
  const auto row_of = [&](double z) {
    return std::clamp(static_cast<int>((ceiling_height - z) / ceiling_height * h), 0, h);
  };
  cv::Mat m(h, w, CV_8UC3, base_bgr);
  if (kind == "speckle") {
    add_speckle(m, rng, 2600, 70, 2);
    add_noise(m, rng, 2);
  } else if (kind == "tiles") {
    const int top = row_of(1.4), ts = 32;  // 0.125 m tiles
    cv::rectangle(m, cv::Rect(0, top, w, h - top), cv::Scalar(232, 234, 236), cv::FILLED);
    for (int y = top; y < h; y += ts)
      for (int x = 0; x < w; x += ts)
        if (rng.chance(0.12))
          cv::rectangle(m, cv::Rect(x, y, ts, ts), jitter_colour(rng, cv::Scalar(170, 140, 90), 15), cv::FILLED);
    for (int y = top; y < h; y += ts) cv::rectangle(m, cv::Rect(0, y, w, 2), cv::Scalar(160, 160, 160), cv::FILLED);
    for (int x = 0; x < w; x += ts)
      cv::rectangle(m, cv::Rect(x, top, 2, h - top), cv::Scalar(160, 160, 160), cv::FILLED);
    add_noise(m, rng, 2);
  } else if (kind == "wood") {
    const int top = row_of(1.1);
    cv::Mat panel = wood_texture(rng, cv::Scalar(90, 135, 175), w, h, true);
    panel(cv::Rect(0, top, w, h - top)).copyTo(m(cv::Rect(0, top, w, h - top)));
    for (int x = 0; x < w; x += 128) cv::rectangle(m, cv::Rect(x, top, 3, h - top), cv::Scalar(40, 60, 80), cv::FILLED);
    cv::rectangle(m, cv::Rect(0, top, w, 5), cv::Scalar(50, 75, 100), cv::FILLED);
    add_noise(m, rng, 1);
  } else if (kind == "paint") {
    add_noise(m, rng, 2);
    // a few scuffs and fixings: small marks that give some corners on long bare walls
    for (int i = 0; i < 40; ++i) {
      const cv::Point c(rng.uniform_int(0, w - 1), rng.uniform_int(row_of(1.6), h - 1));
      cv::circle(m, c, rng.uniform_int(1, 2), base_bgr - cv::Scalar(60, 60, 60), cv::FILLED);
    }
  }
  // skirting board, not on plain walls' upper part (plain walls stay featureless at camera height)
  const int skirt = row_of(0.12);
  cv::rectangle(m, cv::Rect(0, skirt, w, h - skirt), cv::Scalar(70, 75, 80), cv::FILLED);
  return m;
}

cv::Mat ceiling_texture(Rng& rng) {
  const int n = 1024, panel = n / 4;
  cv::Mat m(n, n, CV_8UC3, cv::Scalar(225, 228, 228));
  add_speckle(m, rng, 5000, 60, 2);
  // light panel with a diffuser grid
  const cv::Rect light(panel + 6, panel + 6, panel - 12, panel - 12);
  cv::rectangle(m, light, cv::Scalar(252, 252, 250), cv::FILLED);
  for (int i = 1; i < 8; ++i) {
    cv::rectangle(m, cv::Rect(light.x + i * light.width / 8, light.y, 2, light.height), cv::Scalar(200, 200, 200),
                  cv::FILLED);
    cv::rectangle(m, cv::Rect(light.x, light.y + i * light.height / 8, light.width, 2), cv::Scalar(200, 200, 200),
                  cv::FILLED);
  }
  for (int i = 0; i < 4; ++i) {
    cv::rectangle(m, cv::Rect(i * panel, 0, 6, n), cv::Scalar(175, 178, 180), cv::FILLED);
    cv::rectangle(m, cv::Rect(0, i * panel, n, 6), cv::Scalar(175, 178, 180), cv::FILLED);
  }
  return m;
}

cv::Mat poster_texture(Rng& rng, int width, int height) {
  const cv::Scalar papers[] = {{245, 245, 245}, {200, 235, 250}, {235, 225, 200}, {210, 240, 215}, {60, 60, 60}};
  const cv::Scalar inks[] = {{40, 40, 40}, {150, 60, 20}, {30, 30, 170}, {40, 110, 30}, {220, 220, 220}};
  const int style = rng.uniform_int(0, 4);
  cv::Mat m(height, width, CV_8UC3, papers[style]);
  const cv::Scalar ink = inks[style];
  const cv::Scalar accent = cv::Scalar(rng.uniform_int(0, 255), rng.uniform_int(0, 255), rng.uniform_int(0, 255));
  const int b = std::max(4, width / 32);
  cv::rectangle(m, cv::Rect(0, 0, width, height), accent, b);
  // title band with words
  const cv::Rect title(b * 2, b * 2, width - 4 * b, height / 6);
  cv::rectangle(m, title, accent, cv::FILLED);
  std::string text = kWords[rng.uniform_int(0, kWordCount - 1)];
  if (rng.chance(0.6)) text += std::string(" ") + kWords[rng.uniform_int(0, kWordCount - 1)];
  const cv::Scalar title_ink =
      (accent[0] + accent[1] + accent[2]) > 380 ? cv::Scalar(20, 20, 20) : cv::Scalar(250, 250, 250);
  put_text_fit(m, text, title, title_ink, std::max(1, width / 100));
  // a picture: shapes on a coloured ground
  const int pic_top = title.y + title.height + b;
  const cv::Rect pic(b * 2, pic_top, width - 4 * b, (height - pic_top) / 2);
  cv::rectangle(m, pic, jitter_colour(rng, cv::Scalar(180, 200, 210), 60), cv::FILLED);
  for (int i = 0; i < 6; ++i) {
    const cv::Scalar c(rng.uniform_int(0, 255), rng.uniform_int(0, 255), rng.uniform_int(0, 255));
    const cv::Point p(pic.x + rng.uniform_int(0, pic.width - 1), pic.y + rng.uniform_int(0, pic.height - 1));
    const int r = rng.uniform_int(pic.width / 16 + 1, pic.width / 5 + 2);
    if (rng.chance(0.5))
      cv::circle(m, p, r, c, cv::FILLED, cv::LINE_AA);
    else
      cv::rectangle(m, cv::Rect(p.x - r, p.y - r / 2, 2 * r, r), c, cv::FILLED);
  }
  cv::rectangle(m, pic, ink, 2);
  m(cv::Rect(0, 0, width, height)).colRange(0, b).setTo(accent);
  // print below
  const int print_top = pic.y + pic.height + b;
  add_print(m, rng, cv::Rect(b * 2, print_top, width - 4 * b, height - print_top - 2 * b), ink,
            std::max(3, height / 64));
  return m;
}

cv::Mat sign_texture(Rng& rng, const std::string& text, const cv::Scalar& bg, const cv::Scalar& fg) {
  cv::Mat m(128, 512, CV_8UC3, bg);
  cv::rectangle(m, cv::Rect(0, 0, 512, 128), fg, 6);
  // pictogram square at the left
  cv::rectangle(m, cv::Rect(16, 20, 88, 88), fg, cv::FILLED);
  const int glyph = rng.uniform_int(0, 2);
  if (glyph == 0) cv::circle(m, cv::Point(60, 64), 28, bg, cv::FILLED, cv::LINE_AA);
  if (glyph == 1) cv::rectangle(m, cv::Rect(38, 42, 44, 44), bg, cv::FILLED);
  if (glyph == 2) {
    const cv::Point tri[] = {{60, 30}, {92, 96}, {28, 96}};
    cv::fillConvexPoly(m, tri, 3, bg, cv::LINE_AA);
  }
  put_text_fit(m, text, cv::Rect(112, 8, 392, 112), fg, 3);
  return m;
}

cv::Mat wood_texture(Rng& rng, const cv::Scalar& base, int width, int height, bool vertical_grain) {
  cv::Mat m(height, width, CV_8UC3);
  const double f1 = rng.uniform(0.08, 0.14), f2 = rng.uniform(0.015, 0.03), ph = rng.uniform(0, 6.28);
  std::vector<double> wobble(static_cast<size_t>(std::max(width, height)));
  double acc = 0;
  for (auto& v : wobble) v = (acc += rng.uniform(-0.6, 0.6)) * 0.6;
  for (int y = 0; y < height; ++y) {
    auto* p = m.ptr<uchar>(y);
    for (int x = 0; x < width; ++x) {
      const double across = vertical_grain ? x : y, along = vertical_grain ? y : x;
      const double g =
          std::sin(across * f1 + 0.8 * std::sin(along * f2 + ph) + wobble[static_cast<size_t>(along)] * 0.3);
      const double k = 0.82 + 0.14 * g * g * g + 0.02 * std::sin(across * 0.9);
      for (int c = 0; c < 3; ++c) p[3 * x + c] = clamp8(static_cast<int>(std::lround(base[c] * k)));
    }
  }
  add_noise(m, rng, 3);
  return m;
}

cv::Mat fabric_texture(Rng& rng, const cv::Scalar& base) {
  cv::Mat m(128, 128, CV_8UC3, base);
  for (int y = 0; y < 128; ++y) {
    auto* p = m.ptr<uchar>(y);
    for (int x = 0; x < 128; ++x) {
      const int d = ((x / 2 + y / 2) % 2) ? 8 : -8;
      for (int c = 0; c < 3; ++c) p[3 * x + c] = clamp8(p[3 * x + c] + d);
    }
  }
  add_noise(m, rng, 6);
  return m;
}

cv::Mat metal_texture(Rng& rng, const cv::Scalar& base) {
  cv::Mat m(64, 64, CV_8UC3, base);
  for (int y = 0; y < 64; ++y) {
    const int d = rng.uniform_int(-10, 10);
    for (int x = 0; x < 64; ++x)
      for (int c = 0; c < 3; ++c) m.at<cv::Vec3b>(y, x)[c] = clamp8(static_cast<int>(base[c]) + d);
  }
  add_noise(m, rng, 3);
  return m;
}

cv::Mat solid_texture(const cv::Scalar& bgr) { return cv::Mat(8, 8, CV_8UC3, bgr); }

cv::Mat door_texture(Rng& rng, int variant, const std::string& number) {
  const int w = 256, h = 512;
  cv::Mat m;
  if (variant == 0) {
    m = wood_texture(rng, cv::Scalar(95, 150, 195), w, h, true);
  } else if (variant == 1) {
    m = cv::Mat(h, w, CV_8UC3, cv::Scalar(150, 140, 40));
    add_noise(m, rng, 3);
  } else {
    m = cv::Mat(h, w, CV_8UC3, cv::Scalar(200, 205, 210));
    add_noise(m, rng, 3);
  }
  // rebate lines along the edges
  cv::rectangle(m, cv::Rect(0, 0, w, h), cv::Scalar(60, 60, 60), 3);
  const cv::Scalar glass(215, 200, 180), steel(185, 185, 180);
  if (variant == 0) {
    const cv::Rect win(150, 70, 45, 170);
    cv::rectangle(m, win, glass, cv::FILLED);
    cv::line(m, {win.x + 8, win.y + win.height - 10}, {win.x + win.width - 8, win.y + 20}, cv::Scalar(245, 240, 235),
             3);
    cv::rectangle(m, win, cv::Scalar(40, 40, 40), 4);
  } else if (variant == 1) {
    const cv::Rect win(68, 60, 120, 120);
    cv::rectangle(m, win, glass, cv::FILLED);
    for (int i = 1; i < 6; ++i) {
      cv::line(m, {win.x + i * 20, win.y}, {win.x + i * 20, win.y + win.height}, cv::Scalar(120, 120, 120), 1);
      cv::line(m, {win.x, win.y + i * 20}, {win.x + win.width, win.y + i * 20}, cv::Scalar(120, 120, 120), 1);
    }
    cv::rectangle(m, win, cv::Scalar(30, 30, 30), 4);
    cv::rectangle(m, cv::Rect(30, 250, 30, 90), steel, cv::FILLED);  // push plate
  } else {
    cv::Mat s = sign_texture(rng, "STAFF ONLY", cv::Scalar(30, 30, 160), cv::Scalar(255, 255, 255));
    cv::Mat small;
    cv::resize(s, small, cv::Size(160, 40), 0, 0, cv::INTER_NEAREST);
    small.copyTo(m(cv::Rect(48, 110, 160, 40)));
  }
  // kick plate, handle, number plate
  cv::rectangle(m, cv::Rect(6, h - 60, w - 12, 54), steel, cv::FILLED);
  cv::rectangle(m, cv::Rect(6, h - 60, w - 12, 54), cv::Scalar(120, 120, 120), 2);
  cv::rectangle(m, cv::Rect(20, 250, 12, 26), cv::Scalar(50, 50, 50), cv::FILLED);
  cv::rectangle(m, cv::Rect(20, 256, 46, 9), cv::Scalar(70, 70, 70), cv::FILLED);
  cv::rectangle(m, cv::Rect(90, 30, 76, 26), cv::Scalar(240, 240, 240), cv::FILLED);
  put_text_fit(m, number, cv::Rect(90, 30, 76, 26), cv::Scalar(20, 20, 20), 2);
  return m;
}

cv::Mat cabinet_front_texture(Rng& rng, int variant) {
  const int w = 256, h = 512;
  const cv::Scalar bases[] = {{200, 225, 235}, {235, 235, 235}, {80, 130, 175}};
  cv::Mat m = variant == 2 ? wood_texture(rng, bases[2], w, h, false) : cv::Mat(h, w, CV_8UC3, bases[variant % 3]);
  if (variant != 2) add_noise(m, rng, 3);
  const cv::Scalar line(60, 60, 60), handle(90, 90, 90);
  cv::rectangle(m, cv::Rect(0, 0, w, h), line, 4);
  cv::rectangle(m, cv::Rect(8, 8, w - 16, 110), line, 3);  // drawer
  cv::rectangle(m, cv::Rect(w / 2 - 40, 50, 80, 12), handle, cv::FILLED);
  cv::rectangle(m, cv::Rect(8, 126, w - 16, h - 134), line, 3);  // door
  cv::rectangle(m, cv::Rect(w - 40, 200, 14, 90), handle, cv::FILLED);
  cv::rectangle(m, cv::Rect(30, 150, 90, 60), cv::Scalar(250, 250, 250), cv::FILLED);  // label
  add_print(m, rng, cv::Rect(36, 158, 78, 46), cv::Scalar(40, 40, 40), 5);
  return m;
}

cv::Mat sheet_texture(Rng& rng, const cv::Scalar& base) {
  cv::Mat m(256, 256, CV_8UC3, base);
  for (int i = 0; i < 256; i += 32) cv::rectangle(m, cv::Rect(0, i, 256, 4), base - cv::Scalar(25, 20, 10), cv::FILLED);
  add_noise(m, rng, 3);
  return m;
}

}  // namespace wardmap::sim
