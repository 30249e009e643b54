#include "contacts/common_area.h"
#include "contactcore/common/angles.h"

#include <algorithm>
#include <cmath>

#include <BRepAdaptor_Curve.hxx>
#include <BRepAlgoAPI_Common.hxx>
#include <BRepClass_FaceClassifier.hxx>
#include <BRepGProp.hxx>
#include <GProp_GProps.hxx>
#include <BRepTools.hxx>
#include <BRep_Tool.hxx>
#include <Geom_Surface.hxx>
#include <Precision.hxx>
#include <ShapeAnalysis_Surface.hxx>
#include <Standard_Failure.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_ListOfShape.hxx>
#include <TopoDS.hxx>
#include <gp_Vec.hxx>

namespace contactcore {

namespace {

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
  // Clamped as a double: a coordinate far outside the grid (or NaN) is no int
  // (UBSan, make fuzz: -2e296 from a damaged shape).
  static int cell(double t, int n) {
    if (!(t > 0)) return 0;
    return t >= n - 1 ? n - 1 : static_cast<int>(t);
  }
  std::pair<int, int> columns(double x0, double x1) const {
    return {cell((x0 - box_.xmin) / cell_w_, nx_), cell((x1 - box_.xmin) / cell_w_, nx_)};
  }
  std::pair<int, int> rows(double y0, double y1) const {
    return {cell((y0 - box_.ymin) / cell_h_, ny_), cell((y1 - box_.ymin) / cell_h_, ny_)};
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
// made of the pieces of each boundary inside the other region; each chord
// kept adds the bulge of its curve, so arcs count exactly, not as polygons. A piece running
// along the other boundary counts once (from the first set) when both run the
// same way, i.e. both regions lie on the same side of it.
double boundary_inside(const std::vector<Polygon2>& edges, const EdgeGrid& other, bool count_shared, double tol,
                       const Point2& origin, double& length) {
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
        }
        // The other edge's ends cut this one where they lie on it (within
        // tolerance, at any angle): where two boundaries run together, their
        // shared pieces then end where they really part.
        for (const Point2& e : {a, b}) {
          double t = 0;
          if (distance_to_segment(e, p, q, &t) <= tol && t > 0 && t < 1) cuts.push_back(t);
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
        // The chord's bulge, in proportion to the piece (a segment of a
        // circle grows with the cube of its chord): exact on whole chords.
        const double piece = t1 - t0;
        if (inside) {
          twice_area += cross(sub(s0, origin), sub(s1, origin)) + p.bulge * piece * piece * piece;
          length += piece * std::sqrt(r_len2);
        }
      }
    }
  }
  return twice_area;
}

// -------------------------------------------------------------- 3D helpers

bool parallel(const gp_Dir& a, const gp_Dir& b, double angular) {
  return std::abs(a.Dot(b)) >= std::cos(angular);
}

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

// The end of a run of circle samples found on the faces, to the probes'
// precision: bisection between an angle on all faces and one off them.
double refine_circle_end(const gp_Pnt& centre, const gp_Dir& x, const gp_Dir& y, double radius,
                         std::vector<FaceProbe*>& probes, double tol, double inside, double outside) {
  for (int i = 0; i < 40 && std::abs(outside - inside) > 1e-12; ++i) {
    const double middle = 0.5 * (inside + outside);
    const gp_Pnt p = centre.Translated(gp_Vec(x) * (radius * std::cos(middle)) + gp_Vec(y) * (radius * std::sin(middle)));
    bool on_all = true;
    for (FaceProbe* probe : probes) on_all = on_all && probe->contains(p, tol);
    (on_all ? inside : outside) = middle;
  }
  return inside;
}

