// Rigid-motion helpers of the haptic loop (Eigen, header only, no allocation).
// A pose is the part's displacement from its assembled placement (mm); a
// twist is (linear displacement of a reference point, rotation vector) in the
// world frame, the reference point being the part's centre of mass.
#pragma once

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "contactcore/common/angles.h"

namespace contactcore::haptics {

using Vec3 = Eigen::Vector3d;
using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat3 = Eigen::Matrix3d;
using Pose = Eigen::Isometry3d;

using contactcore::kPi;  // the one pi (common/angles.h), also as haptics::kPi
inline double deg(double radians) { return radians * 180.0 / kPi; }
inline double rad(double degrees) { return degrees * kPi / 180.0; }

// Rotation by rx, then ry, then rz (radians) about the global axes.
inline Mat3 rotation_xyz(const Vec3& r) {
  return (Eigen::AngleAxisd(r.z(), Vec3::UnitZ()) * Eigen::AngleAxisd(r.y(), Vec3::UnitY()) *
          Eigen::AngleAxisd(r.x(), Vec3::UnitX()))
      .toRotationMatrix();
}
// Inverse of rotation_xyz for angles within (-90, 90) degrees about y.
inline Vec3 angles_xyz(const Mat3& m) {
  const double ry = std::asin(std::clamp(-m(2, 0), -1.0, 1.0));
  return {std::atan2(m(2, 1), m(2, 2)), ry, std::atan2(m(1, 0), m(0, 0))};
}

// The displacement that translates by `t` and rotates by `r_xyz` about global
// axes through `centre` (the trial script's convention).
inline Pose offset_pose(const Vec3& t, const Vec3& r_xyz, const Vec3& centre) {
  Pose p = Pose::Identity();
  p.linear() = rotation_xyz(r_xyz);
  p.translation() = centre + t - p.linear() * centre;
  return p;
}
// Back to (translate, rotate) about `centre`.
inline void offset_of(const Pose& p, const Vec3& centre, Vec3& t, Vec3& r_xyz) {
  t = p * centre - centre;
  r_xyz = angles_xyz(p.linear());
}

inline Vec3 rotation_vector(const Mat3& r) {
  Eigen::AngleAxisd aa(r);
  return aa.angle() * aa.axis();
}
inline Mat3 rotation_from_vector(const Vec3& w) {
  const double angle = w.norm();
  if (angle < 1e-15) return Mat3::Identity();
  return Eigen::AngleAxisd(angle, w / angle).toRotationMatrix();
}

// The twist taking `from` to `to`: (displacement of the reference point
// `centre` carried by `from`, rotation vector), world frame.
inline Vec6 twist_between(const Pose& from, const Pose& to, const Vec3& centre) {
  Vec6 xi;
  xi.head<3>() = to * centre - from * centre;
  xi.tail<3>() = rotation_vector(to.linear() * from.linear().transpose());
  return xi;
}
// `pose` moved by `xi` (rotation about the moved reference point).
inline Pose apply_twist(const Pose& pose, const Vec6& xi, const Vec3& centre) {
  const Vec3 c = pose * centre;
  Pose out = Pose::Identity();
  out.linear() = rotation_from_vector(xi.tail<3>()) * pose.linear();
  out.translation() = c + xi.head<3>() - out.linear() * centre;
  return out;
}

}  // namespace contactcore::haptics
