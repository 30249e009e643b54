#include "contactcore/common_area.h"

#include <algorithm>
#include <cmath>

#include <BRepClass_FaceClassifier.hxx>
#include <BRepTools.hxx>
#include <BRep_Tool.hxx>
#include <Geom_Surface.hxx>
#include <ShapeAnalysis_Surface.hxx>
#include <gp_Vec.hxx>

namespace contactcore {

namespace {

constexpr double kTwoPi = 2.0 * M_PI;

// ---------------------------------------------------------------- 2D polygons

double cross(const Point2& a, const Point2& b) { return a.x * b.y - a.y * b.x; }
Point2 sub(const Point2& a, const Point2& b) { return {a.x - b.x, a.y - b.y}; }

double distance_to_segment(const Point2& p, const Point2& a, const Point2& b, double* along = nullptr) {
  const Point2 ab = sub(b, a), ap = sub(p, a);
  const double len2 = ab.x * ab.x + ab.y * ab.y;
  double t = len2 > 0 ? (ap.x * ab.x + ap.y * ab.y) / len2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  if (along) *along = t;
  const double dx = a.x + t * ab.x - p.x, dy = a.y + t * ab.y - p.y;
  return std::sqrt(dx * dx + dy * dy);
}

struct Box2 {
  double xmin = 1e300, ymin = 1e300, xmax = -1e300, ymax = -1e300;
  void add(const Point2& p) {
    xmin = std::min(xmin, p.x), ymin = std::min(ymin, p.y);
    xmax = std::max(xmax, p.x), ymax = std::max(ymax, p.y);
  }
  bool meets(const Box2& o, double tol) const {
    return xmin <= o.xmax + tol && o.xmin <= xmax + tol && ymin <= o.ymax + tol && o.ymin <= ymax + tol;
  }
};

Box2 box_of(const std::vector<Polygon2>& loops) {
  Box2 box;
  for (const Polygon2& loop : loops)
    for (const Point2& p : loop) box.add(p);
  return box;
}

// The edges of a polygon set in a uniform grid, so that the edges near a
// point or a segment are found without scanning them all.
class EdgeGrid {
 public:
  struct Edge {
    Point2 a, b;
  };

  EdgeGrid(const std::vector<Polygon2>& loops, double tol) : tol_(tol) {
    for (const Polygon2& loop : loops)
      for (size_t i = 0; i < loop.size(); ++i) edges_.push_back({loop[i], loop[(i + 1) % loop.size()]});
    for (const Edge& e : edges_) box_.add(e.a), box_.add(e.b);
    const double cells = std::max(1.0, std::sqrt(static_cast<double>(edges_.size())));
    nx_ = ny_ = static_cast<int>(std::ceil(cells));
    cell_w_ = std::max((box_.xmax - box_.xmin) / nx_, 1e-300);
    cell_h_ = std::max((box_.ymax - box_.ymin) / ny_, 1e-300);
    cells_.assign(static_cast<size_t>(nx_) * ny_, {});
    for (size_t k = 0; k < edges_.size(); ++k) {
      const Edge& e = edges_[k];
      const auto [i0, i1] = columns(std::min(e.a.x, e.b.x) - tol, std::max(e.a.x, e.b.x) + tol);
      const auto [j0, j1] = rows(std::min(e.a.y, e.b.y) - tol, std::max(e.a.y, e.b.y) + tol);
      for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i) cells_[static_cast<size_t>(j) * nx_ + i].push_back(static_cast<int>(k));
    }
    stamp_.assign(edges_.size(), 0);
  }

  const Box2& box() const { return box_; }
  const Edge& edge(int k) const { return edges_[k]; }

  // Edges whose cells meet the box [x0, x1] x [y0, y1], each once.
  template <class Visit>
  void near(double x0, double y0, double x1, double y1, Visit&& visit) const {
    if (x1 < box_.xmin - tol_ || x0 > box_.xmax + tol_ || y1 < box_.ymin - tol_ || y0 > box_.ymax + tol_) return;
    ++epoch_;
    const auto [i0, i1] = columns(x0, x1);
    const auto [j0, j1] = rows(y0, y1);
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i)
        for (int k : cells_[static_cast<size_t>(j) * nx_ + i]) {
          if (stamp_[k] == epoch_) continue;
          stamp_[k] = epoch_;
          visit(k);
        }
  }

