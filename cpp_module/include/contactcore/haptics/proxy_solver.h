// The god-object proxy's step (after CHAI3D's god-object and the 6-DOF
// god-object of Ortega, Redon and Coquillart): the twist nearest the one the
// hand commands, in the part's mass metric, among the twists the engaged
// joint leaves free, subject to one-sided linear constraints (non-penetration
// at the contact points, the joint's stops). A small convex quadratic program
// solved on its dual by projected Gauss-Seidel: fixed-size Eigen, no
// allocation, a few microseconds for a handful of constraints.
#pragma once

#include "contactcore/haptics/pose_math.h"

namespace contactcore::haptics {

using Mat6 = Eigen::Matrix<double, 6, 6>;

// row . x >= bound, x = (velocity of the reference point, angular velocity) * dt.
struct ProxyConstraint {
  Vec6 row = Vec6::Zero();
  double bound = 0;
};

struct ProxyStep {
  Vec6 twist = Vec6::Zero();
  int active = 0;            // constraints holding (multiplier > 0)
  double violation = 0;      // largest bound - row . twist left (mm), 0 when every constraint holds
  // Sum of the multipliers: the constraints' push on the part in the metric's
  // units (for unit-normal rows through the centre, mm of the hand's offset
  // into them: the normal load a friction cone compares the slip with).
  double load = 0;
};

// min 1/2 (x - desired)^T M (x - desired) over x = S q (S: the first `free`
// columns of `basis`), subject to the constraints. M symmetric positive
// definite (the part's mass metric).
ProxyStep solve_proxy_step(const Vec6& desired, const Mat6& metric, const Mat6& basis, int free,
                           const ProxyConstraint* constraints, int count, int sweeps = 80);

// The row of a non-penetration constraint at contact point `p` with unit
// normal `n` (out of the other body), reference point `c`: the point's
// displacement along n for twist x is row . x.
inline Vec6 contact_row(const Vec3& p, const Vec3& n, const Vec3& c) {
  Vec6 row;
  row.head<3>() = n;
  row.tail<3>() = (p - c).cross(n);
  return row;
}

}  // namespace contactcore::haptics
