#include "contacts/separation.h"
#include "contactcore/common/angles.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <BRepAdaptor_Surface.hxx>
#include <BRepTools.hxx>
#include <TopExp.hxx>
#include <gp_Torus.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopTools_ListOfShape.hxx>
#include <gp_Vec.hxx>

namespace contactcore {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kParallel = 1e-9;  // |sin| below this: directions parallel

// Cylindrical coordinates of a point about the axis.
struct Cyl {
  double r, z;
};
Cyl cylindrical(const gp_Pnt& p, const SeparationAxis& axis) {
  const gp_Vec v(axis.origin, p);
  const gp_Vec d(axis.direction);
  const double z = v.Dot(d);
  return {(v - d * z).Magnitude(), z};
}

double line_distance(const gp_Pnt& point, const SeparationAxis& axis) { return cylindrical(point, axis).r; }

// The box's corners bound r from above and z both ways (distance to a line
// is convex, z linear: extremes at corners); r from below by the distance of
// its centre less its half diagonal.
Shadow box_shadow(const Bnd_Box& box, const SeparationAxis& axis) {
  Shadow s{0, 0, kInf, -kInf};
  if (box.IsVoid()) return {0, kInf, -kInf, kInf};
  double x[2], y[2], z[2];
  box.Get(x[0], y[0], z[0], x[1], y[1], z[1]);
  const gp_Pnt centre(0.5 * (x[0] + x[1]), 0.5 * (y[0] + y[1]), 0.5 * (z[0] + z[1]));
  const double half_diagonal = 0.5 * std::sqrt(box.SquareExtent());
  s.r0 = std::max(0.0, cylindrical(centre, axis).r - half_diagonal);
  for (double cx : x)
    for (double cy : y)
      for (double cz : z) {
        const Cyl c = cylindrical(gp_Pnt(cx, cy, cz), axis);
        s.r1 = std::max(s.r1, c.r);
        s.z0 = std::min(s.z0, c.z);
        s.z1 = std::max(s.z1, c.z);
      }
  return s;
}

// z of a point at axial position s along a partition's own axis.
double axial_z(const Partition& p, double s, const SeparationAxis& axis) {
  return gp_Vec(axis.origin, p.params.location).Dot(gp_Vec(axis.direction)) +
         s * gp_Vec(p.params.axis).Dot(gp_Vec(axis.direction));
}

double point_segment_distance(double px, double py, const Point2& a, const Point2& b) {
  const double dx = b.x - a.x, dy = b.y - a.y;
  const double length2 = dx * dx + dy * dy;
  double t = length2 > 0 ? ((px - a.x) * dx + (py - a.y) * dy) / length2 : 0;
  t = std::clamp(t, 0.0, 1.0);
  return std::hypot(px - (a.x + t * dx), py - (a.y + t * dy));
}

// Even-odd over every loop: outer loops and holes alike.
bool inside_outline(double px, double py, const std::vector<Polygon2>& loops) {
  bool inside = false;
  for (const Polygon2& loop : loops) {
    for (std::size_t i = 0, j = loop.size() - 1; i < loop.size(); j = i++) {
      const Point2& a = loop[i];
      const Point2& b = loop[j];
      if ((a.y > py) != (b.y > py) && px < (b.x - a.x) * (py - a.y) / (b.y - a.y) + a.x) inside = !inside;
    }
  }
  return inside;
}

Shadow plane_shadow(const Partition& p, const std::vector<Polygon2>& outline, const SeparationAxis& axis,
                    double linear) {
  if (outline.empty()) return box_shadow(p.box, axis);
  const gp_Vec normal(p.params.axis), x_dir(p.extent.ref_dir);
  const gp_Vec y_dir = normal.Crossed(x_dir);
  const gp_Vec d(axis.direction);
  // Chords lie within the chordal tolerance (the linear one) of their curve.
  const double slack = 2 * linear;
  Shadow s{0, 0, kInf, -kInf};
  for (const Polygon2& loop : outline)
    for (const Point2& q : loop) {
      const Cyl c = cylindrical(p.params.location.Translated(x_dir * q.x + y_dir * q.y), axis);
      s.r1 = std::max(s.r1, c.r);
      s.z0 = std::min(s.z0, c.z);
      s.z1 = std::max(s.z1, c.z);
    }
  s.r1 += slack, s.z0 -= slack, s.z1 += slack;
  const double across = std::abs(normal.Dot(d));
  if (across > 1 - kParallel) {
    // Across the axis: r is the distance from the axis' foot in the plane.
    const gp_Vec to_axis(p.params.location, axis.origin);
    const gp_Vec in_plane = to_axis - normal * to_axis.Dot(normal);
    const double fx = in_plane.Dot(x_dir), fy = in_plane.Dot(y_dir);
    if (!inside_outline(fx, fy, outline)) {
      double nearest = kInf;
      for (const Polygon2& loop : outline)
        for (std::size_t i = 0; i < loop.size(); ++i)
          nearest = std::min(nearest, point_segment_distance(fx, fy, loop[i], loop[(i + 1) % loop.size()]));
      s.r0 = std::max(0.0, nearest - slack);
    }
  } else if (across < kParallel) {
    // Along the axis: r = hypot(distance of the plane, offset t across the axis).
    const gp_Vec t_dir = normal.Crossed(d);
    const double h = std::abs(gp_Vec(axis.origin, p.params.location).Dot(normal));
    double t0 = kInf, t1 = -kInf;
    for (const Polygon2& loop : outline)
      for (const Point2& q : loop) {
        const double t = gp_Vec(axis.origin, p.params.location.Translated(x_dir * q.x + y_dir * q.y)).Dot(t_dir);
        t0 = std::min(t0, t), t1 = std::max(t1, t);
      }
    t0 -= slack, t1 += slack;
    const double t_min = (t0 <= 0 && t1 >= 0) ? 0 : std::min(std::abs(t0), std::abs(t1));
    s.r0 = std::hypot(h, t_min) - slack;
    s.r0 = std::max(0.0, s.r0);
  }
  return s;
}

// A cylinder whose axis is not parallel to the line: exact when the two are
// perpendicular (a cross hole); otherwise its axis segment's distance less
// the radius.
Shadow crossing_cylinder_shadow(const Partition& p, const SeparationAxis& axis, double linear) {
  const gp_Vec d(axis.direction), a(p.params.axis);
  const gp_Vec c(axis.origin, p.params.location);
  const double s0 = p.extent.axial_min, s1 = p.extent.axial_max, rho = p.params.radius;
  const double along = a.Dot(d);
  Shadow out = box_shadow(p.box, axis);
  // z: the axis segment's, widened by the circle's reach along d.
  const double reach = rho * std::sqrt(std::max(0.0, 1 - along * along));
  const double za = c.Dot(d) + s0 * along, zb = c.Dot(d) + s1 * along;
  out.z0 = std::max(out.z0, std::min(za, zb) - reach - linear);
  out.z1 = std::min(out.z1, std::max(za, zb) + reach + linear);
  const gp_Vec w0 = c - d * c.Dot(d);
  if (std::abs(along) < kParallel) {
    // In the plane across d: r^2 = (alpha + s)^2 + (beta + rho sin t)^2.
    const gp_Vec v = a.Crossed(d);
    const double alpha = w0.Dot(a), beta = w0.Dot(v);
    const double u0 = alpha + s0, u1 = alpha + s1;
    const double u_min = (u0 <= 0 && u1 >= 0) ? 0 : std::min(std::abs(u0), std::abs(u1));
    const double u_max = std::max(std::abs(u0), std::abs(u1));
    out.r0 = std::max(0.0, std::hypot(u_min, std::max(0.0, std::abs(beta) - rho)) - linear);
    out.r1 = std::min(out.r1, std::hypot(u_max, std::abs(beta) + rho) + linear);
    // d(r^2)/du = 2u: no minimum inside unless u = 0 is in range.
    out.r0_on_edges = u_min > linear;
    return out;
  }
  // Distance to the line is 1-Lipschitz: the axis segment's nearest point less rho.
  const gp_Vec w1 = a - d * along;
  const double s_star = std::clamp(-w0.Dot(w1) / w1.SquareMagnitude(), s0, s1);
  out.r0 = std::max(out.r0, (w0 + w1 * s_star).Magnitude() - rho - linear);
  return out;
}

// Extremes of cos (or sin, shift = pi/2) over [v0, v1].
void trig_range(double v0, double v1, double shift, double& low, double& high) {
  low = std::min(std::cos(v0 - shift), std::cos(v1 - shift));
  high = std::max(std::cos(v0 - shift), std::cos(v1 - shift));
  if (v1 - v0 >= 2 * kPi) {
    low = -1, high = 1;
    return;
  }
  for (int k = -4; k <= 4; ++k) {
    const double at = shift + k * kPi;  // cos(v - shift) is +-1 there
    if (at > v0 && at < v1) (k % 2 == 0 ? high : low) = (k % 2 == 0 ? 1.0 : -1.0);
  }
}

// A coaxial torus partition of native toroidal faces: the part of the tube
// its faces cover (v range: r = R + rho cos v, z = zc + rho sin v), within `whole`.
Shadow torus_tube_shadow(const Partition& p, const BodyPartitions& body, const SeparationAxis& axis,
                         const Shadow& whole, double linear) {
  Shadow s{kInf, -kInf, kInf, -kInf};
  const double zc = gp_Vec(axis.origin, p.params.location).Dot(gp_Vec(axis.direction));
  for (int index : p.faces) {
    if (index < 1 || index > static_cast<int>(body.faces.size())) return whole;
    const FaceInfo& info = body.faces[index - 1];
    if (info.recognised) return whole;
    BRepAdaptor_Surface surface(info.face, Standard_False);
    if (surface.GetType() != GeomAbs_Torus) return whole;
    const gp_Torus torus = surface.Torus();
    const double sign = gp_Vec(torus.Axis().Direction()).Dot(gp_Vec(axis.direction)) > 0 ? 1 : -1;
    double u0, u1, v0, v1;
    BRepTools::UVBounds(info.face, u0, u1, v0, v1);
    double c_low, c_high, s_low, s_high;
    trig_range(v0, v1, 0, c_low, c_high);
    trig_range(v0, v1, kPi / 2, s_low, s_high);
    const double rho = torus.MinorRadius(), major = torus.MajorRadius();
    s.r0 = std::min(s.r0, major + rho * c_low);
    s.r1 = std::max(s.r1, major + rho * c_high);
    const double za = zc + sign * rho * s_low, zb = zc + sign * rho * s_high;
    s.z0 = std::min(s.z0, std::min(za, zb));
    s.z1 = std::max(s.z1, std::max(za, zb));
  }
  // UV bounds are those of the pcurves: widen by the tolerance.
  return {std::max({0.0, whole.r0, s.r0 - 2 * linear}), std::min(whole.r1, s.r1 + 2 * linear),
          std::max(whole.z0, s.z0 - 2 * linear), std::min(whole.z1, s.z1 + 2 * linear)};
}

// Where a partition's whole surface (its full axial range and turn) lies.
Shadow surface_shadow(const Partition& p, const SeparationAxis& axis, double linear, const BodyPartitions* body) {
  const SurfaceParams& sp = p.params;
  const bool parallel = gp_Vec(sp.axis).Crossed(gp_Vec(axis.direction)).Magnitude() < kParallel;
  const double offset = line_distance(sp.location, axis);
  const double z_a = axial_z(p, p.extent.axial_min, axis), z_b = axial_z(p, p.extent.axial_max, axis);
  const double z0 = std::min(z_a, z_b) - linear, z1 = std::max(z_a, z_b) + linear;
  switch (sp.kind) {
    case SurfaceKind::Cylinder:
      if (!parallel) return crossing_cylinder_shadow(p, axis, linear);
      if (offset <= linear) return {sp.radius - linear, sp.radius + linear, z0, z1};
      // A circle of radius R seen from a point at distance D from its centre.
      return {std::max(0.0, std::abs(offset - sp.radius) - linear), offset + sp.radius + linear, z0, z1};
    case SurfaceKind::Cone: {
      if (!parallel) break;
      const double t = std::tan(sp.half_angle);
      const double ra = std::abs(p.extent.axial_min) * t, rb = std::abs(p.extent.axial_max) * t;
      const bool through_apex = p.extent.axial_min < 0 && p.extent.axial_max > 0;
      const double low = through_apex ? 0.0 : std::min(ra, rb), high = std::max(ra, rb);
      if (offset <= linear) return {std::max(0.0, low - linear), high + linear, z0, z1};
      return {std::max({0.0, offset - high - linear, low - offset - linear}), offset + high + linear, z0, z1};
    }
    case SurfaceKind::Torus: {
      if (!parallel || offset > linear) break;
      const double zc = gp_Vec(axis.origin, sp.location).Dot(gp_Vec(axis.direction));
      const double reach = sp.minor_radius + linear;
      Shadow whole{std::max(0.0, sp.radius - reach), sp.radius + reach, zc - reach, zc + reach};
      if (body) return torus_tube_shadow(p, *body, axis, whole, linear);
      return whole;
    }
    case SurfaceKind::Sphere: {
      if (offset > linear) break;
      const double zc = gp_Vec(axis.origin, sp.location).Dot(gp_Vec(axis.direction));
      Shadow whole{0, sp.radius + linear, zc - sp.radius - linear, zc + sp.radius + linear};
      if (!body) return whole;
      // The faces' own range along the line (a cap spans a fraction of the
      // diameter: a domed end), in any frame on it (sphere faces are
      // re-measured about the line).
      double low = kInf, high = -kInf;
      const gp_Dir ref_dir = gp_Ax2(sp.location, axis.direction).XDirection();
      for (int index : p.faces) {
        if (index < 1 || index > static_cast<int>(body->faces.size())) return whole;
        const Extent e = revolution_extent_in(body->faces[index - 1], sp.location, axis.direction, ref_dir, linear);
        if (!(e.axial_min <= e.axial_max)) return whole;
        low = std::min(low, e.axial_min);
        high = std::max(high, e.axial_max);
      }
      if (p.faces.empty()) return whole;
      whole.z0 = std::max(whole.z0, zc + low - 2 * linear);
      whole.z1 = std::min(whole.z1, zc + high + 2 * linear);
      return whole;
    }
    default: break;
  }
  return box_shadow(p.box, axis);
}

// The surface's shadow within the partition's box's: both hold the partition,
// so their intersection does too. The box cuts what the surface alone cannot
// see: a domed end (a sphere of radius 29 whose cap spans 10 mm of the axis,
// R08's PRT0001) reaches 58 mm along it as a whole sphere, past the plane the
// part rests on; a torus or cone face covering part of its turn.
Shadow revolution_shadow(const Partition& p, const SeparationAxis& axis, double linear,
                         const BodyPartitions* body = nullptr) {
  Shadow s = surface_shadow(p, axis, linear, body);
  const Shadow box = box_shadow(p.box, axis);
  s.r0 = std::max(s.r0, box.r0);
  s.r1 = std::min(s.r1, box.r1);
  s.z0 = std::max(s.z0, box.z0);
  s.z1 = std::min(s.z1, box.z1);
  return s;
}

// A curve r = f(z), monotone in z, with every shadow of `inner` on its axis
// side and every shadow of `outer` beyond it: a shaft with a shoulder in a
// bearing, a screw whose head sits on a cover. Sound because the side of
// each body away from the curve reaches infinity along r or along z (f
// monotone), so each body's projection, bounded by its faces' shadows, stays
// on its own side: the two meet at most on the curve (within the margin).
bool monotone_split(const std::vector<Shadow>& inner, const std::vector<Shadow>& outer, double linear) {
  // Both sides' shadows are widened by up to twice the tolerance: touching
  // bodies may seem to overlap by that much on each side.
  const double margin = 5 * linear;
  bool rising = true, falling = true;  // f non-decreasing, non-increasing
  for (const Shadow& a : inner) {
    for (const Shadow& b : outer) {
      if (a.r1 <= b.r0 + margin) continue;
      // f >= a.r1 from a.z0 upward (rising) and f <= b.r0 up to b.z1.
      if (a.z0 < b.z1 - margin) rising = false;
      if (a.z1 > b.z0 + margin) falling = false;
      if (!rising && !falling) return false;
    }
  }
  return true;
}

bool same_line(const SeparationAxis& l, const SeparationAxis& r, const Tolerances& tol) {
  if (!l.direction.IsParallel(r.direction, tol.angular)) return false;
  return line_distance(r.origin, l) <= tol.linear;
}

void add_axes(const BodyPartitions& body, const Tolerances& tol, std::vector<SeparationAxis>& axes,
              std::vector<gp_Dir>& normals) {
  for (const Partition& p : body.partitions) {
    switch (p.params.kind) {
      case SurfaceKind::Cylinder:
      case SurfaceKind::Cone:
      case SurfaceKind::Torus: {
        const SeparationAxis axis{p.params.location, p.params.axis};
        if (std::none_of(axes.begin(), axes.end(), [&](const SeparationAxis& a) { return same_line(a, axis, tol); }))
          axes.push_back(axis);
        break;
      }
      case SurfaceKind::Plane:
        if (std::none_of(normals.begin(), normals.end(),
                         [&](const gp_Dir& n) { return n.IsParallel(p.params.axis, tol.angular); }))
          normals.push_back(p.params.axis);
        break;
      default: break;
    }
  }
}

}  // namespace