// The smallest arc covering angular intervals of a circle (the complement
// of their largest gap): its middle angle and half span; half span pi when
// they go all around.
void covering_arc(const std::vector<AngularInterval>& intervals, double& middle, double& half_span) {
  std::vector<AngularInterval> sorted = unite(intervals);
  middle = 0, half_span = kPi;
  double covered = 0;
  for (const AngularInterval& i : sorted) covered += i.span;
  if (sorted.empty() || covered >= kTwoPi - 1e-9) return;
  std::sort(sorted.begin(), sorted.end(), [](const AngularInterval& l, const AngularInterval& r) { return l.start < r.start; });
  double best_gap = -1, arc_start = 0;
  for (size_t k = 0; k < sorted.size(); ++k) {
    const double end = sorted[k].start + sorted[k].span;
    const double next = k + 1 < sorted.size() ? sorted[k + 1].start : sorted[0].start + kTwoPi;
    const double gap = next - end;
    if (gap > best_gap) best_gap = gap, arc_start = next;
  }
  half_span = 0.5 * (kTwoPi - best_gap);
  middle = arc_start + half_span;
}

// A cap of the sphere (centre, radius) covering faces lying on it: its axis
// through the region's centroid, its angle the largest angle from the axis
// to the faces' boundaries (exactly sampled along circles; other edges get
// the angle between samples added, so the cap always covers). pi when the
// region goes all around (the point opposite the axis lies on a face).
void covering_cap(const std::vector<FaceInfo>& pieces, const gp_Pnt& centre, double radius, double tol,
                  gp_Dir& axis, double& angle) {
  angle = kPi;
  gp_XYZ moment(0, 0, 0);
  double area = 0;
  for (const FaceInfo& piece : pieces) {
    GProp_GProps props;
    BRepGProp::SurfaceProperties(piece.face, props);
    moment += (props.CentreOfMass().XYZ() - centre.XYZ()) * props.Mass();
    area += props.Mass();
  }
  if (area <= 0 || moment.Modulus() <= 1e-9 * radius * area) return;
  axis = gp_Dir(moment);
  const gp_Pnt opposite = centre.Translated(gp_Vec(axis) * -radius);
  for (const FaceInfo& piece : pieces) {
    FaceProbe probe(piece);
    if (probe.contains(opposite, tol)) return;
  }
  constexpr int kSamples = 64;
  double widest = 0;
  for (const FaceInfo& piece : pieces) {
    for (TopExp_Explorer edges(piece.face, TopAbs_EDGE); edges.More(); edges.Next()) {
      const TopoDS_Edge& edge = TopoDS::Edge(edges.Current());
      if (BRep_Tool::Degenerated(edge)) continue;
      const BRepAdaptor_Curve curve(edge);
      const double t0 = curve.FirstParameter(), t1 = curve.LastParameter();
      double step_angle = 0;
      gp_Vec previous;
      for (int i = 0; i <= kSamples; ++i) {
        const gp_Vec d(centre, curve.Value(t0 + (t1 - t0) * i / kSamples));
        if (d.Magnitude() <= 0) continue;
        widest = std::max(widest, d.Angle(gp_Vec(axis)));
        if (i > 0) step_angle = std::max(step_angle, d.Angle(previous));
        previous = d;
      }
      // Between samples, a curve other than a circle may reach further.
      if (curve.GetType() != GeomAbs_Circle) widest += step_angle;
    }
  }
  angle = std::min(kPi, widest);
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
      const CommonRegion region = common_region(loops_a, loops_b, ctx.tol.linear);
      // A strip of width w has area w L and perimeter about 2 L: no wider than
      // twice the tolerance, the faces meet along their edges only, whatever
      // the sag of the chords.
      if (region.area <= ctx.tol.linear * region.perimeter) continue;
      const double area = region.area;
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

}  // namespace

// ------------------------------------------------ exact common regions

