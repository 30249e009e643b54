// Point and line contacts: the analytic condition of tangency between two
// partitions' surfaces (a distance equal to a radius or a sum or difference
// of radii, within the linear tolerance), then the point, or the points of
// the line, tested on the faces of both partitions.
#include "contacts/higher_pairs.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include <gp_Vec.hxx>

#include "contacts/common_area.h"

namespace contactcore {

const char* to_string(HigherPairType type) {
  switch (type) {
    case HigherPairType::SphereOnPlane: return "sphere_on_plane";
    case HigherPairType::SphereOnCylinder: return "sphere_on_cylinder";
    case HigherPairType::CylinderOnPlane: return "cylinder_on_plane";
    case HigherPairType::CylinderOnCylinder: return "cylinder_on_cylinder";
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

void record(HigherPair pair, const Side& s, const Side& t, int face_s, int face_t, const gp_Vec& normal_out_of_s,
            std::vector<HigherPair>& out) {
  const bool s_first = s.body < t.body;
  pair.body_a = s_first ? s.body : t.body;
  pair.body_b = s_first ? t.body : s.body;
  pair.partition_a = s_first ? s.partition->id : t.partition->id;
  pair.partition_b = s_first ? t.partition->id : s.partition->id;
  if (face_s) (s_first ? pair.faces_a : pair.faces_b).push_back(face_s);
  if (face_t) (s_first ? pair.faces_b : pair.faces_a).push_back(face_t);
  pair.normal = gp_Dir(s_first ? normal_out_of_s : -normal_out_of_s);
  out.push_back(std::move(pair));
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
  const gp_Pnt p = ball.location.Translated(towards * ball.radius);
  PartitionProbe probe_s(*s.parts, *s.partition), probe_t(*t.parts, *t.partition);
  const int face_s = probe_s.face_at(p, 3 * tol.linear);
  if (!face_s) return;
  const int face_t = probe_t.face_at(p, 3 * tol.linear);
  if (!face_t) return;
  HigherPair pair;
  pair.type = type;
  pair.point = pair.start = pair.end = p;
  record(pair, s, t, face_s, face_t, towards, out);
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
  if (t1 - t0 <= tol.linear) return;
  PartitionProbe probe_s(*s.parts, *s.partition), probe_t(*t.parts, *t.partition);
  const double probe_tol = 3 * tol.linear;
  const gp_Vec axis(cyl.axis);
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
  pair.start = on_line.Translated(axis * first);
  pair.end = on_line.Translated(axis * last);
  pair.point = on_line.Translated(axis * (0.5 * (first + last)));
  pair.length = length;
  record(pair, s, t, fs_kept, ft_kept, out_of_s, out);
}

}  // namespace

std::vector<HigherPair> find_higher_pairs(int ia, const BodyPartitions& a, int ib, const BodyPartitions& b,
                                          const Tolerances& tol) {
  std::vector<HigherPair> out;
  // Every higher pair has a ball or a cylinder on one side: pairs of
  // plane-only bodies (the common case, a grid of blocks) end here.
  const auto rounded = [](const BodyPartitions& body) {
    return std::any_of(body.partitions.begin(), body.partitions.end(),
                       [](const Partition& p) { return is_ball(p) || is_cylinder(p); });
  };
  if (!rounded(a) && !rounded(b)) return out;
  for (const Partition& pa : a.partitions) {
    for (const Partition& pb : b.partitions) {
      if (!boxes_meet(pa.box, pb.box, tol.linear)) continue;
      const Side sa{ia, &a, &pa}, sb{ib, &b, &pb};
      // The ball or cylinder first: each unordered pair of surfaces once.
      if (is_ball(pa) && (is_plane(pb) || is_cylinder(pb))) sphere_point(sa, sb, tol, out);
      else if (is_ball(pb) && (is_plane(pa) || is_cylinder(pa))) sphere_point(sb, sa, tol, out);
      else if (is_cylinder(pa) && is_plane(pb)) cylinder_line(sa, sb, tol, out);
      else if (is_cylinder(pb) && is_plane(pa)) cylinder_line(sb, sa, tol, out);
      else if (is_cylinder(pa) && is_cylinder(pb)) {
        if (pa.side == MaterialSide::Convex) cylinder_line(sa, sb, tol, out);
        else if (pb.side == MaterialSide::Convex) cylinder_line(sb, sa, tol, out);
      }
    }
  }
  return out;
}

}  // namespace contactcore
