// Stage 2: partitions. Face typing (analytic surfaces read from the adaptor,
// free-form surfaces recognised by fitting), extents, and merging of adjacent
// faces on the same surface into maximal partitions (paper, section 3).
#include "contactcore/partitions.h"

#include "outlines.h"
#include "quadrature.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <exception>
#include <numeric>
#include <optional>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <Adaptor3d_Curve.hxx>
#include <Adaptor3d_Surface.hxx>
#include <BRepAdaptor_Curve.hxx>
#include <BRepAdaptor_Curve2d.hxx>
#include <BRepAdaptor_Surface.hxx>
#include <BRepBndLib.hxx>
#include <BRepClass_FaceClassifier.hxx>
#include <BRepGProp.hxx>
#include <BRepLProp_SLProps.hxx>
#include <BRepTools.hxx>
#include <BRepTools_WireExplorer.hxx>
#include <BRepTopAdaptor_FClass2d.hxx>
#include <BRep_Tool.hxx>
#include <BndLib_AddSurface.hxx>
#include <GProp_GProps.hxx>
#include <Precision.hxx>
#include <Standard_Failure.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopTools_ListOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Iterator.hxx>
#include <TopoDS_Wire.hxx>
#include <gp_Ax2.hxx>
#include <gp_Circ.hxx>
#include <gp_Cone.hxx>
#include <gp_Cylinder.hxx>
#include <gp_Lin.hxx>
#include <gp_Pln.hxx>
#include <gp_Sphere.hxx>
#include <gp_Torus.hxx>

