// From the joints stage (joints.h) to the servo loop: the joint of an
// assembled body pair as a JointState for the moving body (its free twists'
// axis and its one-sided stops), to hold a part to a chosen joint.
#pragma once

#include "contactcore/haptics/constraints.h"
#include "contactcore/joints/joints.h"

namespace contactcore::haptics {

// `moving` is pair.body_a or pair.body_b; `centre` the moving part's reference
// point and `part_box` its box (assembled placement). A pair touching by
// point and line contacts only (sphere_plane, cylinder_plane, or general:
// a ball in a V) is a HigherPair joint: every twist free, one stop per
// contact point. False for joint types the loop does not hold
// (sphere-in-cylinder, helical, a general joint of surface contacts).
bool joint_state_from_pair(const PairJoint& pair, int moving, const Vec3& centre,
                           const Eigen::AlignedBox3d& part_box, JointState& out);

}  // namespace contactcore::haptics