  // Winding number around p: only edges crossing the horizontal line through
  // p on its right can count (Sunday's algorithm), so scan that half-row.
  int winding(const Point2& p) const {
    int wind = 0;
    near(p.x, p.y, box_.xmax + tol_, p.y, [&](int k) {
      const Point2& a = edges_[k].a;
      const Point2& b = edges_[k].b;
      if (a.y <= p.y) {
        if (b.y > p.y && cross(sub(b, a), sub(p, a)) > 0) ++wind;
      } else if (b.y <= p.y && cross(sub(b, a), sub(p, a)) < 0) {
        --wind;
      }
    });
    return wind;
  }

 private:
  std::pair<int, int> columns(double x0, double x1) const {
    return {std::clamp(static_cast<int>(std::floor((x0 - box_.xmin) / cell_w_)), 0, nx_ - 1),
            std::clamp(static_cast<int>(std::floor((x1 - box_.xmin) / cell_w_)), 0, nx_ - 1)};
  }
  std::pair<int, int> rows(double y0, double y1) const {
    return {std::clamp(static_cast<int>(std::floor((y0 - box_.ymin) / cell_h_)), 0, ny_ - 1),
            std::clamp(static_cast<int>(std::floor((y1 - box_.ymin) / cell_h_)), 0, ny_ - 1)};
  }

  double tol_;
  std::vector<Edge> edges_;
  Box2 box_;
  int nx_ = 1, ny_ = 1;
  double cell_w_ = 1, cell_h_ = 1;
  std::vector<std::vector<int>> cells_;
  mutable std::vector<unsigned> stamp_;
  mutable unsigned epoch_ = 0;
};

// Which part of `edges`' boundary lies inside `other`: by Green's theorem the
// common area is the sum of x dy - y dx over the boundary of the intersection,
// made of the pieces of each boundary inside the other region. A piece running
// along the other boundary counts once (from the first set) when both run the
// same way, i.e. both regions lie on the same side of it.
double boundary_inside(const std::vector<Polygon2>& edges, const EdgeGrid& other, bool count_shared, double tol) {
  double twice_area = 0;
  std::vector<double> cuts;
  for (const Polygon2& loop : edges) {
    const size_t n = loop.size();
    for (size_t i = 0; i < n; ++i) {
      const Point2 p = loop[i];
      const Point2 q = loop[(i + 1) % n];
      const Point2 r = sub(q, p);
      const double r_len2 = r.x * r.x + r.y * r.y;
      if (r_len2 <= 0) continue;
      const double x0 = std::min(p.x, q.x) - tol, x1 = std::max(p.x, q.x) + tol;
      const double y0 = std::min(p.y, q.y) - tol, y1 = std::max(p.y, q.y) + tol;
      const Box2& obox = other.box();
      if (x1 < obox.xmin || x0 > obox.xmax || y1 < obox.ymin || y0 > obox.ymax) continue;  // outside entirely
      cuts.assign({0.0, 1.0});
      other.near(x0, y0, x1, y1, [&](int k) {
        const Point2& a = other.edge(k).a;
        const Point2& b = other.edge(k).b;
        const Point2 s = sub(b, a);
        const double denom = cross(r, s);
        const Point2 pa = sub(a, p);
        if (std::abs(denom) > 1e-12 * std::sqrt(r_len2 * (s.x * s.x + s.y * s.y))) {
          const double t = cross(pa, s) / denom;
          const double u = cross(pa, r) / denom;
          if (t > 0 && t < 1 && u >= -1e-12 && u <= 1 + 1e-12) cuts.push_back(t);
        } else {
          // Parallel: the other edge's ends cut this one where they lie on it.
          for (const Point2& e : {a, b}) {
            double t = 0;
            if (distance_to_segment(e, p, q, &t) <= tol && t > 0 && t < 1) cuts.push_back(t);
          }
        }
      });
      std::sort(cuts.begin(), cuts.end());
      for (size_t k = 0; k + 1 < cuts.size(); ++k) {
        const double t0 = cuts[k], t1 = cuts[k + 1];
        if (t1 - t0 <= 1e-12) continue;
        const Point2 s0{p.x + t0 * r.x, p.y + t0 * r.y};
        const Point2 s1{p.x + t1 * r.x, p.y + t1 * r.y};
        const Point2 mid{(s0.x + s1.x) / 2, (s0.y + s1.y) / 2};
        // Is the piece on the other boundary? Then keep it only if it runs the same way.
        int shared = 0;  // +1 same direction, -1 opposite
        other.near(mid.x - tol, mid.y - tol, mid.x + tol, mid.y + tol, [&](int j) {
          if (shared) return;
          const Point2& a = other.edge(j).a;
          const Point2& b = other.edge(j).b;
          if (distance_to_segment(mid, a, b) > tol) return;
          const Point2 s = sub(b, a);
          const double sin_angle = std::abs(cross(s, r)) / std::sqrt((s.x * s.x + s.y * s.y) * r_len2);
          if (sin_angle < 1e-3) shared = (s.x * r.x + s.y * r.y) > 0 ? 1 : -1;
        });
        const bool inside = shared ? (count_shared && shared > 0) : other.winding(mid) > 0;
        if (inside) twice_area += cross(s0, s1);
      }
    }
  }
  return twice_area;
}

