// A synthetic sequence: scenario + variant + seed -> scene, camera path, challenge segments, and
// frames rendered on demand (RGB with the challenges' effects, depth, instances, annotations).
#pragma once

#include <string>
#include <vector>

#include "sim/annotations.h"
#include "sim/camera_path.h"
#include "sim/rasterizer.h"
#include "sim/scenario.h"
#include "sim/scene.h"
#include "slam/core/camera.h"

namespace wardmap::sim {

struct SequenceOptions {
  Variant variant = Variant::kSlow;
  uint32_t seed = 1;
  int width = 640, height = 480;
  int max_frames = 0;  // 0: the whole path; N: only the first N frames
  double fps = 30.0;
  double start_time = 1000.0;  // timestamp of frame 0
  double focal_640 = 525.0;    // focal length at 640 px width (scaled with the width)
  int blur_subframes =
      6;  // at least this many renders averaged per motion-blurred frame (more when it moves fast, up to 32)
};

struct ChallengeSegment {
  ChallengeKind kind = ChallengeKind::kBlur;
  int first_frame = 0, last_frame = 0;  // inclusive
  double t_begin = 0, t_end = 0;        // timestamps of those frames
};

struct Frame {
  int index = 0;
  double timestamp = 0;
  slam::SE3 T_wc;
  RenderBuffers buffers;  // rgb with effects; depth, instance (and triangle) from the pose at timestamp
  std::vector<Annotation> annotations;
};

class Sequence {
 public:
  Sequence(Scenario scenario, const SequenceOptions& options, const RenderOptions& render = {});

  int frame_count() const { return frame_count_; }
  double timestamp(int i) const;
  slam::SE3 pose(int i) const { return path_.pose(i / options_.fps); }
  // Challenge segments that contain at least one of the frames.
  const std::vector<ChallengeSegment>& challenges() const { return challenges_; }
  // The challenge frame i is in, if any.
  const ChallengeSegment* challenge_at(int i) const;

  // Render frame i; annotations only when asked (they cost one extra object raster per object seen).
  void render(int i, Frame& frame, bool annotate_objects = true);

  const Scenario& scenario() const { return scenario_; }
  const SequenceOptions& options() const { return options_; }
  const Scene& scene() const { return scene_; }
  const slam::PinholeCamera& camera() const { return camera_; }

 private:
  Scenario scenario_;
  SequenceOptions options_;
  Scene scene_;
  slam::PinholeCamera camera_;
  CameraPath path_;
  Rasterizer rasterizer_;
  int frame_count_ = 0;
  std::vector<ChallengeSegment> challenges_;
  std::vector<double> gain_strength_;                     // per challenge (dark)
  std::vector<std::pair<double, double>> segment_times_;  // per challenge, path seconds
};

// The camera the sequences use: fx = fy = focal_640 * width / 640, principal point at the centre.
slam::PinholeCamera synth_camera(int width, int height, double focal_640 = 525.0);

}  // namespace wardmap::sim
