// Plane outlines (stage 2, used by the planar common areas of stage 3): edge
// discretisation, the outline polygons with the bulge of each chord, and the
// same outline seen from another plane frame.
#include "partitions/outlines.h"

#include <algorithm>
#include <cmath>

#include <Adaptor3d_Curve.hxx>
#include <BRepTools_WireExplorer.hxx>
#include <BRep_Tool.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Iterator.hxx>
#include <TopoDS_Wire.hxx>
#include <gp_Circ.hxx>

#include "common/quadrature.h"
#include "common/xyz_components.h"
#include "contactcore/common/angles.h"

namespace contactcore {
namespace detail {

namespace {

// Fewest points a full circle gets, whatever the sag allows: keeps the
// polygon's crossings with other edges where the arc's are.
constexpr int kMinCircleSegments = 64;

// Unit tangent of a curve at t; a zero vector where the derivative vanishes.
gp_XYZ unit_tangent(const Adaptor3d_Curve& curve, double t) {
  gp_Pnt p;
  gp_Vec d;
  curve.D1(t, p, d);
  const double length = d.Magnitude();
  return length > 0 ? d.XYZ() / length : gp_XYZ(0, 0, 0);
}

double angle_between(const gp_XYZ& a, const gp_XYZ& b) {
  return std::atan2((a ^ b).Modulus(), a * b);
}

// Parameters along a free-form curve (both ends included, ascending): cut at
// its knots (a C2 spline is still piecewise) and each span in four parts whose
// tangent turning sets their count (cheaper than GCPnts_TangentialDeflection,
// which minimises per segment).
void free_curve_parameters(const BRepAdaptor_Curve& curve, double arc_step, std::vector<double>& parameters) {
  const double first = curve.FirstParameter(), last = curve.LastParameter();
  std::vector<double> knots{first};
  if (curve.GetType() == GeomAbs_BSplineCurve || curve.GetType() == GeomAbs_BezierCurve) {
    const int spans = curve.NbIntervals(GeomAbs_CN);
    TColStd_Array1OfReal breaks(1, spans + 1);
    curve.Intervals(breaks, GeomAbs_CN);
    for (int i = 2; i <= spans; ++i)
      if (breaks(i) > knots.back() && breaks(i) < last) knots.push_back(breaks(i));
  } else {
    for (int i = 1; i < 8; ++i) knots.push_back(first + (last - first) * i / 8);
  }
  knots.push_back(last);
  constexpr int kParts = 4;
  parameters.clear();
  for (std::size_t k = 0; k + 1 < knots.size(); ++k) {
    const double a = knots[k], b = knots[k + 1];
    gp_XYZ previous = unit_tangent(curve, a);
    for (int part = 0; part < kParts; ++part) {
      const double pa = a + (b - a) * part / kParts, pb = a + (b - a) * (part + 1) / kParts;
      const gp_XYZ mid = unit_tangent(curve, (pa + pb) / 2), end = unit_tangent(curve, pb);
      const double turning = angle_between(previous, mid) + angle_between(mid, end);
      const int segments = std::max(1, static_cast<int>(std::ceil(turning / arc_step)));
      for (int i = 0; i < segments; ++i) parameters.push_back(pa + (pb - pa) * i / segments);
      previous = end;
    }
  }
  parameters.push_back(last);
}

// Twice the signed area swept by a curve about `origin` in the plane (x, y):
// the boundary integral of x dy - y dx (Green), by Gauss on `breaks`.
double twice_swept_area(const BRepAdaptor_Curve& curve, const gp_XYZ& origin, const gp_XYZ& x_dir,
                        const gp_XYZ& y_dir, std::vector<double>& breaks) {
  return curve_integral(curve, breaks, [&](const gp_XYZ& p, const gp_XYZ& d) {
    const gp_XYZ r = p - origin;
    return (r * x_dir) * (d * y_dir) - (r * y_dir) * (d * x_dir);
  });
}

// Plane frame: origin, axes, normal (x ^ y).
struct PlaneFrame {
  gp_XYZ origin, x, y, normal;
  Point2 project(const gp_XYZ& p) const {
    const gp_XYZ d = p - origin;
    return {d * x, d * y};
  }
};

int circle_segments(double radius, double sag) {
  const double max_step = 2 * std::acos(std::max(-1.0, 1 - sag / radius));
  int segments = kMinCircleSegments;
  while (kTwoPi / segments > max_step && segments < (1 << 20)) segments *= 2;
  return segments;
}

// A free-form edge that is a circular arc within a tenth of `sag` (B-spline
// circles are common in exported files): its centre, radius and the points
// of its outline, cut on the same canonical grid as true circles so that it
// meets a circle or another such arc of another face point for point. The
// points run in the face's direction, all but the last; false when the curve
// is no such arc.
bool outline_circular_arc(const BRepAdaptor_Curve& curve, bool reversed, const PlaneFrame& frame, double sag,
                          const Point2& grid_ref, Polygon2& loop) {
  constexpr int kSamples = 17;
  const double first = curve.FirstParameter(), last = curve.LastParameter();
  std::vector<Point2> p(kSamples);
  for (int i = 0; i < kSamples; ++i) {
    const double t = reversed ? last - (last - first) * i / (kSamples - 1) : first + (last - first) * i / (kSamples - 1);
    p[i] = frame.project(curve.Value(t).XYZ());
  }
  // Circumcentre of the ends and the middle (of the first half for a closed curve).
  const Point2 a = p[0], b = p[kSamples / 4], c = p[kSamples / 2];
  const double d = 2 * ((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
  const double ab = (b.x - a.x) * (b.x - a.x) + (b.y - a.y) * (b.y - a.y);
  const double ac = (c.x - a.x) * (c.x - a.x) + (c.y - a.y) * (c.y - a.y);
  if (std::fabs(d) <= 1e-12 * (ab + ac)) return false;
  const Point2 centre{a.x + ((c.y - a.y) * ab - (b.y - a.y) * ac) / d, a.y + ((b.x - a.x) * ac - (c.x - a.x) * ab) / d};
  const double radius = std::hypot(a.x - centre.x, a.y - centre.y);
  double sweep = 0, previous = std::atan2(a.y - centre.y, a.x - centre.x);
  const double start = previous;
  for (int i = 0; i < kSamples; ++i) {
    if (std::fabs(std::hypot(p[i].x - centre.x, p[i].y - centre.y) - radius) > 0.1 * sag) return false;
    if (i == 0) continue;
    const double angle = std::atan2(p[i].y - centre.y, p[i].x - centre.x);
    const double step = std::remainder(angle - previous, kTwoPi);
    if (sweep != 0 && step * sweep < 0) return false;  // turns back: not an arc
    sweep += step;
    previous = angle;
  }
  const double step = kTwoPi / circle_segments(radius, sag);
  const double phase = std::atan2(grid_ref.y, grid_ref.x);
  std::vector<double> angles{start};
  const double end = start + sweep, margin = 1e-6 * step;
  if (sweep > 0) {
    for (double k = std::floor((start - phase) / step) + 1;; ++k) {
      const double u = phase + k * step;
      if (u >= end - margin) break;
      if (u > start + margin) angles.push_back(u);
    }
  } else {
    for (double k = std::ceil((start - phase) / step) - 1;; --k) {
      const double u = phase + k * step;
      if (u <= end + margin) break;
      if (u < start - margin) angles.push_back(u);
    }
  }
  angles.push_back(end);
  for (std::size_t i = 0; i + 1 < angles.size(); ++i) {
    const double delta = angles[i + 1] - angles[i];
    Point2 q = i == 0 ? a : Point2{centre.x + radius * std::cos(angles[i]), centre.y + radius * std::sin(angles[i])};
    q.bulge = radius * radius * (delta - std::sin(delta));
    loop.push_back(q);
  }
  return true;
}

// Appends an edge's outline points (all but its last one, which the next
// edge starts with) in the direction the face runs along it, each with the
// bulge of the curve beyond the chord to the next point: twice the signed
// area between the curve piece and the chord (positive where the curve swings
// counter-clockwise of the chord).
void outline_edge(const TopoDS_Edge& edge, const PlaneFrame& frame, double sag, const gp_XYZ& grid_ref,
                  Polygon2& loop) {
  const BRepAdaptor_Curve curve(edge);
  const bool reversed = edge.Orientation() == TopAbs_REVERSED;
  const double first = curve.FirstParameter();
  double last = curve.LastParameter();
  std::vector<double> t;
  std::vector<double> bulge;  // of the chord (t[i], t[i + 1]) run forward
  // A damaged circle edge can span 4e11 rad (make fuzz): at most one turn.
  if (curve.GetType() == GeomAbs_Circle && last - first > kTwoPi) last = first + kTwoPi;
  switch (curve.GetType()) {
    case GeomAbs_Line: t = {first, last}, bulge = {0.0}; break;
    case GeomAbs_Circle: {
      const gp_Circ circle = curve.Circle();
      const double r = circle.Radius();
      const double step = kTwoPi / circle_segments(r, sag);
      const gp_XYZ cx = circle.XAxis().Direction().XYZ(), cy = circle.YAxis().Direction().XYZ();
      const double phase = std::atan2(grid_ref * cy, grid_ref * cx);  // grid angle 0, in the circle's parameter
      const double margin = 1e-6 * step;
      t.push_back(first);
      for (double k = std::floor((first - phase) / step) + 1;; ++k) {
        const double u = phase + k * step;
        if (u >= last - margin) break;
        if (u > first + margin) t.push_back(u);
      }
      t.push_back(last);
      // Parameter increasing: counter-clockwise about the circle's axis.
      const double turn = circle.Axis().Direction().XYZ() * frame.normal > 0 ? 1.0 : -1.0;
      for (std::size_t i = 0; i + 1 < t.size(); ++i) {
        const double delta = t[i + 1] - t[i];
        bulge.push_back(turn * r * r * (delta - std::sin(delta)));
      }
      break;
    }
    default: {
      const Point2 grid{grid_ref * frame.x, grid_ref * frame.y};
      if (outline_circular_arc(curve, reversed, frame, sag, grid, loop)) return;
      free_curve_parameters(curve, kArcStep, t);
      for (std::size_t i = 0; i + 1 < t.size(); ++i) {
        const gp_XYZ start = curve.Value(t[i]).XYZ();
        bulge.push_back(gauss(t[i], t[i + 1], [&](double s) {
          gp_Pnt p;
          gp_Vec d;
          curve.D1(s, p, d);
          return ((p.XYZ() - start) ^ d.XYZ()) * frame.normal;
        }));
      }
      break;
    }
  }
  const std::size_t n = t.size();
  for (std::size_t k = 0; k + 1 < n; ++k) {
    const std::size_t i = reversed ? n - 1 - k : k;  // point index, run in the face's direction
    Point2 p = frame.project(curve.Value(t[i]).XYZ());
    p.bulge = reversed ? -bulge[i - 1] : bulge[i];
    loop.push_back(p);
  }
}

}  // namespace

// Points along an edge's curve, both ends included, in the edge's direction
// when `reversed` is false, no two consecutive ones more than `arc_step` apart
// in tangent direction: lines give their ends, circles uniform steps (by a
// rotation recurrence: no sin/cos per point), other curves as
// free_curve_parameters cuts them.
void discretise_curve(const BRepAdaptor_Curve& curve, bool reversed, std::vector<gp_Pnt>& points, double arc_step) {
  const std::size_t first_index = points.size();
  const double first = curve.FirstParameter(), last = curve.LastParameter();
  switch (curve.GetType()) {
    case GeomAbs_Line: points.push_back(curve.Value(first)); break;
    case GeomAbs_Circle: {
      const gp_Circ circle = curve.Circle();
      const int segments = std::max(1, static_cast<int>(std::ceil((last - first) / arc_step)));
      const double step = (last - first) / segments, cos_step = std::cos(step), sin_step = std::sin(step);
      const gp_XYZ centre = circle.Location().XYZ();
      const gp_XYZ x = circle.XAxis().Direction().XYZ() * circle.Radius();
      const gp_XYZ y = circle.YAxis().Direction().XYZ() * circle.Radius();
      double c = std::cos(first), s = std::sin(first);
      for (int i = 0; i < segments; ++i) {
        points.push_back(gp_Pnt(centre + x * c + y * s));
        const double next_c = c * cos_step - s * sin_step;
        s = s * cos_step + c * sin_step;
        c = next_c;
      }
      break;
    }
    default: {
      std::vector<double> parameters;
      free_curve_parameters(curve, arc_step, parameters);
      for (std::size_t k = 0; k + 1 < parameters.size(); ++k) points.push_back(curve.Value(parameters[k]));
      break;
    }
  }
  points.push_back(curve.Value(last));
  if (reversed) std::reverse(points.begin() + first_index, points.end());
}

void discretise_edge(const TopoDS_Edge& edge, std::vector<gp_Pnt>& points, double arc_step) {
  discretise_curve(BRepAdaptor_Curve(edge), edge.Orientation() == TopAbs_REVERSED, points, arc_step);
}

bool bounds_the_face(const TopoDS_Edge& edge) {
  return edge.Orientation() == TopAbs_FORWARD || edge.Orientation() == TopAbs_REVERSED;
}

gp_Dir canonical_plane_ref(const gp_Dir& normal) {
  // The normal's line as a vector whose largest component is positive, then
  // the perpendicular towards the axis it is least along.
  const double c[3] = {normal.X(), normal.Y(), normal.Z()};
  int largest = 0, smallest = 0;
  for (int i = 1; i < 3; ++i) {
    if (std::fabs(c[i]) > std::fabs(c[largest])) largest = i;
    if (std::fabs(c[i]) < std::fabs(c[smallest])) smallest = i;
  }
  const gp_XYZ line = normal.XYZ() * (c[largest] > 0 ? 1.0 : -1.0);
  const gp_XYZ towards = xyz_unit(smallest);  // not SetCoord: common/xyz_components.h
  const gp_XYZ ref = towards - line * (towards * line);
  return gp_Dir(ref);
}

double signed_area(const Polygon2& loop) {
  double twice = 0;
  for (std::size_t i = 0, n = loop.size(); i < n; ++i) {
    const Point2& a = loop[i];
    const Point2& b = loop[(i + 1) % n];
    twice += a.x * b.y - b.x * a.y + a.bulge;
  }
  return twice / 2;
}

void reverse_loop(Polygon2& loop) {
  const std::size_t n = loop.size();
  if (n == 0) return;
  // Point i+1 now leads the chord back to point i: that chord's bulge, negated.
  std::vector<double> bulges(n);
  for (std::size_t i = 0; i < n; ++i) bulges[(i + 1) % n] = -loop[i].bulge;
  for (std::size_t i = 0; i < n; ++i) loop[i].bulge = bulges[i];
  std::reverse(loop.begin(), loop.end());
}

// Wires are read in their stored order, which chains their edges almost
// always; a wire that does not chain is re-read through BRepTools_WireExplorer
// (which builds vertex maps, and OuterWire would project pcurves on planes:
// both avoided on the fast path). The outer loop is the largest (it encloses
// the others).
std::vector<Polygon2> plane_outline(const TopoDS_Face& face, const gp_XYZ& origin, const gp_XYZ& x_dir,
                                    const gp_XYZ& y_dir, double sag, double* area) {
  const PlaneFrame frame{origin, x_dir, y_dir, x_dir ^ y_dir};
  const gp_XYZ grid_ref = canonical_plane_ref(gp_Dir(frame.normal)).XYZ();
  std::vector<Polygon2> loops;
  std::vector<double> breaks;
  double twice_area = 0;
  for (TopExp_Explorer wires(face, TopAbs_WIRE); wires.More(); wires.Next()) {
    const TopoDS_Wire& wire = TopoDS::Wire(wires.Current());
    Polygon2 loop;
    bool chained = true;
    gp_Pnt previous_end;
    double previous_tolerance = 0;
    // A reversed wire lists its edges backwards: walk it forward (the loop is
    // re-oriented below) and count its orientation in the area's sign only.
    const bool wire_reversed = wire.Orientation() == TopAbs_REVERSED;
    for (TopoDS_Iterator it(wire.Oriented(TopAbs_FORWARD)); it.More(); it.Next()) {
      const TopoDS_Edge& edge = TopoDS::Edge(it.Value());
      if (BRep_Tool::Degenerated(edge) || !bounds_the_face(edge)) continue;
      const bool reversed = edge.Orientation() == TopAbs_REVERSED;
      if (area) {
        const double swept = twice_swept_area(BRepAdaptor_Curve(edge), origin, x_dir, y_dir, breaks);
        twice_area += reversed != wire_reversed ? -swept : swept;
      }
      if (!chained) continue;  // keep summing the area; the loop is redone below
      const BRepAdaptor_Curve curve(edge);
      const gp_Pnt start = curve.Value(reversed ? curve.LastParameter() : curve.FirstParameter());
      const gp_Pnt end = curve.Value(reversed ? curve.FirstParameter() : curve.LastParameter());
      const double tolerance = BRep_Tool::Tolerance(edge);
      if (!loop.empty() && start.Distance(previous_end) > 2 * std::max(tolerance, previous_tolerance) + 1e-7) {
        chained = false;
        continue;
      }
      outline_edge(edge, frame, sag, grid_ref, loop);
      previous_end = end;
      previous_tolerance = tolerance;
    }
    if (!chained) {
      loop.clear();
      for (BRepTools_WireExplorer edges(wire, face); edges.More(); edges.Next()) {
        if (BRep_Tool::Degenerated(edges.Current())) continue;
        outline_edge(edges.Current(), frame, sag, grid_ref, loop);
      }
    }
    if (loop.size() >= 2) loops.push_back(std::move(loop));
  }
  if (area) *area = std::fabs(twice_area) / 2;
  std::size_t outer = 0;
  std::vector<double> areas(loops.size());
  for (std::size_t i = 0; i < loops.size(); ++i) {
    areas[i] = signed_area(loops[i]);
    if (std::fabs(areas[i]) > std::fabs(areas[outer])) outer = i;
  }
  for (std::size_t i = 0; i < loops.size(); ++i)
    if ((i == outer) != (areas[i] > 0)) reverse_loop(loops[i]);
  return loops;
}

}  // namespace detail

std::vector<Polygon2> outline_in(const FaceInfo& face, const gp_Pnt& origin, const gp_Dir& x_dir,
                                 const gp_Dir& y_dir) {
  const gp_XYZ own_x = face.extent.ref_dir.XYZ(), own_y = face.params.axis.XYZ() ^ own_x;
  const gp_XYZ shift = face.params.location.XYZ() - origin.XYZ();
  // 2x2 map of the face's plane coordinates to the requested ones.
  const double xx = own_x * x_dir.XYZ(), xy = own_y * x_dir.XYZ();
  const double yx = own_x * y_dir.XYZ(), yy = own_y * y_dir.XYZ();
  const double x0 = shift * x_dir.XYZ(), y0 = shift * y_dir.XYZ();
  const bool mirrored = xx * yy - xy * yx < 0;
  std::vector<Polygon2> loops;
  loops.reserve(face.extent.outline.size());
  for (const Polygon2& loop : face.extent.outline) {
    Polygon2 mapped;
    mapped.reserve(loop.size());
    // A mirror turns the bulges' sense; reversing the loop turns it back.
    for (const Point2& p : loop)
      mapped.push_back({x0 + xx * p.x + xy * p.y, y0 + yx * p.x + yy * p.y, mirrored ? -p.bulge : p.bulge});
    if (mirrored) detail::reverse_loop(mapped);
    loops.push_back(std::move(mapped));
  }
  return loops;
}

}  // namespace contactcore