// The region two faces on the same surface have in common, by OCCT's Boolean
// common of the two faces alone (fuzzy value: the linear tolerance; the
// arguments are left untouched, so shared geometry is never modified), each
// piece typed as a face of its own: exact area (Green on its boundary) and
// extent. Used where the boundary of a face is not made of iso-lines of the
// shared parametrisation, and for spheres and tori.
// A failed Boolean or piece is a failed Status (the driver skips the pair).
Status boolean_common(const TopoDS_Face& a, const TopoDS_Face& b, const Tolerances& tol,
                      std::vector<FaceInfo>& pieces) {
  pieces.clear();
  TopTools_ListOfShape arguments, tools;
  arguments.Append(a);
  tools.Append(b);
  BRepAlgoAPI_Common common;
  common.SetArguments(arguments);
  common.SetTools(tools);
  common.SetFuzzyValue(tol.linear);
  common.SetNonDestructive(Standard_True);
  common.SetRunParallel(Standard_False);
  common.Build();
  if (!common.IsDone()) return Status::failure(StatusCode::GeometryError, "OCCT: Boolean common of two faces failed");
  for (TopExp_Explorer faces(common.Shape(), TopAbs_FACE); faces.More(); faces.Next()) {
    FaceInfo piece;
    const Status typed = type_face(TopoDS::Face(faces.Current()), tol, piece);
    if (!typed.ok()) return Status::failure(StatusCode::GeometryError, "OCCT: " + typed.message);
    pieces.push_back(std::move(piece));
  }
  return Status::success();
}

// Is the face a rectangle in (angle, axial) about the axis: every edge either
// a parallel (constant axial coordinate) or a meridian line (constant angle)?
// Then its axial range and angular span describe it exactly. Samples each
// edge at its ends and seven inner points.
bool is_angle_axial_rectangle(const TopoDS_Face& face, const gp_Pnt& origin, const gp_Dir& axis, double tol) {
  constexpr int kSamples = 9;
  const gp_XYZ o = origin.XYZ(), z = axis.XYZ();
  for (TopExp_Explorer edges(face, TopAbs_EDGE); edges.More(); edges.Next()) {
    const TopoDS_Edge& edge = TopoDS::Edge(edges.Current());
    if (BRep_Tool::Degenerated(edge)) continue;
    const BRepAdaptor_Curve curve(edge);
    const double t0 = curve.FirstParameter(), t1 = curve.LastParameter();
    bool parallel_circle = true, meridian = true;
    double h0 = 0;
    gp_XYZ r0;
    for (int i = 0; i < kSamples; ++i) {
      const gp_XYZ d = curve.Value(t0 + (t1 - t0) * i / (kSamples - 1)).XYZ() - o;
      const double h = d * z;
      const gp_XYZ r = d - z * h;
      if (i == 0) {
        h0 = h, r0 = r;
        continue;
      }
      parallel_circle = parallel_circle && std::abs(h - h0) <= tol;
      const double r0_length = r0.Modulus();
      // Distance of the point from the half-plane through the axis and r0.
      meridian = meridian && r0_length > tol && std::abs((r0 ^ r) * z) / r0_length <= tol && r * r0 > 0;
    }
    if (!parallel_circle && !meridian) return false;
  }
  return true;
}