std::vector<std::vector<int>> partition_neighbours(const BodyPartitions& body) {
  TopTools_IndexedMapOfShape faces;
  for (const FaceInfo& face : body.faces) faces.Add(face.face);
  std::vector<int> partition_of(faces.Extent() + 1, -1);
  for (const Partition& p : body.partitions)
    for (int f : p.faces)
      if (f >= 1 && f <= faces.Extent()) partition_of[f] = p.id;
  TopTools_IndexedDataMapOfShapeListOfShape edge_faces;
  for (const FaceInfo& face : body.faces) TopExp::MapShapesAndAncestors(face.face, TopAbs_EDGE, TopAbs_FACE, edge_faces);
  std::vector<std::vector<int>> neighbours(body.partitions.size());
  for (int e = 1; e <= edge_faces.Extent(); ++e) {
    std::vector<int> around;
    for (const TopoDS_Shape& face : edge_faces(e)) {
      const int index = faces.FindIndex(face);
      if (index > 0 && partition_of[index] >= 0) around.push_back(partition_of[index]);
    }
    for (int p : around)
      for (int q : around)
        if (p != q && std::find(neighbours[p].begin(), neighbours[p].end(), q) == neighbours[p].end())
          neighbours[p].push_back(q);
  }
  return neighbours;
}

