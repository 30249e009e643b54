#include "contacts/coaxial_overlap.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include <BRepAdaptor_Surface.hxx>
#include <BRepClass3d_SolidClassifier.hxx>
#include <BRepTools.hxx>
#include <BRepExtrema_DistShapeShape.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <gp_Ax2.hxx>

#include "contactcore/common/angles.h"

namespace contactcore {

namespace {

// A face about the axis: a plane across it (z0 == z1), or a surface of
// revolution whose radius is a function of z on [z0, z1] (z0 < z1): linear
// for cylinders and cones (r0 at z0 to r1 at z1), sqrt(R^2 - (z - zc)^2) for
// a sphere, R +- sqrt(rho^2 - (z - zc)^2) for the outer or inner half of a
// torus tube.
enum class ProfileKind { Plane, Line, Sphere, TorusOuter, TorusInner };

struct Profile {
  ProfileKind kind = ProfileKind::Plane;
  double z0 = 0, z1 = 0, r0 = 0, r1 = 0;
  double zc = 0, major = 0, minor = 0;  // sphere (major: its radius), torus
  bool convex = false;  // material on the axis side of the face, along a ray from the axis
  bool plane() const { return kind == ProfileKind::Plane; }
  bool linear() const { return kind == ProfileKind::Line; }
  double radius_at(double z) const {
    switch (kind) {
      case ProfileKind::Line: return r0 + (r1 - r0) * (z - z0) / (z1 - z0);
      case ProfileKind::Sphere: return std::sqrt(std::max(0.0, major * major - (z - zc) * (z - zc)));
      case ProfileKind::TorusOuter: return major + std::sqrt(std::max(0.0, minor * minor - (z - zc) * (z - zc)));
      case ProfileKind::TorusInner: return major - std::sqrt(std::max(0.0, minor * minor - (z - zc) * (z - zc)));
      default: return 0;
    }
  }
  double max_radius() const {
    if (plane()) return 0;
    double r = std::max(radius_at(z0), radius_at(z1));
    if ((kind == ProfileKind::Sphere || kind == ProfileKind::TorusOuter) && z0 < zc && zc < z1)
      r = std::max(r, radius_at(zc));
    return r;
  }
};

std::optional<Profile> face_profile(const FaceInfo& face, const gp_Pnt& origin, const gp_Dir& direction,
                                    const Tolerances& tol) {
  const SurfaceParams& p = face.params;
  const gp_Vec d(direction);
  if (p.kind == SurfaceKind::Plane) {
    if (!p.axis.IsParallel(direction, tol.angular)) return std::nullopt;
    const double z = gp_Vec(origin, p.location).Dot(d);
    Profile plane;
    plane.z0 = plane.z1 = z;
    return plane;
  }
  if (face.side == MaterialSide::Outward) return std::nullopt;
  const gp_Vec offset(origin, p.location);
  if (offset.Crossed(d).Magnitude() > tol.linear) return std::nullopt;  // centre, apex or axis off the line
  const double at = offset.Dot(d);
  Profile out;
  out.convex = face.side == MaterialSide::Convex;
  if (p.kind == SurfaceKind::Sphere) {
    // Symmetric about any line through its centre: its range re-measured along ours.
    const Extent e = revolution_extent_in(face, p.location, direction, gp_Ax2(p.location, direction).XDirection(),
                                          tol.linear);
    out.kind = ProfileKind::Sphere;
    out.zc = at, out.major = p.radius;
    out.z0 = at + e.axial_min, out.z1 = at + e.axial_max;
  } else {
    if (!p.axis.IsParallel(direction, tol.angular)) return std::nullopt;
    // Axial range measured along the surface's axis from its location (a
    // cone's apex): into the frame of `direction`.
    const double sign = gp_Vec(p.axis).Dot(d) > 0 ? 1 : -1;
    out.z0 = at + sign * face.extent.axial_min;
    out.z1 = at + sign * face.extent.axial_max;
    if (out.z0 > out.z1) std::swap(out.z0, out.z1);
    if (p.kind == SurfaceKind::Cylinder || p.kind == SurfaceKind::Cone) {
      out.kind = ProfileKind::Line;
      double ra = p.radius, rb = p.radius;
      if (p.kind == SurfaceKind::Cone) {
        const double slope = std::tan(p.half_angle);
        ra = std::abs(face.extent.axial_min) * slope;
        rb = std::abs(face.extent.axial_max) * slope;
      }
      const bool flipped = at + sign * face.extent.axial_min > at + sign * face.extent.axial_max;
      out.r0 = flipped ? rb : ra;
      out.r1 = flipped ? ra : rb;
    } else if (p.kind == SurfaceKind::Torus) {
      // Which half of the tube the face lies on (a fillet is a quarter of
      // it): from its own parameters, so only tori stored as tori.
      const BRepAdaptor_Surface surface(face.face);
      if (surface.GetType() != GeomAbs_Torus) return std::nullopt;
      double u0, u1, v0, v1;
      BRepTools::UVBounds(face.face, u0, u1, v0, v1);
      const double c0 = std::cos(v0), c1 = std::cos(v1), cm = std::cos(0.5 * (v0 + v1));
      const double eps = 1e-9;
      bool outer;
      if (c0 >= -eps && c1 >= -eps && cm >= -eps) outer = true;
      else if (c0 <= eps && c1 <= eps && cm <= eps) outer = false;
      else return std::nullopt;
      out.kind = outer ? ProfileKind::TorusOuter : ProfileKind::TorusInner;
      out.zc = at, out.major = p.radius, out.minor = p.minor_radius;
      // Material inside the tube lies towards the axis from its outer half, away from it from its inner half.
      if (!outer) out.convex = !out.convex;
    } else {
      return std::nullopt;
    }
  }
  if (out.z1 - out.z0 <= tol.linear * 1e-3) return std::nullopt;  // a degenerate strip
  return out;
}

// Every face of `body` about the axis; false when one is not (then the body is
// not a solid of revolution about it).
bool all_profiles(const BodyPartitions& body, const gp_Pnt& origin, const gp_Dir& direction, const Tolerances& tol,
                  std::vector<Profile>& out) {
  for (const FaceInfo& face : body.faces) {
    const std::optional<Profile> profile = face_profile(face, origin, direction, tol);
    if (!profile) return false;
    out.push_back(*profile);
  }
  return true;
}

// The axis-aligned box of the cylinder of radius `radius` about the axis from z0 to z1.
Bnd_Box cylinder_box(const gp_Pnt& origin, const gp_Dir& d, double radius, double z0, double z1) {
  const double ex = radius * std::sqrt(std::max(0.0, 1 - d.X() * d.X()));
  const double ey = radius * std::sqrt(std::max(0.0, 1 - d.Y() * d.Y()));
  const double ez = radius * std::sqrt(std::max(0.0, 1 - d.Z() * d.Z()));
  Bnd_Box box;
  for (const double z : {z0, z1}) {
    const gp_Pnt c = origin.Translated(gp_Vec(d) * z);
    box.Update(c.X() - ex, c.Y() - ey, c.Z() - ez, c.X() + ex, c.Y() + ey, c.Z() + ez);
  }
  return box;
}

// A solid cylinder about the axis, radius `radius` from z0 to z1: one of
// the pieces of the reach of a solid of revolution (each of its faces' axial
// range and largest radius, grown by a margin).
struct ReachPiece {
  double z0, z1, radius;
};

// The largest radius the reach has at z (0 outside it).
double reach_at(const std::vector<ReachPiece>& reach, double z) {
  double r = 0;
  for (const ReachPiece& piece : reach)
    if (piece.z0 <= z && z <= piece.z1) r = std::max(r, piece.radius);
  return r;
}

// A distance from the axis that no point of the face comes under, from its
// surface alone (0 when unknown): a plane along the axis (a flat of a hexagon
// around a bore), a cylinder parallel to it and off it (a bolt hole). Spares
// the distance query against the reach for faces that stay out of it.
double distance_from_axis_at_least(const FaceInfo& face, const gp_Pnt& origin, const gp_Dir& direction,
                                   const Tolerances& tol) {
  const SurfaceParams& p = face.params;
  const gp_Vec offset(origin, p.location);
  if (p.kind == SurfaceKind::Plane && std::abs(gp_Vec(p.axis).Dot(gp_Vec(direction))) < 1e-12)
    return std::abs(offset.Dot(gp_Vec(p.axis)));
  if (p.kind == SurfaceKind::Cylinder && p.axis.IsParallel(direction, tol.angular)) {
    // Both axes parallel within the angular tolerance: over the face's
    // length the offset varies by at most that angle times its reach.
    const double off_axis = offset.Crossed(gp_Vec(direction)).Magnitude();
    const double length = std::max(std::abs(face.extent.axial_min), std::abs(face.extent.axial_max));
    return std::max(0.0, off_axis - p.radius - std::sin(tol.angular) * length);
  }
  return 0;
}

// The faces of `body` within the reach, all planes across the axis or
// coaxial surfaces of revolution: their profiles; false when another face
// comes within it (proven away by its box, or by its distance to the solid
// cylinders of the reach).
bool profiles_within(const BodyPartitions& body, const gp_Pnt& origin, const gp_Dir& direction,
                     const std::vector<ReachPiece>& reach, const Tolerances& tol, std::vector<Profile>& out) {
  std::vector<Bnd_Box> boxes;
  for (const ReachPiece& piece : reach) boxes.push_back(cylinder_box(origin, direction, piece.radius, piece.z0, piece.z1));
  std::vector<TopoDS_Shape> solids(reach.size());
  for (const FaceInfo& face : body.faces) {
    bool near = false;
    for (const Bnd_Box& box : boxes) near = near || !face.box.IsOut(box);
    if (!near) continue;
    if (const std::optional<Profile> profile = face_profile(face, origin, direction, tol)) {
      out.push_back(*profile);
      continue;
    }
    const double beyond = distance_from_axis_at_least(face, origin, direction, tol);
    for (std::size_t k = 0; k < reach.size(); ++k) {
      if (face.box.IsOut(boxes[k])) continue;
      if (beyond > reach[k].radius + tol.linear) continue;  // the whole face farther from the axis than the piece
      if (solids[k].IsNull())
        solids[k] = BRepPrimAPI_MakeCylinder(gp_Ax2(origin.Translated(gp_Vec(direction) * reach[k].z0), direction),
                                             reach[k].radius, reach[k].z1 - reach[k].z0)
                        .Shape();
      BRepExtrema_DistShapeShape distance(face.face, solids[k]);
      if (!distance.IsDone() || distance.NbSolution() == 0 || distance.InnerSolution() ||
          distance.Value() <= tol.linear)
        return false;
    }
  }
  return true;
}

// True when the point lies farther than `linear` outside the box.
bool outside_box(const Bnd_Box& box, const gp_Pnt& p, double linear) {
  if (box.IsVoid()) return false;
  double x0, y0, z0, x1, y1, z1;
  box.Get(x0, y0, z0, x1, y1, z1);
  return p.X() < x0 - linear || p.X() > x1 + linear || p.Y() < y0 - linear || p.Y() > y1 + linear ||
         p.Z() < z0 - linear || p.Z() > z1 + linear;
}

struct Radius {
  double r;
  bool convex;
};

// Material at radius r (between radii, never on one) from the nearest face
// radius above it (material below a convex face) or else below it (material
// above a concave one); -1 when there is none.
int material_at(const std::vector<Radius>& radii, double r) {
  const Radius* above = nullptr;
  const Radius* below = nullptr;
  for (const Radius& q : radii) {
    if (q.r > r && (!above || q.r < above->r)) above = &q;
    if (q.r < r && (!below || q.r > below->r)) below = &q;
  }
  if (above) return above->convex ? 1 : 0;
  if (below) return below->convex ? 0 : 1;
  return -1;
}

// The common volume of `rev` (a solid of revolution about the axis, all its
// faces in `rev_profiles`) and `other`; nullopt when `other` has a face in
// reach that is not about the axis, or a section cannot be classified.
std::optional<double> common_of_revolution(const std::vector<Profile>& rev_profiles, const BodyPartitions& other,
                                           const TopoDS_Shape& other_shape, const gp_Pnt& origin,
                                           const gp_Dir& direction, const Tolerances& tol) {
  double rev_radius = 0, z_low = HUGE_VAL, z_high = -HUGE_VAL;
  for (const Profile& p : rev_profiles) {
    rev_radius = std::max(rev_radius, p.max_radius());
    z_low = std::min(z_low, p.z0);
    z_high = std::max(z_high, p.z1);
  }
  if (rev_radius <= tol.linear || z_high - z_low <= tol.linear) return std::nullopt;
  const double margin = std::max(10 * tol.linear, 0.01 * rev_radius);
  std::vector<ReachPiece> reach;
  for (const Profile& p : rev_profiles)
    if (!p.plane()) reach.push_back({p.z0 - margin, p.z1 + margin, p.max_radius() + margin});
  std::vector<Profile> other_profiles;
  if (!profiles_within(other, origin, direction, reach, tol, other_profiles)) return std::nullopt;

  // Breakpoints: every face's ends, the radii's crossings (with each other
  // and with the revolution's largest radius, which bounds the rings).
  std::vector<Profile> curved;
  for (const std::vector<Profile>* list : {&rev_profiles, static_cast<const std::vector<Profile>*>(&other_profiles)})
    for (const Profile& p : *list)
      if (!p.plane()) curved.push_back(p);
  std::vector<double> cuts = {z_low, z_high};
  const auto add_cut = [&](double z) {
    if (z > z_low && z < z_high) cuts.push_back(z);
  };
  for (const std::vector<Profile>* list : {&rev_profiles, static_cast<const std::vector<Profile>*>(&other_profiles)})
    for (const Profile& p : *list) {
      add_cut(p.z0);
      add_cut(p.z1);
    }
  Profile bound;
  bound.kind = ProfileKind::Line;
  bound.z0 = z_low;
  bound.z1 = z_high;
  bound.r0 = bound.r1 = rev_radius;
  curved.push_back(bound);
  for (std::size_t i = 0; i < curved.size(); ++i)
    for (std::size_t j = i + 1; j < curved.size(); ++j) {
      const Profile& p = curved[i];
      const Profile& q = curved[j];
      const double lo = std::max(p.z0, q.z0), hi = std::min(p.z1, q.z1);
      if (hi <= lo) continue;
      const auto f = [&](double z) { return p.radius_at(z) - q.radius_at(z); };
      const bool linear = p.linear() && q.linear();
      const int steps = linear ? 1 : 64;  // a sphere or a torus: sign changes sampled, then bisected
      for (int k = 0; k < steps; ++k) {
        double a = lo + (hi - lo) * k / steps, b = lo + (hi - lo) * (k + 1) / steps;
        double fa = f(a), fb = f(b);
        if (!((fa < 0 && fb > 0) || (fa > 0 && fb < 0))) continue;
        if (linear) {
          add_cut(a + (b - a) * fa / (fa - fb));
          continue;
        }
        for (int it = 0; it < 100 && b - a > 1e-13 * (1 + std::abs(a)); ++it) {
          const double m = 0.5 * (a + b), fm = f(m);
          if ((fm < 0) == (fa < 0)) a = m, fa = fm;
          else b = m;
        }
        add_cut(0.5 * (a + b));
      }
    }
  curved.pop_back();
  std::sort(cuts.begin(), cuts.end());

  std::unique_ptr<BRepClass3d_SolidClassifier> classifier;
  const double shortest = 1e-9 * (z_high - z_low);
  const double gauss = 1 / std::sqrt(3.0);
  double volume = 0;
  for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
    const double z0 = cuts[k], z1 = cuts[k + 1];
    if (z1 - z0 <= shortest) continue;  // nothing to integrate
    const double middle = 0.5 * (z0 + z1);
    // Ring areas are quadratic in z over cylinders, cones and spheres (two
    // Gauss points exact); over a torus they are not: 32 sub-slices then.
    bool polynomial = true;
    for (const auto* list : {&rev_profiles, static_cast<const std::vector<Profile>*>(&other_profiles)})
      for (const Profile& p : *list)
        if ((p.kind == ProfileKind::TorusOuter || p.kind == ProfileKind::TorusInner) && p.z0 < middle && middle < p.z1)
          polynomial = false;
    const int slices = polynomial ? 1 : 32;
    std::vector<double> points;
    for (int k = 0; k < slices; ++k) {
      const double a = z0 + (z1 - z0) * k / slices, b = z0 + (z1 - z0) * (k + 1) / slices;
      points.push_back(0.5 * (a + b) - 0.5 * (b - a) * gauss);
      points.push_back(0.5 * (a + b) + 0.5 * (b - a) * gauss);
    }
    const double half = 0.5 * (z1 - z0) / slices;
    int other_everywhere = -1;  // the other body's state where none of its faces is in reach
    for (const double z : points) {
      std::vector<Radius> rev_radii, other_radii;
      std::vector<double> bounds = {0, rev_radius};
      for (const Profile& p : rev_profiles)
        if (!p.plane() && p.z0 < z && z < p.z1) {
          rev_radii.push_back({p.radius_at(z), p.convex});
          bounds.push_back(std::min(rev_radius, rev_radii.back().r));
        }
      for (const Profile& p : other_profiles)
        if (!p.plane() && p.z0 < z && z < p.z1) {
          const double r = p.radius_at(z);
          if (r > reach_at(reach, z)) continue;
          other_radii.push_back({r, p.convex});
          if (r < rev_radius) bounds.push_back(r);
        }
      if (other_radii.empty() && other_everywhere < 0) {
        // Off the other body's box (a shaft's ends beyond its housing): out,
        // without a classifier (built from the whole solid: B-spline faces).
        const gp_Pnt on_axis = origin.Translated(gp_Vec(direction) * middle);
        if (outside_box(other.box, on_axis, tol.linear)) {
          other_everywhere = 0;
        } else {
          if (!classifier) classifier = std::make_unique<BRepClass3d_SolidClassifier>(other_shape);
          classifier->Perform(on_axis, tol.linear);
          const TopAbs_State state = classifier->State();
          if (state != TopAbs_IN && state != TopAbs_OUT) return std::nullopt;
          other_everywhere = state == TopAbs_IN ? 1 : 0;
        }
      }
      std::sort(bounds.begin(), bounds.end());
      double area = 0;
      for (std::size_t i = 0; i + 1 < bounds.size(); ++i) {
        const double lo = bounds[i], hi = bounds[i + 1];
        if (hi <= lo) continue;
        const double r = 0.5 * (lo + hi);
        if (material_at(rev_radii, r) != 1) continue;
        const int other_state = other_radii.empty() ? other_everywhere : material_at(other_radii, r);
        if (other_state == 1) area += kPi * (hi * hi - lo * lo);
      }
      volume += half * area;  // two-point Gauss: weights 1 on [-1, 1]
    }
  }
  return volume;
}

}  // namespace

std::optional<double> coaxial_common_volume(const BodyPartitions& a, const TopoDS_Shape& shape_a,
                                            const BodyPartitions& b, const TopoDS_Shape& shape_b,
                                            const gp_Ax1& axis, const Tolerances& tol) {
  const gp_Pnt& origin = axis.Location();
  const gp_Dir& direction = axis.Direction();
  std::vector<Profile> profiles;
  if (all_profiles(a, origin, direction, tol, profiles))
    if (const auto volume = common_of_revolution(profiles, b, shape_b, origin, direction, tol)) return volume;
  profiles.clear();
  if (all_profiles(b, origin, direction, tol, profiles))
    if (const auto volume = common_of_revolution(profiles, a, shape_a, origin, direction, tol)) return volume;
  return std::nullopt;
}

}  // namespace contactcore
