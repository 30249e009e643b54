// Point, line and circle contacts: the analytic condition of tangency
// between two partitions' surfaces (a distance equal to a radius or a sum or
// difference of radii, within the linear tolerance; an angle within the
// angular one), then the point, the points of the line or the circle's
// samples tested on the faces of both partitions.
#include "contacts/higher_pairs.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include <gp_Ax2.hxx>
#include <gp_Vec.hxx>

#include "contacts/common_area.h"

namespace contactcore {

const char* to_string(HigherPairType type) {
  switch (type) {
    case HigherPairType::SphereOnPlane: return "sphere_on_plane";
    case HigherPairType::SphereOnCylinder: return "sphere_on_cylinder";
    case HigherPairType::CylinderOnPlane: return "cylinder_on_plane";
    case HigherPairType::CylinderOnCylinder: return "cylinder_on_cylinder";
    case HigherPairType::ConeOnPlane: return "cone_on_plane";
    case HigherPairType::TorusOnPlane: return "torus_on_plane";
    case HigherPairType::TorusOnCylinder: return "torus_on_cylinder";
    case HigherPairType::ConeOnCylinder: return "cone_on_cylinder";
  }
  return "?";
}

const char* to_string(HigherPairKind kind) {
  switch (kind) {
    case HigherPairKind::Point: return "point";
    case HigherPairKind::Line: return "line";
    case HigherPairKind::Circle: return "circle";
  }
  return "?";
}

namespace {

// The faces of one partition, probed lazily (a probe projects on the surface).
class PartitionProbe {
 public:
  PartitionProbe(const BodyPartitions& body, const Partition& partition) : body_(body), partition_(partition) {
    probes_.resize(partition.faces.size());
  }
  // The 1-based index of a face holding p, or 0.
  int face_at(const gp_Pnt& p, double tol) {
    for (size_t k = 0; k < partition_.faces.size(); ++k) {
      const FaceInfo& face = body_.faces[partition_.faces[k] - 1];
      if (face.box.IsOut(p)) {
        Bnd_Box grown = face.box;
        grown.Enlarge(tol);
        if (grown.IsOut(p)) continue;
      }
      if (!probes_[k]) probes_[k] = std::make_unique<FaceProbe>(face);
      if (probes_[k]->contains(p, tol)) return partition_.faces[k];
    }
    return 0;
  }

