// Object measurement L = {ID_obj, ID_kf, Box, Pose} (Assoc. Eq. 1), with the detector's class and
// score, the appearance embedding, and the 6-DoF pose with size in the world frame.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "semantics/options.h"
#include "slam/core/camera.h"
#include "slam/core/se3.h"

namespace wardmap::semantics {

// Object frame: x across, y front to back, z up (the world's up); origin at the box centre.
struct ObjectPose {
  slam::SE3 pose;  // object-to-world
  Eigen::Vector3d size = Eigen::Vector3d::Zero();
};

struct ObjectMeasurement {
  int id = -1;          // ID_obj: index in the run's measurement list
  int keyframe = -1;    // ID_kf
  double timestamp = 0;
  Eigen::Vector4d box = Eigen::Vector4d::Zero();  // x0 y0 x1 y1
  std::string label;
  float score = 0;
  Eigen::VectorXf embedding;         // L2-normalised; empty when no embedder ran
  std::optional<ObjectPose> pose;    // empty: degenerate (no depth, too few points)
  // A thin class's box cut at the left or right border (no pose) measured as if uncut: only for a
  // landmark no placed measurement holds (association.border_side_cut_poses).
  std::optional<ObjectPose> side_cut_pose;
  int gt_instance = -1;              // true object id when the detector knows it (synthetic data)
};

// A nearer detection of the same keyframe whose box overlaps the one being measured. Its pixels
// are left out: those whose 3-D point falls inside its measured box (inflated by
// occluder_inflate) when it has a pose, else every pixel of its image box (also for the
// box_masked_classes, whose measured box misses much of their frame: with
// measurement.box_mask_to_far_end and a pose, only the pixels of their image box no deeper than the
// far end of their inflated 3-D box). With measurement.mask_to_far_end, also every pixel of its
// image box no deeper than that far end (the parts its measurement missed).
struct Occluder {
  Eigen::Vector4d box = Eigen::Vector4d::Zero();
  std::optional<ObjectPose> pose;
  bool same_class = false;  // of the measured detection's class (measurement.mask_to_far_end)
  bool box_masked = false;  // of a box_masked_classes class
  bool support = false;     // of a support_classes class (measurement.support_top_inflate)
};

// Assoc. Eq. 1 "Pose": the object's pose and size from the depth inside its box. Points are taken
// from the box shrunk by box_shrink; the depth window as deep as the class that holds the most of
// them is the object; they are moved to the world; the orientation is the principal horizontal axis
// (about `up`), or for a plane_axes_classes class (a bed) the axis its vertical faces' normals agree
// on, the size the 5-95 % extents. With complete_depth_with_class_size, a centre seen
// only from the front is pushed back by half the missing depth of the class's typical size, and a
// box cut off by the image's top or bottom border is completed to the class's height from its
// visible end, unless a long class shows its top there (seen from above, the cut hides its near
// end). Returns no pose rather than a wrong one (a box cut at the left or right; a box lying mostly in
// a nearer same-class occluder's measured box, seen through to what stands well behind it).
std::optional<ObjectPose> measure_pose_from_depth(const cv::Mat& depth, const slam::PinholeCamera& camera,
                                                  const slam::SE3& T_wc, const Eigen::Vector4d& box,
                                                  const Eigen::Vector3d& up, const std::string& label,
                                                  const SemanticOptions& options,
                                                  const std::vector<Occluder>& occluders = {});

// A box of a thin class (thin_classes: a chair, a pole, a wheelchair) cut by the left or the right
// image border gets no pose from measure_pose_from_depth: its nearest points show no face to
// complete along. This measures it as if that border did not cut it (its nearest surface pushed
// back by the class's depth), for a landmark that no other measurement places
// (association.border_side_cut_poses); none for any other box.
std::optional<ObjectPose> measure_thin_side_cut(const cv::Mat& depth, const slam::PinholeCamera& camera,
                                                const slam::SE3& T_wc, const Eigen::Vector4d& box,
                                                const Eigen::Vector3d& up, const std::string& label,
                                                const SemanticOptions& options,
                                                const std::vector<Occluder>& occluders = {});

// Median depth of the trimmed box (0 when it has no valid depth): orders a keyframe's detections
// front to back, so that each one is measured without the pixels of the nearer ones. With
// `exclude`, the pixels inside that box are left out (0 when fewer than min_points remain).
double box_median_depth(const cv::Mat& depth, const Eigen::Vector4d& box, const MeasurementOptions& options,
                        const Eigen::Vector4d* exclude = nullptr);

// Share of the trimmed box's valid depths lying occluder_margin or more in front of its median
// depth (0 without depth): how much of the box something nearer covers.
double box_front_share(const cv::Mat& depth, const Eigen::Vector4d& box, const MeasurementOptions& options);

// For each box, the indices of the nearer detections overlapping it.
// `supports[i]` tells that detection i is of a class things stand on (a table): a much larger
// support box holding most of a box is not its occluder.
std::vector<std::vector<int>> nearer_overlapping_detections(const cv::Mat& depth, const std::vector<Eigen::Vector4d>& boxes,
                                                            const MeasurementOptions& options,
                                                            const std::vector<bool>& supports = {});

// The image box of an object's 3-D box seen from camera pose T_wc, clipped to the image: of its
// part in front of the camera (0.1 m on) when the camera stands beside or inside it; none when none
// of it lies there or it falls outside the image.
std::optional<Eigen::Vector4d> project_box(const ObjectPose& box, const slam::PinholeCamera& camera, const slam::SE3& T_wc);

// Two detections of one keyframe whose poses stand at one place (horizontal centres closer than
// measurement.coincident_ratio times the smaller class's smaller horizontal size; support classes
// excepted) cannot both be right: the occluded one was measured on its occluder (chairs in a row
// seen from behind). The farther one, whose box ends occluder_footprint_px higher, loses its pose.
// When neither is clearly farther (a box cut by the image's bottom border), the poses' projections
// judge (IoU with one box less IoU with the other, margin measurement.coincident_projection_margin):
// each filling its own box, both are kept (two objects, one placed a little off); both filling one
// box on average, the other box's detection loses its pose; otherwise neither keeps one.
void drop_coincident_poses(std::vector<std::optional<ObjectPose>>& poses, const std::vector<Eigen::Vector4d>& boxes,
                           const std::vector<std::string>& labels, const Eigen::Vector3d& up,
                           const slam::PinholeCamera& camera, const slam::SE3& T_wc, const SemanticOptions& options);

// Assoc. Eq. 1 "Pose" for all detections of one keyframe: front to back, so that each is measured
// without the pixels of the nearer ones, masked by their measured 3-D boxes when they have one.
// With `side_cut_poses`, also each unplaced thin class's side-cut box that no nearer detection
// overlaps, measured as if uncut (measure_thin_side_cut; empty for the others); they mask nothing.
// With `duplicates`, which detections are a nearer detection of their class detected again and seen
// through (measurement.max_inside_same_class_share, duplicate_containment, duplicate_rest_window_share:
// a chair's back inside the whole chair's box, placed on the wall behind its slats); they get no pose.
std::vector<std::optional<ObjectPose>> measure_keyframe_poses(
    const cv::Mat& depth, const slam::PinholeCamera& camera, const slam::SE3& T_wc,
    const std::vector<Eigen::Vector4d>& boxes, const std::vector<std::string>& labels, const Eigen::Vector3d& up,
    const SemanticOptions& options, std::vector<std::optional<ObjectPose>>* side_cut_poses = nullptr,
    std::vector<bool>* duplicates = nullptr);

// The world's up direction from camera poses, which seldom roll but may look down: orthogonal to
// their right (x) axes once those span a plane (the camera has turned), on the side of the mean of
// their -y axes; before that, the mean -y axis made orthogonal to the mean right axis.
Eigen::Vector3d estimate_up(const std::vector<slam::SE3>& camera_poses);

// A rotation with z along `up` and x along the horizontal direction of `axis` (canonical sign).
Eigen::Matrix3d upright_rotation(const Eigen::Vector3d& up, const Eigen::Vector3d& axis);

}  // namespace wardmap::semantics
