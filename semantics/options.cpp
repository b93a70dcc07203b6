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
  c(keyframes.still_translation, 0, 10, "keyframes.still_translation");
  c(keyframes.still_rotation_deg, 0, 180, "keyframes.still_rotation_deg");
  c(measurement.box_shrink, 0, 0.45, "measurement.box_shrink");
  c(measurement.target_samples, 10, 1e6, "measurement.target_samples");
  c(measurement.cluster_support, 0.01, 1, "measurement.cluster_support");
  c(measurement.border_margin, 0, 1000, "measurement.border_margin");
  c(measurement.occluder_margin, 0, 10, "measurement.occluder_margin");
  c(measurement.occluder_footprint_px, 0, 10000, "measurement.occluder_footprint_px");
  c(measurement.occluder_inflate, 0, 1, "measurement.occluder_inflate");
  c(measurement.support_top_inflate, 0, 1, "measurement.support_top_inflate");
  c(measurement.thin_support, 0.001, 1, "measurement.thin_support");
  c(measurement.max_inside_same_class_share, 0, 2, "measurement.max_inside_same_class_share");
  c(measurement.duplicate_containment, 0, 1, "measurement.duplicate_containment");
  c(measurement.duplicate_rest_window_share, 0, 1, "measurement.duplicate_rest_window_share");
  c(measurement.flat_ratio, 0, 1, "measurement.flat_ratio");
  c(measurement.occluded_bottom_share, 0, 2, "measurement.occluded_bottom_share");
  c(measurement.bottom_face_band, 0, 1, "measurement.bottom_face_band");
  c(measurement.bottom_cut_reach, 0, 1, "measurement.bottom_cut_reach");
  c(measurement.bottom_face_min_length, 0, 100, "measurement.bottom_face_min_length");
  c(measurement.top_surface_tolerance, 0, 10, "measurement.top_surface_tolerance");
  c(measurement.floor_spread, 0, 10, "measurement.floor_spread");
  c(measurement.foot_window_rows, 0, 1, "measurement.foot_window_rows");
  c(measurement.foot_window_slack, 0, 10, "measurement.foot_window_slack");
  c(measurement.foot_floor_share, 0, 1, "measurement.foot_floor_share");
  c(measurement.foot_min_height_share, 0, 10, "measurement.foot_min_height_share");
  c(measurement.floor_clearance, 0, 10, "measurement.floor_clearance");
  c(measurement.support_containment, 0, 1, "measurement.support_containment");
  c(measurement.support_area_ratio, 1, 1e6, "measurement.support_area_ratio");
  c(measurement.support_front_share, 0, 1, "measurement.support_front_share");
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
  c(association.min_track_measurements, 1, 10000, "association.min_track_measurements");
  c(association.border_min_measurements, 1, 10000, "association.border_min_measurements");
  c(association.border_min_placed_measurements, 1, 10000, "association.border_min_placed_measurements");
  c(association.border_touch_px, 0, 1e4, "association.border_touch_px");
  c(association.border_pass_groups, 0, 10000, "association.border_pass_groups");
  c(association.border_reprojection_iou, 0, 1, "association.border_reprojection_iou");
  c(association.place_apart_min_share, 0.0, 1.0, "association.place_apart_min_share");
  c(association.border_side_cut_floor_tolerance, 0.01, 10, "association.border_side_cut_floor_tolerance");
  c(association.reproject_min_iou, 0, 1, "association.reproject_min_iou");
  c(association.reproject_margin, 0, 1, "association.reproject_margin");
  c(association.chains, 1, 64, "association.chains");
  c(association.threads, 1, 64, "association.threads");
  c(measurement.max_size_ratio, 1, 100, "measurement.max_size_ratio");
  c(measurement.side_cut_min_slope, 0, 1e6, "measurement.side_cut_min_slope");
  c(measurement.min_box_side, 1, 1e4, "measurement.min_box_side");
  c(measurement.coincident_ratio, 0, 2, "measurement.coincident_ratio");
  c(measurement.coincident_projection_margin, 0, 2, "measurement.coincident_projection_margin");
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
  using slam::io::SectionKeys;
  SemanticOptions o;
  if (!s) return o;
  SectionKeys sk(s, "semantics", file);
  SectionKeys kfk = sk.section("keyframes"), mk = sk.section("measurement"), gk = sk.section("groups"),
              ak = sk.section("association"), pk = sk.section("pose_selection"), mok = sk.section("monocular");
  kfk.read("min_translation", o.keyframes.min_translation);
  kfk.read("min_rotation_deg", o.keyframes.min_rotation_deg);
  kfk.read("max_interval", o.keyframes.max_interval);
  kfk.read("still_translation", o.keyframes.still_translation);
  kfk.read("still_rotation_deg", o.keyframes.still_rotation_deg);
  mk.read("box_shrink", o.measurement.box_shrink);
  mk.read("target_samples", o.measurement.target_samples);
  mk.read("cluster_support", o.measurement.cluster_support);
  mk.read("border_margin", o.measurement.border_margin);
  mk.read("occluder_margin", o.measurement.occluder_margin);
  mk.read("occluder_footprint_px", o.measurement.occluder_footprint_px);
  mk.read("occluder_inflate", o.measurement.occluder_inflate);
  mk.read("support_top_inflate", o.measurement.support_top_inflate);
  mk.read("support_containment", o.measurement.support_containment);
  mk.read("support_area_ratio", o.measurement.support_area_ratio);
  mk.read("support_front_share", o.measurement.support_front_share);
  mk.read("thin_support", o.measurement.thin_support);
  mk.read("max_inside_same_class_share", o.measurement.max_inside_same_class_share);
  mk.read("duplicate_containment", o.measurement.duplicate_containment);
  mk.read("duplicate_rest_window_share", o.measurement.duplicate_rest_window_share);
  mk.read("flat_ratio", o.measurement.flat_ratio);
  mk.read("occluded_bottom_share", o.measurement.occluded_bottom_share);
  mk.read("bottom_face_band", o.measurement.bottom_face_band);
  mk.read("bottom_cut_reach", o.measurement.bottom_cut_reach);
  mk.read("bottom_face_min_length", o.measurement.bottom_face_min_length);
  mk.read("top_surface_tolerance", o.measurement.top_surface_tolerance);
  mk.read("thin_height_from_box_rows", o.measurement.thin_height_from_box_rows);
  mk.read("solid_class_size_floor", o.measurement.solid_class_size_floor);
  mk.read("flat_height_from_box_rows", o.measurement.flat_height_from_box_rows);
  mk.read("min_depth", o.measurement.min_depth);
  mk.read("max_depth", o.measurement.max_depth);
  gk.read("split_distance", o.groups.split_distance);
  gk.read("camera_motion", o.groups.camera_motion);
  gk.read("min_appearance_width", o.groups.min_appearance_width);
  mk.read("depth_band", o.measurement.depth_band);
  mk.read("min_points", o.measurement.min_points);
  mk.read("complete_depth_with_class_size", o.measurement.complete_depth_with_class_size);
  mk.read("complete_side_cuts", o.measurement.complete_side_cuts);
  mk.read("side_cut_min_slope", o.measurement.side_cut_min_slope);
  mk.read("min_box_side", o.measurement.min_box_side);
  mk.read("coincident_ratio", o.measurement.coincident_ratio);
  mk.read("coincident_projection_margin", o.measurement.coincident_projection_margin);
  mk.read("tall_class_ratio", o.measurement.tall_class_ratio);
  mk.read("tall_depth_ratio", o.measurement.tall_depth_ratio);
  mk.read("ambiguous_pair_iou", o.measurement.ambiguous_pair_iou);
  mk.read("mask_to_far_end", o.measurement.mask_to_far_end);
  mk.read("box_mask_to_far_end", o.measurement.box_mask_to_far_end);
  mk.read("front_from_foot", o.measurement.front_from_foot);
  mk.read("front_from_low_rows", o.measurement.front_from_low_rows);
  mk.read("floor_clearance", o.measurement.floor_clearance);
  mk.read("centre_from_upper_part_when_cut", o.measurement.centre_from_upper_part_when_cut);
  mk.read("axes_from_planes", o.measurement.axes_from_planes);
  mk.read("anchor_side_face", o.measurement.anchor_side_face);
  mk.read("floor_spread", o.measurement.floor_spread);
  mk.read("foot_window_rows", o.measurement.foot_window_rows);
  mk.read("foot_window_slack", o.measurement.foot_window_slack);
  mk.read("foot_floor_share", o.measurement.foot_floor_share);
  mk.read("foot_min_height_share", o.measurement.foot_min_height_share);
  gk.read("size", o.groups.size);
  gk.read("overlap", o.groups.overlap);
  ak.read("mode", o.association.mode);
  ak.read("sigma_position", o.association.sigma_position);
  ak.read("sigma_rotation", o.association.sigma_rotation);
  ak.read("overlap_boost", o.association.overlap_boost);
  ak.read("landmark_mixture", o.association.landmark_mixture);
  ak.read("compactness_weight", o.association.compactness_weight);
  ak.read("suffix_swaps", o.association.suffix_swaps);
  ak.read("suffix_swap_min_gain", o.association.suffix_swap_min_gain);
  ak.read("new_landmark_distance", o.association.new_landmark_distance);
  ak.read("appearance_weight", o.association.appearance_weight);
  ak.read("appearance_neutral", o.association.appearance_neutral);
  ak.read("min_measurements", o.association.min_measurements);
  ak.read("min_placed_measurements", o.association.min_placed_measurements);
  ak.read("min_track_measurements", o.association.min_track_measurements);
  ak.read("border_min_measurements", o.association.border_min_measurements);
  ak.read("border_min_placed_measurements", o.association.border_min_placed_measurements);
  ak.read("border_touch_px", o.association.border_touch_px);
  ak.read("border_pass_groups", o.association.border_pass_groups);
  ak.read("border_reprojection_iou", o.association.border_reprojection_iou);
  ak.read("border_other_classes", o.association.border_other_classes);
  ak.read("border_side_cut_poses", o.association.border_side_cut_poses);
  ak.read("border_side_cut_floor_tolerance", o.association.border_side_cut_floor_tolerance);
  ak.read("merge_contained", o.association.merge_contained);
  ak.read("place_apart_min_share", o.association.place_apart_min_share);
  ak.read("drop_inside_other_class", o.association.drop_inside_other_class);
  ak.read("bridge_unplaced_tracks", o.association.bridge_unplaced_tracks);
  ak.read("one_per_keyframe", o.association.one_per_keyframe);
  ak.read("reproject", o.association.reproject);
  ak.read("reproject_min_iou", o.association.reproject_min_iou);
  ak.read("reproject_margin", o.association.reproject_margin);
  ak.read("chains", o.association.chains);
  ak.read("threads", o.association.threads);
  mk.read("max_size_ratio", o.measurement.max_size_ratio);
  ak.read("alpha", o.association.crf.alpha);
  ak.read("gamma", o.association.crf.gamma);
  ak.read("burn_in_sweeps", o.association.crf.burn_in_sweeps);
  ak.read("sweeps", o.association.crf.sweeps);
  pk.read("max_angle_deg", o.pose_selection.max_angle_deg);
  pk.read("max_distance", o.pose_selection.max_distance);
  pk.read("alpha", o.pose_selection.alpha);
  pk.read("beta", o.pose_selection.beta);
  mok.read("point_radius", o.monocular.point_radius);
  mok.read("min_points", o.monocular.min_points);
  mok.read("near_quantile", o.monocular.near_quantile);
  mok.read("max_box_overlap", o.monocular.max_box_overlap);
  mok.know("scale_classes");
  if (const YAML::Node& mo = mok.node(); mo && mo.IsMap() && mo["scale_classes"]) {
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
  mok.read("min_scale_estimates", o.monocular.min_scale_estimates);
  for (const SectionKeys* k : {&sk, &kfk, &mk, &gk, &ak, &pk, &mok}) k->reject_unknown();
  if (auto err = o.validate()) throw InputError(file.string(), *err);
  return o;
}

}  // namespace wardmap::semantics