// -------------------------------------------------------------- 3D helpers

bool parallel(const gp_Dir& a, const gp_Dir& b, double angular) {
  return std::abs(a.Dot(b)) >= std::cos(angular);
}

double distance_to_line(const gp_Pnt& p, const gp_Pnt& origin, const gp_Dir& axis) {
  const gp_Vec v(origin, p);
  return v.Crossed(gp_Vec(axis)).Magnitude();
}

// A point on a face (within tolerance of its surface and inside its
// boundaries)? For samples of circle and sphere contacts.
class FaceProbe {
 public:
  explicit FaceProbe(const FaceInfo& info)
      : face_(info.face), analysis_(BRep_Tool::Surface(info.face)) {}
  bool contains(const gp_Pnt& p, double tol) {
    const gp_Pnt2d uv = analysis_.ValueOfUV(p, tol);
    if (analysis_.Gap() > 10 * tol) return false;
    BRepClass_FaceClassifier classifier(face_, uv, tol);
    const TopAbs_State state = classifier.State();
    return state == TopAbs_IN || state == TopAbs_ON;
  }

 private:
  TopoDS_Face face_;
  ShapeAnalysis_Surface analysis_;
};

gp_Dir any_perpendicular(const gp_Dir& axis) {
  const gp_Dir trial = std::abs(axis.X()) < 0.9 ? gp_Dir(1, 0, 0) : gp_Dir(0, 1, 0);
  return gp_Dir(gp_Vec(axis).Crossed(gp_Vec(trial)));
}

// Fraction of a circle lying on all the given faces, as angular intervals.
// The circle: centre, axis, radius; `samples` points.
std::vector<AngularInterval> circle_on_faces(const gp_Pnt& centre, const gp_Dir& axis, double radius,
                                             std::vector<FaceProbe*> probes, double tol,
                                             int samples = 72) {
  const gp_Dir x = any_perpendicular(axis);
  const gp_Dir y = axis.Crossed(x);
  std::vector<AngularInterval> hits;
  const double step = kTwoPi / samples;
  for (int k = 0; k < samples; ++k) {
    const double angle = (k + 0.5) * step;
    const gp_Pnt p = centre.Translated(gp_Vec(x) * (radius * std::cos(angle)) +
                                       gp_Vec(y) * (radius * std::sin(angle)));
    bool on_all = true;
    for (FaceProbe* probe : probes) on_all = on_all && probe->contains(p, tol);
    if (on_all) hits.push_back({k * step, step});
  }
  return unite(hits);
}

// -------------------------------------------------------------- contacts

const FaceInfo& face_of(const BodyPartitions& body, int index) { return body.faces[index - 1]; }

void record(Contact& c, const PairContext& ctx, std::vector<Contact>& out) {
  c.tolerances = ctx.tol;
  std::sort(c.faces_a.begin(), c.faces_a.end());
  c.faces_a.erase(std::unique(c.faces_a.begin(), c.faces_a.end()), c.faces_a.end());
  std::sort(c.faces_b.begin(), c.faces_b.end());
  c.faces_b.erase(std::unique(c.faces_b.begin(), c.faces_b.end()), c.faces_b.end());
  out.push_back(std::move(c));
}

bool area_counts(double area, const Partition& a, const Partition& b, const PairContext& ctx) {
  const double smaller = std::min(a.area, b.area);
  return area > ctx.min_area_ratio * smaller && area > ctx.tol.linear * ctx.tol.linear;
}

