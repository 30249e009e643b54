// Typing one face: analytic surfaces read from OCCT's adaptor (parameters in
// global coordinates, extent, exact area by Green's theorem on the boundary,
// material side, box), free-form ones handed to the fits
// (surface_fitting.cpp), plane outlines to outlines.cpp.
#include "partitions/face_typing.h"

#include "partitions/outlines.h"
#include "contactcore/common/out_of_memory.h"
#include "common/quadrature.h"
#include "common/xyz_components.h"
#include "partitions/surface_fitting.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <exception>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <Adaptor3d_Surface.hxx>
#include <BRepAdaptor_Curve.hxx>
#include <BRepAdaptor_Curve2d.hxx>
#include <BRepAdaptor_Surface.hxx>
#include <BRepBndLib.hxx>
#include <BRepClass_FaceClassifier.hxx>
#include <BRepGProp.hxx>
#include <BRepTopAdaptor_FClass2d.hxx>
#include <BRep_Tool.hxx>
#include <BndLib_AddSurface.hxx>
#include <GProp_GProps.hxx>
#include <Precision.hxx>
#include <Standard_Failure.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <gp_Ax2.hxx>
#include <gp_Cone.hxx>
#include <gp_Cylinder.hxx>
#include <gp_Lin2d.hxx>
#include <gp_Pln.hxx>
#include <gp_Sphere.hxx>
#include <gp_Torus.hxx>