std::vector<Shadow> partition_shadows(const BodyPartitions& body, const BodyPartitions& outlines,
                                      const SeparationAxis& axis, double linear,
                                      const std::vector<std::vector<int>>& neighbours) {
  std::vector<Shadow> shadows;
  shadows.reserve(body.partitions.size());
  for (std::size_t k = 0; k < body.partitions.size(); ++k) {
    const Partition& p = body.partitions[k];
    if (p.params.kind == SurfaceKind::Plane) {
      const std::vector<Polygon2>& outline =
          k < outlines.partitions.size() ? outlines.partitions[k].extent.outline : p.extent.outline;
      shadows.push_back(plane_shadow(p, outline, axis, linear));
    } else {
      shadows.push_back(revolution_shadow(p, axis, linear, &body));
    }
  }
  if (neighbours.size() == shadows.size()) {
    // From the untightened values, so no partition leans on itself.
    const std::vector<Shadow> plain = shadows;
    for (std::size_t k = 0; k < shadows.size(); ++k) {
      if (!shadows[k].r0_on_edges || neighbours[k].empty()) continue;
      double edge_r0 = kInf;
      for (int q : neighbours[k]) edge_r0 = std::min(edge_r0, plain[q].r0);
      shadows[k].r0 = std::max(shadows[k].r0, edge_r0);
    }
  }
  return shadows;
}