namespace contactcore {

namespace {

using detail::bounds_the_face;
using detail::discretise_edge;
using detail::gauss;
using detail::integration_pieces;

constexpr double kPi = 3.14159265358979323846;
constexpr double kTwoPi = 2 * kPi;

// unite() joins angular intervals separated by less than this: faces that
// meet on a seam or a split line must give one closed interval even when their
// boundaries carry round-off.
constexpr double kAngularJoinGap = 1e-6;

// Recognised revolution faces: their edges are sampled this finely (radians
// of tangent turning) to measure the angles and axial range they sweep.
constexpr double kCoverageStep = 0.05;

// Samples per parameter direction for fitting a free-form face; the fit is
// then checked on a grid twice as fine (the fitted points and the cell middles).
constexpr int kFitGrid = 7;
constexpr int kCheckGrid = 2 * kFitGrid - 1;

// Samples of a meridian for swept boxes and axial ranges of surfaces of
// revolution.
constexpr int kMeridianSamples = 32;

// Relative precision of OCCT's adaptive area integration, used only for
// recognised spheres and tori (no boundary formula here: poles, tube angle).
constexpr double kFittedAreaPrecision = 1e-6;

double wrap_angle(double angle) {
  angle = std::fmod(angle, kTwoPi);
  if (angle < 0) angle += kTwoPi;
  if (angle >= kTwoPi) angle = 0;
  return angle;
}

// ---------------------------------------------------------------------------
// Small dense linear algebra for the fits (3x3 and 4x4 only).

// Eigen decomposition of a symmetric 3x3 matrix by cyclic Jacobi rotations;
// eigenvalues ascending, eigenvectors unit length.
struct Eigen3 {
  std::array<double, 3> values{};
  std::array<gp_XYZ, 3> vectors;
};

Eigen3 symmetric_eigen(std::array<std::array<double, 3>, 3> a) {
  double v[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (int sweep = 0; sweep < 50; ++sweep) {
    const double off = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
    const double diag = a[0][0] * a[0][0] + a[1][1] * a[1][1] + a[2][2] * a[2][2];
    if (off <= 1e-30 * diag || off == 0) break;
    for (int p = 0; p < 2; ++p) {
      for (int q = p + 1; q < 3; ++q) {
        if (a[p][q] == 0) continue;
        const double theta = (a[q][q] - a[p][p]) / (2 * a[p][q]);
        const double t = (theta >= 0 ? 1.0 : -1.0) / (std::fabs(theta) + std::sqrt(theta * theta + 1));
        const double c = 1 / std::sqrt(t * t + 1), s = t * c;
        for (int k = 0; k < 3; ++k) {  // A <- A J
          const double akp = a[k][p], akq = a[k][q];
          a[k][p] = c * akp - s * akq;
          a[k][q] = s * akp + c * akq;
        }
        for (int k = 0; k < 3; ++k) {  // A <- J^T A
          const double apk = a[p][k], aqk = a[q][k];
          a[p][k] = c * apk - s * aqk;
          a[q][k] = s * apk + c * aqk;
        }
        for (int k = 0; k < 3; ++k) {  // V <- V J
          const double vkp = v[k][p], vkq = v[k][q];
          v[k][p] = c * vkp - s * vkq;
          v[k][q] = s * vkp + c * vkq;
        }
      }
    }
  }
  std::array<int, 3> order = {0, 1, 2};
  std::sort(order.begin(), order.end(), [&a](int i, int j) { return a[i][i] < a[j][j]; });
  Eigen3 out;
  for (int i = 0; i < 3; ++i) {
    const int k = order[i];
    out.values[i] = a[k][k];
    gp_XYZ vec(v[0][k], v[1][k], v[2][k]);
    const double n = vec.Modulus();
    out.vectors[i] = n > 0 ? vec / n : gp_XYZ(0, 0, 1);
  }
  return out;
}

// Solves the n x n system (n <= 4) by Gaussian elimination with partial
// pivoting; false when singular.
template <int N>
bool solve_linear(std::array<std::array<double, N>, N> a, std::array<double, N> b,
                  std::array<double, N>& x) {
  double scale = 0;
  for (const auto& row : a)
    for (double value : row) scale = std::max(scale, std::fabs(value));
  if (scale == 0) return false;
  for (int col = 0; col < N; ++col) {
    int pivot = col;
    for (int r = col + 1; r < N; ++r)
      if (std::fabs(a[r][col]) > std::fabs(a[pivot][col])) pivot = r;
    if (std::fabs(a[pivot][col]) <= 1e-14 * scale) return false;
    std::swap(a[col], a[pivot]);
    std::swap(b[col], b[pivot]);
    for (int r = col + 1; r < N; ++r) {
      const double f = a[r][col] / a[col][col];
      for (int c = col; c < N; ++c) a[r][c] -= f * a[col][c];
      b[r] -= f * b[col];
    }
  }
  for (int r = N - 1; r >= 0; --r) {
    double sum = b[r];
    for (int c = r + 1; c < N; ++c) sum -= a[r][c] * x[c];
    x[r] = sum / a[r][r];
  }
  return true;
}

gp_XYZ centroid(const std::vector<gp_XYZ>& points) {
  gp_XYZ sum(0, 0, 0);
  for (const gp_XYZ& p : points) sum += p;
  return points.empty() ? sum : sum / static_cast<double>(points.size());
}

// Covariance (not normalised) of points about `centre`.
std::array<std::array<double, 3>, 3> scatter(const std::vector<gp_XYZ>& points, const gp_XYZ& centre) {
  std::array<std::array<double, 3>, 3> m{};
  for (const gp_XYZ& p : points) {
    const gp_XYZ d = p - centre;
    const double c[3] = {d.X(), d.Y(), d.Z()};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) m[i][j] += c[i] * c[j];
  }
  return m;
}

// Two unit vectors completing `axis` to a right-handed frame.
std::pair<gp_XYZ, gp_XYZ> perpendicular_basis(const gp_Dir& axis) {
  const gp_Ax2 frame(gp::Origin(), axis);
  return {frame.XDirection().XYZ(), frame.YDirection().XYZ()};
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
  std::array<std::array<double, 3>, 3> a{};
  std::array<double, 3> b{};
  for (const auto& [px, py] : pts) {
    const double x = (px - mx) / scale, y = (py - my) / scale;
    const double row[3] = {x, y, 1};
    const double rhs = -(x * x + y * y);
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) a[i][j] += row[i] * row[j];
      b[i] += row[i] * rhs;
    }
  }
  std::array<double, 3> sol{};
  if (!solve_linear<3>(a, b, sol)) return std::nullopt;
  double cx = -sol[0] / 2, cy = -sol[1] / 2;
  const double r2 = cx * cx + cy * cy - sol[2];
  if (!(r2 > 0)) return std::nullopt;
  double r = std::sqrt(r2);
  for (int iteration = 0; iteration < 4; ++iteration) {
    std::array<std::array<double, 3>, 3> jtj{};
    std::array<double, 3> jtr{};
    for (const auto& [px, py] : pts) {
      const double x = (px - mx) / scale - cx, y = (py - my) / scale - cy;
      const double d = std::hypot(x, y);
      if (d <= 0) continue;
      const double row[3] = {-x / d, -y / d, -1};
      const double residual = d - r;
      for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) jtj[i][j] += row[i] * row[j];
        jtr[i] -= row[i] * residual;
      }
    }
    std::array<double, 3> step{};
    if (!solve_linear<3>(jtj, jtr, step)) break;
    cx += step[0], cy += step[1], r += step[2];
    if (std::fabs(step[0]) + std::fabs(step[1]) + std::fabs(step[2]) < 1e-15) break;
  }
  if (!(r > 0)) return std::nullopt;
  return Circle2{mx + cx * scale, my + cy * scale, r * scale};
}

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