namespace contactcore {

using namespace detail;

namespace {

// Recognised revolution faces: their edges are sampled this finely (radians
// of tangent turning) to measure the angles and axial range they sweep.
constexpr double kCoverageStep = 0.05;

// Samples of a meridian for swept boxes and axial ranges of surfaces of
// revolution.
constexpr int kMeridianSamples = 32;

// Relative precision of OCCT's adaptive area integration, used only for
// recognised spheres and tori (no boundary formula here: poles, tube angle).
constexpr double kFittedAreaPrecision = 1e-6;

// ---------------------------------------------------------------------------
// Frames, extents and angles.

struct Frame {
  gp_XYZ origin;
  gp_XYZ axis;  // unit
  gp_XYZ ref;   // unit, perpendicular to axis
  gp_XYZ binormal() const { return axis ^ ref; }
};

Frame frame_of(const gp_Pnt& origin, const gp_Dir& axis, const gp_Dir& ref) {
  return {origin.XYZ(), axis.XYZ(), ref.XYZ()};
}

// A reference direction perpendicular to `axis` close to `hint` (any when
// `hint` is parallel to the axis).
gp_Dir perpendicular_ref(const gp_Dir& axis, const gp_XYZ& hint) {
  const gp_XYZ a = axis.XYZ();
  const gp_XYZ projected = hint - a * (hint * a);
  if (projected.Modulus() > 1e-9) return gp_Dir(projected);
  return gp_Dir(perpendicular_basis(axis).first);
}

AngularInterval interval_from(double first, double last, double orientation_sign) {
  const double span = std::min(last - first, kTwoPi);
  if (span >= kTwoPi - kAngularJoinGap) return {0, kTwoPi};
  return {wrap_angle(orientation_sign > 0 ? first : -last), std::max(span, 0.0)};
}

// Angular interval of a parameter range [u1, u2] of a revolution surface
// whose frame is (x_dir, y_dir) about `axis`, seen from the frame (axis, x_dir).
AngularInterval surface_interval(double u1, double u2, const gp_Dir& axis, const gp_Dir& x_dir,
                                 const gp_Dir& y_dir) {
  const double sign = y_dir.Dot(axis.Crossed(x_dir)) >= 0 ? 1.0 : -1.0;
  return interval_from(u1, u2, sign);
}

// Axial range and angular coverage of a face about `frame`, from its edges:
// each edge sweeps a range of angles (unwrapped along the edge), and the face
// covers the union of them (a connected face on a cylinder, cone or torus
// projects onto the angles its boundary does). Axial extremes between samples
// come from a parabola through the three samples around them. Sphere and
// torus extremes can lie inside the face: interior points of the UV domain
// count too. A sphere face holding a pole of the frame axis goes all the way
// round, which its boundary cannot show (a whole sphere is bounded by one
// meridian): the poles are classified on the face.
Extent extent_from_geometry(const TopoDS_Face& face, const SurfaceParams& params, const Frame& frame,
                            double tolerance) {
  const gp_XYZ binormal = frame.binormal();
  double axial_min = 1e300, axial_max = -1e300;
  auto add_height = [&](double h) {
    axial_min = std::min(axial_min, h);
    axial_max = std::max(axial_max, h);
  };
  std::vector<AngularInterval> swept;
  std::vector<gp_Pnt> points;
  std::vector<double> heights;
  for (TopExp_Explorer edges(face, TopAbs_EDGE); edges.More(); edges.Next()) {
    const TopoDS_Edge& edge = TopoDS::Edge(edges.Current());
    if (BRep_Tool::Degenerated(edge)) continue;
    points.clear();
    discretise_edge(edge, points, kCoverageStep);
    heights.clear();
    bool started = false;
    double angle = 0, low = 0, high = 0;
    for (const gp_Pnt& p : points) {
      const gp_XYZ d = p.XYZ() - frame.origin;
      heights.push_back(d * frame.axis);
      const double x = d * frame.ref, y = d * binormal;
      if (std::hypot(x, y) <= 1e-9 * (1 + d.Modulus())) continue;  // on the axis: no angle
      const double a = std::atan2(y, x);
      if (!started) {
        angle = low = high = a;
        started = true;
        continue;
      }
      angle += std::remainder(a - angle, kTwoPi);  // unwrapped: steps are far below pi
      low = std::min(low, angle);
      high = std::max(high, angle);
    }
    for (std::size_t i = 0; i < heights.size(); ++i) {
      add_height(heights[i]);
      if (i == 0 || i + 1 == heights.size()) continue;
      const double a = heights[i - 1], b = heights[i], c = heights[i + 1];
      const double curvature = a - 2 * b + c;
      if ((b - a) * (c - b) < 0 && curvature != 0) add_height(b - (c - a) * (c - a) / (8 * curvature));
    }
    if (started && high > low) swept.push_back(high - low >= kTwoPi ? AngularInterval{0, kTwoPi}
                                                                    : AngularInterval{wrap_angle(low), high - low});
  }
  if (params.kind == SurfaceKind::Sphere || params.kind == SurfaceKind::Torus) {
    const BRepAdaptor_Surface surface(face, Standard_False);
    const UVBounds uv = uv_bounds(face);
    BRepTopAdaptor_FClass2d classifier(face, Precision::PConfusion());
    for (int i = 0; i < kCheckGrid; ++i) {
      for (int j = 0; j < kCheckGrid; ++j) {
        const gp_Pnt2d p(uv.u1 + (uv.u2 - uv.u1) * i / (kCheckGrid - 1), uv.v1 + (uv.v2 - uv.v1) * j / (kCheckGrid - 1));
        if (classifier.Perform(p) == TopAbs_IN) add_height((surface.Value(p.X(), p.Y()).XYZ() - frame.origin) * frame.axis);
      }
    }
  }
  if (params.kind == SurfaceKind::Sphere) {
    for (double side : {1.0, -1.0}) {
      const gp_Pnt pole(params.location.XYZ() + frame.axis * (side * params.radius));
      BRepClass_FaceClassifier classifier(face, pole, tolerance);
      if (classifier.State() == TopAbs_IN || classifier.State() == TopAbs_ON) {
        add_height((pole.XYZ() - frame.origin) * frame.axis);
        swept.push_back({0, kTwoPi});
      }
    }
  }
  Extent extent;
  extent.ref_dir = gp_Dir(frame.ref);
  if (axial_min > axial_max) return extent;
  extent.axial_min = axial_min;
  extent.axial_max = axial_max;
  extent.angular = unite(std::move(swept));
  return extent;
}

// ---------------------------------------------------------------------------
// Areas by Green's theorem on the boundary: exact for analytic surfaces and
// far cheaper than BRepGProp::SurfaceProperties, which integrates over the
// domain (~100 us a face) and is off by up to 0.5 % on faces bounded by
// B-spline edges unless run adaptively (slower still).

// Area of a face on an analytic revolution surface whose area element
// |S_u x S_v| = J(v) depends on v only: the integral of J over the UV domain
// is the boundary integral of G(v) du with G' = J (Green), on the pcurves.
// Seams (du = 0) add nothing; degenerate edges at poles do and are kept.
template <class Primitive>
double uv_area(const TopoDS_Face& face, Primitive primitive_of_j) {
  std::vector<double> breaks;
  double total = 0;
  for (TopExp_Explorer edges(face, TopAbs_EDGE); edges.More(); edges.Next()) {
    const TopoDS_Edge& edge = TopoDS::Edge(edges.Current());
    if (!bounds_the_face(edge)) continue;
    const BRepAdaptor_Curve2d pcurve(edge, face);
    const double first = pcurve.FirstParameter(), last = pcurve.LastParameter();
    double sum = 0;
    if (pcurve.GetType() == GeomAbs_Line) {
      const gp_Lin2d line = pcurve.Line();
      const double du = line.Direction().X(), dv = line.Direction().Y();
      if (du == 0) continue;
      const double v0 = line.Location().Y();
      // Pieces of at most 0.5 rad in v keep Gauss exact on sin and cos.
      const int pieces = std::max(1, static_cast<int>(std::ceil(std::fabs(dv * (last - first)) / 0.5)));
      for (int i = 0; i < pieces; ++i) {
        const double a = first + (last - first) * i / pieces, b = first + (last - first) * (i + 1) / pieces;
        sum += gauss(a, b, [&](double t) { return primitive_of_j(v0 + t * dv) * du; });
      }
    } else {
      integration_pieces(pcurve, first, last, breaks);
      for (std::size_t i = 0; i + 1 < breaks.size(); ++i) {
        sum += gauss(breaks[i], breaks[i + 1], [&](double t) {
          gp_Pnt2d p;
          gp_Vec2d d;
          pcurve.D1(t, p, d);
          // Meridians and seams stored as B-splines: du = 0, skip G (which
          // can cost an integration on surfaces of revolution).
          if (std::fabs(d.X()) <= 1e-12 * std::fabs(d.Y())) return 0.0;
          return primitive_of_j(p.Y()) * d.X();
        });
      }
    }
    total += edge.Orientation() == TopAbs_REVERSED ? -sum : sum;
  }
  return std::fabs(total);
}

// Area of a face on a recognised cylinder or cone from its 3D boundary in
// (angle, axial) coordinates about the fitted axis: the area element is
// r d(theta) dh on a cylinder and s sin(a) d(theta) ds on a cone (s the
// distance from the apex), so Green needs G = r h or s^2 sin(a) / 2.
double fitted_revolution_area(const TopoDS_Face& face, const SurfaceParams& params) {
  const auto basis = perpendicular_basis(params.axis);
  const gp_XYZ e1 = basis.first, e2 = basis.second;  // not a structured binding: lambdas below use them (clang 14)
  const gp_XYZ origin = params.location.XYZ(), axis = params.axis.XYZ();
  const bool cone = params.kind == SurfaceKind::Cone;
  const double half_sin = std::sin(params.half_angle) / 2;
  std::vector<double> breaks;
  double total = 0;
  for (TopExp_Explorer edges(face, TopAbs_EDGE); edges.More(); edges.Next()) {
    const TopoDS_Edge& edge = TopoDS::Edge(edges.Current());
    if (BRep_Tool::Degenerated(edge) || !bounds_the_face(edge)) continue;
    const double sum = curve_integral(BRepAdaptor_Curve(edge), breaks, [&](const gp_XYZ& p, const gp_XYZ& d) {
      const gp_XYZ r = p - origin;
      const double x = r * e1, y = r * e2, rho2 = x * x + y * y;
      if (rho2 <= 0) return 0.0;
      const double dtheta = (x * (d * e2) - y * (d * e1)) / rho2;
      const double g = cone ? r.SquareModulus() * half_sin : params.radius * (r * axis);
      return g * dtheta;
    });
    total += edge.Orientation() == TopAbs_REVERSED ? -sum : sum;
  }
  return std::fabs(total);
}

// Box of the patch swept by meridian points (taken at u = 0) turning by u in
// [u1, u2] counter-clockwise about `axis`: per coordinate each point's arc is
// c + a cos(u) + b sin(u), extreme at the ends or where tan(u) = b / a.
// Between samples a meridian of radius of curvature R bulges by at most
// chord^2 / (8 R) (R = 0: straight). Tight where BndLib_AddSurface is loose
// (tori) or samples too little (surfaces of revolution).
Bnd_Box swept_box(const std::vector<gp_XYZ>& meridian, const gp_Ax1& axis, double u1, double u2,
                  double meridian_radius, double tolerance) {
  const gp_XYZ axis_point = axis.Location().XYZ(), axis_dir = axis.Direction().XYZ();
  Bnd_Box box;
  double longest_chord = 0;
  for (std::size_t i = 0; i < meridian.size(); ++i) {
    if (i > 0) longest_chord = std::max(longest_chord, (meridian[i] - meridian[i - 1]).Modulus());
    const gp_XYZ centre = axis_point + axis_dir * ((meridian[i] - axis_point) * axis_dir);
    const gp_XYZ radial = meridian[i] - centre, turned = axis_dir ^ radial;
    double lo[3], hi[3];
    for (int k = 0; k < 3; ++k) {
      // Not Coord(k + 1): common/xyz_components.h.
      const double a = xyz_component(radial, k), b = xyz_component(turned, k), mid = xyz_component(centre, k);
      auto value = [&](double u) { return mid + a * std::cos(u) + b * std::sin(u); };
      if (!(u2 - u1 < 2 * kPi)) {  // a whole turn or more (a damaged range of 6.8e6 rad: make fuzz), NaN too
        const double reach = std::hypot(a, b);
        lo[k] = mid - reach;
        hi[k] = mid + reach;
        continue;
      }
      lo[k] = std::min(value(u1), value(u2));
      hi[k] = std::max(value(u1), value(u2));
      const double phi = std::atan2(b, a);  // at most three extremes below: the range is under a turn
      for (double u = phi + kPi * std::ceil((u1 - phi) / kPi); u <= u2; u += kPi) {
        lo[k] = std::min(lo[k], value(u));
        hi[k] = std::max(hi[k], value(u));
      }
    }
    box.Update(lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]);
  }
  const double bulge = meridian_radius > 0 ? longest_chord * longest_chord / (8 * meridian_radius) : 0;
  box.Enlarge(bulge + tolerance);
  return box;
}

// Points of the meridian u = 0 over [v1, v2].
std::vector<gp_XYZ> meridian_points(const Adaptor3d_Surface& surface, double v1, double v2, int segments) {
  std::vector<gp_XYZ> points;
  points.reserve(segments + 1);
  for (int i = 0; i <= segments; ++i) points.push_back(surface.Value(0, v1 + (v2 - v1) * i / segments).XYZ());
  return points;
}

// A face on OCCT's surface of revolution (a meridian curve C(v) turned by
// the angle u about an axis) that was recognised as a revolution surface:
// measured exactly instead of through its boundary samples. By symmetry the
// area element J = |S_u x S_v| depends on v only, so the area is the same
// boundary integral as on analytic surfaces with G(v) = integral of J,
// tabulated by Gauss on the face's v range; u is the angle about the axis, so
// the angular extent is the u range and the axial one the meridian's range.
// False (nothing changed) when the meridian does not lie in one plane
// through the axis, where u is no longer the angle.
bool measure_surface_of_revolution(const TopoDS_Face& face, const BRepAdaptor_Surface& surface,
                                   const UVBounds& uv, FaceInfo& out) {
  const gp_Ax1 revolution = surface.AxeOfRevolution();
  const gp_XYZ axis_point = revolution.Location().XYZ(), axis_dir = revolution.Direction().XYZ();
  const SurfaceParams& s = out.params;
  auto radial = [&](const gp_XYZ& p) {
    const gp_XYZ rel = p - axis_point;
    return rel - axis_dir * (rel * axis_dir);
  };
  // The meridian at u = 0, sampled to check it is planar and for the axial range.
  const gp_XYZ mid_radial = radial(surface.Value(0, (uv.v1 + uv.v2) / 2).XYZ());
  if (mid_radial.Modulus() <= Precision::Confusion()) return false;
  const gp_Dir ref(mid_radial);
  std::vector<double> heights;
  std::vector<gp_XYZ> meridian;
  for (int i = 0; i <= kMeridianSamples; ++i) {
    const gp_XYZ p = surface.Value(0, uv.v1 + (uv.v2 - uv.v1) * i / kMeridianSamples).XYZ();
    const gp_XYZ r = radial(p);
    if (r.Modulus() > 1e-9 * (1 + p.Modulus()) && std::fabs((r ^ ref.XYZ()) * axis_dir) > 1e-9 * r.Modulus())
      return false;  // off the meridian plane
    heights.push_back((p - s.location.XYZ()) * s.axis.XYZ());
    meridian.push_back(p);
  }
  const double meridian_radius = s.kind == SurfaceKind::Torus    ? s.minor_radius
                                 : s.kind == SurfaceKind::Sphere ? s.radius
                                                                 : 0;
  out.box = swept_box(meridian, revolution, uv.u1, uv.u2, meridian_radius, BRep_Tool::Tolerance(face));
  double axial_min = 1e300, axial_max = -1e300;
  for (std::size_t i = 0; i < heights.size(); ++i) {
    axial_min = std::min(axial_min, heights[i]);
    axial_max = std::max(axial_max, heights[i]);
    if (i == 0 || i + 1 == heights.size()) continue;
    const double a = heights[i - 1], b = heights[i], c = heights[i + 1], curvature = a - 2 * b + c;
    if ((b - a) * (c - b) < 0 && curvature != 0) {
      axial_min = std::min(axial_min, b - (c - a) * (c - a) / (8 * curvature));
      axial_max = std::max(axial_max, b - (c - a) * (c - a) / (8 * curvature));
    }
  }
  // G(v) tabulated at the nodes of [v1, v2], Gauss in between.
  constexpr int kNodes = 32;
  auto element = [&](double v) {
    gp_Pnt p;
    gp_Vec du, dv;
    surface.D1(0, v, p, du, dv);
    return du.Crossed(dv).Magnitude();
  };
  const double step = (uv.v2 - uv.v1) / kNodes;
  std::array<double, kNodes + 1> table{};
  for (int i = 0; i < kNodes; ++i) table[i + 1] = table[i] + gauss(uv.v1 + i * step, uv.v1 + (i + 1) * step, element);
  auto primitive = [&](double v) {
    const int node = std::clamp(static_cast<int>(std::floor((v - uv.v1) / step + 0.5)), 0, kNodes);
    const double v_node = uv.v1 + node * step;
    return table[node] + gauss(v_node, v, element);
  };
  out.area = step > 0 ? uv_area(face, primitive) : 0;
  Extent& e = out.extent;
  e.ref_dir = ref;
  e.axial_min = axial_min;
  e.axial_max = axial_max;
  e.angular = {interval_from(uv.u1, uv.u2, s.axis.XYZ() * axis_dir > 0 ? 1.0 : -1.0)};
  return true;
}

double adaptive_area(const TopoDS_Face& face, double relative_precision) {
  GProp_GProps props;
  BRepGProp::SurfaceProperties(face, props, relative_precision);
  return std::fabs(props.Mass());
}

// ---------------------------------------------------------------------------
// Material side.

// Material side of an analytic revolution face from its normal at a few
// interior parameters (the first regular one decides: the sign is the same
// everywhere on a regular analytic surface).
MaterialSide analytic_side(const BRepAdaptor_Surface& surface, bool reversed, const UVBounds& uv,
                           const SurfaceParams& s) {
  const double u1 = uv.u1, u2 = uv.u2, v1 = uv.v1, v2 = uv.v2;
  for (double fraction : {0.5, 0.25, 0.75, 0.1, 0.9}) {
    gp_XYZ p, n;
    if (oriented_normal(surface, reversed, u1 + (u2 - u1) * fraction, v1 + (v2 - v1) * fraction, p, n))
      return n * away_from_core(s, p) >= 0 ? MaterialSide::Convex : MaterialSide::Concave;
  }
  return MaterialSide::Convex;
}

// ---------------------------------------------------------------------------
// Analytic faces.

// Range of r sin(v) for v in [v1, v2] (axial extent of a torus tube section).
std::pair<double, double> sine_range(double r, double v1, double v2) {
  double lo = std::min(std::sin(v1), std::sin(v2)), hi = std::max(std::sin(v1), std::sin(v2));
  // sin reaches +1 at pi/2 + 2k pi and -1 at -pi/2 + 2k pi.
  if (std::ceil((v1 - kPi / 2) / kTwoPi) <= std::floor((v2 - kPi / 2) / kTwoPi)) hi = 1;
  if (std::ceil((v1 + kPi / 2) / kTwoPi) <= std::floor((v2 + kPi / 2) / kTwoPi)) lo = -1;
  return {r * lo, r * hi};
}

// Types a planar face: the plane through its surface with the outward normal
// (the surface normal D1U ^ D1V, reversed with the face).
void type_plane(const gp_Pln& plane, bool reversed, FaceInfo& out) {
  const gp_Dir x = plane.XAxis().Direction(), y = plane.YAxis().Direction();
  gp_Dir normal = x.Crossed(y);
  if (reversed) normal.Reverse();
  out.params.kind = SurfaceKind::Plane;
  out.params.location = plane.Location();
  out.params.axis = normal;
  out.side = MaterialSide::Outward;
  out.extent.ref_dir = x;
}

// Types a face on an analytic revolution surface from the adaptor (global
// coordinates) and its UV bounds, with its extent and its area (exact, by
// Green on the pcurves). `scale` is the scale factor of the face's location,
// 1 for rigid placements: parameters v and the area element are in the
// surface's own units. False when the surface is no analytic revolution.
bool type_revolution(const TopoDS_Face& face, const BRepAdaptor_Surface& surface, bool reversed,
                     const UVBounds& uv, FaceInfo& out) {
  const double scale = std::fabs(surface.Trsf().ScaleFactor());
  SurfaceParams& s = out.params;
  Extent& e = out.extent;
  switch (surface.GetType()) {
    case GeomAbs_Cylinder: {
      const gp_Cylinder cylinder = surface.Cylinder();
      const gp_Ax3& frame = cylinder.Position();
      s.kind = SurfaceKind::Cylinder;
      s.location = frame.Location();
      s.axis = frame.Direction();
      s.radius = cylinder.Radius();
      e.ref_dir = frame.XDirection();
      e.axial_min = uv.v1 * scale;  // P(u, v) = O + R e(u) + v Dir
      e.axial_max = uv.v2 * scale;
      e.angular = {surface_interval(uv.u1, uv.u2, s.axis, frame.XDirection(), frame.YDirection())};
      const double r = s.radius / scale;
      out.area = uv_area(face, [r](double v) { return r * v; }) * scale * scale;
      break;
    }
    case GeomAbs_Cone: {
      const gp_Cone cone = surface.Cone();
      const gp_Ax3& frame = cone.Position();
      const double semi = cone.SemiAngle();  // signed: the radius grows along +Dir when positive
      const double sign = semi > 0 ? 1.0 : -1.0;
      const double ref_radius = cone.RefRadius() / scale, sin_a = std::sin(semi);
      s.kind = SurfaceKind::Cone;
      s.location = cone.Apex();
      s.axis = sign > 0 ? frame.Direction() : frame.Direction().Reversed();
      s.half_angle = std::fabs(semi);
      e.ref_dir = frame.XDirection();
      // P(u, v) = O + (R + v sin a) e(u) + v cos a Dir; the apex is at v = -R / sin a.
      auto axial = [&](double v) { return scale * sign * std::cos(semi) * (v + ref_radius / sin_a); };
      e.axial_min = std::min(axial(uv.v1), axial(uv.v2));
      e.axial_max = std::max(axial(uv.v1), axial(uv.v2));
      e.angular = {surface_interval(uv.u1, uv.u2, s.axis, frame.XDirection(), frame.YDirection())};
      // |S_u x S_v| = |R + v sin a|, one sign on the face's nappe.
      const double nappe = ref_radius + (uv.v1 + uv.v2) / 2 * sin_a >= 0 ? 1.0 : -1.0;
      out.area = uv_area(face, [&](double v) { return nappe * (ref_radius * v + v * v * sin_a / 2); }) * scale * scale;
      break;
    }
    case GeomAbs_Sphere: {
      const gp_Sphere sphere = surface.Sphere();
      const gp_Ax3& frame = sphere.Position();
      s.kind = SurfaceKind::Sphere;
      s.location = frame.Location();
      s.axis = frame.Direction();
      s.radius = sphere.Radius();
      e.ref_dir = frame.XDirection();
      // v is the latitude in [-pi/2, pi/2]: sin is monotonic there.
      e.axial_min = s.radius * std::sin(std::max(uv.v1, -kPi / 2));
      e.axial_max = s.radius * std::sin(std::min(uv.v2, kPi / 2));
      e.angular = {surface_interval(uv.u1, uv.u2, s.axis, frame.XDirection(), frame.YDirection())};
      const double r2 = s.radius * s.radius;  // J = R^2 cos v, angles do not scale
      out.area = uv_area(face, [r2](double v) { return r2 * std::sin(v); });
      break;
    }
    case GeomAbs_Torus: {
      const gp_Torus torus = surface.Torus();
      const gp_Ax3& frame = torus.Position();
      s.kind = SurfaceKind::Torus;
      s.location = frame.Location();
      s.axis = frame.Direction();
      s.radius = torus.MajorRadius();
      s.minor_radius = torus.MinorRadius();
      e.ref_dir = frame.XDirection();
      std::tie(e.axial_min, e.axial_max) = sine_range(s.minor_radius, uv.v1, uv.v2);
      e.angular = {surface_interval(uv.u1, uv.u2, s.axis, frame.XDirection(), frame.YDirection())};
      const double major = s.radius, minor = s.minor_radius;  // J = r (R + r cos v)
      out.area = uv_area(face, [&](double v) { return minor * (major * v + minor * std::sin(v)); });
      break;
    }
    default: return false;
  }
  out.side = analytic_side(surface, reversed, uv, s);
  return true;
}

}  // namespace