void planar_fit(int ia, const Partition& a, int ib, const Partition& b, const PairContext& ctx,
                std::vector<Contact>& out) {
  const SurfaceParams& pa = a.params;
  const SurfaceParams& pb = b.params;
  if (pa.axis.Dot(pb.axis) > -std::cos(ctx.tol.angular)) return;  // normals not opposite
  if (std::abs(gp_Vec(pa.location, pb.location).Dot(gp_Vec(pa.axis))) > ctx.tol.linear) return;
  const gp_Dir x = a.extent.ref_dir;
  const gp_Dir y = pa.axis.Crossed(x);
  Contact c;
  c.type = ContactType::PLF;
  c.direction = pa.axis;
  double sx = 0, sy = 0, weight = 0;
  // b's outlines in a's frame, each mapped the first time a face of a meets it.
  std::vector<std::vector<Polygon2>> outlines_b(b.faces.size());
  for (int fa : a.faces) {
    const FaceInfo& face_a = face_of(ctx.parts[ia], fa);
    std::vector<Polygon2> loops_a;
    for (size_t kb = 0; kb < b.faces.size(); ++kb) {
      const int fb = b.faces[kb];
      const FaceInfo& face_b = face_of(ctx.parts[ib], fb);
      if (!boxes_meet(face_a.box, face_b.box, ctx.tol.linear)) continue;
      if (loops_a.empty()) loops_a = outline_in(face_a, pa.location, x, y);
      std::vector<Polygon2>& loops_b = outlines_b[kb];
      if (loops_b.empty()) loops_b = outline_in(face_b, pa.location, x, y);
      const double area = common_area(loops_a, loops_b, ctx.tol.linear);
      if (area <= ctx.tol.linear * ctx.tol.linear) continue;
      c.area += area;
      c.faces_a.push_back(fa);
      c.faces_b.push_back(fb);
      // A point of the common area: the centre of the smaller face's box, weighted.
      const Box2 bb = box_of(face_a.area < face_b.area ? loops_a : loops_b);
      sx += area * (bb.xmin + bb.xmax) / 2, sy += area * (bb.ymin + bb.ymax) / 2, weight += area;
    }
  }
  if (!area_counts(c.area, a, b, ctx)) return;
  c.point = pa.location.Translated(gp_Vec(x) * (sx / weight) + gp_Vec(y) * (sy / weight));
  c.partition_a = a.id, c.partition_b = b.id;
  record(c, ctx, out);
}

// Cylinders (CLJ) and cones (CJU): overlap of axial ranges and angular spans,
// face by face, in the frame of partition a.
void revolution_fit(int ia, const Partition& a, int ib, const Partition& b, const PairContext& ctx,
                    std::vector<Contact>& out) {
  const SurfaceParams& pa = a.params;
  const SurfaceParams& pb = b.params;
  const bool cone = pa.kind == SurfaceKind::Cone;
  if (cone) {
    if (pa.axis.Dot(pb.axis) < std::cos(ctx.tol.angular)) return;
    if (std::abs(pa.half_angle - pb.half_angle) > ctx.tol.angular) return;
    if (pa.location.Distance(pb.location) > ctx.tol.linear) return;
  } else {
    if (!parallel(pa.axis, pb.axis, ctx.tol.angular)) return;
    if (std::abs(pa.radius - pb.radius) > ctx.tol.linear) return;
    if (distance_to_line(pb.location, pa.location, pa.axis) > ctx.tol.linear) return;
  }
  Contact c;
  c.type = cone ? ContactType::CJU : ContactType::CLJ;
  c.point = pa.location;
  c.direction = pa.axis;
  c.radius = cone ? 0 : pa.radius;
  c.half_angle = cone ? pa.half_angle : 0;
  std::vector<AngularInterval> common_angles;
  const gp_Dir ref = a.extent.ref_dir;
  for (int fa : a.faces) {
    const FaceInfo& face_a = face_of(ctx.parts[ia], fa);
    const Extent ea = revolution_extent_in(face_a, pa.location, pa.axis, ref);
    for (int fb : b.faces) {
      const FaceInfo& face_b = face_of(ctx.parts[ib], fb);
      if (!boxes_meet(face_a.box, face_b.box, ctx.tol.linear)) continue;
      const Extent eb = revolution_extent_in(face_b, pa.location, pa.axis, ref);
      const double z0 = std::max(ea.axial_min, eb.axial_min);
      const double z1 = std::min(ea.axial_max, eb.axial_max);
      if (z1 - z0 <= ctx.tol.linear) continue;
      std::vector<AngularInterval> common;
      const double angle = overlap(ea.angular, eb.angular, &common);
      if (angle <= ctx.tol.angular) continue;
      // Cylinder: r * angle * length. Cone (z from the apex, r = z tan a, slant
      // dz / cos a): angle * tan a / cos a * (z1^2 - z0^2) / 2.
      const double area = cone ? angle * std::tan(pa.half_angle) / std::cos(pa.half_angle) *
                                     (z1 * z1 - z0 * z0) / 2.0
                                : pa.radius * angle * (z1 - z0);
      c.area += std::abs(area);
      common_angles.insert(common_angles.end(), common.begin(), common.end());
      c.faces_a.push_back(fa);
      c.faces_b.push_back(fb);
    }
  }
  if (!area_counts(c.area, a, b, ctx)) return;
  c.span = 0;
  for (const AngularInterval& i : unite(common_angles)) c.span += i.span;
  c.partial = c.span < M_PI - ctx.tol.angular;
  c.partition_a = a.id, c.partition_b = b.id;
  record(c, ctx, out);
}