// Parameter range of a face on its surface, from its pcurves.
struct UVBounds {
  double u1 = 0, u2 = 0, v1 = 0, v2 = 0;
};

UVBounds uv_bounds(const TopoDS_Face& face) {
  UVBounds b;
  BRepTools::UVBounds(face, b.u1, b.u2, b.v1, b.v2);
  return b;
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
  const gp_XYZ e1 = basis.first, e2 = basis.second;  // not a structured binding: lambdas below use them
  const gp_XYZ origin = params.location.XYZ(), axis = params.axis.XYZ();
  const bool cone = params.kind == SurfaceKind::Cone;
  const double half_sin = std::sin(params.half_angle) / 2;
  std::vector<double> breaks;
  double total = 0;
  for (TopExp_Explorer edges(face, TopAbs_EDGE); edges.More(); edges.Next()) {
    const TopoDS_Edge& edge = TopoDS::Edge(edges.Current());
    if (BRep_Tool::Degenerated(edge) || !bounds_the_face(edge)) continue;
    const BRepAdaptor_Curve curve(edge);
    integration_pieces(curve, curve.FirstParameter(), curve.LastParameter(), breaks);
    double sum = 0;
    for (std::size_t i = 0; i + 1 < breaks.size(); ++i) {
      sum += gauss(breaks[i], breaks[i + 1], [&](double t) {
        gp_Pnt p;
        gp_Vec d;
        curve.D1(t, p, d);
        const gp_XYZ r = p.XYZ() - origin;
        const double x = r * e1, y = r * e2, rho2 = x * x + y * y;
        if (rho2 <= 0) return 0.0;
        const double dtheta = (x * (d.XYZ() * e2) - y * (d.XYZ() * e1)) / rho2;
        const double g = cone ? r.SquareModulus() * half_sin : params.radius * (r * axis);
        return g * dtheta;
      });
    }
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
      const double a = radial.Coord(k + 1), b = turned.Coord(k + 1);
      auto value = [&](double u) { return centre.Coord(k + 1) + a * std::cos(u) + b * std::sin(u); };
      lo[k] = std::min(value(u1), value(u2));
      hi[k] = std::max(value(u1), value(u2));
      const double phi = std::atan2(b, a);
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

// The direction away from the "core" of a revolution surface at p: from the
// axis (cylinder, cone), the centre (sphere) or the tube centre (torus).
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

// Convex when the oriented normals point away from the core: the material is
// inside the surface.
MaterialSide side_from_normals(const SurfaceParams& s, const std::vector<gp_XYZ>& points,
                               const std::vector<gp_XYZ>& oriented_normals) {
  double vote = 0;
  for (std::size_t i = 0; i < points.size(); ++i) vote += oriented_normals[i] * away_from_core(s, points[i]);
  return vote >= 0 ? MaterialSide::Convex : MaterialSide::Concave;
}

// Oriented unit normal and point of the face at (u, v); false at singular points.
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
  const Eigen3 eig = symmetric_eigen(scatter(s.points, c));
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
  std::array<std::array<double, 4>, 4> a{};
  std::array<double, 4> b{};
  for (const gp_XYZ& p : s.points) {
    const gp_XYZ q = (p - c) / scale;
    const double row[4] = {q.X(), q.Y(), q.Z(), 1};
    const double rhs = -q.SquareModulus();
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) a[i][j] += row[i] * row[j];
      b[i] += row[i] * rhs;
    }
  }
  std::array<double, 4> sol{};
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

