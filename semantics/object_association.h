// Hierarchical object association (Assoc. III-A): MOT inside each keyframe group gives group
// objects; the HDP Gibbs sampler associates them across groups into landmarks; each landmark takes
// the pose chosen by Eq. 4-6. The HDP-only baseline (HDP-SLAM) makes every keyframe its own group,
// runs no MOT, and keeps each landmark's first measurement pose.
#pragma once

#include <functional>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "semantics/association_model.h"
#include "semantics/object_measurement.h"
#include "semantics/options.h"
#include "slam/core/camera.h"
#include "slam/core/se3.h"

namespace wardmap::semantics {

struct ObjectLandmark {
  int id = -1;
  std::string label;
  ObjectPose pose;
  std::vector<int> measurements;  // ids
  int pose_measurement = -1;      // the measurement whose pose the landmark took
};

struct AssociationResult {
  std::vector<ObjectLandmark> landmarks;  // those with at least min_measurements, ids 0..n-1
  std::vector<int> landmark_of;           // per measurement id: landmark id or -1 (dropped)
  std::vector<int> track_of;              // per measurement id: MOT track id inside its group, or -1
  std::vector<int> group_of;              // per measurement id: the (last) keyframe group holding it
  int num_group_objects = 0;
  int num_groups = 0;
  double hdp_log_joint = 0;  // log p(x, t, k) of the MAP state kept (the best chain's)
  double mot_seconds = 0, hdp_seconds = 0, pose_selection_seconds = 0;  // stage times
};

// Two objects of one class cannot stand in one place (association.merge_contained, our addition):
// each landmark whose position lies inside the footprint (its box seen from above) of a same-class
// landmark with more measurements, or whose footprint holds that landmark's position when
// `never_together` says the two were never measured in one keyframe, is merged into it, and `place`
// chooses the merged landmark's pose again. Landmarks keep their order; ids are left to the caller.
// Hierarchical mode only.
// When `place_apart` is given and moves one of a pair apart (it returns the one moved; its last
// argument says whether a pose is free for a landmark: clear of every other kept landmark of its
// class), the two stay; else they merge.
using FreePose = std::function<bool(const ObjectLandmark&, const ObjectPose&)>;
using PlaceApart = std::function<ObjectLandmark*(ObjectLandmark&, ObjectLandmark&, const FreePose&)>;
void merge_contained_landmarks(
    std::vector<ObjectLandmark>& landmarks, const std::function<void(ObjectLandmark&)>& place,
    const std::function<bool(const ObjectLandmark&, const ObjectLandmark&)>& never_together = nullptr,
    const PlaceApart& place_apart = nullptr);

// Two landmarks of one class detected apart in keyframes are two objects even when one stands
// inside the other's footprint: one was placed on measurements taken on its neighbour (a row of
// chairs seen end-on, the farther one's boxes measured on the nearer). One of `a` and `b` is placed
// by `place` (Assoc. Eq. 4-6) from its placed measurements outside the other's footprint alone,
// when it has at least `min_placed` of them, its new position and the other's footprint keep clear
// of each other, and `free` (when given) accepts the new pose. The one with more such measurements
// is tried first (`a` on a tie), then the other. Returns the one moved, or null; measurements stay
// with their landmarks (association.place_apart_min_share, our addition).
ObjectLandmark* place_apart(ObjectLandmark& a, ObjectLandmark& b, const std::vector<ObjectMeasurement>& ms,
                            const std::function<void(ObjectLandmark&)>& place, int min_placed,
                            const FreePose& free = nullptr);

// Group objects none of whose measurements could be placed never reach the sampler, so a track
// that runs through keyframes without poses (a bed seen from above, cut by the bottom border)
// leaves a gap the HDP cannot see across (association.bridge_unplaced_tracks, our addition).
// `unplaced` holds those group objects (measurement ids, `unplaced_labels` their classes);
// `dish_of` gives each measurement's landmark (dish) or -1, `dish_labels` each dish's class and
// `dish_measurements` its measurement ids (in id order, as `dish_of` gives them).
// Unplaced group objects of one class sharing a detection (an overlapping keyframe) form one track;
// the same-class dishes a track touches that are each `reportable` (a fragment below the reporting
// minimums is no second object) are merged into the first when `never_together` holds for the
// pair (their lists of measurement ids, with those of the dishes already merged into each). A
// track touching two such dishes measured together switched between objects (far boxes without a
// pose, tracked along a row of doors) and merges none. `dish_of` is rewritten; returns the dishes
// merged away.
int link_through_unplaced_tracks(const std::vector<std::vector<int>>& unplaced,
                                 const std::vector<std::string>& unplaced_labels,
                                 const std::vector<std::string>& dish_labels,
                                 const std::vector<std::vector<int>>& dish_measurements,
                                 const std::vector<bool>& reportable,
                                 const std::function<bool(const std::vector<int>&, const std::vector<int>&)>& never_together,
                                 std::vector<int>& dish_of);

// The floor the landmarks of `classes` stand on: the median height of their boxes' bottoms along
// their up axis; none with fewer than two of them.
std::optional<double> floor_height(const std::vector<ObjectLandmark>& landmarks, const std::set<std::string>& classes);

// The tracks (as link_through_unplaced_tracks forms them) none of whose measurements any dish
// holds, after that linking: per track its class and measurement ids (sorted). A thin object seen
// only where a side border cuts it (a chair in a corner of every view) is such a track
// (association.border_side_cut_poses).
std::vector<std::pair<std::string, std::vector<int>>> tracks_without_landmark(
    const std::vector<std::vector<int>>& unplaced, const std::vector<std::string>& unplaced_labels,
    const std::vector<int>& dish_of);

// Two objects cannot stand in one place either (association.drop_inside_other_class, our addition):
// a landmark whose position lies inside the 3-D box of a landmark of another class with more
// measurements was measured on that object (a cabinet behind a wheelchair, whose few placed
// measurements fell on the wheelchair) and is dropped; its measurements are left without a
// landmark. Landmarks of the support classes (things stand on them, or under them) neither drop nor
// are dropped. Landmarks keep their order; ids are left to the caller. Hierarchical mode only.
void drop_landmarks_inside_other_classes(std::vector<ObjectLandmark>& landmarks,
                                         const std::set<std::string>& support_classes);

// Where the keyframes were taken: with it, MOT predicts a track's box in the next keyframe from the
// camera's motion (groups.camera_motion); without it, from the Kalman filter's image velocity only.
struct KeyframeViews {
  slam::PinholeCamera camera;
  std::vector<slam::SE3> T_wc;  // per keyframe index
};

// A measurement joins a landmark through its MOT track and, if placed, its pose; where the track
// erred (an occluded chair's box, a far door a few pixels wide) or the pose was measured on another
// object, the landmarks' projections tell (association.reproject, our addition). Per keyframe, the
// measurements without a pose (with `placed_too`, every measurement but the ones that gave their
// landmark its pose) are assigned to the landmarks the others leave free by their box's IoU with
// each same-class landmark's projected 3-D box (Hungarian), their current landmark favoured by
// `margin`; a pair under `min_iou` is never made, and a measurement left unmatched keeps its
// landmark. Landmark poses are kept: they decided the projections.
void reassign_by_projection(std::vector<ObjectLandmark>& landmarks, const std::vector<ObjectMeasurement>& ms,
                            const KeyframeViews& views, double min_iou, double margin, bool placed_too);

// A detector gives one box per object and keyframe, so two measurements of one keyframe on one
// landmark cannot both be right (our addition; the sampler's cannot-link holds the same fact for
// group objects, but a landmark merge or an MOT track that switched objects can still bring two
// together). Per landmark and keyframe the measurement whose box best fits the landmark's
// projection (IoU; without a projection the pose measurement, then a placed one, then the higher
// score) stays; the others leave the landmark (reported as dropped). When the pose measurement
// itself leaves, the landmark is placed again by `place` from the others and every keyframe judged
// again by the new projection (up to 3 times, until the pose measurement stays; a landmark with no
// stable choice is left as it was). Returns the number of measurements taken off.
int keep_one_per_keyframe(std::vector<ObjectLandmark>& landmarks, const std::vector<ObjectMeasurement>& ms,
                          const KeyframeViews* views, const std::function<void(ObjectLandmark&)>& place);

// MOT inside one keyframe group (Assoc. III-A.1): runs a fresh tracker over the group's keyframes
// in order; returns for every measurement of those keyframes its track id (-1 when the tracker
// dropped it). `by_keyframe[k]` lists the measurement ids of keyframe k. With `views`, a track's
// box is predicted by moving its last box's centre ray, at the depth of its last measured pose,
// into the next keyframe (its size scaled by the depth ratio): a quick pan moves every box by more
// than the spacing of identical chairs side by side, which an image-space velocity cannot follow.
// Boxes narrower than `min_appearance_width` px enter without their embedding (IoU stages only).
std::vector<std::pair<int, int>> track_in_group(const std::vector<int>& group_keyframes,
                                                const std::vector<std::vector<int>>& by_keyframe,
                                                const std::vector<ObjectMeasurement>& measurements,
                                                const mot::TrackerOptions& options,
                                                const KeyframeViews* views = nullptr,
                                                double min_appearance_width = 0);

// Runs the whole association over the measurements of all keyframes, grouped as `groups` (keyframe
// indices; ignored in hdp-only mode, where every keyframe with measurements is its own group).
AssociationResult associate_objects(const std::vector<ObjectMeasurement>& measurements,
                                    const std::vector<std::vector<int>>& groups, const SemanticOptions& options,
                                    const KeyframeViews* views = nullptr);

}  // namespace wardmap::semantics
