#include "contactcore/haptics/constraints.h"

#include <algorithm>
#include <cmath>

namespace contactcore::haptics {

const char* to_string(JointKind kind) {
  switch (kind) {
    case JointKind::Free: return "Free";
    case JointKind::Cylindrical: return "Cylindrical";
    case JointKind::Revolute: return "Revolute";
    case JointKind::Prismatic: return "Slider";
    case JointKind::Spherical: return "Ball";
    case JointKind::Fixed: return "Fixed";
    case JointKind::Planar: return "Planar";
    case JointKind::HigherPair: return "Point/line contact";
  }
  return "?";
}

int free_twists(const JointState& joint, const Vec3& c, Eigen::Matrix<double, 6, 6>& basis) {
  basis.setZero();
  const Vec3& u = joint.axis;
  auto rotation_about = [&](const Vec3& w, const Vec3& through) {
    Vec6 t;
    t.head<3>() = w.cross(c - through);
    t.tail<3>() = w;
    return t;
  };
  switch (joint.kind) {
    case JointKind::Free:
    case JointKind::HigherPair:  // its stops hold it
      basis.setIdentity();
      return 6;
    case JointKind::Fixed:
      return 0;
    case JointKind::Prismatic:
      basis.col(0).head<3>() = u;
      return 1;
    case JointKind::Revolute:
      basis.col(0) = rotation_about(u, joint.point);
      return 1;
    case JointKind::Cylindrical:
      basis.col(0).head<3>() = u;
      basis.col(1) = rotation_about(u, joint.point);
      return 2;
    case JointKind::Spherical:
      for (int i = 0; i < 3; ++i) basis.col(i) = rotation_about(Vec3::Unit(i), joint.point);
      return 3;
    case JointKind::Planar: {
      // In-plane slides, lift-off along the normal (held by a stop), a turn about the normal.
      const Vec3 e1 = u.unitOrthogonal(), e2 = u.cross(e1);
      basis.col(0).head<3>() = e1;
      basis.col(1).head<3>() = e2;
      basis.col(2).head<3>() = u;
      basis.col(3).tail<3>() = u;
      return 4;
    }
  }
  return 0;
}

Pose snap_to_joint(const JointState& joint, const Pose& pose) {
  if (joint.kind == JointKind::Free || joint.kind == JointKind::HigherPair) return pose;
  const Vec3 q = pose * joint.part_point;
  Pose out = pose;
  if (joint.kind == JointKind::Spherical) {
    out.translation() += joint.point - q;
    return out;
  }
  // Align the part's axis with the joint's (the nearer of the two senses; a
  // face on a plane faces it).
  Vec3 d = pose.linear() * joint.part_axis;
  Vec3 u = joint.axis;
  if (joint.kind == JointKind::Planar || d.dot(u) < 0) u = -u;
  const Mat3 align = Eigen::Quaterniond::FromTwoVectors(d, u).toRotationMatrix();
  out.linear() = align * pose.linear();
  out.translation() = align * (pose.translation() - q) + q;
  if (joint.kind == JointKind::Planar) return out;
  // Put its point on the line.
  const Vec3 on_line = joint.point + (q - joint.point).dot(joint.axis) * joint.axis;
  out.translation() += on_line - q;
  return out;
}

double joint_deviation(const JointState& joint, const Pose& pose) {
  if (joint.kind == JointKind::Free || joint.kind == JointKind::HigherPair) return 0;  // stops: their overshoot
  if (joint.kind == JointKind::Spherical) return (pose * joint.part_point - joint.point).norm();
  if (joint.kind == JointKind::Planar) {
    const double c = std::clamp(-(pose.linear() * joint.part_axis).dot(joint.axis), -1.0, 1.0);
    return std::sin(std::acos(c)) * joint.part_axial_max;
  }
  double worst = 0;
  for (double s : {joint.part_axial_min, joint.part_axial_max}) {
    const Vec3 p = pose * (joint.part_point + s * joint.part_axis);
    const Vec3 r = p - joint.point;
    worst = std::max(worst, (r - r.dot(joint.axis) * joint.axis).norm());
  }
  return worst;
}

}  // namespace contactcore::haptics