// Sample-based common area of two faces on the same sphere or torus: the
// part of b's UV grid lying on a, scaled by b's area.
double sampled_common_area(const FaceInfo& a, const FaceInfo& b, double tol) {
  constexpr int kGrid = 16;
  double u0, u1, v0, v1;
  BRepTools::UVBounds(b.face, u0, u1, v0, v1);
  const Handle(Geom_Surface) surface = BRep_Tool::Surface(b.face);
  FaceProbe on_a(a);
  int in_b = 0, in_both = 0;
  for (int i = 0; i < kGrid; ++i) {
    for (int j = 0; j < kGrid; ++j) {
      const gp_Pnt2d uv(u0 + (i + 0.5) * (u1 - u0) / kGrid, v0 + (j + 0.5) * (v1 - v0) / kGrid);
      BRepClass_FaceClassifier classifier(b.face, uv, tol);
      if (classifier.State() != TopAbs_IN) continue;
      ++in_b;
      if (on_a.contains(surface->Value(uv.X(), uv.Y()), tol)) ++in_both;
    }
  }
  return in_b ? b.area * in_both / in_b : 0.0;
}

// Spheres (SPF) and tori (TRF) with the same parameters: sampled common area.
void closed_revolution_fit(int ia, const Partition& a, int ib, const Partition& b,
                           const PairContext& ctx, std::vector<Contact>& out) {
  const SurfaceParams& pa = a.params;
  const SurfaceParams& pb = b.params;
  const bool torus = pa.kind == SurfaceKind::Torus;
  if (pa.location.Distance(pb.location) > ctx.tol.linear) return;
  if (std::abs(pa.radius - pb.radius) > ctx.tol.linear) return;
  if (torus && (std::abs(pa.minor_radius - pb.minor_radius) > ctx.tol.linear ||
                !parallel(pa.axis, pb.axis, ctx.tol.angular)))
    return;
  Contact c;
  c.type = torus ? ContactType::TRF : ContactType::SPF;
  c.point = pa.location;
  c.direction = pa.axis;
  c.radius = torus ? pa.minor_radius : pa.radius;
  for (int fa : a.faces) {
    const FaceInfo& face_a = face_of(ctx.parts[ia], fa);
    for (int fb : b.faces) {
      const FaceInfo& face_b = face_of(ctx.parts[ib], fb);
      if (!boxes_meet(face_a.box, face_b.box, ctx.tol.linear)) continue;
      const double area = sampled_common_area(face_a, face_b, ctx.tol.linear);
      if (area <= 0) continue;
      c.area += area;
      c.faces_a.push_back(fa);
      c.faces_b.push_back(fb);
    }
  }
  if (!area_counts(c.area, a, b, ctx)) return;
  c.span = kTwoPi;  // not a revolution-about-an-axis contact: never partial
  c.partition_a = a.id, c.partition_b = b.id;
  record(c, ctx, out);
}

