#include "semantics/detection/annotations_detector.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "semantics/detection/frame_rng.h"
#include "slam/core/errors.h"

namespace wardmap::semantics {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// False-positive boxes: side lengths as a fraction of the image side, uniform in this range.
constexpr double kFalsePositiveMinSide = 0.05;
constexpr double kFalsePositiveMaxSide = 0.35;
// A false positive scores like a true detection of an object at most this visible.
constexpr double kFalsePositiveMaxVisible = 0.5;
constexpr double kMinScore = 0.01;
constexpr double kMinSide = 1.0;  // pixels: a jittered box never collapses below this

double number_field(const json& j, const char* key, const fs::path& file, long line, const std::string& where) {
  const auto it = j.find(key);
  if (it == j.end()) throw InputError(file.string(), where + "missing field '" + key + "'", line);
  if (!it->is_number()) throw InputError(file.string(), where + "field '" + key + "' must be a number", line);
  return it->get<double>();
}

AnnotatedObject read_object(const json& o, const fs::path& file, long line, size_t index) {
  const std::string where = "objects[" + std::to_string(index) + "]: ";
  if (!o.is_object()) throw InputError(file.string(), where + "expected an object", line);
  AnnotatedObject a;
  const auto id = o.find("id");
  if (id == o.end() || !id->is_number_integer())
    throw InputError(file.string(), where + "field 'id' must be an integer", line);
  a.id = id->get<int>();
  const auto cls = o.find("class");
  if (cls == o.end() || !cls->is_string() || cls->get<std::string>().empty())
    throw InputError(file.string(), where + "field 'class' must be a non-empty string", line);
  a.label = cls->get<std::string>();
  const auto box = o.find("box");
  if (box == o.end() || !box->is_array() || box->size() != 4 ||
      !std::all_of(box->begin(), box->end(), [](const json& v) { return v.is_number(); }))
    throw InputError(file.string(), where + "field 'box' must be [x0, y0, x1, y1]", line);
  for (int k = 0; k < 4; ++k) a.box[k] = (*box)[k].get<double>();
  if (!(a.box[2] >= a.box[0] && a.box[3] >= a.box[1]))
    throw InputError(file.string(), where + "field 'box' needs x1 >= x0 and y1 >= y0", line);
  if (o.contains("visible")) a.visible = number_field(o, "visible", file, line, where);
  if (!(a.visible >= 0 && a.visible <= 1))
    throw InputError(file.string(), where + "field 'visible' must be in [0, 1]", line);
  return a;
}

// Sides lo, hi at least kMinSide apart (and in order), keeping their midpoint.
void widen_to_min_side(double& lo, double& hi) {
  if (hi - lo >= kMinSide) return;
  const double mid = 0.5 * (lo + hi);
  lo = mid - 0.5 * kMinSide;
  hi = mid + 0.5 * kMinSide;
}

void clip_box(Eigen::Vector4d& b, double width, double height) {
  b[0] = std::clamp(b[0], 0.0, width);
  b[2] = std::clamp(b[2], 0.0, width);
  b[1] = std::clamp(b[1], 0.0, height);
  b[3] = std::clamp(b[3], 0.0, height);
}

}  // namespace

const std::vector<std::string>& hospital_classes() {
  static const std::vector<std::string> classes{"door", "chair", "bed", "cabinet", "wheelchair", "iv_pole"};
  return classes;
}

std::vector<AnnotatedFrame> read_annotations(const fs::path& file) {
  std::ifstream in(file);
  if (!in)
    throw InputError(file.string(),
                     "cannot open the annotations (the annotations detector needs a sequence made by "
                     "'wardmap synth')");
  std::vector<std::pair<AnnotatedFrame, long>> frames;
  std::string text;
  long line = 0;
  while (std::getline(in, text)) {
    ++line;
    if (text.find_first_not_of(" \t\r") == std::string::npos) continue;
    json j;
    try {
      j = json::parse(text);
    } catch (const json::exception& ex) {  // parse_error, or out_of_range for a number too large
      throw InputError(file.string(), std::string("malformed JSON: ") + ex.what(), line);
    }
    if (!j.is_object()) throw InputError(file.string(), "expected a JSON object per line", line);
    AnnotatedFrame f;
    f.timestamp = number_field(j, "timestamp", file, line, "");
    const auto objects = j.find("objects");
    if (objects == j.end() || !objects->is_array())
      throw InputError(file.string(), "field 'objects' must be an array", line);
    for (size_t i = 0; i < objects->size(); ++i) f.objects.push_back(read_object((*objects)[i], file, line, i));
    frames.emplace_back(std::move(f), line);
  }
  std::stable_sort(frames.begin(), frames.end(),
                   [](const auto& a, const auto& b) { return a.first.timestamp < b.first.timestamp; });
  std::vector<AnnotatedFrame> out;
  for (size_t i = 0; i < frames.size(); ++i) {
    if (i > 0 && frames[i].first.timestamp - frames[i - 1].first.timestamp <= AnnotationsDetector::kTimestampTolerance)
      throw InputError(file.string(),
                       "timestamp " + std::to_string(frames[i].first.timestamp) + " repeats the frame of line " +
                           std::to_string(frames[i - 1].second),
                       frames[i].second);
    out.push_back(std::move(frames[i].first));
  }
  return out;
}

