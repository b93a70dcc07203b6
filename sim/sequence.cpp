#include "sim/sequence.h"

#include <algorithm>
#include <cmath>

namespace wardmap::sim {

namespace {
constexpr double kShakeAmplitude = 7.0 * M_PI / 180.0;  // blur challenge: yaw shake at strength 1

double smoothstep(double x) {
  x = std::clamp(x, 0.0, 1.0);
  return x * x * (3 - 2 * x);
}
}  // namespace

slam::PinholeCamera synth_camera(int width, int height, double focal_640) {
  slam::PinholeCamera c;
  c.width = width;
  c.height = height;
  c.fx = c.fy = focal_640 * width / 640.0;
  c.cx = (width - 1) / 2.0;
  c.cy = (height - 1) / 2.0;
  return c;
}

Sequence::Sequence(Scenario scenario, const SequenceOptions& options, const RenderOptions& render)
    : scenario_(std::move(scenario)),
      options_(options),
      scene_(build_scene(scenario_, options.seed)),
      camera_(synth_camera(options.width, options.height, options.focal_640)),
      path_(scenario_, options.variant, options.seed),
      rasterizer_(scene_, camera_, render) {
  for (const ChallengeSpec& c : scenario_.challenges) {
    const double ta = path_.waypoint_time(c.from), tb = path_.waypoint_time(c.to);
    segment_times_.emplace_back(ta, tb);
    if (c.kind == ChallengeKind::kBlur) path_.add_shake({ta, tb, kShakeAmplitude * c.strength});
  }
  frame_count_ = static_cast<int>(std::floor(path_.duration() * options_.fps + 1e-9)) + 1;
  if (options_.max_frames > 0) frame_count_ = std::min(frame_count_, options_.max_frames);
  for (size_t k = 0; k < scenario_.challenges.size(); ++k) {
    const auto [ta, tb] = segment_times_[k];
    ChallengeSegment seg;
    seg.kind = scenario_.challenges[k].kind;
    seg.first_frame = static_cast<int>(std::ceil(ta * options_.fps - 1e-9));
    seg.last_frame = std::min(frame_count_ - 1, static_cast<int>(std::floor(tb * options_.fps + 1e-9)));
    if (seg.first_frame > seg.last_frame) continue;
    seg.t_begin = timestamp(seg.first_frame);
    seg.t_end = timestamp(seg.last_frame);
    challenges_.push_back(seg);
  }
}

double Sequence::timestamp(int i) const { return options_.start_time + i / options_.fps; }

const ChallengeSegment* Sequence::challenge_at(int i) const {
  for (const ChallengeSegment& c : challenges_)
    if (i >= c.first_frame && i <= c.last_frame) return &c;
  return nullptr;
}

void Sequence::render(int i, Frame& frame, bool annotate_objects) {
  const double t = i / options_.fps;
  frame.index = i;
  frame.timestamp = timestamp(i);
  frame.T_wc = path_.pose(t);
  rasterizer_.render(frame.T_wc, frame.buffers);

  bool blur = false;
  double gain = 1.0;
  for (size_t k = 0; k < scenario_.challenges.size(); ++k) {
    const ChallengeSpec& c = scenario_.challenges[k];
    const auto [ta, tb] = segment_times_[k];
    if (t < ta || t > tb) continue;
    if (c.kind == ChallengeKind::kBlur || c.kind == ChallengeKind::kFastTurn) blur = true;
    if (c.kind == ChallengeKind::kDark) {
      const double ramp = std::min(0.4, 0.25 * (tb - ta));
      const double env = smoothstep(std::min(t - ta, tb - t) / ramp);
      gain = std::min(gain, 1.0 - (1.0 - c.strength) * env);
    }
  }
  cv::Mat& rgb = frame.buffers.rgb;
  if (blur) {  // average sub-frames over one frame interval of exposure
    // enough sub-frames that the image moves at most ~3 px between two of them
    const slam::SE3 a = path_.pose(t - 0.5 / options_.fps), b = path_.pose(t + 0.5 / options_.fps);
    const double px = slam::rotation_angle(a.rotation().inverse() * b.rotation()) * camera_.fx +
                      (a.translation() - b.translation()).norm() * camera_.fx;  // ~1 m away
    const int n = std::clamp(static_cast<int>(std::ceil(px / 3.0)), std::max(2, options_.blur_subframes), 32);
    std::vector<int> sum(rgb.total() * 3, 0);
    cv::Mat sub;
    for (int k = 0; k < n; ++k) {
      const double ts = t + ((k + 0.5) / n - 0.5) / options_.fps;
      rasterizer_.render_colour(path_.pose(ts), sub);
      const uint8_t* p = sub.ptr<uint8_t>(0);  // continuous
      for (size_t j = 0; j < sum.size(); ++j) sum[j] += p[j];
    }
    uint8_t* o = rgb.ptr<uint8_t>(0);
    for (size_t j = 0; j < sum.size(); ++j) o[j] = static_cast<uint8_t>((sum[j] + n / 2) / n);
  }
  if (gain < 1.0) {
    const int64_t g = std::llround(gain * 65536.0);
    uint8_t* o = rgb.ptr<uint8_t>(0);
    for (size_t j = 0; j < rgb.total() * 3; ++j) o[j] = static_cast<uint8_t>((o[j] * g + 32768) >> 16);
  }
  frame.annotations.clear();
  if (annotate_objects) frame.annotations = annotate(scene_, frame.buffers.instance, rasterizer_, frame.T_wc);
}

}  // namespace wardmap::sim