Status type_face(const TopoDS_Face& face, const Tolerances& tol, FaceInfo& out) {
  out.face = face;
  out.params = SurfaceParams{};
  out.side = MaterialSide::Outward;
  out.recognised = false;
  out.max_deviation = 0;
  out.area = 0;
  out.extent = Extent{};
  out.box.SetVoid();
  try {
    if (face.IsNull()) return Status::failure(StatusCode::InvalidInput, "null face");
    // OCCT dereferences a missing surface without raising: check it first.
    TopLoc_Location location;
    if (BRep_Tool::Surface(face, location).IsNull())
      return Status::failure(StatusCode::GeometryError, "the face has no surface");
    const bool reversed = face.Orientation() == TopAbs_REVERSED;
    // Unrestricted: the UV bounds (BRepTools::UVBounds, a third of the cost
    // of a plane) are only needed for revolution and free-form faces.
    const BRepAdaptor_Surface surface(face, Standard_False);
    UVBounds uv;
    bool analytic_revolution = false;
    if (surface.GetType() == GeomAbs_Plane) {
      type_plane(surface.Plane(), reversed, out);
    } else {
      uv = uv_bounds(face);
      analytic_revolution = type_revolution(face, surface, reversed, uv, out);
      if (!analytic_revolution) {
        if (recognise(surface, reversed, uv, tol, out)) {
          const SurfaceParams& s = out.params;
          const gp_Dir ref = perpendicular_ref(s.axis, gp_Ax2(s.location, s.axis).XDirection().XYZ());
          out.extent.ref_dir = ref;
          const bool measured = is_revolution(s.kind) && surface.GetType() == GeomAbs_SurfaceOfRevolution &&
                                measure_surface_of_revolution(face, surface, uv, out);
          if (!measured && is_revolution(s.kind)) {
            out.extent = extent_from_geometry(face, s, frame_of(s.location, s.axis, ref), tol.linear);
            out.area = s.kind == SurfaceKind::Cylinder || s.kind == SurfaceKind::Cone
                           ? fitted_revolution_area(face, s)
                           : adaptive_area(face, kFittedAreaPrecision);
          }  // planes: area with the outline below
        } else {
          // Other faces never merge nor touch: their area is informative, taken
          // from the face's mesh when it has one, else OCCT's fast rule (~0.5 %
          // off on B-spline faces; the adaptive one costs ms a face).
          GProp_GProps props;
          BRepGProp::SurfaceProperties(face, props, Standard_False, Standard_True);
          out.area = std::fabs(props.Mass());
        }
      }
    }
    if (out.params.kind == SurfaceKind::Plane) {
      // Chords within the linear tolerance of their arcs; the bulges make the
      // outline's area exact whatever the chords.
      const gp_XYZ x = out.extent.ref_dir.XYZ(), y = out.params.axis.XYZ() ^ x;
      out.extent.outline = detail::plane_outline(face, out.params.location.XYZ(), x, y, tol.linear, &out.area);
    }
    if (analytic_revolution && (out.params.kind == SurfaceKind::Torus || out.params.kind == SurfaceKind::Sphere)) {
      // u turns about the frame's direction, clockwise in an indirect frame.
      const gp_Ax3 frame = surface.GetType() == GeomAbs_Torus ? surface.Torus().Position() : surface.Sphere().Position();
      const gp_Ax1 turning = frame.Direct() ? frame.Axis() : frame.Axis().Reversed();
      const double meridian_radius = out.params.kind == SurfaceKind::Torus ? out.params.minor_radius : out.params.radius;
      out.box = swept_box(meridian_points(surface, uv.v1, uv.v2, kMeridianSamples), turning,
                          frame.Direct() ? uv.u1 : -uv.u2, frame.Direct() ? uv.u2 : -uv.u1, meridian_radius,
                          BRep_Tool::Tolerance(face));
    } else if (analytic_revolution) {
      // BRepBndLib would recompute the UV bounds (a second pcurve pass).
      BndLib_AddSurface::Add(surface, uv.u1, uv.u2, uv.v1, uv.v2, BRep_Tool::Tolerance(face), out.box);
    } else if (out.box.IsVoid()) {  // surfaces of revolution have theirs already
      BRepBndLib::Add(face, out.box);  // planes: from the edges' 3D curves
    }
    // Damaged geometry (a pcurve range of 4e13 on a cylinder: make fuzz)
    // integrates to NaN or infinity: the face is an error, typed Other.
    if (!std::isfinite(out.area) || out.area < 0) {
      const TopoDS_Face kept = face;
      const std::string area = std::to_string(out.area);
      out = FaceInfo{};
      out.face = kept;
      return Status::failure(StatusCode::GeometryError, "the face's area is not a finite number (" + area +
                                                            "): damaged geometry");
    }
    return Status::success();
  } CONTACTS_PASS_OUT_OF_MEMORY catch (const Standard_Failure& failure) {
    const TopoDS_Face kept = face;  // `face` may be out.face itself
    out = FaceInfo{};
    out.face = kept;
    return Status::failure(StatusCode::GeometryError, std::string("OCCT failed on the face: ") +
                                                          failure.GetMessageString());
  } catch (const std::exception& error) {
    const TopoDS_Face kept = face;
    out = FaceInfo{};
    out.face = kept;
    return Status::failure(StatusCode::GeometryError, std::string("face typing failed: ") + error.what());
  }
}

