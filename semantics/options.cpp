#include "semantics/options.h"

#include <sstream>

#include "slam/core/errors.h"
#include "slam/io/settings.h"

namespace wardmap::semantics {

namespace {

struct RangeCheck {
  std::ostringstream err;
  void operator()(double v, double lo, double hi, const char* key) {
    if (err.tellp() == 0 && !(v >= lo && v <= hi)) err << "key 'semantics." << key << "': must be in [" << lo << ", " << hi << "], got " << v;
  }
};

}  // namespace

std::optional<std::string> SemanticOptions::validate() const {
  RangeCheck c;
  c(keyframes.min_translation, 0, 10, "keyframes.min_translation");
  c(keyframes.min_rotation_deg, 0, 180, "keyframes.min_rotation_deg");
  c(keyframes.max_interval, 1, 10000, "keyframes.max_interval");
  c(measurement.box_shrink, 0, 0.45, "measurement.box_shrink");
  c(measurement.target_samples, 10, 1e6, "measurement.target_samples");
  c(measurement.cluster_support, 0.01, 1, "measurement.cluster_support");
  c(measurement.border_margin, 0, 1000, "measurement.border_margin");
  c(measurement.occluder_margin, 0, 10, "measurement.occluder_margin");
  c(measurement.occluder_footprint_px, 0, 10000, "measurement.occluder_footprint_px");
  c(measurement.occluder_inflate, 0, 1, "measurement.occluder_inflate");
  c(measurement.thin_support, 0.001, 1, "measurement.thin_support");
  c(measurement.flat_ratio, 0, 1, "measurement.flat_ratio");
  c(measurement.occluded_bottom_share, 0, 2, "measurement.occluded_bottom_share");
  c(measurement.bottom_face_band, 0, 1, "measurement.bottom_face_band");
  c(measurement.bottom_cut_reach, 0, 1, "measurement.bottom_cut_reach");
  c(measurement.bottom_face_min_length, 0, 100, "measurement.bottom_face_min_length");
  c(measurement.top_surface_tolerance, 0, 10, "measurement.top_surface_tolerance");
  c(measurement.support_containment, 0, 1, "measurement.support_containment");
  c(measurement.support_area_ratio, 1, 1e6, "measurement.support_area_ratio");
  c(measurement.max_depth, 0.01, 1000, "measurement.max_depth");
  c(groups.split_distance, 0.01, 100, "groups.split_distance");
  c(groups.min_appearance_width, 0, 1e4, "groups.min_appearance_width");
  c(measurement.depth_band, 0.01, 10, "measurement.depth_band");
  c(measurement.min_points, 3, 100000, "measurement.min_points");
  c(measurement.min_depth, 0, measurement.max_depth, "measurement.min_depth");
  c(groups.size, 1, 100, "groups.size");
  c(groups.overlap, 0, groups.size - 1, "groups.overlap");
  c(association.sigma_position, 1e-3, 10, "association.sigma_position");
  c(association.sigma_rotation, 1e-3, 10, "association.sigma_rotation");
  c(association.overlap_boost, 1, 100, "association.overlap_boost");
  c(association.new_landmark_distance, 1e-3, 100, "association.new_landmark_distance");
  c(association.compactness_weight, 0, 100, "association.compactness_weight");
  c(association.suffix_swap_min_gain, 0, 1e6, "association.suffix_swap_min_gain");
  c(association.appearance_weight, 0, 100, "association.appearance_weight");
  c(association.appearance_neutral, -1, 1, "association.appearance_neutral");
  c(association.min_measurements, 1, 10000, "association.min_measurements");
  c(association.min_placed_measurements, 1, 10000, "association.min_placed_measurements");
  c(association.border_min_measurements, 1, 10000, "association.border_min_measurements");
  c(association.border_min_placed_measurements, 1, 10000, "association.border_min_placed_measurements");
  c(association.border_touch_px, 0, 1e4, "association.border_touch_px");
  c(association.border_reprojection_iou, 0, 1, "association.border_reprojection_iou");
  c(association.reproject_min_iou, 0, 1, "association.reproject_min_iou");
  c(association.reproject_margin, 0, 1, "association.reproject_margin");
  c(association.chains, 1, 64, "association.chains");
  c(association.threads, 1, 64, "association.threads");
  c(measurement.max_size_ratio, 1, 100, "measurement.max_size_ratio");
  c(measurement.side_cut_min_slope, 0, 1e6, "measurement.side_cut_min_slope");
  c(measurement.min_box_side, 1, 1e4, "measurement.min_box_side");
  c(measurement.coincident_ratio, 0, 2, "measurement.coincident_ratio");
  c(measurement.tall_class_ratio, 1, 100, "measurement.tall_class_ratio");
  c(measurement.tall_depth_ratio, 0, 100, "measurement.tall_depth_ratio");
  c(measurement.ambiguous_pair_iou, 0, 2, "measurement.ambiguous_pair_iou");
  c(pose_selection.max_angle_deg, 1e-3, 180, "pose_selection.max_angle_deg");
  c(pose_selection.max_distance, 1e-3, 100, "pose_selection.max_distance");
  c(pose_selection.alpha, 0, 1, "pose_selection.alpha");
  c(pose_selection.beta, 0, 1, "pose_selection.beta");
  c(monocular.point_radius, 0, 50, "monocular.point_radius");
  c(monocular.min_points, 1, 100000, "monocular.min_points");
  c(monocular.near_quantile, 0, 1, "monocular.near_quantile");
  c(monocular.max_box_overlap, 0, 1, "monocular.max_box_overlap");
  c(monocular.min_scale_estimates, 1, 100000, "monocular.min_scale_estimates");
  if (c.err.tellp() == 0 && association.mode != "hierarchical" && association.mode != "hdp-only")
    c.err << "key 'semantics.association.mode': must be hierarchical or hdp-only, got '" << association.mode << "'";
  const auto& far_end = measurement.mask_to_far_end;
  if (c.err.tellp() == 0 && far_end != "none" && far_end != "same_class" && far_end != "all")
    c.err << "key 'semantics.measurement.mask_to_far_end': must be none, same_class or all, got '" << far_end << "'";
  const auto& reproject = association.reproject;
  if (c.err.tellp() == 0 && reproject != "none" && reproject != "unplaced" && reproject != "all")
    c.err << "key 'semantics.association.reproject': must be none, unplaced or all, got '" << reproject << "'";
  if (c.err.tellp() != 0) return c.err.str();
  if (auto e = association.crf.validate()) return "key 'semantics.association.crf': " + *e;
  if (auto e = tracker.validate()) return "key 'semantics.tracker': " + *e;
  return std::nullopt;
}

SemanticOptions load_semantic_options(const YAML::Node& s, const std::filesystem::path& file) {
  using slam::io::read_option;
  SemanticOptions o;
  if (!s) return o;
  const auto kf = s["keyframes"], m = s["measurement"], g = s["groups"], a = s["association"], p = s["pose_selection"],
             mo = s["monocular"];
  read_option(kf, "semantics.keyframes", "min_translation", o.keyframes.min_translation, file);
  read_option(kf, "semantics.keyframes", "min_rotation_deg", o.keyframes.min_rotation_deg, file);
  read_option(kf, "semantics.keyframes", "max_interval", o.keyframes.max_interval, file);
  read_option(m, "semantics.measurement", "box_shrink", o.measurement.box_shrink, file);
  read_option(m, "semantics.measurement", "target_samples", o.measurement.target_samples, file);
  read_option(m, "semantics.measurement", "cluster_support", o.measurement.cluster_support, file);
  read_option(m, "semantics.measurement", "border_margin", o.measurement.border_margin, file);
  read_option(m, "semantics.measurement", "occluder_margin", o.measurement.occluder_margin, file);
  read_option(m, "semantics.measurement", "occluder_footprint_px", o.measurement.occluder_footprint_px, file);
  read_option(m, "semantics.measurement", "occluder_inflate", o.measurement.occluder_inflate, file);
  read_option(m, "semantics.measurement", "support_containment", o.measurement.support_containment, file);
  read_option(m, "semantics.measurement", "support_area_ratio", o.measurement.support_area_ratio, file);
  read_option(m, "semantics.measurement", "thin_support", o.measurement.thin_support, file);
  read_option(m, "semantics.measurement", "flat_ratio", o.measurement.flat_ratio, file);
  read_option(m, "semantics.measurement", "occluded_bottom_share", o.measurement.occluded_bottom_share, file);
  read_option(m, "semantics.measurement", "bottom_face_band", o.measurement.bottom_face_band, file);
  read_option(m, "semantics.measurement", "bottom_cut_reach", o.measurement.bottom_cut_reach, file);
  read_option(m, "semantics.measurement", "bottom_face_min_length", o.measurement.bottom_face_min_length, file);
  read_option(m, "semantics.measurement", "top_surface_tolerance", o.measurement.top_surface_tolerance, file);
  read_option(m, "semantics.measurement", "thin_height_from_box_rows", o.measurement.thin_height_from_box_rows, file);
  read_option(m, "semantics.measurement", "min_depth", o.measurement.min_depth, file);
  read_option(m, "semantics.measurement", "max_depth", o.measurement.max_depth, file);
  read_option(g, "semantics.groups", "split_distance", o.groups.split_distance, file);
  read_option(g, "semantics.groups", "camera_motion", o.groups.camera_motion, file);
  read_option(g, "semantics.groups", "min_appearance_width", o.groups.min_appearance_width, file);
  read_option(m, "semantics.measurement", "depth_band", o.measurement.depth_band, file);
  read_option(m, "semantics.measurement", "min_points", o.measurement.min_points, file);
  read_option(m, "semantics.measurement", "complete_depth_with_class_size", o.measurement.complete_depth_with_class_size, file);
  read_option(m, "semantics.measurement", "complete_side_cuts", o.measurement.complete_side_cuts, file);
  read_option(m, "semantics.measurement", "side_cut_min_slope", o.measurement.side_cut_min_slope, file);
  read_option(m, "semantics.measurement", "min_box_side", o.measurement.min_box_side, file);
  read_option(m, "semantics.measurement", "coincident_ratio", o.measurement.coincident_ratio, file);
  read_option(m, "semantics.measurement", "tall_class_ratio", o.measurement.tall_class_ratio, file);
  read_option(m, "semantics.measurement", "tall_depth_ratio", o.measurement.tall_depth_ratio, file);
  read_option(m, "semantics.measurement", "ambiguous_pair_iou", o.measurement.ambiguous_pair_iou, file);
  read_option(m, "semantics.measurement", "mask_to_far_end", o.measurement.mask_to_far_end, file);
  read_option(g, "semantics.groups", "size", o.groups.size, file);
  read_option(g, "semantics.groups", "overlap", o.groups.overlap, file);
  read_option(a, "semantics.association", "mode", o.association.mode, file);
  read_option(a, "semantics.association", "sigma_position", o.association.sigma_position, file);
  read_option(a, "semantics.association", "sigma_rotation", o.association.sigma_rotation, file);
  read_option(a, "semantics.association", "overlap_boost", o.association.overlap_boost, file);
  read_option(a, "semantics.association", "landmark_mixture", o.association.landmark_mixture, file);
  read_option(a, "semantics.association", "compactness_weight", o.association.compactness_weight, file);
  read_option(a, "semantics.association", "suffix_swaps", o.association.suffix_swaps, file);
  read_option(a, "semantics.association", "suffix_swap_min_gain", o.association.suffix_swap_min_gain, file);
  read_option(a, "semantics.association", "new_landmark_distance", o.association.new_landmark_distance, file);
  read_option(a, "semantics.association", "appearance_weight", o.association.appearance_weight, file);
  read_option(a, "semantics.association", "appearance_neutral", o.association.appearance_neutral, file);
  read_option(a, "semantics.association", "min_measurements", o.association.min_measurements, file);
  read_option(a, "semantics.association", "min_placed_measurements", o.association.min_placed_measurements, file);
  read_option(a, "semantics.association", "border_min_measurements", o.association.border_min_measurements, file);
  read_option(a, "semantics.association", "border_min_placed_measurements",
              o.association.border_min_placed_measurements, file);
  read_option(a, "semantics.association", "border_touch_px", o.association.border_touch_px, file);
  read_option(a, "semantics.association", "border_reprojection_iou", o.association.border_reprojection_iou, file);
  read_option(a, "semantics.association", "merge_contained", o.association.merge_contained, file);
  read_option(a, "semantics.association", "drop_inside_other_class", o.association.drop_inside_other_class, file);
  read_option(a, "semantics.association", "bridge_unplaced_tracks", o.association.bridge_unplaced_tracks, file);
  read_option(a, "semantics.association", "reproject", o.association.reproject, file);
  read_option(a, "semantics.association", "reproject_min_iou", o.association.reproject_min_iou, file);
  read_option(a, "semantics.association", "reproject_margin", o.association.reproject_margin, file);
  read_option(a, "semantics.association", "chains", o.association.chains, file);
  read_option(a, "semantics.association", "threads", o.association.threads, file);
  read_option(m, "semantics.measurement", "max_size_ratio", o.measurement.max_size_ratio, file);
  read_option(a, "semantics.association", "alpha", o.association.crf.alpha, file);
  read_option(a, "semantics.association", "gamma", o.association.crf.gamma, file);
  read_option(a, "semantics.association", "burn_in_sweeps", o.association.crf.burn_in_sweeps, file);
  read_option(a, "semantics.association", "sweeps", o.association.crf.sweeps, file);
  read_option(p, "semantics.pose_selection", "max_angle_deg", o.pose_selection.max_angle_deg, file);
  read_option(p, "semantics.pose_selection", "max_distance", o.pose_selection.max_distance, file);
  read_option(p, "semantics.pose_selection", "alpha", o.pose_selection.alpha, file);
  read_option(p, "semantics.pose_selection", "beta", o.pose_selection.beta, file);
  read_option(mo, "semantics.monocular", "point_radius", o.monocular.point_radius, file);
  read_option(mo, "semantics.monocular", "min_points", o.monocular.min_points, file);
  read_option(mo, "semantics.monocular", "near_quantile", o.monocular.near_quantile, file);
  read_option(mo, "semantics.monocular", "max_box_overlap", o.monocular.max_box_overlap, file);
  if (mo && mo["scale_classes"]) {
    const YAML::Node list = mo["scale_classes"];
    if (!list.IsSequence())
      throw InputError(file.string(), "key 'semantics.monocular.scale_classes': must be a list of class names");
    o.monocular.scale_classes.clear();
    for (const auto& c : list) {
      if (!c.IsScalar())
        throw InputError(file.string(), "key 'semantics.monocular.scale_classes': must be a list of class names");
      o.monocular.scale_classes.insert(c.as<std::string>());
    }
  }
  read_option(mo, "semantics.monocular", "min_scale_estimates", o.monocular.min_scale_estimates, file);
  if (auto err = o.validate()) throw InputError(file.string(), *err);
  return o;
}

}  // namespace wardmap::semantics
