// Options of the semantic layer (Assoc. paper), one struct per stage, defaults from the paper where
// it gives them; loaded from the `semantics` section of a settings YAML and validated on load.
#pragma once

#include <filesystem>
#include <array>
#include <map>
#include <set>
#include <optional>
#include <string>

#include <yaml-cpp/yaml.h>

#include "hdp/crf_sampler.h"
#include "hdp/gaussian_mixture.h"
#include "mot/tracker.h"

namespace wardmap::semantics {

// Keyframes taken from known poses (--poses gt): a new keyframe when the camera has moved or turned
// enough since the last one, or after max_interval frames unless it stands still: moved less than
// still_translation and turned less than still_rotation_deg since the last keyframe (both 0: off).
struct KeyframeSelectionOptions {
  double min_translation = 0.10;  // metres
  double min_rotation_deg = 5.0;
  int max_interval = 10;          // frames
  double still_translation = 0.01;  // metres
  double still_rotation_deg = 0.5;
};

// Object measurement from depth inside the detection box (Assoc. Eq. 1 "Pose").
struct MeasurementOptions {
  double box_shrink = 0.2;        // fraction of the box trimmed on each side (background at the edges)
  int target_samples = 600;       // depth pixels sampled in the trimmed box (stride adapts to its size;
                                  // an axis class's box in every column, its rows at the stride)
  double depth_band = 0.6;        // surface depth window (m) for classes without a typical size
  double cluster_support = 0.25;  // the fullest depth window must hold this share of the points
  int min_points = 20;            // fewer valid points: no pose
  double min_box_side = 10;       // px: a narrower or lower box gets no pose
  int border_margin = 2;          // a box this close to the image border is cut off (completed, or no pose)
  double occluder_margin = 0.15;  // a detection this much nearer (m) than another hides its pixels,
  double occluder_footprint_px = 8;  // or one whose box reaches this much lower in the image
  double occluder_inflate = 0.1;     // margin (m) of a measured occluder's 3-D box when masking its pixels
                                     // (its 5-95 % extents fall short of its ends)
  double support_top_inflate = 0.03;  // a support's (a table's) vertical margin instead: its top is the
                                      // measured top surface, not short of it (depth noise only)
  double support_containment = 0.8;  // a box holding this share of mine, and
  double support_area_ratio = 4.0;   // this many times larger, is a support, not an occluder
  // A support without a pose that holds a box hides none of its pixels when at most this share of
  // them lies occluder_margin in front of the box's median depth (a cup on a table cut by the
  // border: 0 on 7-Scenes), else its whole box, as any unplaced occluder.
  double support_front_share = 0.1;  // measurement.support_front_share
  double thin_support = 0.08;     // thin classes: share of the points the nearest window must hold
  // More than this share of the trimmed box's depths inside the measured 3-D box of a nearer
  // detection of its class, the rest beginning more than half the class's depth behind that box: the
  // same object detected again and seen through (no measurement is made). Above 1: off.
  double max_inside_same_class_share = 0.5;
  double duplicate_containment = 0.8;  // and that detection's image box holding this share of its box
  // and the rest one surface: a class-deep depth window holding this share of it (the wall behind a
  // chair's slats). Another object hidden behind shows itself and what stands around it. 0: any rest.
  double duplicate_rest_window_share = 0.8;
  double occluded_bottom_share = 0.5;  // nearer detections' pixels under this share of my box's bottom edge:
                                       // completed as a bottom cut (above 1: never)
  // A bottom cut (border or occluder) is completed downwards only when the lowest rows of the
  // object's points show a face (their heights change from row to row more than their horizontal
  // distances do). When they show a horizontal surface instead (a bed's top seen from above as the
  // camera passes close), the cut hides the object's near end, whose extent is unknown: no pose.
  // The share of the trimmed box's rows checked; 0: off. On the 72 synthetic runs (24 sequences x
  // noise seeds 1-3) it removes a quarter of the beds' measurements placed over 0.3 m off (288 -> 220,
  // seed 1) and the beds split in two (aisle_right_turn_slow_1 seed 2, quick_1 seed 3).
  double bottom_face_band = 0.3;
  double bottom_face_min_length = 1.0;  // m: classes with a shorter horizontal size are completed as before
  // A box ending this share of its height (or border_margin) above the image's bottom border is cut
  // there when that horizontal surface, within top_surface_tolerance (m) of its height, fills the
  // rows below it (jittered boxes end a few pixels short of the border).
  double bottom_cut_reach = 0.1;
  double top_surface_tolerance = 0.1;
  bool thin_height_from_box_rows = true;  // thin classes: vertical ends from the box rows at the points' depth
  // Other classes that are not flat (a bed, a cabinet) get their class's seen width and height at
  // least too: their trimmed points (box_shrink) span about 60 % of what the box shows.
  bool solid_class_size_floor = true;
  bool flat_height_from_box_rows = true;  // flat classes (doors) too
  double max_size_ratio = 1.6;    // extents beyond this times the class's largest size: wall or floor, no pose
  double min_depth = 0.2, max_depth = 10.0;
  bool complete_depth_with_class_size = true;  // push the centre back when only a front face is seen
  // A box cut off at the left or right image border gets a pose completed to the class's size on
  // the cut side (false: no pose). Objects at the edge of a turn are seen no other way.
  bool complete_side_cuts = true;
  double side_cut_min_slope = 20;  // px per metre along the seen face: below, the face runs along the ray
  // A flat class (its smaller horizontal size at most flat_ratio times its larger: a door) always
  // shows its face, from any side: the hidden depth is the axis its seen points are thinnest along,
  // not the one closer to the line of sight. Seen obliquely down a corridor, a door's width is the
  // axis closer to the line of sight, and was pushed back by half its width (synthetic doors 0.08-0.14
  // m too far along their wall). 0: off.
  double flat_ratio = 0.2;
  // Two detections of one keyframe measured at one place (horizontal centres closer than this times
  // the smaller class's smaller horizontal size): an occluded object measured on its occluder. The
  // farther one (its box ends higher by occluder_footprint_px) loses its pose; when neither is
  // clearly farther, the projections judge (below), else both do. 0: off.
  double coincident_ratio = 0.5;
  // Neither being clearly farther (a box cut by the image's bottom), the poses' projections judge:
  // each projecting onto its own box better by this much IoU, both keep their poses (two chairs of
  // a row, one placed 0.3 m off); both projecting onto one box better by this much on average, the
  // other detection loses its pose (a chair 16 % visible in the bottom corner, measured on the chair
  // behind it, took that chair's pose with it). Above 1: off (neither keeps one).
  double coincident_projection_margin = 0.1;
  // Tall classes (height at least tall_class_ratio times their larger horizontal size): a pose
  // farther than tall_depth_ratio times the distance at which the class's height fills the box's
  // rows is the wall behind, not the object (uncut boxes only; an occluded box is shorter, so nearer
  // poses are never refused). Synthetic doors and poles measured right reach 1.31. 0: off.
  double tall_class_ratio = 2.0;
  double tall_depth_ratio = 1.45;
  // Two detections of one class in one keyframe whose boxes overlap this much (IoU), neither
  // clearly nearer by its footprint: which one hides the other is unknown, so neither is placed.
  // Above 1: off (0.6 was mixed on the six seed-1 aisle_straight runs: quick 88.7-96.3 -> 94.8-99.3 %,
  // slow 97.7-99.7 -> 93.5-99.4 %).
  double ambiguous_pair_iou = 2.0;
  // Inside a measured occluder's image box, also hide every pixel no deeper than the far end of its
  // inflated 3-D box: "none", "same_class" (occluders of the measured detection's class) or "all".
  std::string mask_to_far_end = "none";
  // A measured occluder of a box_masked_classes class (an open frame: a pole, a wheelchair) hides
  // its image box only up to the far end of its inflated 3-D box, instead of the whole box.
  bool box_mask_to_far_end = true;
  // The front of a foot_front_classes class from the ray through its box's bottom row and the floor
  // just below the box (the pixels there agreeing on a height within floor_spread, m).
  bool front_from_foot = true;
  // With front_from_foot, also from the nearest object pixels of the box's bottom rows (those
  // box_shrink trims), higher than floor_clearance (m) above that floor: a wheelchair's footplate
  // stands in front of the casters the bottom row shows.
  bool front_from_low_rows = true;
  double floor_clearance = 0.03;
  // Cut at the bottom (seen from close, its low front out of view), such a class's front is also
  // where the middle of its parts in the upper half of its class height under its seen top (a
  // wheelchair's seat front to its backrest, 5-95 % of their extent) puts it, when nearer (our
  // addition; seed 1, bottom-cut wheelchairs: median error along the line of sight +0.385 ->
  // +0.256 m; one held-out wheelchair split in two by those measurements now whole).
  bool centre_from_upper_part_when_cut = true;
  // A plane_axes_classes class's horizontal axes from the normals of its vertical faces, instead of
  // its points' principal axes.
  bool axes_from_planes = true;
  // ... and, when the face across the other horizontal axis is seen too, the centre along that axis
  // half the box's size behind that face.
  bool anchor_side_face = true;
  double floor_spread = 0.05;
  // A foot_window_classes class stands on the floor: its nearest parts are where its box's bottom
  // row meets the floor just below the box. Its depth window must begin there, within the depths
  // of that row moved foot_window_rows of the box's height up and down (the detector's error at the
  // bottom edge), and foot_window_slack (m) either side; 0: off (the fullest window anywhere). Off
  // by default: with 0.06 the chair measurements beyond 0.4 m fell from 199 to 125 (layouts 1-3,
  // seed 1), and `wardmap compare` gained four targets over its eight sets and lost none, but on the
  // SLAM's keyframes (`run --objects`) four runs with chairs in rows seen end on fell under 97 %.
  double foot_window_rows = 0;
  double foot_window_slack = 0.1;
  // Without a floor of its own below the box (something stands in front of its lower end), the
  // keyframe's floor (the median of its boxes' floors) when this share of those pixels lies on it.
  double foot_floor_share = 0.5;
  // The box must be at least this share of the class's height (in pixels) standing on that floor.
  double foot_min_height_share = 0.7;
};

// Keyframe groups (Assoc. III-A.1): M adjacent keyframes, j shared with the next group. The paper
// says M is "usually less than 10"; 6 keyframes (about 1-2 s of motion at our keyframe rate) keep
// MOT inside a group reliable, and 2 overlapping keyframes give every group object a chance to share
// measurements with the next group (the 1.5 prior boost).
struct GroupOptions {
  int size = 6;     // M
  int overlap = 2;  // j
  // A track whose measurements jump by more than this (m) from the track's position so far is
  // split: image-space MOT can swap identical neighbours, their 3-D positions cannot.
  double split_distance = 0.5;
  // MOT predicts a track's box in the next keyframe from the keyframe poses (the camera's motion)
  // instead of the Kalman filter's image velocity alone (see track_in_group).
  bool camera_motion = true;
  // Boxes narrower than this (px) enter MOT without their embedding, so only the IoU stages can
  // match them: OSNet sees a crop of a few pixels as noise, and far doors of one wall, a few
  // pixels apart, swapped tracks on it. 0 (the default): every box by appearance (FairMOT). 16
  // measured neutral over seeds 1-3 (docs/EXPERIMENTS.md, "aisle_straight: chairs in a row swapped").
  double min_appearance_width = 0;
};

// GMM prior + likelihood of the HDP association (Assoc. Eq. 2-3, III-A.2).
struct AssociationOptions {
  std::string mode = "hierarchical";  // hierarchical | hdp-only
  double sigma_position = 0.25;       // m, GMM component std of each position coordinate
  double sigma_rotation = 1.2;        // rad (wide: square footprints have no stable yaw), GMM component std of each rotation-vector coordinate
  double overlap_boost = 1.5;         // prior x1.5 when the item shares measurements with the landmark
  bool landmark_mixture = true;       // a landmark's GMM is the mixture of its group objects' GMMs
                                      // (false: the best single group object's)
  // Weight of the spread of a landmark's group-object positions in the suffix swaps' score of a
  // landmark (AssociationModel::log_marginal; the sampler's MAP choice is scored without it). 0: off.
  double compactness_weight = 0;
  double new_landmark_distance = 0.8; // m: a landmark this far away scores like a new one
  double appearance_weight = 4.0;     // log-likelihood weight of the embedding cosine
  double appearance_neutral = 0.6;    // cosine that neither favours nor penalises joining
  hdp::CrfOptions crf;                // alpha, gamma, sweeps, seed
  int min_measurements = 3;           // landmarks with fewer measurements are not reported,
  int min_placed_measurements = 3;    // or with fewer measurements that have a pose,
  // or without a group object (an MOT track inside one group) holding this many of its measurements
  // (1: off; hierarchical mode): a confirmed track, as FairMOT reports only those. Detections never
  // tracked into a second keyframe are false positives or strays of a mapped object (our addition;
  // side-border objects are judged by border_pass_groups instead).
  int min_track_measurements = 2;
  // An object seen mostly at the image's left or right border (its box within border_touch_px of
  // it in at least half of its measurements) is entering or leaving the view: it is reported with
  // border_min_measurements measurements and, if a chair, pole or wheelchair (thin_classes, which
  // get no pose when cut there: measure_pose_from_depth), border_min_placed_measurements placed
  // ones (our addition: a chair in a corner of every view keeps at most 2 placed measurements).
  // Values equal to min_measurements / min_placed_measurements: off. Hierarchical mode, with the
  // keyframe views (the image size), only. 2: a door passed at the border in 2 keyframes is mapped
  // (docs/EXPERIMENTS.md, "Objects seen at a side border").
  int border_min_measurements = 2;
  int border_min_placed_measurements = 1;
  double border_touch_px = 8;
  // ... when border_min_measurements of its measurements lie in this many adjacent keyframe groups
  // (0: anywhere): an object entering or leaving the view is seen in one pass, two false positives a
  // minute apart are not such an object (our addition; a false cabinet of two boxes 58 keyframes
  // apart; a door at the border detected in keyframes 1 and 3 has no track of two but one pass).
  int border_pass_groups = 2;
  // Such a landmark whose boxes lie, in at least half of its keyframes, where a landmark of its class
  // reported on its own projects (this IoU or more) was measured on that object and is dropped (a
  // pole cut by the border, doubled: IoU 0.51-0.71; a chair beside another of its row: 0.17-0.44).
  double border_reprojection_iou = 0.5;
  // ... or where a landmark of another class reported on its own projects, in keyframes without a
  // measurement of it: the detector gave that object a wrong class there (our addition; a bed at the
  // left border detected as a chair twice: IoU 0.85-0.89).
  bool border_other_classes = true;
  // A chair, pole or wheelchair cut by a side border gets no pose, so one seen only there (in a
  // corner of every view) never reaches the sampler. A track of such unplaced measurements that no
  // landmark holds, seen mostly at a side border, is reported through the side-border minimums from
  // its cut boxes measured as if uncut (ObjectMeasurement::side_cut_pose), which place nothing else
  // (our addition; placing them for every use mapped the corner chairs but doubled border fragments
  // and changed other measurements' occluders: docs/EXPERIMENTS.md).
  bool border_side_cut_poses = true;
  // ... and only where its box's bottom lies within this of the floor the other thin landmarks stand
  // on (m; their median bottom; none reported with fewer than two of them): a pole's base in a
  // corner, its shaft out of view, is completed down from the base's top, 1.7 m under the floor.
  double border_side_cut_floor_tolerance = 0.25;
  // Two objects of one class cannot stand in one place: a reported landmark whose position lies
  // inside the footprint of a same-class landmark with more measurements, or whose footprint holds
  // that landmark's position while the two were never measured in one keyframe (one of them turned
  // wrongly), is that object split by the sampler, and its measurements join it (our addition; the
  // paper reports every cluster).
  // Hierarchical mode only (hdp-only is the HDP-SLAM baseline, whose first-measurement poses put
  // neighbours inside each other: merging there lowered its accuracy on 15 of its 72 synthetic runs,
  // by 0.25-5.0 points).
  bool merge_contained = true;
  // ... unless the two were detected apart (two boxes of one keyframe) in at least this share of
  // the keyframes of the one with fewer: then they are two objects, and one of them is placed from
  // its placed measurements outside the other's footprint alone, where no other landmark of the
  // class stands (place_apart: the one with more such measurements first; a row of chairs seen
  // end-on, the farther one's boxes measured on the nearer in some keyframes; our addition). If
  // neither can be, they merge. A share, not a count: a split object's fragments are detected apart
  // wherever one holds a box of a neighbour. 0: off (always merged).
  double place_apart_min_share = 0.5;
  // A reported landmark whose position lies inside the 3-D box of a landmark of another class with
  // more measurements (support classes excepted) was measured on that object, and is dropped (our
  // addition; drop_landmarks_inside_other_classes). Hierarchical mode only. On the 72 synthetic
  // runs it drops only aisle_straight's second cabinet, measured on the wheelchair in front of it
  // (2 runs); its measurements then leave the accuracy, as any dropped landmark's do.
  bool drop_inside_other_class = true;
  // A track whose boxes in some keyframes all lack a pose forms group objects the sampler never
  // sees; the same-class landmarks such a run of unplaced group objects touches (through detections
  // of the overlapping keyframes) are one object when never measured in one keyframe
  // (link_through_unplaced_tracks, our addition). Hierarchical mode only. On the 72 synthetic runs
  // it changes one: aisle_right_turn_slow_3 seed 2, a bed's far end measured 2 m off after 10
  // keyframes without a pose (11 -> 10 landmarks for 10 objects, 97.85 -> 100 %). A run touching two
  // landmarks measured in one keyframe switched objects and merges none; merges are judged with the
  // landmarks already merged (far doors of a row tracked with ID switches had chained two doors and
  // a fragment of a third into one: aisle_straight_slow_1 on the SLAM's keyframes, 12 -> 13 of 13).
  bool bridge_unplaced_tracks = true;
  // Measurements are checked against the landmarks' projected boxes in their keyframe
  // (reassign_by_projection, our addition): per keyframe a Hungarian assignment on box IoU (pairs
  // under reproject_min_iou never made), the current landmark favoured by reproject_margin.
  // none | unplaced (measurements without a pose, given a landmark by their MOT track alone) | all
  // (placed ones too, except those that gave a landmark its pose; landmark poses are kept).
  // Hierarchical mode, with the keyframe views. On the four synthetic runs below 97 % before it,
  // 9-23 % of the unplaced measurements were on a wrong landmark against 0.5-2.5 % of the placed
  // ones (MOT on occluded, cut and tiny boxes); see docs/EXPERIMENTS.md for the 72 runs. A margin
  // of 0.1 (0.2 until 2026-11-27) gave the same targets and a higher accuracy on 21 of the 22 runs
  // it changed; 0 lets a fragment keep boxes the true landmark projects onto as well.
  std::string reproject = "all";
  double reproject_min_iou = 0.3;
  double reproject_margin = 0.1;
  // Two measurements of one keyframe on one landmark: the one that fits its projection best stays
  // (keep_one_per_keyframe, our addition). A merge or an MOT track that switched objects can bring
  // them together past the sampler's cannot-link; on the 72 synthetic runs it happened in 3, all
  // aisle_right_turn's chair 6 carried into chair 7's landmark.
  bool one_per_keyframe = true;
  // Independent Gibbs chains (seeds seed, seed + 1, ...): the MAP state of the one with the highest
  // joint probability. On the 72 synthetic runs (24 sequences x seeds 1-3), 4 chains against 1:
  // mean accuracy 98.79 -> 98.89 %, >= 97 % on 62 against 63, count equal on 45 both: within the
  // runs' spread, at 4x the HDP time. The highest joint is not always the most accurate state.
  int chains = 1;
  // After sampling, two landmarks exchange their group objects from one group on when that raises
  // their log marginals by suffix_swap_min_gain (hdp/suffix_swap.h): neighbours that swapped over a
  // run of groups. Hierarchical mode only (hdp-only is the HDP-SLAM baseline). Off until the eighth
  // session (with compactness_weight 1 then: one right and one wrong swap on seeds 1-2). With the
  // log marginal alone: no target changes on the 72 runs of layouts 1-3; on layouts 4-5 (32 runs)
  // >= 97 % on 31 against 30, count equal once more (docs/EXPERIMENTS.md, "Layouts never used").
  bool suffix_swaps = true;
  double suffix_swap_min_gain = 1.0;
  int threads = 2;                    // threads the chains run on
};

// Landmark pose selection (Assoc. Eq. 4-6). The paper does not give A and B.
struct PoseSelectionOptions {
  double max_angle_deg = 45.0;   // A
  double max_distance = 1.0;     // B, metres
  double alpha = 0.4;            // angle weight
  double beta = 0.6;             // distance weight
};

// Monocular SLAM keyframes (Assoc. Eq. 1 "Pose" from the keyframe's map points): the points paint a
// sparse depth image, and the map, whose unit is arbitrary, is brought to metres first by a scale
// estimated from the box heights of the scale classes (see semantics/monocular_scale.h).
struct MonocularOptions {
  // Classes whose box height is their height, for the scale: standing objects at least as tall as
  // they are wide and deep, and those a camera at about their height sees (a car's top is barely
  // visible from a car's camera). Not a bed or a screen: their boxes show their length or width.
  std::set<std::string> scale_classes = {"door", "chair", "cabinet", "iv_pole", "person", "vehicle"};
  int point_radius = 2;               // px: each map point fills a (2r+1) x (2r+1) square of the depth image
  int min_points = 4;                 // map points needed inside a trimmed box, for a pose or a scale estimate
  double near_quantile = 0.25;        // the object's depth for the scale: this quantile of its points' depths
  double max_box_overlap = 0.1;       // a box overlapped more (share of its area) by another gives no scale estimate
  int min_scale_estimates = 5;        // fewer usable detections in the run: no scale, no poses
};

struct SemanticOptions {
  KeyframeSelectionOptions keyframes;
  MeasurementOptions measurement;
  GroupOptions groups;
  mot::TrackerOptions tracker;
  AssociationOptions association;
  PoseSelectionOptions pose_selection;
  MonocularOptions monocular;
  // Typical sizes (x across, y front-back, z up; metres) of the landmark classes, used to complete
  // a measurement that sees only the front of an object.
  std::map<std::string, std::array<double, 3>> class_sizes = {
      {"door", {0.9, 0.06, 2.05}}, {"chair", {0.5, 0.5, 0.9}},   {"bed", {0.95, 2.0, 0.6}},
      {"cabinet", {0.45, 0.45, 0.8}}, {"wheelchair", {0.65, 1.0, 0.9}}, {"iv_pole", {0.5, 0.5, 1.8}},
      // Indoor COCO: a desktop screen on its stand (24 inch).
      {"tv", {0.55, 0.15, 0.45}},
      // Road: a car (the road landmark set maps car and truck to vehicle), a standing person.
      {"vehicle", {1.8, 4.5, 1.5}}, {"person", {0.5, 0.3, 1.7}}};