double distance_to_axis(const gp_XYZ& p, const gp_XYZ& origin, const gp_XYZ& axis) {
  const gp_XYZ rel = p - origin;
  return (rel - axis * (rel * axis)).Modulus();
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
  const Eigen3 eig = symmetric_eigen(scatter(s.normals, gp_XYZ(0, 0, 0)));
  const gp_Dir axis(eig.vectors[0]);
  const auto circle = axis_circle(s.points, axis);
  if (!circle) return std::nullopt;
  const gp_XYZ centre = circle->first;  // not a structured binding: a lambda below uses it
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
  const Eigen3 eig = symmetric_eigen(scatter(s.normals, centroid(s.normals)));
  gp_XYZ axis = eig.vectors[0];
  // Every tangent plane passes through the apex: n . apex = n . p.
  std::array<std::array<double, 3>, 3> a{};
  std::array<double, 3> b{};
  for (std::size_t i = 0; i < s.normals.size(); ++i) {
    const gp_XYZ& n = s.normals[i];
    const double c[3] = {n.X(), n.Y(), n.Z()};
    const double rhs = n * s.normal_points[i];
    for (int r = 0; r < 3; ++r) {
      for (int k = 0; k < 3; ++k) a[r][k] += c[r] * c[k];
      b[r] += c[r] * rhs;
    }
  }
  std::array<double, 3> apex_coords{};
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
    const Eigen3 eig = symmetric_eigen(scatter(centres, c));
    const gp_Dir axis(eig.vectors[0]);
    const auto circle = axis_circle(centres, axis);
    if (!circle) continue;
    const gp_XYZ centre = circle->first;  // not a structured binding: a lambda below uses it
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

// Types a free-form face by trying plane, sphere, cylinder, cone and torus
// fits in that order; the first whose deviation on the check grid is within
// tolerance wins. Returns false (face stays Other) when none fits.
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

bool is_revolution(SurfaceKind kind) {
  return kind == SurfaceKind::Cylinder || kind == SurfaceKind::Cone || kind == SurfaceKind::Sphere ||
         kind == SurfaceKind::Torus;
}

// ---------------------------------------------------------------------------
// Merging.

class UnionFind {
 public:
  explicit UnionFind(int n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0); }
  int find(int i) {
    while (parent_[i] != i) i = parent_[i] = parent_[parent_[i]];
    return i;
  }
  void unite(int a, int b) {
    a = find(a), b = find(b);
    if (a != b) parent_[std::max(a, b)] = std::min(a, b);  // smallest index is the root
  }

 private:
  std::vector<int> parent_;
};

bool mergeable(const FaceInfo& a, const FaceInfo& b, const Tolerances& tol) {
  return a.params.kind == b.params.kind && a.params.kind != SurfaceKind::Other && a.side == b.side &&
         same_surface(a.params, b.params, tol);
}

}  // namespace

// ---------------------------------------------------------------------------
// Public API.

const char* to_string(SurfaceKind kind) {
  switch (kind) {
    case SurfaceKind::Plane: return "Plane";
    case SurfaceKind::Cylinder: return "Cylinder";
    case SurfaceKind::Cone: return "Cone";
    case SurfaceKind::Sphere: return "Sphere";
    case SurfaceKind::Torus: return "Torus";
    case SurfaceKind::Other: return "Other";
  }
  return "Other";
}

const char* to_string(MaterialSide side) {
  switch (side) {
    case MaterialSide::Outward: return "outward";
    case MaterialSide::Convex: return "convex";
    case MaterialSide::Concave: return "concave";
  }
  return "outward";
}