AnnotationsDetector::AnnotationsDetector(const fs::path& annotations_file, const AnnotationNoise& noise)
    : file_(annotations_file), noise_(noise), frames_(read_annotations(annotations_file)) {}

const AnnotatedFrame* AnnotationsDetector::find_frame(double timestamp) const {
  auto it = std::lower_bound(frames_.begin(), frames_.end(), timestamp - kTimestampTolerance,
                             [](const AnnotatedFrame& f, double t) { return f.timestamp < t; });
  if (it == frames_.end() || it->timestamp > timestamp + kTimestampTolerance) return nullptr;
  return &*it;
}

std::vector<Detection> AnnotationsDetector::detect(const cv::Mat& image, double timestamp) {
  const AnnotatedFrame* frame = find_frame(timestamp);
  if (!frame) {
    if (!warned_missing_)
      spdlog::warn("{}: no annotated frame at t = {:.6f} (further misses not reported)", file_.string(), timestamp);
    warned_missing_ = true;
    return {};
  }
  const bool clip = !image.empty();
  const double width = clip ? image.cols : noise_.image_width;
  const double height = clip ? image.rows : noise_.image_height;
  const auto& classes = hospital_classes();
  // Seeded by the annotated timestamp, so a slightly different query time gives the same noise.
  FrameRng rng(noise_.seed, frame->timestamp);

  std::vector<Detection> out;
  for (const AnnotatedObject& o : frame->objects) {
    // Every object consumes the same draws whatever the options, so changing one probability does
    // not reshuffle the noise of the other objects.
    const double u_miss = rng.uniform(), u_low = rng.uniform(), u_confuse = rng.uniform();
    const int other = rng.index(static_cast<int>(classes.size()) - 1);
    double n[5];
    for (double& v : n) v = rng.normal();

    if (o.visible < noise_.min_visible) continue;
    if (u_miss < noise_.miss_probability) continue;
    if (o.visible < noise_.low_visible_fraction && u_low < noise_.low_visible_miss_probability) continue;

    Detection d;
    d.gt_instance = o.id;
    d.label = o.label;
    if (u_confuse < noise_.confusion_probability) {
      // The other-th hospital class that differs from the true one.
      std::vector<std::string> choices;
      for (const auto& c : classes)
        if (c != o.label) choices.push_back(c);
      d.label = choices[std::min<size_t>(other, choices.size() - 1)];
    }
    d.source_label = d.label;
    Eigen::Vector4d b = o.box;
    if (noise_.box_jitter > 0) {
      const double w = b[2] - b[0], h = b[3] - b[1];
      b += noise_.box_jitter * Eigen::Vector4d(n[0] * w, n[1] * h, n[2] * w, n[3] * h);
      widen_to_min_side(b[0], b[2]);
      widen_to_min_side(b[1], b[3]);
    }
    if (clip) {
      clip_box(b, width, height);
      if (b[2] <= b[0] || b[3] <= b[1]) continue;  // entirely off the image
    }
    d.box = b;
    d.score = static_cast<float>(std::clamp(
        noise_.score_base + noise_.score_visible_gain * o.visible + noise_.score_std * n[4], kMinScore, 1.0));
    out.push_back(std::move(d));
  }

  const int false_positives = rng.poisson(noise_.false_positives_per_frame);
  for (int i = 0; i < false_positives; ++i) {
    const double w = rng.uniform(kFalsePositiveMinSide, kFalsePositiveMaxSide) * width;
    const double h = rng.uniform(kFalsePositiveMinSide, kFalsePositiveMaxSide) * height;
    const double x0 = rng.uniform(0, width - w), y0 = rng.uniform(0, height - h);
    Detection d;
    d.box = Eigen::Vector4d(x0, y0, x0 + w, y0 + h);
    d.label = d.source_label = classes[rng.index(static_cast<int>(classes.size()))];
    d.score = static_cast<float>(std::clamp(
        noise_.score_base + noise_.score_visible_gain * kFalsePositiveMaxVisible * rng.uniform(), kMinScore, 1.0));
    out.push_back(std::move(d));
  }
  return out;
}

}  // namespace wardmap::semantics
