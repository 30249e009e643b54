// Null spaces and the naming of twist spaces (ISO 3952 kinematic pairs).
#include "joints/twist_math.h"

#include <algorithm>
#include <cmath>

namespace contactcore {

const char* to_string(JointType type) {
  switch (type) {
    case JointType::Rigid: return "rigid";
    case JointType::Revolute: return "revolute";
    case JointType::Prismatic: return "prismatic";
    case JointType::Helical: return "helical";
    case JointType::Cylindrical: return "cylindrical";
    case JointType::Spherical: return "spherical";
    case JointType::Planar: return "planar";
    case JointType::SphereCylinder: return "sphere_cylinder";
    case JointType::SpherePlane: return "sphere_plane";
    case JointType::CylinderPlane: return "cylinder_plane";
    case JointType::General: return "general";
  }
  return "general";
}

namespace detail {

void perpendiculars(const Vec3& axis, Vec3& u, Vec3& v) {
  const Vec3 a = axis.normalized();
  const Vec3 seed = std::abs(a.x()) < 0.6 ? Vec3::UnitX() : (std::abs(a.y()) < 0.6 ? Vec3::UnitY() : Vec3::UnitZ());
  u = a.cross(seed).normalized();
  v = a.cross(u);
}

Eigen::Index numerical_rank(Eigen::JacobiSVD<Eigen::MatrixXd>& svd, double relative, double absolute) {
  const auto& s = svd.singularValues();
  const double top = s.size() ? s(0) : 0.0;
  // All noise (a matrix of round-off, 5e-30): rank 0, whatever its shape.
  if (!(top > absolute)) return 0;
  // Eigen's threshold is relative to the largest singular value: the larger
  // of the two ratios makes it absolute-and-relative.
  svd.setThreshold(std::max(relative, absolute / top));
  return svd.rank();
}

Eigen::MatrixXd null_space(const Eigen::MatrixXd& a, double tol, double absolute) {
  const Eigen::Index n = a.cols();
  if (a.rows() == 0) return Eigen::MatrixXd::Identity(n, n);
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(a, Eigen::ComputeFullV);
  const Eigen::Index rank = numerical_rank(svd, tol, absolute);
  return svd.matrixV().rightCols(n - rank);
}

Eigen::MatrixXd range_space(const Eigen::MatrixXd& a, double tol, double absolute) {
  if (a.cols() == 0) return Eigen::MatrixXd(a.rows(), 0);
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(a, Eigen::ComputeFullU);
  const Eigen::Index rank = numerical_rank(svd, tol, absolute);
  return svd.matrixU().leftCols(rank);
}

Eigen::MatrixXd constraint_rows(const Mat6X& free_twists, double tol) {
  return null_space(free_twists.transpose(), tol).transpose();
}

namespace {

// A point x (local) where every rotation twist (e_i, v_i) has zero velocity:
// v_i + e_i x x = 0. Returns false when the axes do not meet.
bool common_point(const std::vector<Vec6>& rotations, double tol, Vec3& x) {
  Eigen::MatrixXd a(3 * rotations.size(), 3);
  Eigen::VectorXd b(3 * rotations.size());
  for (size_t i = 0; i < rotations.size(); ++i) {
    const Vec3 e = rotations[i].head<3>();
    Eigen::Matrix3d cross;  // e x (.)
    cross << 0, -e.z(), e.y(), e.z(), 0, -e.x(), -e.y(), e.x(), 0;
    a.block(3 * i, 0, 3, 3) = cross;
    b.segment(3 * i, 3) = -rotations[i].tail<3>();
  }
  x = a.completeOrthogonalDecomposition().solve(b);
  return (a * x - b).norm() <= tol * std::max(1.0, b.norm()) + tol;
}

}  // namespace

TwistSpace classify_local(const Eigen::MatrixXd& twists, const Frame& frame, double tol) {
  TwistSpace out;
  const Eigen::MatrixXd basis = range_space(twists, tol);
  const int k = static_cast<int>(basis.cols());
  out.dof = k;
  for (int i = 0; i < k; ++i) out.basis.push_back(frame.to_global(basis.col(i)));
  if (k == 0) return out;

  // Rotational directions, and the pure translations (omega = 0).
  const Eigen::MatrixXd omega = basis.topRows(3);
  // The basis is orthonormal, so the omega parts are O(1) or round-off: the
  // rank threshold is absolute (1e-3) as well as relative, else a pure
  // translation's omega (5e-30) would count as one rotation and hide it.
  constexpr double kOmegaRank = 1e-3;
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(omega, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const int r = static_cast<int>(numerical_rank(svd, kOmegaRank, kOmegaRank));
  const Eigen::MatrixXd trans_coeffs = svd.matrixV().rightCols(omega.cols() - r);
  Eigen::MatrixXd translations = range_space((basis * trans_coeffs).bottomRows(3), tol);
  const int t = static_cast<int>(translations.cols());

  // For each rotational direction e: a twist with that omega, its
  // translation part along the pure translations removed.
  std::vector<Vec6> rotations;
  std::vector<double> pitches;
  for (int i = 0; i < r; ++i) {
    const Vec3 e = svd.matrixU().col(i);
    const Eigen::VectorXd x = omega.completeOrthogonalDecomposition().solve(e);
    Vec6 twist = basis * x;
    Vec3 v = twist.tail<3>();
    if (t > 0) v -= translations * (translations.transpose() * v);
    twist << e, v;
    rotations.push_back(twist);
    pitches.push_back(e.dot(v));
  }

  const auto perpendicular_to = [&](const Vec3& e) {
    for (int j = 0; j < t; ++j)
      if (std::abs(translations.col(j).dot(e)) > 1e-4) return false;
    return true;
  };
  Vec3 centre;
  const bool concurrent = r == 3 && common_point(rotations, 1e-4, centre);
  const bool no_pitch = [&] {
    for (double h : pitches)
      if (std::abs(h) > 1e-5) return false;
    return true;
  }();

  JointType type = JointType::General;
  if (k == 1) {
    if (r == 0) type = JointType::Prismatic;
    else if (no_pitch) type = JointType::Revolute;
    else type = JointType::Helical, out.pitch = pitches[0] * frame.length;
  } else if (k == 2 && r == 1 && t == 1 && std::abs(translations.col(0).dot(rotations[0].head<3>())) > 1 - 1e-6) {
    type = JointType::Cylindrical;
  } else if (k == 3 && r == 3 && concurrent) {
    type = JointType::Spherical;
  } else if (k == 3 && r == 1 && t == 2 && no_pitch && perpendicular_to(rotations[0].head<3>())) {
    type = JointType::Planar;
  } else if (k == 4 && r == 3 && t == 1 && concurrent) {
    type = JointType::SphereCylinder;
  } else if (k == 4 && r == 2 && t == 2 && no_pitch) {
    type = JointType::CylinderPlane;
  } else if (k == 5 && r == 3 && t == 2 && concurrent) {
    type = JointType::SpherePlane;
  }
  out.type = type;

  for (const Vec6& rot : rotations) {
    const Vec3 e = rot.head<3>();
    // Nearest point of the axis to the frame centre: e x v (v = q x e).
    const Vec3 q = concurrent ? centre : Vec3(e.cross(rot.tail<3>()));
    out.rotations.push_back({pnt(frame.centre + q * frame.length), dir(e)});
  }
  for (int j = 0; j < t; ++j) out.translations.push_back(dir(translations.col(j)));
  return out;
}

}  // namespace detail

TwistSpace classify_twists(const std::vector<Twist>& twists, const gp_Pnt& centre, double length,
                           double tolerance) {
  detail::Frame frame;
  frame.centre = detail::vec(centre);
  frame.length = length > 0 ? length : 1.0;
  Eigen::MatrixXd local(6, twists.size());
  for (size_t i = 0; i < twists.size(); ++i) local.col(i) = frame.to_local(twists[i]);
  return detail::classify_local(local, frame, tolerance);
}

}  // namespace contactcore