double Extent::angular_span() const {
  double total = 0;
  for (const AngularInterval& interval : angular) total += interval.span;
  return std::min(total, kTwoPi);
}

Tolerances default_tolerances(const Bnd_Box& model_box) {
  Tolerances tol;
  const double diagonal = model_box.IsVoid() ? 0 : std::sqrt(model_box.SquareExtent());
  // Relative, with no floor or ceiling: the motor scaled by 1e-6 or 1e6 must
  // give its own contacts (an empty box keeps the plain default).
  if (diagonal > 0 && std::isfinite(diagonal)) tol.linear = kDefaultRelativeLinear * diagonal;
  tol.angular = 1e-4;
  return tol;
}

Tolerances resolve_tolerances(const Bnd_Box& model_box, std::optional<double> linear,
                              std::optional<double> angular) {
  Tolerances tol = default_tolerances(model_box);
  if (linear) tol.linear = *linear;
  if (angular) tol.angular = *angular;
  return tol;
}

Status check_tolerances(const Bnd_Box& model_box, const Tolerances& tolerances) {
  const auto text = [](double value) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.6g", value);
    return std::string(buffer);
  };
  const auto fail = [](const std::string& message) { return Status::failure(StatusCode::InvalidArgument, message); };
  if (!std::isfinite(tolerances.linear) || !(tolerances.linear > 0))
    return fail("linear tolerance must be a positive, finite length in mm; got " + text(tolerances.linear));
  if (!std::isfinite(tolerances.angular) || !(tolerances.angular > 0))
    return fail("angular tolerance must be a positive, finite angle in radians; got " + text(tolerances.angular));
  if (tolerances.angular > kMaxAngular)
    return fail("angular tolerance " + text(tolerances.angular) + " rad is too large (at most " + text(kMaxAngular) +
                " rad)");
  const double diagonal = model_box.IsVoid() ? 0 : std::sqrt(model_box.SquareExtent());
  if (diagonal > 0 && std::isfinite(diagonal)) {
    if (tolerances.linear > kMaxRelativeLinear * diagonal)
      return fail("linear tolerance " + text(tolerances.linear) + " mm is too large for this model (box diagonal " +
                  text(diagonal) + " mm; at most " + text(kMaxRelativeLinear * diagonal) + " mm)");
    // Below this, coordinates of the model's size cannot tell points apart.
    if (tolerances.linear < 1e-12 * diagonal)
      return fail("linear tolerance " + text(tolerances.linear) + " mm is below the precision of coordinates of a " +
                  text(diagonal) + " mm model");
  }
  return Status::success();
}

std::vector<AngularInterval> unite(std::vector<AngularInterval> intervals) {
  struct Range {
    double start, end;
  };
  std::vector<Range> ranges;
  ranges.reserve(intervals.size());
  for (const AngularInterval& interval : intervals) {
    if (!(interval.span > 0)) continue;
    if (interval.span >= kTwoPi - kAngularJoinGap) return {{0, kTwoPi}};
    const double start = wrap_angle(interval.start);
    ranges.push_back({start, start + interval.span});
  }
  if (ranges.empty()) return {};
  std::sort(ranges.begin(), ranges.end(), [](const Range& a, const Range& b) { return a.start < b.start; });
  std::vector<Range> merged{ranges.front()};
  for (std::size_t i = 1; i < ranges.size(); ++i) {
    if (ranges[i].start <= merged.back().end + kAngularJoinGap)
      merged.back().end = std::max(merged.back().end, ranges[i].end);
    else
      merged.push_back(ranges[i]);
  }
  // The last range may run past 2 pi and swallow ranges at the start.
  while (merged.size() > 1 && merged.back().end - kTwoPi + kAngularJoinGap >= merged.front().start) {
    merged.back().end = std::max(merged.back().end, merged.front().end + kTwoPi);
    merged.erase(merged.begin());
  }
  std::vector<AngularInterval> out;
  out.reserve(merged.size());
  for (const Range& r : merged) {
    if (r.end - r.start >= kTwoPi - kAngularJoinGap) return {{0, kTwoPi}};
    out.push_back({r.start, r.end - r.start});
  }
  return out;
}