namespace {

// Cylinders (CLJ) and cones (CJU), face by face in the frame of partition a:
// faces bounded by parallels and meridians meet in the product of their axial
// ranges and angular spans; any other pair (oblique ends, cross holes,
// trimmed faces) by the exact common region of the two faces.
Status revolution_fit(int ia, const Partition& a, int ib, const Partition& b, const PairContext& ctx,
                      std::vector<Contact>& out) {
  const SurfaceParams& pa = a.params;
  const SurfaceParams& pb = b.params;
  const bool cone = pa.kind == SurfaceKind::Cone;
  if (cone) {
    if (pa.axis.Dot(pb.axis) < std::cos(ctx.tol.angular)) return Status::success();
    if (std::abs(pa.half_angle - pb.half_angle) > ctx.tol.angular) return Status::success();
    if (pa.location.Distance(pb.location) > ctx.tol.linear) return Status::success();
  } else {
    if (!parallel(pa.axis, pb.axis, ctx.tol.angular)) return Status::success();
    if (std::abs(pa.radius - pb.radius) > ctx.tol.linear) return Status::success();
    if (distance_to_line(pb.location, pa.location, pa.axis) > ctx.tol.linear) return Status::success();
  }
  Contact c;
  c.type = cone ? ContactType::CJU : ContactType::CLJ;
  c.point = pa.location;
  c.direction = pa.axis;
  c.radius = cone ? 0 : pa.radius;
  c.half_angle = cone ? pa.half_angle : 0;
  std::vector<AngularInterval> common_angles;
  const gp_Dir ref = a.extent.ref_dir;
  std::vector<signed char> rectangle_b(b.faces.size(), -1);  // unknown yet
  for (int fa : a.faces) {
    const FaceInfo& face_a = face_of(ctx.parts[ia], fa);
    const Extent ea = revolution_extent_in(face_a, pa.location, pa.axis, ref, ctx.tol.linear);
    signed char rectangle_a = -1;
    for (size_t kb = 0; kb < b.faces.size(); ++kb) {
      const int fb = b.faces[kb];
      const FaceInfo& face_b = face_of(ctx.parts[ib], fb);
      if (!boxes_meet(face_a.box, face_b.box, ctx.tol.linear)) continue;
      const Extent eb = revolution_extent_in(face_b, pa.location, pa.axis, ref, ctx.tol.linear);
      const double z0 = std::max(ea.axial_min, eb.axial_min);
      const double z1 = std::min(ea.axial_max, eb.axial_max);
      if (z1 - z0 <= ctx.tol.linear) continue;
      std::vector<AngularInterval> common;
      const double angle = overlap(ea.angular, eb.angular, &common);
      if (angle <= ctx.tol.angular) continue;  // the boxes of the extents do not meet
      if (rectangle_a < 0) rectangle_a = is_angle_axial_rectangle(face_a.face, pa.location, pa.axis, ctx.tol.linear);
      if (rectangle_b[kb] < 0)
        rectangle_b[kb] = is_angle_axial_rectangle(face_b.face, pa.location, pa.axis, ctx.tol.linear);
      double area = 0;
      if (rectangle_a && rectangle_b[kb]) {
        // Cylinder: r * angle * length. Cone (z from the apex, r = z tan a,
        // slant dz / cos a): angle * tan a / cos a * (z1^2 - z0^2) / 2.
        area = std::abs(cone ? angle * std::tan(pa.half_angle) / std::cos(pa.half_angle) * (z1 * z1 - z0 * z0) / 2.0
                             : pa.radius * angle * (z1 - z0));
      } else {
        common.clear();
        std::vector<FaceInfo> pieces;
        const Status found = boolean_common(face_a.face, face_b.face, ctx.tol, pieces);
        if (!found.ok()) return found;
        for (const FaceInfo& piece : pieces) {
          area += piece.area;
          const Extent seen = revolution_extent_in(piece, pa.location, pa.axis, ref, ctx.tol.linear);
          common.insert(common.end(), seen.angular.begin(), seen.angular.end());
        }
      }
      if (area <= ctx.tol.linear * ctx.tol.linear) continue;
      c.area += area;
      common_angles.insert(common_angles.end(), common.begin(), common.end());
      c.faces_a.push_back(fa);
      c.faces_b.push_back(fb);
    }
  }
  if (!area_counts(c.area, a, b, ctx)) return Status::success();
  c.span = 0;
  for (const AngularInterval& i : unite(common_angles)) c.span += i.span;
  c.partial = c.span < kPi - ctx.tol.angular;
  c.partition_a = a.id, c.partition_b = b.id;
  record(c, ctx, out);
  return Status::success();
}

// Spheres (SPF) and tori (TRF) with the same parameters: the exact common
// region of each face pair (the same whichever body comes first).
Status closed_revolution_fit(int ia, const Partition& a, int ib, const Partition& b,
                             const PairContext& ctx, std::vector<Contact>& out) {
  const SurfaceParams& pa = a.params;
  const SurfaceParams& pb = b.params;
  const bool torus = pa.kind == SurfaceKind::Torus;
  if (pa.location.Distance(pb.location) > ctx.tol.linear) return Status::success();
  if (std::abs(pa.radius - pb.radius) > ctx.tol.linear) return Status::success();
  if (torus && (std::abs(pa.minor_radius - pb.minor_radius) > ctx.tol.linear ||
                !parallel(pa.axis, pb.axis, ctx.tol.angular)))
    return Status::success();
  Contact c;
  c.type = torus ? ContactType::TRF : ContactType::SPF;
  c.point = pa.location;
  c.direction = pa.axis;
  c.radius = torus ? pa.minor_radius : pa.radius;
  std::vector<FaceInfo> pieces;  // the common region (spheres: where the cup holds the ball)
  for (int fa : a.faces) {
    const FaceInfo& face_a = face_of(ctx.parts[ia], fa);
    for (int fb : b.faces) {
      const FaceInfo& face_b = face_of(ctx.parts[ib], fb);
      if (!boxes_meet(face_a.box, face_b.box, ctx.tol.linear)) continue;
      std::vector<FaceInfo> found;
      const Status common = boolean_common(face_a.face, face_b.face, ctx.tol, found);
      if (!common.ok()) return common;
      double area = 0;
      for (const FaceInfo& piece : found) area += piece.area;
      if (area <= ctx.tol.linear * ctx.tol.linear) continue;
      c.area += area;
      c.faces_a.push_back(fa);
      c.faces_b.push_back(fb);
      for (FaceInfo& piece : found) pieces.push_back(std::move(piece));
    }
  }
  if (!area_counts(c.area, a, b, ctx)) return Status::success();
  if (!torus) covering_cap(pieces, pa.location, pa.radius, ctx.tol.linear, c.region_axis, c.region_angle);
  c.span = kTwoPi;  // not a revolution-about-an-axis contact: never partial
  c.partition_a = a.id, c.partition_b = b.id;
  record(c, ctx, out);
  return Status::success();
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
  // The circle lies on the seat within the mismatches allowed above (radius,
  // height, distance to the tube-centre circle or the axis).
  const double probe_tol = 3 * ctx.tol.linear;
  constexpr int kCircleSamples = 72;
  const gp_Dir x = any_perpendicular(circle_axis);  // circle_on_faces' frame
  const gp_Dir y = circle_axis.Crossed(x);
  std::vector<AngularInterval> on_both;
  for (int fs : ball.faces) {
    const FaceInfo& ball_face = face_of(ctx.parts[i_ball], fs);
    FaceProbe ball_probe(ball_face);
    // A face that is the whole sphere holds every point of the circle: only
    // the seat is asked (half the classifications of a ball in its raceway).
    const double sphere_area = 4 * kPi * ps.radius * ps.radius;
    const bool whole_sphere = std::abs(ball_face.area - sphere_area) <= 1e-9 * sphere_area;
    for (int fc : seat.faces) {
      FaceProbe seat_probe(face_of(ctx.parts[i_seat], fc));
      std::vector<FaceProbe*> probes{&seat_probe};
      if (!whole_sphere) probes.push_back(&ball_probe);
      auto hits = circle_on_faces(ps.location, circle_axis, ps.radius, probes, probe_tol, kCircleSamples);
      if (hits.empty()) continue;
      // The runs' ends to the probes' precision (the samples are 5 degrees
      // apart): the arc's ends bound the ball's one-sided directions.
      const double half_step = kPi / kCircleSamples;
      for (AngularInterval& run : hits) {
        if (run.span >= kTwoPi - 1e-9) continue;
        const double start = refine_circle_end(ps.location, x, y, ps.radius, probes, probe_tol,
                                               run.start + half_step, run.start - half_step);
        const double end = refine_circle_end(ps.location, x, y, ps.radius, probes, probe_tol,
                                             run.start + run.span - half_step, run.start + run.span + half_step);
        run = {start, end - start};
      }
      on_both.insert(on_both.end(), hits.begin(), hits.end());
      c.faces_a.push_back(fs);
      c.faces_b.push_back(fc);
    }
  }
  if (on_both.empty()) return;
  c.span = 0;
  for (const AngularInterval& i : unite(on_both)) c.span += i.span;
  c.partial = c.span < kPi - ctx.tol.angular;
  double middle = 0, half_span = kPi;
  covering_arc(on_both, middle, half_span);
  c.region_angle = half_span;
  if (half_span < kPi) c.region_axis = gp_Dir(gp_Vec(x) * std::cos(middle) + gp_Vec(y) * std::sin(middle));
  c.partition_a = ball.id, c.partition_b = seat.id;
  record(c, ctx, out);
}
void swap_sides(Contact& c) {
  std::swap(c.partition_a, c.partition_b);
  std::swap(c.faces_a, c.faces_b);
}

}  // namespace

