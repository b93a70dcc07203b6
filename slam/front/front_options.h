// Options of the realtime front-process (ORB features, matching, tracking, local mapping), loaded from
// a settings YAML: ORB-SLAM3's `ORBextractor.*` keys plus wardmap's `tracking:` and `mapping:` sections.
#pragma once

#include <filesystem>
#include <string>

#include "slam/front/two_view.h"
#include "slam/io/settings.h"

namespace wardmap::slam {

struct OrbOptions {
  int n_features = 1000;      // ORBextractor.nFeatures
  double scale_factor = 1.2;  // ORBextractor.scaleFactor
  int n_levels = 8;           // ORBextractor.nLevels
  int ini_th_fast = 20;       // ORBextractor.iniThFAST
  int min_th_fast = 7;        // ORBextractor.minThFAST
  int cell_size = 30;         // tracking.fast_cell_size: FAST threshold fallback cell (pixels)
  int edge_threshold = 19;    // tracking.orb_edge_threshold: keypoints keep this far from the border
};

struct MatcherOptions {
  int th_low = 50;                // tracking.match_th_low: Hamming distance for strict matches
  int th_high = 100;              // tracking.match_th_high: Hamming distance for projection matches
  double ratio_projection = 0.8;  // tracking.match_ratio_projection: best / second best (same level)
  double ratio_knn = 0.75;        // tracking.match_ratio_knn: Lowe ratio for brute-force bootstrapping
  bool check_orientation = true;  // tracking.match_check_orientation: rotation-consistency histogram
  int histogram_bins = 30;        // tracking.match_histogram_bins
};

struct TrackingOptions {
  double virtual_baseline = 0.08;      // tracking.virtual_baseline (m), else Stereo.b: depth as a disparity
  double close_depth = 3.0;            // tracking.close_depth (m), else Stereo.b x Stereo.ThDepth
  double max_depth = 5.0;              // tracking.max_depth (m): larger depths are ignored
  double max_depth_step = 0.05;        // tracking.max_depth_step: relative depth jump marking a silhouette
  int min_init_points = 300;           // tracking.min_init_points: keypoints with depth to initialise
  double motion_radius = 7.0;          // tracking.motion_radius (px at level 0): constant-velocity search
  double local_map_radius = 3.0;       // tracking.local_map_radius (px at level 0): local-map search
  int min_motion_matches = 20;         // tracking.min_motion_matches
  int min_pose_inliers = 10;           // tracking.min_pose_inliers: after motion / reference tracking
  int min_local_map_inliers = 30;      // tracking.min_local_map_inliers: a frame counts as tracked
  double short_term_seconds = 2.0;     // tracking.short_term_seconds: RUMI Formula 5 Th_t
  double mid_term_distance = 4.0;      // tracking.mid_term_distance (m): RUMI Formula 5 Th_p
  int max_local_keyframes = 80;        // tracking.max_local_keyframes
  int pose_rounds = 4;                 // tracking.pose_rounds: optimise / reject outliers rounds
  int pose_iterations = 10;            // tracking.pose_iterations: solver iterations per round
  // tracking.pose_solver: "ceres" (the pose-only optimisation with Ceres) or "lm" (the same
  // rounds solved by the 6-parameter Levenberg-Marquardt of pose_optimizer.h: 1.3-1.5x faster per
  // solve since Ceres gets each round as one residual block, same accuracy within 1-2 %).
  std::string pose_solver = "ceres";
  double chi2_mono = 5.991;            // tracking.chi2_mono: 95 % of chi2 with 2 dof
  double chi2_stereo = 7.815;          // tracking.chi2_stereo: 95 % of chi2 with 3 dof
  int keyframe_max_frames = 10;        // tracking.keyframe_max_frames: insert at least this often
  // ...while the view moves: a frame whose tracked points moved less than this many pixels (median)
  // from where the last keyframe's pose puts them makes no keyframe unless it tracks under a quarter
  // of the reference's points. ORB-SLAM has no such rule; standing still, it (and this tracker)
  // made a keyframe every 3 (monocular) or 10 (RGB-D) frames, each mapped and then culled. 0: off.
  double keyframe_still_px = 1.0;      // tracking.keyframe_still_px
  // A keyframe the busy mapper cannot take now waits for the next frame (ORB-SLAM3's monocular rule),
  // unless the next frame would come more than this long after the last keyframe: then it is queued
  // now, and the mapper cuts its local BA short for it. At 30 Hz the wait is at most a frame or two
  // of motion and the BA's time matters more; at KITTI's 10 Hz one frame is 0.1 s (about 1 m of road)
  // and keyframes every other frame cost more than BAs cut short (docs/EXPERIMENTS.md).
  double keyframe_max_gap_seconds = 0.15;  // tracking.keyframe_max_gap_seconds
  double keyframe_ref_ratio = 0.75;    // tracking.keyframe_ref_ratio: tracked / reference-keyframe points
  // The reference keyframe's points the ratio counts: those seen by at least this many keyframes (at
  // most 2 while the submap holds 2 keyframes). ORB-SLAM counts 3 in every mode. A point made from a
  // keyframe's depth is whole from its first keyframe; in a fast turn the view moves on before later
  // keyframes see it again, so with 3 the count lagged and keyframes thinned out where the view changes
  // fastest (synthetic turns, docs/EXPERIMENTS.md). Monocular points need their second view to exist.
  int keyframe_ref_min_observations = 2;       // tracking.keyframe_ref_min_observations
  int keyframe_ref_min_observations_mono = 3;  // tracking.keyframe_ref_min_observations_mono
  int keyframe_close_tracked = 100;    // tracking.keyframe_close_tracked
  int keyframe_close_untracked = 70;   // tracking.keyframe_close_untracked (ORB-SLAM: 70)
  int min_depth_points = 100;          // tracking.min_depth_points: new close points per keyframe
  int lost_frames_to_reset = 15;       // tracking.lost_frames_to_reset: lost this long, start a new submap
  // A submap of at most this many keyframes is not worth relocalising into: lost there, a new one starts
  // at once (ORB-SLAM2 resets a map of 5 keyframes or fewer, ORB-SLAM3 of 10).
  int young_submap_keyframes = 5;       // tracking.young_submap_keyframes
  // A submap left with at most this many keyframes is discarded, as ORB-SLAM3 resets its active map
  // (below 10 keyframes): its frames become lost and the new submap takes its id. Larger ones are kept
  // for the merge, whose Sim(3) from timestamp-matched keyframes needs three (RUMI, Umeyama). 0: keep all.
  int discard_submap_keyframes = 2;     // tracking.discard_submap_keyframes
  // Monocular (ORB-SLAM's values where the sensor changes them).
  double motion_radius_mono = 15.0;     // tracking.motion_radius_mono (px): no depth to bound the search
  double keyframe_ref_ratio_mono = 0.9; // tracking.keyframe_ref_ratio_mono
  int init_min_features = 100;          // tracking.init_min_features: keypoints of an initialisation frame
  int init_min_matches = 100;           // tracking.init_min_matches: else the reference frame is replaced
  double init_window = 100.0;           // tracking.init_window (px): initialisation search window
  double init_ratio = 0.9;              // tracking.init_ratio: best / second best distance
  // Levels either side of a keypoint's own searched when same-level matching finds fewer than
  // init_min_matches (a camera closing in fast); 0: the same level only, as ORB-SLAM.
  int init_level_span = 1;              // tracking.init_level_span
  int init_max_frames = 30;             // tracking.init_max_frames: a reference older than this is replaced
  // ...unless every frame since it showed its view unmoved (median match displacement under this many
  // pixels): a camera standing still cannot initialise, and those frames are kept, by timestamp only,
  // to take the first keyframe's pose once the map exists. 0: replaced regardless, as ORB-SLAM.
  double init_still_px = 1.0;           // tracking.init_still_px
  TwoViewOptions two_view;              // tracking.init_*: H / F model selection and triangulation
  // Relocalisation (needs a vocabulary): candidates by bag of words, then PnP RANSAC.
  int reloc_candidates = 10;            // tracking.reloc_candidates: keyframes tried per lost frame
  int reloc_min_matches = 15;           // tracking.reloc_min_matches: descriptor matches to try PnP
  double reloc_pnp_error = 4.0;         // tracking.reloc_pnp_error (px): RANSAC reprojection threshold
  int reloc_min_inliers = 50;           // tracking.reloc_min_inliers: after pose optimisation
  // The last frame's map points that the descriptor searches missed are followed into the frame by
  // pyramidal Lucas-Kanade flow (forward-backward checked, gated by the point's projection) and
  // observed there, so that points whose corner FAST does not find again or whose descriptor changed
  // live longer (docs/EXPERIMENTS.md, "Following map points by optical flow"). It costs 1.2-2.2x the
  // tracking time. Monocular: on, under the time budget below (it lowers the synthetic drift, and a
  // host too slow for it within the budget runs without it). RGB-D: off (18-21 ms a frame against
  // 12-13 ms on the slow hours of 2026-12-01/02, and it lowers the drift of --deterministic synthetic
  // runs only, not of ordinary (threaded) ones nor on 7-Scenes: "The flow off in RGB-D again").
  bool flow_extend = false;             // tracking.flow_extend: RGB-D
  bool flow_extend_mono = true;         // tracking.flow_extend_mono
  bool flow(bool monocular) const { return monocular ? flow_extend_mono : flow_extend; }
  // The flow under a time budget (threaded runs; slam/front/flow_budget.h): it runs for windows of
  // flow_budget_frames tracked frames, and stops while it would bring a window's median frame time
  // (extraction and tracking) over the budget. 0: no budget (always on). Given for a 640 x 480 frame
  // and scaled by the image's pixel count; the defaults are the realtime targets.
  // --deterministic runs keep the flow on: their output must not depend on timing.
  double flow_budget_ms = 15.0;         // tracking.flow_budget_ms: RGB-D
  double flow_budget_ms_mono = 10.0;    // tracking.flow_budget_ms_mono
  double flow_budget_ms_for(bool monocular) const { return monocular ? flow_budget_ms_mono : flow_budget_ms; }
  int flow_budget_frames = 30;          // tracking.flow_budget_frames: frames one decision holds
  int flow_budget_retry = 10;           // tracking.flow_budget_retry: off-windows before its cost is measured again
  double flow_max_fb_error = 0.5;       // tracking.flow_max_fb_error (px): forward-backward check
  double flow_gate = 3.0;               // tracking.flow_gate (px): flow position against the projection
  int flow_window = 15;                 // tracking.flow_window (px)
  int flow_levels = 2;                  // tracking.flow_levels: pyramid levels above the image
  // A detected keypoint this near the flow position (and one level apart at most) takes the point;
  // if it is matched to another point already, the followed one is a duplicate and is dropped.
  double flow_snap = 2.0;               // tracking.flow_snap (px); 0: always a new keypoint
  int flow_max_age = 20;                // tracking.flow_max_age: frames followed without being matched
  // Followed per frame, the most observed first: 150 keeps most of the synthetic gain of following
  // all, at a third of the flow's time on 7-Scenes RGB-D (docs/EXPERIMENTS.md).
  int flow_max_points = 150;            // tracking.flow_max_points
  bool flow_depth = false;              // tracking.flow_depth: RGB-D: followed keypoints sample the depth
  bool flow_reoptimise = true;          // tracking.flow_reoptimise: solve the pose again with them (else chi2 test)
  // Whether the followed points count as tracked in the keyframe decision; not counting them keeps
  // (monocular) or raises (RGB-D) the keyframe rate.
  bool flow_counts_for_keyframes = false;  // tracking.flow_counts_for_keyframes
  double reloc_max_speed = 2.0;         // tracking.reloc_max_speed (m/s, RGB-D): farther is a look-alike
  double reloc_distance_margin = 0.5;   // tracking.reloc_distance_margin (m, RGB-D)
};

struct MappingOptions {
  int queue_capacity = 8;            // mapping.queue_capacity: keyframes waiting for the mapper
  int triangulation_neighbours = 5;  // mapping.triangulation_neighbours
  int fuse_neighbours = 10;          // mapping.fuse_neighbours
  double min_parallax_deg = 1.0;     // mapping.min_parallax_deg: triangulation parallax (RGB-D)
  double recent_found_ratio = 0.25;  // mapping.recent_found_ratio: culling of new points
  int recent_min_observations = 3;   // mapping.recent_min_observations
  int ba_iterations_robust = 5;      // mapping.ba_iterations_robust
  int ba_iterations_refine = 10;     // mapping.ba_iterations_refine
  int ba_max_keyframes = 10;         // mapping.ba_max_keyframes: covisible keyframes optimised
  int ba_max_fixed_keyframes = 10;   // mapping.ba_max_fixed_keyframes: other observers held fixed
  // Monocular maps drift in scale where RGB-D ones have depth: a wider window holds it (ORB-SLAM3
  // takes every covisible keyframe). Synthetic corridors, threaded, two runs each of six: 1 of 12
  // above 2 cm with 20 / 20 against 6 of 12 with 10 / 10.
  int ba_max_keyframes_mono = 20;        // mapping.ba_max_keyframes_mono
  int ba_max_fixed_keyframes_mono = 20;  // mapping.ba_max_fixed_keyframes_mono
  double redundant_ratio = 0.9;      // mapping.redundant_ratio: keyframe culling
  int redundant_observers = 3;       // mapping.redundant_observers
  bool keyframe_culling = true;      // mapping.keyframe_culling
  // The mapper counts as busy for this long after each keyframe, in the sequence's time (frame
  // timestamps), whether it is or not: about a mapper thread's time per keyframe on this machine
  // (median 30-75 ms, p90 up to 84 ms on 7-Scenes, the synthetic sequences and KITTI). 2 frames at
  // 30 Hz, none at KITTI's 10 Hz. On the tracking thread (--deterministic) the mapper is always idle
  // when the tracker asks; on its own thread it can be done with a young map's keyframe within a
  // frame, and the next frame's keyframe then has too short a baseline: two threaded monocular runs
  // (ward quick_5 and slow_5) lost their scale in the first second so (113-122 cm ATE).
  double min_busy_seconds = 0.08;          // mapping.min_busy_seconds
  // Threaded: the tracker waits for the mapper when a keyframe is still being mapped this many frames
  // after it was made (offline input arrives faster than a camera's; the map must keep up).
  int max_lag_frames = 3;                  // mapping.max_lag_frames
  // Threaded: while the mapper is busy, the tracker waits for it until the wall time since the last
  // keyframe was made equals the sequence time since that keyframe's frame, not longer: about what a
  // live camera gives it (live, the keyframe frame's own tracking time also counts against it).
  bool sequence_time_for_mapper = true;    // mapping.sequence_time_for_mapper
  // Threaded: local BA stops at the iteration where a keyframe is waiting, or where the tracker wanted
  // one while the mapper was busy (ORB-SLAM's abort flag and InterruptBA).
  bool abort_ba_when_behind = true;        // mapping.abort_ba_when_behind
  int triangulation_neighbours_mono = 20;  // mapping.triangulation_neighbours_mono
  // Monocular: a new point seen by fewer keyframes than this two keyframes after its creation is
  // culled, ORB-SLAM3's rule for monocular maps (<= 2 observations).
  int recent_min_observations_mono = 3;    // mapping.recent_min_observations_mono
  double min_baseline_depth_ratio = 0.01;  // mapping.min_baseline_depth_ratio: monocular triangulation
  // Monocular triangulation parallax. ORB-SLAM3 takes cos < 0.9998 (1.146 degrees), but wardmap's
  // mapper keeps a keyframe on nearly every KITTI frame and every second synthetic one, so the
  // nearest neighbours' rays are nearly parallel: at 2 degrees a feature waits for a wider pair
  // among the neighbours, and its depth is better conditioned (KITTI 03 --realtime 0.68-0.81 m in
  // ten runs against 0.89-0.95 m; docs/EXPERIMENTS.md, "Triangulation parallax").
  double min_parallax_deg_mono = 2.0;      // mapping.min_parallax_deg_mono
};

struct FrontOptions {
  bool monocular = false;       // set by the caller (--mode mono), not from the settings file
  bool mapping_thread = false;  // local mapping on its own thread (set by the caller; off = deterministic)
  OrbOptions orb;
  MatcherOptions matcher;
  TrackingOptions tracking;
  MappingOptions mapping;
  // Throws InputError naming the key and the allowed range; `file` names the settings file.
  void validate(const std::filesystem::path& file = "<front options>") const;
};

// Reads the keys present in the settings (others keep their defaults), then validates.
FrontOptions load_front_options(const io::Settings& settings);

}  // namespace wardmap::slam
