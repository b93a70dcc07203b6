#include "slam/front/front_options.h"

#include "slam/core/errors.h"

namespace wardmap::slam {

void FrontOptions::validate(const std::filesystem::path& file) const {
  using io::check_range;
  check_range(orb.n_features, 50, 20000, "ORBextractor.nFeatures", file);
  check_range(orb.scale_factor, 1.01, 2.0, "ORBextractor.scaleFactor", file);
  check_range(orb.n_levels, 1, 16, "ORBextractor.nLevels", file);
  check_range(orb.ini_th_fast, 1, 255, "ORBextractor.iniThFAST", file);
  check_range(orb.min_th_fast, 1, orb.ini_th_fast, "ORBextractor.minThFAST", file);
  check_range(orb.cell_size, 10, 200, "tracking.fast_cell_size", file);
  check_range(orb.edge_threshold, 16, 64, "tracking.orb_edge_threshold", file);

  check_range(matcher.th_low, 0, 256, "tracking.match_th_low", file);
  check_range(matcher.th_high, matcher.th_low, 256, "tracking.match_th_high", file);
  check_range(matcher.ratio_projection, 0.1, 1.0, "tracking.match_ratio_projection", file);
  check_range(matcher.ratio_knn, 0.1, 1.0, "tracking.match_ratio_knn", file);
  check_range(matcher.histogram_bins, 4, 360, "tracking.match_histogram_bins", file);

  const TrackingOptions& t = tracking;
  check_range(t.virtual_baseline, 1e-3, 10.0, "tracking.virtual_baseline", file);
  check_range(t.close_depth, 0.1, 1000.0, "tracking.close_depth", file);
  check_range(t.max_depth, t.close_depth, 1000.0, "tracking.max_depth", file);
  check_range(t.max_depth_step, 0.0, 10.0, "tracking.max_depth_step", file);
  check_range(t.min_init_points, 10, 100000, "tracking.min_init_points", file);
  check_range(t.motion_radius, 1.0, 200.0, "tracking.motion_radius", file);
  check_range(t.local_map_radius, 0.5, 200.0, "tracking.local_map_radius", file);
  check_range(t.min_motion_matches, 3, 10000, "tracking.min_motion_matches", file);
  check_range(t.min_pose_inliers, 3, 10000, "tracking.min_pose_inliers", file);
  check_range(t.min_local_map_inliers, 3, 10000, "tracking.min_local_map_inliers", file);
  check_range(t.short_term_seconds, 0.0, 3600.0, "tracking.short_term_seconds", file);
  check_range(t.mid_term_distance, 0.0, 1e6, "tracking.mid_term_distance", file);
  check_range(t.max_local_keyframes, 1, 10000, "tracking.max_local_keyframes", file);
  check_range(t.pose_rounds, 1, 20, "tracking.pose_rounds", file);
  check_range(t.pose_iterations, 1, 200, "tracking.pose_iterations", file);
  if (t.pose_solver != "lm" && t.pose_solver != "ceres")
    throw InputError(file.string(), "key 'tracking.pose_solver': must be 'lm' or 'ceres', got '" + t.pose_solver + "'");
  check_range(t.chi2_mono, 0.1, 100.0, "tracking.chi2_mono", file);
  check_range(t.chi2_stereo, 0.1, 100.0, "tracking.chi2_stereo", file);
  check_range(t.keyframe_max_frames, 1, 10000, "tracking.keyframe_max_frames", file);
  check_range(t.keyframe_max_gap_seconds, 0.0, 3600.0, "tracking.keyframe_max_gap_seconds", file);
  check_range(t.keyframe_ref_ratio, 0.0, 1.0, "tracking.keyframe_ref_ratio", file);
  check_range(t.keyframe_close_tracked, 0, 100000, "tracking.keyframe_close_tracked", file);
  check_range(t.keyframe_close_untracked, 0, 100000, "tracking.keyframe_close_untracked", file);
  check_range(t.lost_frames_to_reset, 1, 100000, "tracking.lost_frames_to_reset", file);
  check_range(t.min_depth_points, 0, 100000, "tracking.min_depth_points", file);
  check_range(t.motion_radius_mono, 1.0, 200.0, "tracking.motion_radius_mono", file);
  check_range(t.keyframe_ref_ratio_mono, 0.0, 1.0, "tracking.keyframe_ref_ratio_mono", file);
  check_range(t.init_min_features, 8, 100000, "tracking.init_min_features", file);
  check_range(t.init_min_matches, 8, 100000, "tracking.init_min_matches", file);
  check_range(t.init_window, 1.0, 2000.0, "tracking.init_window", file);
  check_range(t.init_ratio, 0.1, 1.0, "tracking.init_ratio", file);
  check_range(t.init_max_frames, 1, 100000, "tracking.init_max_frames", file);
  check_range(t.reloc_candidates, 1, 1000, "tracking.reloc_candidates", file);
  check_range(t.reloc_min_matches, 6, 100000, "tracking.reloc_min_matches", file);
  check_range(t.reloc_pnp_error, 0.5, 100.0, "tracking.reloc_pnp_error", file);
  check_range(t.reloc_min_inliers, 6, 100000, "tracking.reloc_min_inliers", file);
  check_range(t.reloc_max_speed, 0.0, 1000.0, "tracking.reloc_max_speed", file);
  check_range(t.reloc_distance_margin, 0.0, 1e6, "tracking.reloc_distance_margin", file);
  const TwoViewOptions& v = t.two_view;
  check_range(v.ransac_iterations, 1, 100000, "tracking.init_ransac_iterations", file);
  check_range(v.sigma, 0.1, 10.0, "tracking.init_sigma", file);
  check_range(v.homography_share, 0.0, 1.0, "tracking.init_homography_share", file);
  check_range(v.min_parallax_deg, 0.0, 90.0, "tracking.init_min_parallax_deg", file);
  check_range(v.min_triangulated, 8, 100000, "tracking.init_min_triangulated", file);
  check_range(v.min_good_ratio, 0.0, 1.0, "tracking.init_min_good_ratio", file);
  check_range(v.ambiguity_ratio, 0.0, 1.0, "tracking.init_ambiguity_ratio", file);

  const MappingOptions& m = mapping;
  check_range(m.queue_capacity, 1, 1000, "mapping.queue_capacity", file);
  check_range(m.triangulation_neighbours, 0, 100, "mapping.triangulation_neighbours", file);
  check_range(m.fuse_neighbours, 0, 100, "mapping.fuse_neighbours", file);
  check_range(m.min_parallax_deg, 0.0, 90.0, "mapping.min_parallax_deg", file);
  check_range(m.recent_found_ratio, 0.0, 1.0, "mapping.recent_found_ratio", file);
  check_range(m.recent_min_observations, 1, 100, "mapping.recent_min_observations", file);
  check_range(m.ba_iterations_robust, 0, 1000, "mapping.ba_iterations_robust", file);
  check_range(m.ba_iterations_refine, 0, 1000, "mapping.ba_iterations_refine", file);
  check_range(m.ba_max_keyframes, 1, 1000, "mapping.ba_max_keyframes", file);
  check_range(m.ba_max_fixed_keyframes, 0, 1000, "mapping.ba_max_fixed_keyframes", file);
  check_range(m.ba_max_keyframes_mono, 1, 1000, "mapping.ba_max_keyframes_mono", file);
  check_range(m.ba_max_fixed_keyframes_mono, 0, 1000, "mapping.ba_max_fixed_keyframes_mono", file);
  check_range(m.redundant_ratio, 0.0, 1.0, "mapping.redundant_ratio", file);
  check_range(m.redundant_observers, 1, 100, "mapping.redundant_observers", file);
  check_range(m.inline_busy_seconds, 0.0, 3600.0, "mapping.inline_busy_seconds", file);
  check_range(m.max_lag_frames, 0, 100000, "mapping.max_lag_frames", file);
  check_range(m.triangulation_neighbours_mono, 0, 100, "mapping.triangulation_neighbours_mono", file);
  check_range(m.recent_min_observations_mono, 1, 100, "mapping.recent_min_observations_mono", file);
  check_range(m.min_baseline_depth_ratio, 0.0, 1.0, "mapping.min_baseline_depth_ratio", file);
  check_range(m.min_parallax_deg_mono, 0.0, 90.0, "mapping.min_parallax_deg_mono", file);
}

FrontOptions load_front_options(const io::Settings& settings) {
  FrontOptions o;
  const auto& f = settings.file;
  const YAML::Node& r = settings.root;
  using io::read_option;
  read_option(r, "", "ORBextractor.nFeatures", o.orb.n_features, f);
  read_option(r, "", "ORBextractor.scaleFactor", o.orb.scale_factor, f);
  read_option(r, "", "ORBextractor.nLevels", o.orb.n_levels, f);
  read_option(r, "", "ORBextractor.iniThFAST", o.orb.ini_th_fast, f);
  read_option(r, "", "ORBextractor.minThFAST", o.orb.min_th_fast, f);

  // ORB-SLAM3's RGB-D keys: the virtual baseline and the close-depth threshold (b x ThDepth).
  double baseline = 0, th_depth = 0;
  read_option(r, "", "Stereo.b", baseline, f);
  read_option(r, "", "Stereo.ThDepth", th_depth, f);
  if (baseline > 0) o.tracking.virtual_baseline = baseline;
  if (baseline > 0 && th_depth > 0) o.tracking.close_depth = baseline * th_depth;

  const YAML::Node t = settings.section("tracking");
  const std::string ts = "tracking";
  read_option(t, ts, "fast_cell_size", o.orb.cell_size, f);
  read_option(t, ts, "orb_edge_threshold", o.orb.edge_threshold, f);
  read_option(t, ts, "match_th_low", o.matcher.th_low, f);
  read_option(t, ts, "match_th_high", o.matcher.th_high, f);
  read_option(t, ts, "match_ratio_projection", o.matcher.ratio_projection, f);
  read_option(t, ts, "match_ratio_knn", o.matcher.ratio_knn, f);
  read_option(t, ts, "match_check_orientation", o.matcher.check_orientation, f);
  read_option(t, ts, "match_histogram_bins", o.matcher.histogram_bins, f);
  TrackingOptions& k = o.tracking;
  read_option(t, ts, "virtual_baseline", k.virtual_baseline, f);
  read_option(t, ts, "close_depth", k.close_depth, f);
  read_option(t, ts, "max_depth", k.max_depth, f);
  read_option(t, ts, "max_depth_step", k.max_depth_step, f);
  read_option(t, ts, "min_init_points", k.min_init_points, f);
  read_option(t, ts, "motion_radius", k.motion_radius, f);
  read_option(t, ts, "local_map_radius", k.local_map_radius, f);
  read_option(t, ts, "min_motion_matches", k.min_motion_matches, f);
  read_option(t, ts, "min_pose_inliers", k.min_pose_inliers, f);
  read_option(t, ts, "min_local_map_inliers", k.min_local_map_inliers, f);
  read_option(t, ts, "short_term_seconds", k.short_term_seconds, f);
  read_option(t, ts, "mid_term_distance", k.mid_term_distance, f);
  read_option(t, ts, "max_local_keyframes", k.max_local_keyframes, f);
  read_option(t, ts, "pose_rounds", k.pose_rounds, f);
  read_option(t, ts, "pose_iterations", k.pose_iterations, f);
  read_option(t, ts, "pose_solver", k.pose_solver, f);
  read_option(t, ts, "chi2_mono", k.chi2_mono, f);
  read_option(t, ts, "chi2_stereo", k.chi2_stereo, f);
  read_option(t, ts, "keyframe_max_frames", k.keyframe_max_frames, f);
  read_option(t, ts, "keyframe_max_gap_seconds", k.keyframe_max_gap_seconds, f);
  read_option(t, ts, "keyframe_ref_ratio", k.keyframe_ref_ratio, f);
  read_option(t, ts, "keyframe_close_tracked", k.keyframe_close_tracked, f);
  read_option(t, ts, "keyframe_close_untracked", k.keyframe_close_untracked, f);
  read_option(t, ts, "lost_frames_to_reset", k.lost_frames_to_reset, f);
  read_option(t, ts, "min_depth_points", k.min_depth_points, f);
  read_option(t, ts, "motion_radius_mono", k.motion_radius_mono, f);
  read_option(t, ts, "keyframe_ref_ratio_mono", k.keyframe_ref_ratio_mono, f);
  read_option(t, ts, "init_min_features", k.init_min_features, f);
  read_option(t, ts, "init_min_matches", k.init_min_matches, f);
  read_option(t, ts, "init_window", k.init_window, f);
  read_option(t, ts, "init_ratio", k.init_ratio, f);
  read_option(t, ts, "init_max_frames", k.init_max_frames, f);
  read_option(t, ts, "reloc_candidates", k.reloc_candidates, f);
  read_option(t, ts, "reloc_min_matches", k.reloc_min_matches, f);
  read_option(t, ts, "reloc_pnp_error", k.reloc_pnp_error, f);
  read_option(t, ts, "reloc_min_inliers", k.reloc_min_inliers, f);
  read_option(t, ts, "reloc_max_speed", k.reloc_max_speed, f);
  read_option(t, ts, "reloc_distance_margin", k.reloc_distance_margin, f);
  read_option(t, ts, "init_ransac_iterations", k.two_view.ransac_iterations, f);
  read_option(t, ts, "init_sigma", k.two_view.sigma, f);
  read_option(t, ts, "init_homography_share", k.two_view.homography_share, f);
  read_option(t, ts, "init_min_parallax_deg", k.two_view.min_parallax_deg, f);
  read_option(t, ts, "init_min_triangulated", k.two_view.min_triangulated, f);
  read_option(t, ts, "init_min_good_ratio", k.two_view.min_good_ratio, f);
  read_option(t, ts, "init_ambiguity_ratio", k.two_view.ambiguity_ratio, f);

  const YAML::Node m = settings.section("mapping");
  const std::string ms = "mapping";
  MappingOptions& p = o.mapping;
  read_option(m, ms, "queue_capacity", p.queue_capacity, f);
  read_option(m, ms, "triangulation_neighbours", p.triangulation_neighbours, f);
  read_option(m, ms, "fuse_neighbours", p.fuse_neighbours, f);
  read_option(m, ms, "min_parallax_deg", p.min_parallax_deg, f);
  read_option(m, ms, "recent_found_ratio", p.recent_found_ratio, f);
  read_option(m, ms, "recent_min_observations", p.recent_min_observations, f);
  read_option(m, ms, "ba_iterations_robust", p.ba_iterations_robust, f);
  read_option(m, ms, "ba_iterations_refine", p.ba_iterations_refine, f);
  read_option(m, ms, "ba_max_keyframes", p.ba_max_keyframes, f);
  read_option(m, ms, "ba_max_fixed_keyframes", p.ba_max_fixed_keyframes, f);
  read_option(m, ms, "ba_max_keyframes_mono", p.ba_max_keyframes_mono, f);
  read_option(m, ms, "ba_max_fixed_keyframes_mono", p.ba_max_fixed_keyframes_mono, f);
  read_option(m, ms, "redundant_ratio", p.redundant_ratio, f);
  read_option(m, ms, "redundant_observers", p.redundant_observers, f);
  read_option(m, ms, "keyframe_culling", p.keyframe_culling, f);
  read_option(m, ms, "inline_busy_seconds", p.inline_busy_seconds, f);
  read_option(m, ms, "max_lag_frames", p.max_lag_frames, f);
  read_option(m, ms, "sequence_time_for_mapper", p.sequence_time_for_mapper, f);
  read_option(m, ms, "abort_ba_when_behind", p.abort_ba_when_behind, f);
  read_option(m, ms, "triangulation_neighbours_mono", p.triangulation_neighbours_mono, f);
  read_option(m, ms, "recent_min_observations_mono", p.recent_min_observations_mono, f);
  read_option(m, ms, "min_baseline_depth_ratio", p.min_baseline_depth_ratio, f);
  read_option(m, ms, "min_parallax_deg_mono", p.min_parallax_deg_mono, f);
  o.validate(f);
  return o;
}

}  // namespace wardmap::slam