// Dispatches one candidate pair to its test (a from body ia, b from body ib,
// ia < ib); every test records its first argument as side a.
Status test_candidate(int ia, const Partition& a, int ib, const Partition& b, const PairContext& ctx,
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
  Status status;
  if (ka == SurfaceKind::Plane && kb == SurfaceKind::Plane) {
    planar_fit(ia, a, ib, b, ctx, out);
  } else if (ka == kb && (ka == SurfaceKind::Cylinder || ka == SurfaceKind::Cone)) {
    if (convex_against_concave(a.side, b.side)) status = revolution_fit(ia, a, ib, b, ctx, out);
  } else if (ka == kb && (ka == SurfaceKind::Sphere || ka == SurfaceKind::Torus)) {
    if (convex_against_concave(a.side, b.side)) status = closed_revolution_fit(ia, a, ib, b, ctx, out);
  } else if (is_ball(a) && is_seat(b)) {
    ball_fit(ia, a, ib, b, ctx, out);
  } else if (is_ball(b) && is_seat(a)) {
    ball_fit(ib, b, ia, a, ctx, out);
    swapped = true;
  }
  if (!status.ok()) {
    out.resize(before);  // nothing half-done from a failed test
    return status;
  }
  for (size_t k = before; k < out.size(); ++k) {
    if (swapped) swap_sides(out[k]);
    out[k].body_a = ia, out[k].body_b = ib;
  }
  return status;
}

CommonRegion common_region(const std::vector<Polygon2>& a, const std::vector<Polygon2>& b, double tol) {
  CommonRegion region;
  if (a.empty() || b.empty()) return region;
  if (!box_of(a).meets(box_of(b), tol)) return region;
  const EdgeGrid grid_a(a, tol), grid_b(b, tol);
  // Green's sums about a point of the common box: where the two boundaries
  // part within tolerance, the round-off of the pieces does not grow with the
  // distance to the frame's origin.
  const Box2 box_a = box_of(a), box_b = box_of(b);
  const Point2 origin{(std::max(box_a.xmin, box_b.xmin) + std::min(box_a.xmax, box_b.xmax)) / 2,
                      (std::max(box_a.ymin, box_b.ymin) + std::min(box_a.ymax, box_b.ymax)) / 2};
  const double twice = boundary_inside(a, grid_b, true, tol, origin, region.perimeter) +
                       boundary_inside(b, grid_a, false, tol, origin, region.perimeter);
  region.area = std::max(0.0, twice / 2.0);
  return region;
}

double common_area(const std::vector<Polygon2>& a, const std::vector<Polygon2>& b, double tol) {
  return common_region(a, b, tol).area;
}

}  // namespace contactcore