bool provably_apart(const BodyPartitions& a, const BodyPartitions& a_outlines, const BodyPartitions& b,
                    const BodyPartitions& b_outlines, const Tolerances& tol) {
  std::vector<SeparationAxis> axes;
  std::vector<gp_Dir> normals;
  add_axes(a, tol, axes, normals);
  const std::size_t from_a = axes.size();
  add_axes(b, tol, axes, normals);
  // Axes both bodies turn about first (a shaft and its bore's): they are the
  // ones that usually keep the two apart.
  std::vector<char> shared(axes.size(), 0);
  for (std::size_t i = 0; i < from_a; ++i)
    for (const Partition& p : b.partitions)
      if ((p.params.kind == SurfaceKind::Cylinder || p.params.kind == SurfaceKind::Cone ||
           p.params.kind == SurfaceKind::Torus) &&
          same_line(axes[i], {p.params.location, p.params.axis}, tol)) {
        shared[i] = 1;
        break;
      }
  std::vector<SeparationAxis> ordered;
  for (int pass : {1, 0})
    for (std::size_t i = 0; i < axes.size(); ++i)
      if (shared[i] == pass) ordered.push_back(axes[i]);
  axes.swap(ordered);
  // Along a plane normal only z matters (a separating plane); any origin.
  for (const gp_Dir& n : normals) axes.push_back({gp_Pnt(0, 0, 0), n});
  // Neighbours only for bodies that need them (cross holes), once.
  std::vector<std::vector<int>> a_neighbours, b_neighbours;
  bool a_looked = false, b_looked = false;
  const auto neighbours_if_needed = [](const std::vector<Shadow>& shadows, const BodyPartitions& body,
                                       std::vector<std::vector<int>>& neighbours, bool& looked) {
    if (looked || std::none_of(shadows.begin(), shadows.end(), [](const Shadow& s) { return s.r0_on_edges; })) return false;
    neighbours = partition_neighbours(body);
    looked = true;
    return true;
  };
  for (const SeparationAxis& axis : axes) {
    std::vector<Shadow> sa = partition_shadows(a, a_outlines, axis, tol.linear, a_neighbours);
    std::vector<Shadow> sb = partition_shadows(b, b_outlines, axis, tol.linear, b_neighbours);
    if (neighbours_if_needed(sa, a, a_neighbours, a_looked))
      sa = partition_shadows(a, a_outlines, axis, tol.linear, a_neighbours);
    if (neighbours_if_needed(sb, b, b_neighbours, b_looked))
      sb = partition_shadows(b, b_outlines, axis, tol.linear, b_neighbours);
    if (monotone_split(sa, sb, tol.linear) || monotone_split(sb, sa, tol.linear)) return true;
  }
  return false;
}

}  // namespace contactcore