double overlap(const std::vector<AngularInterval>& a, const std::vector<AngularInterval>& b,
               std::vector<AngularInterval>* common) {
  const std::vector<AngularInterval> ua = unite(a), ub = unite(b);
  std::vector<AngularInterval> pieces;
  double total = 0;
  for (const AngularInterval& x : ua) {
    for (const AngularInterval& y : ub) {
      // y shifted by -2 pi, 0 and 2 pi covers every way two arcs starting in
      // [0, 2 pi) can meet.
      for (int shift = -1; shift <= 1; ++shift) {
        const double ys = y.start + shift * kTwoPi;
        const double lo = std::max(x.start, ys), hi = std::min(x.start + x.span, ys + y.span);
        if (hi > lo) {
          total += hi - lo;
          pieces.push_back({wrap_angle(lo), hi - lo});
        }
      }
    }
  }
  if (common) *common = unite(std::move(pieces));
  return std::min(total, kTwoPi);
}

bool same_surface(const SurfaceParams& a, const SurfaceParams& b, const Tolerances& tol) {
  if (a.kind != b.kind) return false;
  const double cos_tol = std::cos(tol.angular);
  const double dot = a.axis.Dot(b.axis);
  auto off_line = [](const gp_Pnt& p, const gp_Pnt& origin, const gp_Dir& axis) {
    return distance_to_axis(p.XYZ(), origin.XYZ(), axis.XYZ());
  };
  switch (a.kind) {
    case SurfaceKind::Plane:
      return dot >= cos_tol && std::fabs((b.location.XYZ() - a.location.XYZ()) * a.axis.XYZ()) <= tol.linear &&
             std::fabs((a.location.XYZ() - b.location.XYZ()) * b.axis.XYZ()) <= tol.linear;
    case SurfaceKind::Cylinder:
      return std::fabs(dot) >= cos_tol && std::fabs(a.radius - b.radius) <= tol.linear &&
             off_line(b.location, a.location, a.axis) <= tol.linear &&
             off_line(a.location, b.location, b.axis) <= tol.linear;
    case SurfaceKind::Cone:
      return dot >= cos_tol && std::fabs(a.half_angle - b.half_angle) <= tol.angular &&
             a.location.Distance(b.location) <= tol.linear;
    case SurfaceKind::Sphere:
      return a.location.Distance(b.location) <= tol.linear && std::fabs(a.radius - b.radius) <= tol.linear;
    case SurfaceKind::Torus:
      return std::fabs(dot) >= cos_tol && a.location.Distance(b.location) <= tol.linear &&
             std::fabs(a.radius - b.radius) <= tol.linear &&
             std::fabs(a.minor_radius - b.minor_radius) <= tol.linear;
    case SurfaceKind::Other: return false;
  }
  return false;
}

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
      // A copy: Torus() and Sphere() return temporaries (ASan: stack-use-after-scope).
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
    return Status::success();
  } catch (const Standard_Failure& failure) {
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

BodyPartitions partition_shape(const TopoDS_Shape& shape, const Tolerances& tol) {
  BodyPartitions result;
  try {
    if (shape.IsNull()) {
      result.status = Status::failure(StatusCode::InvalidInput, "empty shape");
      return result;
    }
    // FreeCAD's FaceN numbering: TopExp::MapShapes order (explorer order, repeats dropped).
    TopTools_IndexedMapOfShape face_map;
    TopExp::MapShapes(shape, TopAbs_FACE, face_map);
    const int count = face_map.Extent();
    if (count == 0) {
      result.status = Status::failure(StatusCode::InvalidInput, "shape has no faces");
      return result;
    }
    result.faces.resize(count);
    int failures = 0;
    Status first_failure;
    for (int i = 0; i < count; ++i) {
      FaceInfo& info = result.faces[i];
      const Status status = type_face(TopoDS::Face(face_map(i + 1)), tol, info);
      info.index = i + 1;
      if (!status.ok() && failures++ == 0) {
        first_failure = status;
        first_failure.face = i + 1;
      }
      result.box.Add(info.box);
    }
    if (failures == count) {
      result.status = first_failure;
      result.status.message = "no face could be evaluated: " + first_failure.message;
    } else if (failures > 0) {
      // Keep going: the failed faces are typed Other; the status stays Ok and
      // says which face failed first.
      result.status.message = std::to_string(failures) + " face(s) could not be evaluated and are typed Other; first: " +
                              first_failure.message;
      result.status.face = first_failure.face;
    }

    UnionFind groups(count);
    TopTools_IndexedDataMapOfShapeListOfShape edge_faces;
    TopExp::MapShapesAndUniqueAncestors(shape, TopAbs_EDGE, TopAbs_FACE, edge_faces);
    std::vector<int> neighbours;
    for (int e = 1; e <= edge_faces.Extent(); ++e) {
      neighbours.clear();
      for (TopTools_ListOfShape::Iterator it(edge_faces(e)); it.More(); it.Next())
        neighbours.push_back(face_map.FindIndex(it.Value()) - 1);
      for (std::size_t i = 0; i < neighbours.size(); ++i) {
        for (std::size_t j = i + 1; j < neighbours.size(); ++j) {
          const int a = neighbours[i], b = neighbours[j];
          if (a < 0 || b < 0 || a == b) continue;
          if (groups.find(a) != groups.find(b) && mergeable(result.faces[a], result.faces[b], tol))
            groups.unite(a, b);
        }
      }
    }

    // Partitions in the order of their first face; faces ascending.
    std::vector<int> partition_of_root(count, -1);
    for (int i = 0; i < count; ++i) {
      const int root = groups.find(i);
      if (partition_of_root[root] < 0) {
        partition_of_root[root] = static_cast<int>(result.partitions.size());
        Partition partition;
        partition.id = partition_of_root[root];
        partition.params = result.faces[i].params;
        partition.side = result.faces[i].side;
        result.partitions.push_back(std::move(partition));
      }
      Partition& partition = result.partitions[partition_of_root[root]];
      partition.faces.push_back(i + 1);
      partition.area += result.faces[i].area;
      partition.box.Add(result.faces[i].box);
    }

    for (Partition& partition : result.partitions) {
      const FaceInfo& first = result.faces[partition.faces.front() - 1];
      if (partition.faces.size() == 1) {
        partition.extent = first.extent;
        continue;
      }
      const SurfaceParams& s = partition.params;
      Extent& extent = partition.extent;
      extent.ref_dir = first.extent.ref_dir;
      if (s.kind == SurfaceKind::Plane) {
        const gp_Dir y_dir = s.axis.Crossed(extent.ref_dir);
        for (int index : partition.faces) {
          const FaceInfo& face = result.faces[index - 1];
          std::vector<Polygon2> loops = index == partition.faces.front()
                                            ? face.extent.outline
                                            : outline_in(face, s.location, extent.ref_dir, y_dir);
          for (Polygon2& loop : loops) extent.outline.push_back(std::move(loop));
        }
      } else if (is_revolution(s.kind)) {
        extent.axial_min = 1e300;
        extent.axial_max = -1e300;
        std::vector<AngularInterval> angular;
        for (int index : partition.faces) {
          const FaceInfo& face = result.faces[index - 1];
          const Extent seen = index == partition.faces.front()
                                  ? face.extent
                                  : revolution_extent_in(face, s.location, s.axis, extent.ref_dir, tol.linear);
          extent.axial_min = std::min(extent.axial_min, seen.axial_min);
          extent.axial_max = std::max(extent.axial_max, seen.axial_max);
          angular.insert(angular.end(), seen.angular.begin(), seen.angular.end());
        }
        extent.angular = unite(std::move(angular));
      }
    }
  } catch (const Standard_Failure& failure) {
    result.status = Status::failure(StatusCode::GeometryError,
                                    std::string("OCCT failed while partitioning: ") + failure.GetMessageString());
  } catch (const std::exception& error) {
    result.status = Status::failure(StatusCode::GeometryError, std::string("partitioning failed: ") + error.what());
  }
  return result;
}

}  // namespace contactcore
