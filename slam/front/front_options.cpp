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
  check_range(t.keyframe_still_px, 0.0, 100.0, "tracking.keyframe_still_px", file);
  check_range(t.keyframe_max_gap_seconds, 0.0, 3600.0, "tracking.keyframe_max_gap_seconds", file);
  check_range(t.keyframe_ref_ratio, 0.0, 1.0, "tracking.keyframe_ref_ratio", file);
  check_range(t.keyframe_ref_min_observations, 1, 100, "tracking.keyframe_ref_min_observations", file);
  check_range(t.keyframe_ref_min_observations_mono, 1, 100, "tracking.keyframe_ref_min_observations_mono", file);
  check_range(t.keyframe_close_tracked, 0, 100000, "tracking.keyframe_close_tracked", file);
  check_range(t.keyframe_close_untracked, 0, 100000, "tracking.keyframe_close_untracked", file);
  check_range(t.lost_frames_to_reset, 1, 100000, "tracking.lost_frames_to_reset", file);
  check_range(t.young_submap_keyframes, 0, 100000, "tracking.young_submap_keyframes", file);
  check_range(t.discard_submap_keyframes, 0, 100000, "tracking.discard_submap_keyframes", file);
  check_range(t.min_depth_points, 0, 100000, "tracking.min_depth_points", file);
  check_range(t.motion_radius_mono, 1.0, 200.0, "tracking.motion_radius_mono", file);
  check_range(t.keyframe_ref_ratio_mono, 0.0, 1.0, "tracking.keyframe_ref_ratio_mono", file);
  check_range(t.init_min_features, 8, 100000, "tracking.init_min_features", file);
  check_range(t.init_min_matches, 8, 100000, "tracking.init_min_matches", file);
  check_range(t.init_window, 1.0, 2000.0, "tracking.init_window", file);
  check_range(t.init_ratio, 0.1, 1.0, "tracking.init_ratio", file);
  check_range(t.init_level_span, 0, 7, "tracking.init_level_span", file);
  check_range(t.init_max_frames, 1, 100000, "tracking.init_max_frames", file);
  check_range(t.init_still_px, 0.0, 100.0, "tracking.init_still_px", file);
  check_range(t.reloc_candidates, 1, 1000, "tracking.reloc_candidates", file);
  check_range(t.reloc_min_matches, 6, 100000, "tracking.reloc_min_matches", file);
  check_range(t.reloc_pnp_error, 0.5, 100.0, "tracking.reloc_pnp_error", file);
  check_range(t.reloc_min_inliers, 6, 100000, "tracking.reloc_min_inliers", file);
  check_range(t.flow_max_fb_error, 0.01, 100.0, "tracking.flow_max_fb_error", file);
  check_range(t.flow_gate, 0.1, 100.0, "tracking.flow_gate", file);
  check_range(t.flow_window, 5, 101, "tracking.flow_window", file);
  check_range(t.flow_levels, 0, 8, "tracking.flow_levels", file);
  check_range(t.flow_snap, 0.0, 20.0, "tracking.flow_snap", file);
  check_range(t.flow_max_age, 1, 100000, "tracking.flow_max_age", file);
  check_range(t.flow_max_points, 1, 1000000, "tracking.flow_max_points", file);
  check_range(t.flow_budget_ms, 0.0, 10000.0, "tracking.flow_budget_ms", file);
  check_range(t.flow_budget_ms_mono, 0.0, 10000.0, "tracking.flow_budget_ms_mono", file);
  check_range(t.flow_budget_frames, 1, 100000, "tracking.flow_budget_frames", file);
  check_range(t.flow_budget_retry, 1, 100000, "tracking.flow_budget_retry", file);
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
  check_range(m.min_busy_seconds, 0.0, 3600.0, "mapping.min_busy_seconds", file);
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

  // ORB-SLAM3's RGB-D keys: the virtual baseline and the close-depth threshold (b x ThDepth); or
  // ORB-SLAM2's, the baseline times fx (Camera.bf) and ThDepth. 0 when absent.
  const auto positive = [&](const char* key) {
    double value = 0;
    read_option(r, "", key, value, f);
    if (r[key] && !(value > 0))
      throw InputError(f.string(), std::string("key '") + key + "': must be positive, got " + std::to_string(value),
                       r[key].Mark().line + 1);
    return value;
  };
  double baseline = positive("Stereo.b");
  if (!r["Stereo.b"] && r["Camera.bf"]) baseline = positive("Camera.bf") / settings.camera.camera.fx;
  const double th_depth = positive(r["Stereo.ThDepth"] ? "Stereo.ThDepth" : "ThDepth");
  if (baseline > 0) o.tracking.virtual_baseline = baseline;
  if (baseline > 0 && th_depth > 0) o.tracking.close_depth = baseline * th_depth;

  io::SectionKeys tk(settings.section("tracking"), "tracking", f);
  tk.read("fast_cell_size", o.orb.cell_size);
  tk.read("orb_edge_threshold", o.orb.edge_threshold);
  tk.read("match_th_low", o.matcher.th_low);
  tk.read("match_th_high", o.matcher.th_high);
  tk.read("match_ratio_projection", o.matcher.ratio_projection);
  tk.read("match_ratio_knn", o.matcher.ratio_knn);
  tk.read("match_check_orientation", o.matcher.check_orientation);
  tk.read("match_histogram_bins", o.matcher.histogram_bins);
  TrackingOptions& k = o.tracking;
  tk.read("virtual_baseline", k.virtual_baseline);
  tk.read("close_depth", k.close_depth);
  tk.read("max_depth", k.max_depth);
  tk.read("max_depth_step", k.max_depth_step);
  tk.read("min_init_points", k.min_init_points);
  tk.read("motion_radius", k.motion_radius);
  tk.read("local_map_radius", k.local_map_radius);
  tk.read("min_motion_matches", k.min_motion_matches);
  tk.read("min_pose_inliers", k.min_pose_inliers);
  tk.read("min_local_map_inliers", k.min_local_map_inliers);
  tk.read("short_term_seconds", k.short_term_seconds);
  tk.read("mid_term_distance", k.mid_term_distance);
  tk.read("max_local_keyframes", k.max_local_keyframes);
  tk.read("pose_rounds", k.pose_rounds);
  tk.read("pose_iterations", k.pose_iterations);
  tk.read("pose_solver", k.pose_solver);
  tk.read("chi2_mono", k.chi2_mono);
  tk.read("chi2_stereo", k.chi2_stereo);
  tk.read("keyframe_max_frames", k.keyframe_max_frames);
  tk.read("keyframe_still_px", k.keyframe_still_px);
  tk.read("keyframe_max_gap_seconds", k.keyframe_max_gap_seconds);
  tk.read("keyframe_ref_ratio", k.keyframe_ref_ratio);
  tk.read("keyframe_ref_min_observations", k.keyframe_ref_min_observations);
  tk.read("keyframe_ref_min_observations_mono", k.keyframe_ref_min_observations_mono);
  tk.read("keyframe_close_tracked", k.keyframe_close_tracked);
  tk.read("keyframe_close_untracked", k.keyframe_close_untracked);
  tk.read("lost_frames_to_reset", k.lost_frames_to_reset);
  tk.read("young_submap_keyframes", k.young_submap_keyframes);
  tk.read("discard_submap_keyframes", k.discard_submap_keyframes);
  tk.read("min_depth_points", k.min_depth_points);
  tk.read("motion_radius_mono", k.motion_radius_mono);
  tk.read("keyframe_ref_ratio_mono", k.keyframe_ref_ratio_mono);
  tk.read("init_min_features", k.init_min_features);
  tk.read("init_min_matches", k.init_min_matches);
  tk.read("init_window", k.init_window);
  tk.read("init_ratio", k.init_ratio);
  tk.read("init_level_span", k.init_level_span);
  tk.read("init_max_frames", k.init_max_frames);
  tk.read("init_still_px", k.init_still_px);
  tk.read("reloc_candidates", k.reloc_candidates);
  tk.read("reloc_min_matches", k.reloc_min_matches);
  tk.read("reloc_pnp_error", k.reloc_pnp_error);
  tk.read("reloc_min_inliers", k.reloc_min_inliers);
  tk.read("flow_extend", k.flow_extend);
  tk.read("flow_extend_mono", k.flow_extend_mono);
  tk.read("flow_budget_ms", k.flow_budget_ms);
  tk.read("flow_budget_ms_mono", k.flow_budget_ms_mono);
  tk.read("flow_budget_frames", k.flow_budget_frames);
  tk.read("flow_budget_retry", k.flow_budget_retry);
  tk.read("flow_max_fb_error", k.flow_max_fb_error);
  tk.read("flow_gate", k.flow_gate);
  tk.read("flow_window", k.flow_window);
  tk.read("flow_levels", k.flow_levels);
  tk.read("flow_snap", k.flow_snap);
  tk.read("flow_reoptimise", k.flow_reoptimise);
  tk.read("flow_max_points", k.flow_max_points);
  tk.read("flow_depth", k.flow_depth);
  tk.read("flow_max_age", k.flow_max_age);
  tk.read("flow_counts_for_keyframes", k.flow_counts_for_keyframes);
  tk.read("reloc_max_speed", k.reloc_max_speed);
  tk.read("reloc_distance_margin", k.reloc_distance_margin);
  tk.read("init_ransac_iterations", k.two_view.ransac_iterations);
  tk.read("init_sigma", k.two_view.sigma);
  tk.read("init_homography_share", k.two_view.homography_share);
  tk.read("init_min_parallax_deg", k.two_view.min_parallax_deg);
  tk.read("init_min_triangulated", k.two_view.min_triangulated);
  tk.read("init_min_good_ratio", k.two_view.min_good_ratio);
  tk.read("init_ambiguity_ratio", k.two_view.ambiguity_ratio);

  io::SectionKeys mk(settings.section("mapping"), "mapping", f);
  MappingOptions& p = o.mapping;
  mk.read("queue_capacity", p.queue_capacity);
  mk.read("triangulation_neighbours", p.triangulation_neighbours);
  mk.read("fuse_neighbours", p.fuse_neighbours);
  mk.read("min_parallax_deg", p.min_parallax_deg);
  mk.read("recent_found_ratio", p.recent_found_ratio);
  mk.read("recent_min_observations", p.recent_min_observations);
  mk.read("ba_iterations_robust", p.ba_iterations_robust);
  mk.read("ba_iterations_refine", p.ba_iterations_refine);
  mk.read("ba_max_keyframes", p.ba_max_keyframes);
  mk.read("ba_max_fixed_keyframes", p.ba_max_fixed_keyframes);
  mk.read("ba_max_keyframes_mono", p.ba_max_keyframes_mono);
  mk.read("ba_max_fixed_keyframes_mono", p.ba_max_fixed_keyframes_mono);
  mk.read("redundant_ratio", p.redundant_ratio);
  mk.read("redundant_observers", p.redundant_observers);
  mk.read("keyframe_culling", p.keyframe_culling);
  mk.read("min_busy_seconds", p.min_busy_seconds);
  mk.read("max_lag_frames", p.max_lag_frames);
  mk.read("sequence_time_for_mapper", p.sequence_time_for_mapper);
  mk.read("abort_ba_when_behind", p.abort_ba_when_behind);
  mk.read("triangulation_neighbours_mono", p.triangulation_neighbours_mono);
  mk.read("recent_min_observations_mono", p.recent_min_observations_mono);
  mk.read("min_baseline_depth_ratio", p.min_baseline_depth_ratio);
  mk.read("min_parallax_deg_mono", p.min_parallax_deg_mono);
  tk.reject_unknown();
  mk.reject_unknown();
  o.validate(f);
  return o;
}

}  // namespace wardmap::slam