 private:
  const BodyPartitions& body_;
  const Partition& partition_;
  std::vector<std::unique_ptr<FaceProbe>> probes_;
};

bool is_ball(const Partition& p) { return p.params.kind == SurfaceKind::Sphere && p.side == MaterialSide::Convex; }
bool is_cylinder(const Partition& p) {
  return p.params.kind == SurfaceKind::Cylinder && (p.side == MaterialSide::Convex || p.side == MaterialSide::Concave);
}
bool is_plane(const Partition& p) { return p.params.kind == SurfaceKind::Plane; }
bool is_convex_cone(const Partition& p) { return p.params.kind == SurfaceKind::Cone && p.side == MaterialSide::Convex; }
bool is_ring(const Partition& p) {  // the outside of a torus tube: a ring, an O-ring, a rounded rim
  return p.params.kind == SurfaceKind::Torus && p.side == MaterialSide::Convex && p.params.minor_radius > 0 &&
         p.params.radius > p.params.minor_radius;
}
bool is_bore(const Partition& p) { return p.params.kind == SurfaceKind::Cylinder && p.side == MaterialSide::Concave; }
bool is_shaft(const Partition& p) { return p.params.kind == SurfaceKind::Cylinder && p.side == MaterialSide::Convex; }

// Unit vector from the axis line (o, d) towards p, and p's distance to it.
double radial_from(const gp_Pnt& p, const gp_Pnt& o, const gp_Dir& d, gp_Vec& radial) {
  gp_Vec v(o, p);
  v -= gp_Vec(d) * v.Dot(gp_Vec(d));
  const double distance = v.Magnitude();
  if (distance > 0) radial = v / distance;
  return distance;
}

// One candidate: s the ball or cylinder (side `first` of the pair when
// first_is_s), t the plane or cylinder it touches.
struct Side {
  int body;
  const BodyPartitions* parts;
  const Partition* partition;
};

void record(HigherPair pair, const Side& s, const Side& t, const std::vector<int>& faces_s,
            const std::vector<int>& faces_t, const gp_Vec& normal_out_of_s, std::vector<HigherPair>& out) {
  const bool s_first = s.body < t.body;
  pair.body_a = s_first ? s.body : t.body;
  pair.body_b = s_first ? t.body : s.body;
  pair.partition_a = s_first ? s.partition->id : t.partition->id;
  pair.partition_b = s_first ? t.partition->id : s.partition->id;
  for (int f : faces_s)
    if (f) (s_first ? pair.faces_a : pair.faces_b).push_back(f);
  for (int f : faces_t)
    if (f) (s_first ? pair.faces_b : pair.faces_a).push_back(f);
  pair.normal = gp_Dir(s_first ? normal_out_of_s : -normal_out_of_s);
  out.push_back(std::move(pair));
}

void record(HigherPair pair, const Side& s, const Side& t, int face_s, int face_t, const gp_Vec& normal_out_of_s,
            std::vector<HigherPair>& out) {
  record(std::move(pair), s, t, std::vector<int>{face_s}, std::vector<int>{face_t}, normal_out_of_s, out);
}

// A point contact at p (tested on the faces of both), normal out of s.
void point_contact(HigherPairType type, const gp_Pnt& p, const gp_Vec& out_of_s, const Side& s, const Side& t,
                   const Tolerances& tol, std::vector<HigherPair>& out) {
  PartitionProbe probe_s(*s.parts, *s.partition), probe_t(*t.parts, *t.partition);
  const int face_s = probe_s.face_at(p, 3 * tol.linear);
  if (!face_s) return;
  const int face_t = probe_t.face_at(p, 3 * tol.linear);
  if (!face_t) return;
  HigherPair pair;
  pair.type = type;
  pair.kind = HigherPairKind::Point;
  pair.point = pair.start = pair.end = p;
  record(pair, s, t, face_s, face_t, out_of_s, out);
}

// A circle contact (centre, axis, radius): every one of its samples on faces
// of both partitions (s's at the circle; t's at the circle moved by
// `t_inset` along the axis: a bore's rim is probed just inside the bore).
// `normal_at(radial)` is the normal out of s at the circle's point in the
// direction `radial` from the centre.
template <class NormalAt>
void circle_contact(HigherPairType type, const gp_Pnt& centre, const gp_Dir& axis, double radius, double t_inset,
                    NormalAt normal_at, const Side& s, const Side& t, const Tolerances& tol,
                    std::vector<HigherPair>& out) {
  constexpr int kSamples = 24;
  PartitionProbe probe_s(*s.parts, *s.partition), probe_t(*t.parts, *t.partition);
  const gp_Dir u = gp_Ax2(centre, axis).XDirection();
  const gp_Dir v = axis.Crossed(u);
  std::vector<int> faces_s, faces_t;
  const auto keep = [](std::vector<int>& faces, int f) {
    if (std::find(faces.begin(), faces.end(), f) == faces.end()) faces.push_back(f);
  };
  for (int k = 0; k < kSamples; ++k) {
    const double theta = 2 * M_PI * k / kSamples;
    const gp_Vec radial = gp_Vec(u) * std::cos(theta) + gp_Vec(v) * std::sin(theta);
    const gp_Pnt p = centre.Translated(radial * radius);
    const int fs = probe_s.face_at(p, 3 * tol.linear);
    if (!fs) return;
    const int ft = probe_t.face_at(p.Translated(gp_Vec(axis) * t_inset), 3 * tol.linear);
    if (!ft) return;
    keep(faces_s, fs);
    keep(faces_t, ft);
  }
  HigherPair pair;
  pair.type = type;
  pair.kind = HigherPairKind::Circle;
  pair.point = centre;
  pair.axis = axis;
  pair.radius = radius;
  pair.length = 2 * M_PI * radius;
  pair.start = pair.end = centre.Translated(gp_Vec(u) * radius);
  record(pair, s, t, faces_s, faces_t, normal_at(gp_Vec(u)), out);
}

// A ball s touching t (a plane, or a cylinder of another radius) at one point.
void sphere_point(const Side& s, const Side& t, const Tolerances& tol, std::vector<HigherPair>& out) {
  const SurfaceParams& ball = s.partition->params;
  const SurfaceParams& other = t.partition->params;
  gp_Vec towards;  // from the ball's centre to the point of contact
  HigherPairType type;
  if (is_plane(*t.partition)) {
    const double height = gp_Vec(other.location, ball.location).Dot(gp_Vec(other.axis));
    if (std::abs(height - ball.radius) > tol.linear) return;  // on the plane's outer side only
    towards = -gp_Vec(other.axis);
    type = HigherPairType::SphereOnPlane;
  } else {
    gp_Vec radial;
    const double distance = radial_from(ball.location, other.location, other.axis, radial);
    if (t.partition->side == MaterialSide::Convex) {
      if (std::abs(distance - (ball.radius + other.radius)) > tol.linear) return;
      towards = -radial;
    } else {
      // Inside a larger bore, touching its wall (the same radius is LAF).
      if (other.radius - ball.radius <= tol.linear || distance <= tol.linear) return;
      if (std::abs(distance - (other.radius - ball.radius)) > tol.linear) return;
      towards = radial;
    }
    type = HigherPairType::SphereOnCylinder;
  }
  point_contact(type, ball.location.Translated(towards * ball.radius), towards, s, t, tol, out);
}

// A line contact: the runs of the line on_line + u axis, u in [t0, t1],
// lying on faces of both partitions (samples, their runs' ends bisected),
// from the first run's start to the last one's end; normal out of s.
void line_contact(HigherPairType type, const gp_Pnt& on_line, const gp_Dir& line_axis, double t0, double t1,
                  const gp_Vec& out_of_s, const Side& s, const Side& t, const Tolerances& tol,
                  std::vector<HigherPair>& out) {
  if (t1 - t0 <= tol.linear) return;
  PartitionProbe probe_s(*s.parts, *s.partition), probe_t(*t.parts, *t.partition);
  const double probe_tol = 3 * tol.linear;
  const gp_Vec axis(line_axis);
  int face_s = 0, face_t = 0;
  const auto on_both = [&](double u) {
    const gp_Pnt p = on_line.Translated(axis * u);
    const int fs = probe_s.face_at(p, probe_tol);
    if (!fs) return false;
    const int ft = probe_t.face_at(p, probe_tol);
    if (!ft) return false;
    face_s = fs, face_t = ft;
    return true;
  };
  // Samples, then the ends of the runs found refined by bisection.
  constexpr int kSamples = 64;
  const double step = (t1 - t0) / kSamples;
  double first = 0, last = 0, length = 0;
  bool found = false;
  int fs_kept = 0, ft_kept = 0;
  for (int k = 0; k <= kSamples;) {
    if (!on_both(t0 + step * k)) {
      ++k;
      continue;
    }
    fs_kept = face_s, ft_kept = face_t;
    const auto refine = [&](double inside, double outside) {
      for (int i = 0; i < 40 && std::abs(outside - inside) > 1e-9 * (1 + std::abs(inside)); ++i) {
        const double middle = 0.5 * (inside + outside);
        (on_both(middle) ? inside : outside) = middle;
      }
      return inside;
    };
    const double start = k == 0 ? t0 : refine(t0 + step * k, t0 + step * (k - 1));
    int j = k;
    while (j + 1 <= kSamples && on_both(t0 + step * (j + 1))) ++j;
    const double end = j == kSamples ? t1 : refine(t0 + step * j, t0 + step * (j + 1));
    if (!found) first = start;
    last = end;
    length += end - start;
    found = true;
    k = j + 1;
  }
  if (!found || length <= tol.linear) return;
  HigherPair pair;
  pair.type = type;
  pair.kind = HigherPairKind::Line;
  pair.start = on_line.Translated(axis * first);
  pair.end = on_line.Translated(axis * last);
  pair.point = on_line.Translated(axis * (0.5 * (first + last)));
  pair.length = length;
  record(pair, s, t, fs_kept, ft_kept, out_of_s, out);
}

// A cylinder s lying along t (a plane, or a parallel cylinder of another
// radius): the segment of their common line lying on faces of both.
void cylinder_line(const Side& s, const Side& t, const Tolerances& tol, std::vector<HigherPair>& out) {
  const SurfaceParams& cyl = s.partition->params;
  const SurfaceParams& other = t.partition->params;
  gp_Vec out_of_s;  // the normal out of s's material at the line
  gp_Pnt on_line;   // a point of the line
  double t0 = s.partition->extent.axial_min, t1 = s.partition->extent.axial_max;
  HigherPairType type;
  if (is_plane(*t.partition)) {
    if (s.partition->side != MaterialSide::Convex) return;
    if (std::abs(gp_Vec(cyl.axis).Dot(gp_Vec(other.axis))) > std::sin(tol.angular)) return;
    const double height = gp_Vec(other.location, cyl.location).Dot(gp_Vec(other.axis));
    if (std::abs(height - cyl.radius) > tol.linear) return;
    out_of_s = -gp_Vec(other.axis);
    on_line = cyl.location.Translated(out_of_s * cyl.radius);
    type = HigherPairType::CylinderOnPlane;
  } else {
    if (!cyl.axis.IsParallel(other.axis, tol.angular)) return;
    gp_Vec radial;  // from t's axis towards s's
    const double distance = radial_from(cyl.location, other.location, other.axis, radial);
    const bool s_convex = s.partition->side == MaterialSide::Convex;
    const bool t_convex = t.partition->side == MaterialSide::Convex;
    if (s_convex && t_convex) {
      if (std::abs(distance - (cyl.radius + other.radius)) > tol.linear) return;
      out_of_s = -radial;
    } else if (s_convex && !t_convex) {  // a shaft inside a larger bore, against its wall
      if (other.radius - cyl.radius <= tol.linear || distance <= tol.linear) return;
      if (std::abs(distance - (other.radius - cyl.radius)) > tol.linear) return;
      out_of_s = radial;
    } else {
      return;  // the pair is met again with the convex one as s
    }
    on_line = cyl.location.Translated(out_of_s * cyl.radius);
    // The other cylinder's axial range, on s's axis.
    const double shift = gp_Vec(cyl.location, other.location).Dot(gp_Vec(cyl.axis));
    const double sign = gp_Vec(other.axis).Dot(gp_Vec(cyl.axis)) > 0 ? 1.0 : -1.0;
    const double o0 = shift + sign * t.partition->extent.axial_min, o1 = shift + sign * t.partition->extent.axial_max;
    t0 = std::max(t0, std::min(o0, o1));
    t1 = std::min(t1, std::max(o0, o1));
    type = HigherPairType::CylinderOnCylinder;
  }
  line_contact(type, on_line, cyl.axis, t0, t1, out_of_s, s, t, tol, out);
}

// A cone s lying on a plane t along a generator: its apex (the surface's,
// on the face or not: a frustum) in the plane and its axis at 90 deg minus
// the half angle from the plane's normal, leaning away from it. The line
// runs from the apex along the generator over the cone's axial extent.
void cone_line(const Side& s, const Side& t, const Tolerances& tol, std::vector<HigherPair>& out) {
  const SurfaceParams& cone = s.partition->params;
  const SurfaceParams& plane = t.partition->params;
  const gp_Vec n(plane.axis), d(cone.axis);
  if (std::abs(gp_Vec(plane.location, cone.location).Dot(n)) > tol.linear) return;  // apex in the plane
  const double lean = std::acos(std::clamp(d.Dot(n), -1.0, 1.0));                // 0: the axis along n
  if (std::abs(lean - (M_PI / 2 - cone.half_angle)) > tol.angular) return;
  gp_Vec along = d - n * d.Dot(n);  // the generator in the plane, from the apex into the opening
  if (along.Magnitude() <= 1e-12) return;
  along.Normalize();
  // A point of the generator at distance u from the apex is at u cos(half
  // angle) along the axis: the cone's axial extent gives the line's.
  const double cos_a = std::cos(cone.half_angle);
  const double t0 = std::max(0.0, s.partition->extent.axial_min / cos_a);
  const double t1 = s.partition->extent.axial_max / cos_a;
  line_contact(HigherPairType::ConeOnPlane, cone.location, gp_Dir(along), t0, t1, -n, s, t, tol, out);
}

// A ring s (the outside of a torus tube) on a plane t: lying flat (axis along
// the normal), its tube's circle of centres at the minor radius above the
// plane touches along a circle of the major radius; tilted or standing (a
// rounded wheel), at the one lowest point: the tube's centre nearest the
// plane, C + R e (e the in-plane direction most against the normal), minus
// the minor radius along the normal.
void torus_on_plane(const Side& s, const Side& t, const Tolerances& tol, std::vector<HigherPair>& out) {
  const SurfaceParams& ring = s.partition->params;
  const SurfaceParams& plane = t.partition->params;
  const gp_Vec n(plane.axis), a(ring.axis);
  const double height = gp_Vec(plane.location, ring.location).Dot(n);
  gp_Vec across = n - a * n.Dot(a);  // the normal's part in the ring's equatorial plane
  const double tilt = across.Magnitude();
  if (tilt <= std::sin(tol.angular)) {
    if (std::abs(height - ring.minor_radius) > tol.linear) return;
    const gp_Pnt centre = ring.location.Translated(-n * ring.minor_radius);
    circle_contact(HigherPairType::TorusOnPlane, centre, plane.axis, ring.radius, 0.0,
                   [&](const gp_Vec&) { return -n; }, s, t, tol, out);
    return;
  }
  if (std::abs(height - ring.radius * tilt - ring.minor_radius) > tol.linear) return;
  const gp_Pnt p = ring.location.Translated(-across / tilt * ring.radius - n * ring.minor_radius);
  point_contact(HigherPairType::TorusOnPlane, p, -n, s, t, tol, out);
}

// A ring s against a cylinder t with a parallel axis: its outer equator
// (radius R + r) inside a bore or outside a shaft, or its inner equator
// (R - r) around a shaft. Coaxial: along the equator (a circle: an O-ring in
// its bore or on its shaft); axes apart: at the equator's point nearest or
// furthest from the cylinder's axis (a rounded wheel in a larger bore or
// against a roller).
void torus_on_cylinder(const Side& s, const Side& t, const Tolerances& tol, std::vector<HigherPair>& out) {
  const SurfaceParams& ring = s.partition->params;
  const SurfaceParams& cyl = t.partition->params;
  if (!ring.axis.IsParallel(cyl.axis, tol.angular)) return;
  gp_Vec radial;  // from the cylinder's axis towards the ring's centre
  const double offset = radial_from(ring.location, cyl.location, cyl.axis, radial);
  const double outer = ring.radius + ring.minor_radius, inner = ring.radius - ring.minor_radius;
  const bool coaxial = offset <= tol.linear;
  const gp_Dir axis = ring.axis;
  if (is_bore(*t.partition)) {  // the outer equator against the wall, from inside
    if (coaxial) {
      if (std::abs(cyl.radius - outer) > tol.linear) return;
      circle_contact(HigherPairType::TorusOnCylinder, ring.location, axis, outer, 0.0,
                     [](const gp_Vec& r) { return r; }, s, t, tol, out);
      return;
    }
    if (cyl.radius - outer <= tol.linear || std::abs(offset - (cyl.radius - outer)) > tol.linear) return;
    point_contact(HigherPairType::TorusOnCylinder, ring.location.Translated(radial * outer), radial, s, t, tol, out);
    return;
  }
  if (!is_shaft(*t.partition)) return;
  if (coaxial) {  // the inner equator on the shaft
    if (std::abs(cyl.radius - inner) > tol.linear) return;
    circle_contact(HigherPairType::TorusOnCylinder, ring.location, axis, inner, 0.0,
                   [](const gp_Vec& r) { return -r; }, s, t, tol, out);
    return;
  }
  if (std::abs(offset - (cyl.radius + outer)) <= tol.linear) {  // side by side
    point_contact(HigherPairType::TorusOnCylinder, ring.location.Translated(-radial * outer), -radial, s, t, tol, out);
    return;
  }
  if (inner - cyl.radius > tol.linear && std::abs(offset - (inner - cyl.radius)) <= tol.linear)  // the shaft in the ring's hole
    point_contact(HigherPairType::TorusOnCylinder, ring.location.Translated(-radial * inner), radial, s, t, tol, out);
}

// A cone s seated on the rim of a coaxial bore t (the taper of a valve or a
// pin on a hole's sharp edge; a cone's tip in a smaller hole): the cone
// narrows into the bore and its radius at the bore's mouth is the bore's.
// The contact is the rim circle, an edge of the bore's face: it is typed
// apart from the surface contacts (the paper's CJU is cone in cone), its
// normals the cone's, the rim tested on the cone's face and just inside the
// bore on the bore's.
void cone_on_rim(const Side& s, const Side& t, const Tolerances& tol, std::vector<HigherPair>& out) {
  const SurfaceParams& cone = s.partition->params;
  const SurfaceParams& bore = t.partition->params;
  if (!cone.axis.IsParallel(bore.axis, tol.angular)) return;
  gp_Vec radial;
  if (radial_from(cone.location, bore.location, bore.axis, radial) > tol.linear) return;  // coaxial
  const gp_Vec d(cone.axis);
  // The bore's axial range in the cone's axial coordinate (from the apex):
  // its mouth is the end towards the cone's opening.
  const double shift = gp_Vec(cone.location, bore.location).Dot(d);
  const double sign = gp_Vec(bore.axis).Dot(d) > 0 ? 1.0 : -1.0;
  const double mouth = std::max(shift + sign * t.partition->extent.axial_min, shift + sign * t.partition->extent.axial_max);
  if (mouth <= tol.linear) return;
  if (std::abs(mouth * std::tan(cone.half_angle) - bore.radius) > tol.linear) return;
  // The cone crosses the rim (a seat), not ends on it (a chamfer's edge on
  // the rim: an edge on an edge).
  if (s.partition->extent.axial_min > mouth - tol.linear || s.partition->extent.axial_max < mouth + tol.linear) return;
  const double sin_a = std::sin(cone.half_angle), cos_a = std::cos(cone.half_angle);
  const gp_Pnt centre = cone.location.Translated(d * mouth);
  // Out of the cone's material (inside it): cos(a) radial - sin(a) axis.
  circle_contact(HigherPairType::ConeOnCylinder, centre, cone.axis, bore.radius, -3 * tol.linear,
                 [&](const gp_Vec& r) { return r * cos_a - d * sin_a; }, s, t, tol, out);
}

}  // namespace

std::vector<HigherPair> find_higher_pairs(int ia, const BodyPartitions& a, int ib, const BodyPartitions& b,
                                          const Tolerances& tol) {
  std::vector<HigherPair> out;
  // Every higher pair has a ball, a cylinder, a cone or a ring on one side:
  // pairs of plane-only bodies (the common case, a grid of blocks) end here.
  const auto rounded = [](const BodyPartitions& body) {
    return std::any_of(body.partitions.begin(), body.partitions.end(), [](const Partition& p) {
      return is_ball(p) || is_cylinder(p) || is_convex_cone(p) || is_ring(p);
    });
  };
  if (!rounded(a) && !rounded(b)) return out;
  for (const Partition& pa : a.partitions) {
    for (const Partition& pb : b.partitions) {
      if (!boxes_meet(pa.box, pb.box, tol.linear)) continue;
      const Side sa{ia, &a, &pa}, sb{ib, &b, &pb};
      // The ball, cylinder, cone or ring first: each unordered pair of surfaces once.
      if (is_ball(pa) && (is_plane(pb) || is_cylinder(pb))) sphere_point(sa, sb, tol, out);
      else if (is_ball(pb) && (is_plane(pa) || is_cylinder(pa))) sphere_point(sb, sa, tol, out);
      else if (is_cylinder(pa) && is_plane(pb)) cylinder_line(sa, sb, tol, out);
      else if (is_cylinder(pb) && is_plane(pa)) cylinder_line(sb, sa, tol, out);
      else if (is_cylinder(pa) && is_cylinder(pb)) {
        if (pa.side == MaterialSide::Convex) cylinder_line(sa, sb, tol, out);
        else if (pb.side == MaterialSide::Convex) cylinder_line(sb, sa, tol, out);
      }
      else if (is_convex_cone(pa) && is_plane(pb)) cone_line(sa, sb, tol, out);
      else if (is_convex_cone(pb) && is_plane(pa)) cone_line(sb, sa, tol, out);
      else if (is_convex_cone(pa) && is_bore(pb)) cone_on_rim(sa, sb, tol, out);
      else if (is_convex_cone(pb) && is_bore(pa)) cone_on_rim(sb, sa, tol, out);
      else if (is_ring(pa) && is_plane(pb)) torus_on_plane(sa, sb, tol, out);
      else if (is_ring(pb) && is_plane(pa)) torus_on_plane(sb, sa, tol, out);
      else if (is_ring(pa) && is_cylinder(pb)) torus_on_cylinder(sa, sb, tol, out);
      else if (is_ring(pb) && is_cylinder(pa)) torus_on_cylinder(sb, sa, tol, out);
    }
  }
  return out;
}

}  // namespace contactcore
