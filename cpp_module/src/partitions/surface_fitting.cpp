// Recognition of free-form faces that are really analytic: sampled points
// and normals fitted by a plane, sphere, cylinder, cone or torus (least
// squares, Eigen's eigen-solver and LU), or swept surfaces typed from their
// curve; each fit checked on a finer grid within the linear tolerance.
#include "partitions/surface_fitting.h"
#include "contactcore/common/angles.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <optional>
#include <utility>
#include <vector>

#include <Eigen/Dense>

#include <Adaptor3d_Curve.hxx>
#include <BRepLProp_SLProps.hxx>
#include <BRepTools.hxx>
#include <Bnd_Box.hxx>
#include <gp_Ax2.hxx>
#include <gp_Circ.hxx>
#include <gp_Lin.hxx>

namespace contactcore::detail {

UVBounds uv_bounds(const TopoDS_Face& face) {
  UVBounds b;
  BRepTools::UVBounds(face, b.u1, b.u2, b.v1, b.v2);
  return b;
}

std::pair<gp_XYZ, gp_XYZ> perpendicular_basis(const gp_Dir& axis) {
  const gp_Ax2 frame(gp::Origin(), axis);
  return {frame.XDirection().XYZ(), frame.YDirection().XYZ()};
}

double distance_to_axis(const gp_XYZ& p, const gp_XYZ& origin, const gp_XYZ& axis) {
  const gp_XYZ rel = p - origin;
  return (rel - axis * (rel * axis)).Modulus();
}

gp_XYZ away_from_core(const SurfaceParams& s, const gp_XYZ& p) {
  const gp_XYZ axis = s.axis.XYZ(), rel = p - s.location.XYZ();
  const gp_XYZ radial = rel - axis * (rel * axis);
  switch (s.kind) {
    case SurfaceKind::Cylinder:
    case SurfaceKind::Cone: return radial;
    case SurfaceKind::Sphere: return rel;
    case SurfaceKind::Torus: {
      const double rho = radial.Modulus();
      if (rho <= 0) return rel;
      return rel - radial * (s.radius / rho);
    }
    default: return gp_XYZ(0, 0, 0);
  }
}

bool oriented_normal(const BRepAdaptor_Surface& surface, bool reversed, double u, double v, gp_XYZ& point,
                     gp_XYZ& normal) {
  gp_Pnt p;
  gp_Vec du, dv;
  surface.D1(u, v, p, du, dv);
  gp_Vec n = du.Crossed(dv);
  const double length = n.Magnitude();
  if (length <= 1e-12 * (du.Magnitude() * dv.Magnitude()) || length == 0) return false;
  point = p.XYZ();
  normal = n.XYZ() / (reversed ? -length : length);
  return true;
}

namespace {

// ---------------------------------------------------------------------------
// Small dense linear algebra for the fits (3x3 and 4x4), by Eigen.

// Eigen decomposition of a symmetric 3x3 matrix: eigenvalues ascending,
// eigenvectors unit length.
struct SymmetricEigen {
  std::array<double, 3> values{};
  std::array<gp_XYZ, 3> vectors;
};

SymmetricEigen symmetric_eigen(const Eigen::Matrix3d& a) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(a);
  SymmetricEigen out;
  for (int i = 0; i < 3; ++i) {
    out.values[i] = solver.eigenvalues()(i);
    const Eigen::Vector3d v = solver.eigenvectors().col(i);
    const double n = v.norm();
    out.vectors[i] = n > 0 ? gp_XYZ(v.x(), v.y(), v.z()) / n : gp_XYZ(0, 0, 1);
  }
  return out;
}

// Solves the n x n system a x = b; false when a is singular (rank-revealing
// LU, pivots below 1e-14 of the largest count as zero).
template <int N>
bool solve_linear(const Eigen::Matrix<double, N, N>& a, const Eigen::Matrix<double, N, 1>& b,
                  Eigen::Matrix<double, N, 1>& x) {
  if (!a.allFinite() || !b.allFinite() || a.isZero(0)) return false;
  Eigen::FullPivLU<Eigen::Matrix<double, N, N>> lu(a);
  lu.setThreshold(1e-14);
  if (!lu.isInvertible()) return false;
  x = lu.solve(b);
  return x.allFinite();
}

gp_XYZ centroid(const std::vector<gp_XYZ>& points) {
  gp_XYZ sum(0, 0, 0);
  for (const gp_XYZ& p : points) sum += p;
  return points.empty() ? sum : sum / static_cast<double>(points.size());
}

// Covariance (not normalised) of points about `centre`.
Eigen::Matrix3d scatter(const std::vector<gp_XYZ>& points, const gp_XYZ& centre) {
  Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
  for (const gp_XYZ& p : points) {
    const gp_XYZ d = p - centre;
    const Eigen::Vector3d c(d.X(), d.Y(), d.Z());
    m += c * c.transpose();
  }
  return m;
}

struct Circle2 {
  double cx = 0, cy = 0, radius = 0;
};

// Circle through 2D points: algebraic (Kasa) fit on centred, scaled
// coordinates, exact for exact data, then a few Gauss-Newton steps on the
// geometric distance so approximated circles are not biased.
std::optional<Circle2> fit_circle(const std::vector<std::pair<double, double>>& pts) {
  if (pts.size() < 3) return std::nullopt;
  double mx = 0, my = 0;
  for (const auto& [x, y] : pts) mx += x, my += y;
  mx /= pts.size(), my /= pts.size();
  double scale = 0;
  for (const auto& [x, y] : pts) scale = std::max(scale, std::hypot(x - mx, y - my));
  if (scale <= 0) return std::nullopt;
  Eigen::Matrix3d a = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero(), sol;
  for (const auto& [px, py] : pts) {
    const double x = (px - mx) / scale, y = (py - my) / scale;
    const Eigen::Vector3d row(x, y, 1);
    a += row * row.transpose();
    b += row * -(x * x + y * y);
  }
  if (!solve_linear<3>(a, b, sol)) return std::nullopt;
  double cx = -sol[0] / 2, cy = -sol[1] / 2;
  const double r2 = cx * cx + cy * cy - sol[2];
  if (!(r2 > 0)) return std::nullopt;
  double r = std::sqrt(r2);
  for (int iteration = 0; iteration < 4; ++iteration) {
    Eigen::Matrix3d jtj = Eigen::Matrix3d::Zero();
    Eigen::Vector3d jtr = Eigen::Vector3d::Zero(), step;
    for (const auto& [px, py] : pts) {
      const double x = (px - mx) / scale - cx, y = (py - my) / scale - cy;
      const double d = std::hypot(x, y);
      if (d <= 0) continue;
      const Eigen::Vector3d row(-x / d, -y / d, -1);
      jtj += row * row.transpose();
      jtr -= row * (d - r);
    }
    if (!solve_linear<3>(jtj, jtr, step)) break;
    cx += step[0], cy += step[1], r += step[2];
    if (std::fabs(step[0]) + std::fabs(step[1]) + std::fabs(step[2]) < 1e-15) break;
  }
  if (!(r > 0)) return std::nullopt;
  return Circle2{mx + cx * scale, my + cy * scale, r * scale};
}

// ---------------------------------------------------------------------------
// Material side.

// Convex when the oriented normals point away from the core: the material is
// inside the surface.
MaterialSide side_from_normals(const SurfaceParams& s, const std::vector<gp_XYZ>& points,
                               const std::vector<gp_XYZ>& oriented_normals) {
  double vote = 0;
  for (std::size_t i = 0; i < points.size(); ++i) vote += oriented_normals[i] * away_from_core(s, points[i]);
  return vote >= 0 ? MaterialSide::Convex : MaterialSide::Concave;
}

// ---------------------------------------------------------------------------
// Recognition of free-form faces.

struct Samples {
  std::vector<gp_XYZ> points;           // fitting grid
  std::vector<gp_XYZ> normals;          // oriented unit normals at regular points
  std::vector<gp_XYZ> normal_points;    // the points where `normals` were taken
  std::vector<std::pair<double, double>> normal_uv;
  std::vector<gp_XYZ> check_points;     // finer grid for the deviation test
  double size = 0;                      // diagonal of the points' box
};

Samples sample_face(const BRepAdaptor_Surface& surface, bool reversed, const UVBounds& uv) {
  Samples s;
  const double u1 = uv.u1, u2 = uv.u2, v1 = uv.v1, v2 = uv.v2;
  s.points.reserve(kFitGrid * kFitGrid);
  s.check_points.reserve(kCheckGrid * kCheckGrid);
  for (int i = 0; i < kCheckGrid; ++i) {
    for (int j = 0; j < kCheckGrid; ++j) {
      const double u = u1 + (u2 - u1) * i / (kCheckGrid - 1), v = v1 + (v2 - v1) * j / (kCheckGrid - 1);
      const bool on_fit_grid = i % 2 == 0 && j % 2 == 0;
      if (!on_fit_grid) {
        s.check_points.push_back(surface.Value(u, v).XYZ());
        continue;
      }
      gp_XYZ p, n;
      if (oriented_normal(surface, reversed, u, v, p, n)) {
        s.normals.push_back(n);
        s.normal_points.push_back(p);
        s.normal_uv.emplace_back(u, v);
      } else {
        p = surface.Value(u, v).XYZ();
      }
      s.points.push_back(p);
      s.check_points.push_back(p);
    }
  }
  Bnd_Box box;
  for (const gp_XYZ& p : s.check_points) box.Add(gp_Pnt(p));
  s.size = box.IsVoid() ? 0 : std::sqrt(box.SquareExtent());
  return s;
}

struct Fit {
  SurfaceParams params;
  double deviation = 0;
};

template <class Distance>
double max_deviation(const std::vector<gp_XYZ>& points, Distance distance) {
  double worst = 0;
  for (const gp_XYZ& p : points) worst = std::max(worst, std::fabs(distance(p)));
  return worst;
}

std::optional<Fit> fit_plane(const Samples& s) {
  if (s.points.size() < 3 || s.normals.empty()) return std::nullopt;
  const gp_XYZ c = centroid(s.points);
  const SymmetricEigen eig = symmetric_eigen(scatter(s.points, c));
  gp_XYZ n = eig.vectors[0];
  if (centroid(s.normals) * n < 0) n.Reverse();  // outward, as the face is oriented
  Fit fit;
  fit.params.kind = SurfaceKind::Plane;
  fit.params.location = gp_Pnt(c);
  fit.params.axis = gp_Dir(n);
  fit.deviation = max_deviation(s.check_points, [&](const gp_XYZ& p) { return (p - c) * n; });
  return fit;
}

std::optional<Fit> fit_sphere(const Samples& s) {
  if (s.points.size() < 4) return std::nullopt;
  // x^2 + y^2 + z^2 + D x + E y + F z + G = 0 on centred, scaled points.
  const gp_XYZ c = centroid(s.points);
  double scale = 0;
  for (const gp_XYZ& p : s.points) scale = std::max(scale, (p - c).Modulus());
  if (scale <= 0) return std::nullopt;
  Eigen::Matrix4d a = Eigen::Matrix4d::Zero();
  Eigen::Vector4d b = Eigen::Vector4d::Zero(), sol;
  for (const gp_XYZ& p : s.points) {
    const gp_XYZ q = (p - c) / scale;
    const Eigen::Vector4d row(q.X(), q.Y(), q.Z(), 1);
    a += row * row.transpose();
    b += row * -q.SquareModulus();
  }
  if (!solve_linear<4>(a, b, sol)) return std::nullopt;
  const gp_XYZ centre_scaled(-sol[0] / 2, -sol[1] / 2, -sol[2] / 2);
  const double r2 = centre_scaled.SquareModulus() - sol[3];
  if (!(r2 > 0)) return std::nullopt;
  const gp_XYZ centre = c + centre_scaled * scale;
  const double radius = std::sqrt(r2) * scale;
  Fit fit;
  fit.params.kind = SurfaceKind::Sphere;
  fit.params.location = gp_Pnt(centre);
  fit.params.axis = gp::DZ();  // no frame of its own: the global Z axis
  fit.params.radius = radius;
  fit.deviation = max_deviation(s.check_points, [&](const gp_XYZ& p) { return (p - centre).Modulus() - radius; });
  return fit;
}

// Circle through points projected on the plane through their centroid
// perpendicular to `axis`; returns the circle centre (on the axis line) and radius.
std::optional<std::pair<gp_XYZ, double>> axis_circle(const std::vector<gp_XYZ>& points, const gp_Dir& axis) {
  const auto [e1, e2] = perpendicular_basis(axis);
  const gp_XYZ c = centroid(points);
  std::vector<std::pair<double, double>> projected;
  projected.reserve(points.size());
  for (const gp_XYZ& p : points) projected.emplace_back((p - c) * e1, (p - c) * e2);
  const std::optional<Circle2> circle = fit_circle(projected);
  if (!circle) return std::nullopt;
  return std::make_pair(c + e1 * circle->cx + e2 * circle->cy, circle->radius);
}

std::optional<Fit> fit_cylinder(const Samples& s) {
  if (s.normals.size() < 3) return std::nullopt;
  // Normals of a cylinder are perpendicular to its axis.
  const SymmetricEigen eig = symmetric_eigen(scatter(s.normals, gp_XYZ(0, 0, 0)));
  const gp_Dir axis(eig.vectors[0]);
  const auto circle = axis_circle(s.points, axis);
  if (!circle) return std::nullopt;
  const gp_XYZ centre = circle->first;  // not a structured binding: a lambda below uses it (clang 14)
  const double radius = circle->second;
  Fit fit;
  fit.params.kind = SurfaceKind::Cylinder;
  fit.params.location = gp_Pnt(centre);
  fit.params.axis = axis;
  fit.params.radius = radius;
  fit.deviation = max_deviation(s.check_points,
                                [&](const gp_XYZ& p) { return distance_to_axis(p, centre, axis.XYZ()) - radius; });
  return fit;
}

std::optional<Fit> fit_cone(const Samples& s) {
  if (s.normals.size() < 4) return std::nullopt;
  // Normals of a cone make a constant angle with the axis: their tips lie on
  // a circle in a plane perpendicular to it.
  const SymmetricEigen eig = symmetric_eigen(scatter(s.normals, centroid(s.normals)));
  gp_XYZ axis = eig.vectors[0];
  // Every tangent plane passes through the apex: n . apex = n . p.
  Eigen::Matrix3d a = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero(), apex_coords;
  for (std::size_t i = 0; i < s.normals.size(); ++i) {
    const gp_XYZ& n = s.normals[i];
    const Eigen::Vector3d c(n.X(), n.Y(), n.Z());
    a += c * c.transpose();
    b += c * (n * s.normal_points[i]);
  }
  if (!solve_linear<3>(a, b, apex_coords)) return std::nullopt;
  const gp_XYZ apex(apex_coords[0], apex_coords[1], apex_coords[2]);
  double mean_height = 0;
  for (const gp_XYZ& p : s.points) mean_height += (p - apex) * axis;
  if (mean_height < 0) axis.Reverse();  // from the apex into the opening
  double angle_sum = 0;
  int counted = 0;
  for (const gp_XYZ& p : s.points) {
    const gp_XYZ rel = p - apex;
    const double h = rel * axis;
    const double rho = (rel - axis * h).Modulus();
    if (rel.Modulus() <= 1e-12) continue;
    angle_sum += std::atan2(rho, h);
    ++counted;
  }
  if (counted == 0) return std::nullopt;
  const double half_angle = angle_sum / counted;
  if (!(half_angle > 1e-6 && half_angle < kPi / 2 - 1e-6)) return std::nullopt;
  const double cos_a = std::cos(half_angle), sin_a = std::sin(half_angle);
  Fit fit;
  fit.params.kind = SurfaceKind::Cone;
  fit.params.location = gp_Pnt(apex);
  fit.params.axis = gp_Dir(axis);
  fit.params.half_angle = half_angle;
  fit.deviation = max_deviation(s.check_points, [&](const gp_XYZ& p) {
    const gp_XYZ rel = p - apex;
    const double h = rel * axis;
    return (rel - axis * h).Modulus() * cos_a - h * sin_a;
  });
  return fit;
}

std::optional<Fit> fit_torus(const BRepAdaptor_Surface& surface, const Samples& s) {
  if (s.normals.size() < 6) return std::nullopt;
  // One principal curvature of a torus is the tube's, constant 1/r.
  BRepLProp_SLProps props(surface, 2, 1e-9);
  std::vector<double> kmin, kmax;
  std::vector<gp_XYZ> points, normals;
  for (const auto& [u, v] : s.normal_uv) {
    props.SetParameters(u, v);
    if (!props.IsCurvatureDefined()) continue;
    kmin.push_back(props.MinCurvature());
    kmax.push_back(props.MaxCurvature());
    points.push_back(props.Value().XYZ());
    normals.push_back(props.Normal().XYZ());
  }
  if (points.size() < 6) return std::nullopt;
  auto spread = [](const std::vector<double>& k, double& mean) {
    mean = std::accumulate(k.begin(), k.end(), 0.0) / k.size();
    double worst = 0;
    for (double value : k) worst = std::max(worst, std::fabs(value - mean));
    return mean != 0 ? worst / std::fabs(mean) : 1e300;
  };
  double mean_min = 0, mean_max = 0;
  const double spread_min = spread(kmin, mean_min), spread_max = spread(kmax, mean_max);
  const double tube_curvature = spread_min <= spread_max ? mean_min : mean_max;
  if (tube_curvature == 0) return std::nullopt;
  const double minor = 1 / std::fabs(tube_curvature);
  std::optional<Fit> best;
  for (double sign : {1.0, -1.0}) {
    // Tube centres p +/- r n lie on a circle about the torus axis.
    std::vector<gp_XYZ> centres;
    centres.reserve(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) centres.push_back(points[i] + normals[i] * (sign * minor));
    const gp_XYZ c = centroid(centres);
    const SymmetricEigen eig = symmetric_eigen(scatter(centres, c));
    const gp_Dir axis(eig.vectors[0]);
    const auto circle = axis_circle(centres, axis);
    if (!circle) continue;
    const gp_XYZ centre = circle->first;  // not a structured binding: a lambda below uses it (clang 14)
    const double major = circle->second;
    Fit fit;
    fit.params.kind = SurfaceKind::Torus;
    fit.params.location = gp_Pnt(centre);
    fit.params.axis = axis;
    fit.params.radius = major;
    fit.params.minor_radius = minor;
    const gp_XYZ a = axis.XYZ();
    fit.deviation = max_deviation(s.check_points, [&](const gp_XYZ& p) {
      const gp_XYZ rel = p - centre;
      const double h = rel * a;
      const double rho = (rel - a * h).Modulus();
      return std::hypot(rho - major, h) - minor;
    });
    if (!best || fit.deviation < best->deviation) best = fit;
  }
  return best;
}

// Signed distance of p to a typed surface (positive outside a cylinder,
// sphere, torus tube or cone, on the normal's side of a plane).
double signed_distance(const SurfaceParams& s, const gp_XYZ& p) {
  const gp_XYZ rel = p - s.location.XYZ(), axis = s.axis.XYZ();
  const double h = rel * axis, rho = (rel - axis * h).Modulus();
  switch (s.kind) {
    case SurfaceKind::Plane: return h;
    case SurfaceKind::Cylinder: return rho - s.radius;
    case SurfaceKind::Cone: return rho * std::cos(s.half_angle) - h * std::sin(s.half_angle);
    case SurfaceKind::Sphere: return rel.Modulus() - s.radius;
    case SurfaceKind::Torus: return std::hypot(rho - s.radius, h) - s.minor_radius;
    case SurfaceKind::Other: break;
  }
  return 1e300;
}

// Surfaces swept from a line or a circle (OCCT's surfaces of revolution and
// of linear extrusion, as FreeCAD's Revolve and Extrude make them) are, when
// the curve lies right, a plane, cylinder, cone, sphere or torus whose
// parameters follow from the curve and the axis or direction: typed without
// fitting. `face_point` (a point of the face) orients a cone's axis into its
// opening; plane normals are oriented by the caller.
std::optional<SurfaceParams> swept_conic(const BRepAdaptor_Surface& surface, const Tolerances& tol,
                                         const gp_XYZ& face_point) {
  const Handle(Adaptor3d_Curve) basis = surface.BasisCurve();  // in global coordinates
  const double sin_tol = std::sin(tol.angular);
  SurfaceParams s;
  if (surface.GetType() == GeomAbs_SurfaceOfRevolution) {
    const gp_Ax1 revolution = surface.AxeOfRevolution();
    const gp_XYZ a = revolution.Location().XYZ(), z = revolution.Direction().XYZ();
    auto foot = [&](const gp_XYZ& p) { return a + z * ((p - a) * z); };
    if (basis->GetType() == GeomAbs_Line) {
      const gp_Lin line = basis->Line();
      const gp_XYZ d = line.Direction().XYZ(), p = line.Location().XYZ(), dz = d ^ z;
      if (dz.Modulus() <= sin_tol) {  // parallel to the axis
        s.kind = SurfaceKind::Cylinder;
        s.location = gp_Pnt(foot(p));
        s.axis = gp_Dir(z);
        s.radius = (p - foot(p)).Modulus();
        return s;
      }
      if (std::fabs((p - a) * dz) / dz.Modulus() > tol.linear) return std::nullopt;  // skew: a hyperboloid
      if (std::fabs(d * z) <= sin_tol) {  // perpendicular to the axis
        s.kind = SurfaceKind::Plane;
        s.location = gp_Pnt(foot(p));
        s.axis = gp_Dir(z);
        return s;
      }
      // The line meets the axis at the apex: p + t d with (p + t d - a) ^ z = 0.
      const double t = ((a - p) ^ z) * dz / dz.SquareModulus();
      const gp_XYZ apex = p + d * t;
      s.kind = SurfaceKind::Cone;
      s.location = gp_Pnt(apex);
      s.axis = gp_Dir((face_point - apex) * z >= 0 ? z : z.Reversed());
      s.half_angle = std::acos(std::min(1.0, std::fabs(d * z)));
      return s;
    }
    if (basis->GetType() == GeomAbs_Circle) {
      const gp_Circ circle = basis->Circle();
      const gp_XYZ n = circle.Axis().Direction().XYZ(), centre = circle.Location().XYZ();
      if (std::fabs(n * z) > sin_tol || std::fabs((centre - a) * n) > tol.linear) return std::nullopt;
      const double major = (centre - foot(centre)).Modulus();
      s.location = gp_Pnt(foot(centre));
      s.axis = gp_Dir(z);
      s.radius = major <= tol.linear ? circle.Radius() : major;
      if (major <= tol.linear) {
        s.kind = SurfaceKind::Sphere;
      } else {
        s.kind = SurfaceKind::Torus;
        s.minor_radius = circle.Radius();
      }
      return s;
    }
    return std::nullopt;
  }
  if (surface.GetType() == GeomAbs_SurfaceOfExtrusion) {
    const gp_XYZ direction = surface.Direction().XYZ();
    if (basis->GetType() == GeomAbs_Line) {
      const gp_XYZ normal = basis->Line().Direction().XYZ() ^ direction;
      if (normal.Modulus() <= sin_tol) return std::nullopt;
      s.kind = SurfaceKind::Plane;
      s.location = basis->Line().Location();
      s.axis = gp_Dir(normal);
      return s;
    }
    if (basis->GetType() == GeomAbs_Circle) {
      const gp_Circ circle = basis->Circle();
      if ((circle.Axis().Direction().XYZ() ^ direction).Modulus() > sin_tol) return std::nullopt;  // elliptic
      s.kind = SurfaceKind::Cylinder;
      s.location = circle.Location();
      s.axis = gp_Dir(direction);
      s.radius = circle.Radius();
      return s;
    }
  }
  return std::nullopt;
}

// Types a face on a swept surface from its curve (swept_conic), checked on a
// kFitGrid x kFitGrid grid like the fits. False when it is no such surface.
bool recognise_swept(const BRepAdaptor_Surface& surface, bool reversed, const UVBounds& uv, const Tolerances& tol,
                     FaceInfo& out) {
  const double um = (uv.u1 + uv.u2) / 2, vm = (uv.v1 + uv.v2) / 2;
  gp_XYZ mid_point, mid_normal;
  if (!oriented_normal(surface, reversed, um, vm, mid_point, mid_normal)) return false;
  std::optional<SurfaceParams> params = swept_conic(surface, tol, mid_point);
  if (!params) return false;
  if (params->kind == SurfaceKind::Plane && params->axis.XYZ() * mid_normal < 0) params->axis.Reverse();
  Bnd_Box box;
  double deviation = 0;
  for (int i = 0; i < kFitGrid; ++i) {
    for (int j = 0; j < kFitGrid; ++j) {
      const gp_Pnt p = surface.Value(uv.u1 + (uv.u2 - uv.u1) * i / (kFitGrid - 1),
                                     uv.v1 + (uv.v2 - uv.v1) * j / (kFitGrid - 1));
      box.Add(p);
      deviation = std::max(deviation, std::fabs(signed_distance(*params, p.XYZ())));
    }
  }
  if (deviation > std::max(tol.linear, 1e-6 * std::sqrt(box.SquareExtent()))) return false;
  out.params = *params;
  out.recognised = true;
  out.max_deviation = deviation;
  out.side = params->kind == SurfaceKind::Plane ? MaterialSide::Outward
                                                : side_from_normals(*params, {mid_point}, {mid_normal});
  return true;
}

}  // namespace

bool recognise(const BRepAdaptor_Surface& surface, bool reversed, const UVBounds& uv, const Tolerances& tol,
               FaceInfo& out) {
  if ((surface.GetType() == GeomAbs_SurfaceOfRevolution || surface.GetType() == GeomAbs_SurfaceOfExtrusion) &&
      recognise_swept(surface, reversed, uv, tol, out))
    return true;
  const Samples s = sample_face(surface, reversed, uv);
  const double accepted = std::max(tol.linear, 1e-6 * s.size);
  std::optional<Fit> fit = fit_plane(s);
  if (!fit || fit->deviation > accepted) fit = fit_sphere(s);
  if (!fit || fit->deviation > accepted) fit = fit_cylinder(s);
  if (!fit || fit->deviation > accepted) fit = fit_cone(s);
  if (!fit || fit->deviation > accepted) fit = fit_torus(surface, s);
  if (!fit || fit->deviation > accepted) return false;
  out.params = fit->params;
  out.recognised = true;
  out.max_deviation = fit->deviation;
  out.side = fit->params.kind == SurfaceKind::Plane ? MaterialSide::Outward
                                                    : side_from_normals(fit->params, s.normal_points, s.normals);
  return true;
}

}  // namespace contactcore::detail