// A ball touching a bore (LAF) or a torus groove (SPT) of its radius: the
// contact is a circle; it exists where the circle lies on both faces.
void ball_fit(int i_ball, const Partition& ball, int i_seat, const Partition& seat,
              const PairContext& ctx, std::vector<Contact>& out) {
  const SurfaceParams& ps = ball.params;
  const SurfaceParams& pc = seat.params;
  const bool groove = pc.kind == SurfaceKind::Torus;
  const double seat_radius = groove ? pc.minor_radius : pc.radius;
  if (std::abs(ps.radius - seat_radius) > ctx.tol.linear) return;
  gp_Dir circle_axis = pc.axis;
  if (groove) {
    // Ball centre on the torus' tube-centre circle; the contact circle lies in
    // the meridian plane through the ball centre.
    const gp_Vec from_centre(pc.location, ps.location);
    const double height = from_centre.Dot(gp_Vec(pc.axis));
    const gp_Vec radial = from_centre - gp_Vec(pc.axis) * height;
    if (std::abs(height) > ctx.tol.linear) return;
    if (std::abs(radial.Magnitude() - pc.radius) > ctx.tol.linear || radial.Magnitude() <= 0) return;
    circle_axis = gp_Dir(gp_Vec(pc.axis).Crossed(radial));
  } else if (distance_to_line(ps.location, pc.location, pc.axis) > ctx.tol.linear) {
    return;
  }
  Contact c;
  c.type = groove ? ContactType::SPT : ContactType::LAF;
  c.point = ps.location;
  c.direction = circle_axis;
  c.radius = ps.radius;
  std::vector<AngularInterval> on_both;
  for (int fs : ball.faces) {
    FaceProbe ball_probe(face_of(ctx.parts[i_ball], fs));
    for (int fc : seat.faces) {
      FaceProbe seat_probe(face_of(ctx.parts[i_seat], fc));
      const auto hits = circle_on_faces(ps.location, circle_axis, ps.radius, {&ball_probe, &seat_probe},
                                        ctx.tol.linear * 10);
      if (hits.empty()) continue;
      on_both.insert(on_both.end(), hits.begin(), hits.end());
      c.faces_a.push_back(fs);
      c.faces_b.push_back(fc);
    }
  }
  if (on_both.empty()) return;
  c.span = 0;
  for (const AngularInterval& i : unite(on_both)) c.span += i.span;
  c.partial = c.span < M_PI - ctx.tol.angular;
  c.partition_a = ball.id, c.partition_b = seat.id;
  record(c, ctx, out);
}
bool opposite_sides(const Partition& a, const Partition& b) {
  return (a.side == MaterialSide::Convex && b.side == MaterialSide::Concave) ||
         (a.side == MaterialSide::Concave && b.side == MaterialSide::Convex);
}

void swap_sides(Contact& c) {
  std::swap(c.partition_a, c.partition_b);
  std::swap(c.faces_a, c.faces_b);
}

}  // namespace

// Dispatches one candidate pair to its test (a from body ia, b from body ib,
// ia < ib); every test records its first argument as side a.
void test_candidate(int ia, const Partition& a, int ib, const Partition& b, const PairContext& ctx,
                    std::vector<Contact>& out) {
  const SurfaceKind ka = a.params.kind, kb = b.params.kind;
  const auto is_ball = [](const Partition& p) {
    return p.params.kind == SurfaceKind::Sphere && p.side == MaterialSide::Convex;
  };
  const auto is_seat = [](const Partition& p) {
    return (p.params.kind == SurfaceKind::Cylinder || p.params.kind == SurfaceKind::Torus) &&
           p.side == MaterialSide::Concave;
  };
  const size_t before = out.size();
  bool swapped = false;
  if (ka == SurfaceKind::Plane && kb == SurfaceKind::Plane) {
    planar_fit(ia, a, ib, b, ctx, out);
  } else if (ka == kb && (ka == SurfaceKind::Cylinder || ka == SurfaceKind::Cone)) {
    if (opposite_sides(a, b)) revolution_fit(ia, a, ib, b, ctx, out);
  } else if (ka == kb && (ka == SurfaceKind::Sphere || ka == SurfaceKind::Torus)) {
    if (opposite_sides(a, b)) closed_revolution_fit(ia, a, ib, b, ctx, out);
  } else if (is_ball(a) && is_seat(b)) {
    ball_fit(ia, a, ib, b, ctx, out);
  } else if (is_ball(b) && is_seat(a)) {
    ball_fit(ib, b, ia, a, ctx, out);
    swapped = true;
  }
  for (size_t k = before; k < out.size(); ++k) {
    if (swapped) swap_sides(out[k]);
    out[k].body_a = ia, out[k].body_b = ib;
  }
}

double common_area(const std::vector<Polygon2>& a, const std::vector<Polygon2>& b, double tol) {
  if (a.empty() || b.empty()) return 0.0;
  if (!box_of(a).meets(box_of(b), tol)) return 0.0;
  const EdgeGrid grid_a(a, tol), grid_b(b, tol);
  const double twice = boundary_inside(a, grid_b, true, tol) + boundary_inside(b, grid_a, false, tol);
  return std::max(0.0, twice / 2.0);
}

}  // namespace contactcore