Extent revolution_extent_in(const FaceInfo& face, const gp_Pnt& origin, const gp_Dir& axis,
                            const gp_Dir& ref_dir, double linear) {
  const SurfaceParams& s = face.params;
  const Extent& own = face.extent;
  const double orientation = s.axis.Dot(axis);
  if (!is_revolution(s.kind)) return Extent{};
  // Sphere frames of the same sphere may have unrelated axes: re-measure the
  // face itself in the requested frame.
  if (std::fabs(orientation) < 1 - 1e-6) return extent_from_geometry(face.face, s, frame_of(origin, axis, ref_dir), linear);
  const double sign = orientation > 0 ? 1.0 : -1.0;
  Extent out;
  out.ref_dir = ref_dir;
  const double offset = (s.location.XYZ() - origin.XYZ()) * axis.XYZ();
  const double a = offset + sign * own.axial_min, b = offset + sign * own.axial_max;
  out.axial_min = std::min(a, b);
  out.axial_max = std::max(a, b);
  // Angle of the face's reference direction in the requested frame.
  const gp_XYZ binormal = axis.XYZ() ^ ref_dir.XYZ();
  const double phi = std::atan2(own.ref_dir.XYZ() * binormal, own.ref_dir.XYZ() * ref_dir.XYZ());
  for (const AngularInterval& interval : own.angular) {
    if (interval.span >= kTwoPi - kAngularJoinGap) {
      out.angular.push_back({0, kTwoPi});
      continue;
    }
    // Seen from the reversed axis, angles run the other way: theta' = phi - theta.
    const double start = sign > 0 ? phi + interval.start : phi - interval.start - interval.span;
    out.angular.push_back({wrap_angle(start), interval.span});
  }
  out.angular = unite(std::move(out.angular));
  return out;
}

}  // namespace contactcore
