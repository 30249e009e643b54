// Internal to the joints stage: twists and wrenches in a local frame, null
// spaces and the naming of a twist space. A local frame has its origin at a
// centre that moves with the assembly and divides lengths by a size, so ranks
// and singular values do not change under a rigid motion or with units.
#pragma once

#include <Eigen/Dense>

#include <vector>

#include "contactcore/joints/joints.h"

namespace contactcore::detail {

using Vec3 = Eigen::Vector3d;
using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6X = Eigen::Matrix<double, 6, Eigen::Dynamic>;
using Mat3X = Eigen::Matrix<double, 3, Eigen::Dynamic>;

inline Vec3 vec(const gp_XYZ& p) { return {p.X(), p.Y(), p.Z()}; }
inline Vec3 vec(const gp_Pnt& p) { return vec(p.XYZ()); }
inline Vec3 vec(const gp_Dir& d) { return vec(d.XYZ()); }
inline gp_Pnt pnt(const Vec3& v) { return gp_Pnt(v.x(), v.y(), v.z()); }
inline gp_Dir dir(const Vec3& v) { return gp_Dir(v.x(), v.y(), v.z()); }

// Twists (omega, v_centre / length) and wrench rows (moment about centre /
// length, force): row . twist = power / length.
struct Frame {
  Vec3 centre = Vec3::Zero();
  double length = 1;

  // Global twist (omega, v at origin) -> local.
  Vec6 to_local(const Twist& t) const {
    Vec6 out;
    const Vec3 w(t[0], t[1], t[2]), v(t[3], t[4], t[5]);
    out << w, (v + w.cross(centre)) / length;
    return out;
  }
  Twist to_global(const Vec6& t) const {
    const Vec3 w = t.head<3>();
    const Vec3 v = t.tail<3>() * length + centre.cross(w);
    return {w.x(), w.y(), w.z(), v.x(), v.y(), v.z()};
  }
  // A local twist of this frame seen in another frame (same length).
  Vec6 moved_to(const Vec6& t, const Frame& other) const {
    Vec6 out;
    const Vec3 w = t.head<3>();
    out << w, t.tail<3>() + w.cross(other.centre - centre) / length;
    return out;
  }
  // Force f through point p, as a local row.
  Vec6 force_row(const Vec3& p, const Vec3& f) const {
    Vec6 row;
    row << ((p - centre) / length).cross(f), f;
    return row;
  }
  static Vec6 moment_row(const Vec3& m) {
    Vec6 row;
    row << m, Vec3::Zero();
    return row;
  }
};

// Two unit vectors completing `axis` to an orthonormal frame.
void perpendiculars(const Vec3& axis, Vec3& u, Vec3& v);

// Numerical rank of a decomposed matrix: singular values above both
// `relative` times the largest and `absolute` (Eigen's setThreshold/rank()).
Eigen::Index numerical_rank(Eigen::JacobiSVD<Eigen::MatrixXd>& svd, double relative, double absolute);
// Orthonormal basis of the null space of the rows of `a` (rows x n):
// columns of the result (n x k). Singular values below tol * max, or below
// `absolute`, count as 0 (rows here are scaled to O(1)).
Eigen::MatrixXd null_space(const Eigen::MatrixXd& a, double tol, double absolute = 1e-12);
// Orthonormal basis of the column space of `a` (same rank test).
Eigen::MatrixXd range_space(const Eigen::MatrixXd& a, double tol, double absolute = 1e-12);
// Rows spanning the constraints of a twist space (its reciprocal complement
// in the local pairing): (6 - k) x 6.
Eigen::MatrixXd constraint_rows(const Mat6X& free_twists, double tol);

// Names a local twist space (any spanning set as columns) and gives its axes
// in global coordinates.
TwistSpace classify_local(const Eigen::MatrixXd& twists, const Frame& frame, double tol);

}  // namespace contactcore::detail