  // Classes whose box is mostly background (measured on their nearest surface): a chair's box is
  // mostly what is seen between its legs and above its seat (the fullest window placed synthetic
  // ward chairs 0.3 m back, on the wall behind them; the nearest one: 0.11 m median error).
  std::set<std::string> thin_classes = {"iv_pole", "wheelchair", "chair"};
  // Thin classes seen on their central vertical axis: a pole's shaft stands in the middle of its
  // spoked base, so the nearest surface is the axis, not a face half the class's depth in front of
  // the centre (anchored on a face, the synthetic iv poles were placed 0.23 m too far: every one).
  std::set<std::string> axis_classes = {"iv_pole"};
  // Occluders of these classes hide more of their image box from the detections behind them than
  // the pixels inside their measured 3-D box: that box misses much of their spread-out frame (a
  // wheelchair's left pixels of itself to be measured as the cabinet behind it). Measured, they hide
  // it up to their far end (measurement.box_mask_to_far_end); unmeasured, all of it.
  std::set<std::string> box_masked_classes = {"iv_pole", "wheelchair"};
  // Classes whose nearest parts stand low, in the rows box_shrink trims (a wheelchair's footplate and
  // casters): with measurement.front_from_foot their front is where the box's bottom row meets the
  // floor, or with measurement.front_from_low_rows where those rows' parts above the floor begin.
  std::set<std::string> foot_front_classes = {"wheelchair"};
  // Classes whose depth window begins at their foot (measurement.foot_window_rows): a chair of a row
  // seen end on owns fewer of its box's pixels than the chair in front of it, whose depths are then
  // the fullest window when that chair is missed or measured off.
  std::set<std::string> foot_window_classes = {"chair"};
  // Classes whose seen points crowd unevenly over faces that meet at a corner: a bed seen from its
  // foot shows its footboard, its top and one side, and the principal axes of those points ran 15
  // degrees (median) off its length on the synthetic ward; a chair seen at a slant shows its seat's
  // edges and its backrest in an L, whose principal axes run diagonally, and its front was anchored
  // on the nearest corner (chair measurements 0.06-0.09 m too near, median). With
  // measurement.axes_from_planes their axes come from the normals of their vertical faces (beds 0.4
  // degrees), and with measurement.anchor_side_face their side from the face seen across their
  // other axis (docs/EXPERIMENTS.md). Not cabinets (no gain: a box seen on one or two faces) nor
  // wheelchairs (an open frame: worse).
  std::set<std::string> plane_axes_classes = {"bed", "chair"};
  // Classes other objects stand on (their boxes hold the boxes of what is on them).
  std::set<std::string> support_classes = {"table", "bed", "desk", "counter", "bench"};

  // Empty when valid, else the offending key and its allowed range.
  std::optional<std::string> validate() const;
};

// Reads the `semantics` section of a settings file over the defaults; throws InputError naming the
// file and the key.
SemanticOptions load_semantic_options(const YAML::Node& section, const std::filesystem::path& file);

}  // namespace wardmap::semantics
