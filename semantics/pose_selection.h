// Landmark pose selection (Assoc. Eq. 4-6): the landmark takes the pose of its measurement with the
// smallest weighted, normalised angle and distance difference to all its other measurements.
#pragma once

#include <vector>

#include "semantics/object_measurement.h"
#include "semantics/options.h"

namespace wardmap::semantics {

// Angle (radians) between two object orientations, up to the half turn about z that maps a box onto
// itself.
double object_angle_difference(const slam::SE3& a, const slam::SE3& b);

// f_Op(L_k) for every k (Assoc. Eq. 6, with Eq. 4 and 5 normalising by A and B).
std::vector<double> pose_differences(const std::vector<ObjectPose>& poses, const PoseSelectionOptions& options);

// Index of the selected measurement (Assoc. Eq. 6 minimum); -1 for an empty list. Ties go to the
// earlier measurement.
int select_landmark_pose(const std::vector<ObjectPose>& poses, const PoseSelectionOptions& options);

}  // namespace wardmap::semantics
