#include "contacts/interferences.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <tuple>

#include <BRepAdaptor_Curve.hxx>
#include <BRepAdaptor_Surface.hxx>
#include <BRepAlgoAPI_Common.hxx>
#include <BRepBuilderAPI_MakeVertex.hxx>
#include <BRepExtrema_DistShapeShape.hxx>
#include <BRepClass3d_SolidClassifier.hxx>
#include <BRepBndLib.hxx>
#include <BRepGProp.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepTopAdaptor_FClass2d.hxx>
#include <BRep_Tool.hxx>
#include <GProp_GProps.hxx>
#include <Standard_ErrorHandler.hxx>
#include <Standard_Failure.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_ListOfShape.hxx>
#include <TopoDS.hxx>
#include <gp_Ax1.hxx>

#include "contacts/boundary_crossing.h"
#include "contacts/coaxial_overlap.h"
#include "contacts/pair_key.h"
#include "contactcore/common/angles.h"
#include "contactcore/common/occt_guard.h"
#include "contactcore/common/parallel.h"
#include "contactcore/common/out_of_memory.h"
#include "contacts/separation.h"

namespace contactcore {

namespace {

// A common volume below this fraction of the smaller body is numerical noise.
constexpr double kMinRelativeVolume = 1e-6;
// A press fit: a shaft larger than its coaxial bore by at most this fraction
// of the bore's radius (real press fits are a few thousandths; a part's outer
// surface of radius 24 around another part's bore of radius 4 is not one).
constexpr double kPressFitRelative = 0.5;

double box_overlap(const Bnd_Box& a, const Bnd_Box& b) {
  if (a.IsVoid() || b.IsVoid()) return -1;
  double ax0, ay0, az0, ax1, ay1, az1, bx0, by0, bz0, bx1, by1, bz1;
  a.Get(ax0, ay0, az0, ax1, ay1, az1);
  b.Get(bx0, by0, bz0, bx1, by1, bz1);
  return std::min({std::min(ax1, bx1) - std::max(ax0, bx0), std::min(ay1, by1) - std::max(ay0, by0),
                   std::min(az1, bz1) - std::max(az0, bz0)});
}

double box_thickness(const Bnd_Box& box) {
  if (box.IsVoid()) return 0;
  double x0, y0, z0, x1, y1, z1;
  box.Get(x0, y0, z0, x1, y1, z1);
  return std::min({x1 - x0, y1 - y0, z1 - z0});
}

bool boxes_equal(const Bnd_Box& a, const Bnd_Box& b, double tolerance) {
  if (a.IsVoid() || b.IsVoid()) return false;
  double a_[6], b_[6];
  a.Get(a_[0], a_[1], a_[2], a_[3], a_[4], a_[5]);
  b.Get(b_[0], b_[1], b_[2], b_[3], b_[4], b_[5]);
  for (int i = 0; i < 6; ++i)
    if (std::abs(a_[i] - b_[i]) > tolerance) return false;
  return true;
}

// The same solid twice at the same place: same faces, surfaces and areas.
bool duplicates(const BodyPartitions& a, const BodyPartitions& b, double tolerance) {
  if (a.faces.size() != b.faces.size() || a.partitions.size() != b.partitions.size()) return false;
  if (!boxes_equal(a.box, b.box, tolerance)) return false;
  std::vector<std::pair<int, double>> sa, sb;
  for (const Partition& p : a.partitions) sa.push_back({static_cast<int>(p.params.kind), p.area});
  for (const Partition& p : b.partitions) sb.push_back({static_cast<int>(p.params.kind), p.area});
  std::sort(sa.begin(), sa.end());
  std::sort(sb.begin(), sb.end());
  for (size_t i = 0; i < sa.size(); ++i)
    if (sa[i].first != sb[i].first || std::abs(sa[i].second - sb[i].second) > 1e-6 * std::max(1.0, sa[i].second))
      return false;
  return true;
}

// The angles a bore partition covers, measured in the shaft's frame.
std::vector<AngularInterval> bore_angles_in(const BodyPartitions& bore_body, const Partition& bore,
                                            const Partition& shaft, double linear) {
  std::vector<AngularInterval> angles;
  for (int face : bore.faces) {
    const Extent e = revolution_extent_in(bore_body.faces[face - 1], shaft.params.location, shaft.params.axis,
                                          shaft.extent.ref_dir, linear);
    angles.insert(angles.end(), e.angular.begin(), e.angular.end());
  }
  return unite(angles);
}

// Coaxial press fits of shafts of `a` in bores of `b`: a shaft larger than the
// bore by a small fraction of its radius, over a common axial range and
// angle. The material they share is the ring between the two radii over that
// range: 1/2 span (r_s^2 - r_b^2) L, exact for coaxial cylinder faces (no
// solid Boolean). Adds the volumes found to `volume`.
bool press_fits(const BodyPartitions& a, const BodyPartitions& b, const Tolerances& tol, double& volume,
                std::vector<gp_Ax1>* axes = nullptr) {
  bool found = false;
  for (const Partition& shaft : a.partitions) {
    if (shaft.params.kind != SurfaceKind::Cylinder || shaft.side != MaterialSide::Convex) continue;
    const gp_Ax1 axis(shaft.params.location, shaft.params.axis);
    for (const Partition& bore : b.partitions) {
      if (bore.params.kind != SurfaceKind::Cylinder || bore.side != MaterialSide::Concave) continue;
      const double excess = shaft.params.radius - bore.params.radius;
      if (excess <= tol.linear || excess > kPressFitRelative * bore.params.radius) continue;
      if (box_overlap(shaft.box, bore.box) <= tol.linear) continue;
      if (!bore.params.axis.IsParallel(shaft.params.axis, tol.angular)) continue;
      const gp_Vec offset(axis.Location(), bore.params.location);
      const gp_Vec direction(axis.Direction());
      if (offset.Crossed(direction).Magnitude() > tol.linear) continue;
      // Axial ranges on the shaft's axis must overlap, not just meet.
      const double shift = offset.Dot(direction);
      const double sign = gp_Vec(bore.params.axis).Dot(direction) > 0 ? 1 : -1;
      const double b0 = shift + sign * bore.extent.axial_min, b1 = shift + sign * bore.extent.axial_max;
      const double low = std::max(shaft.extent.axial_min, std::min(b0, b1));
      const double high = std::min(shaft.extent.axial_max, std::max(b0, b1));
      if (high - low <= tol.linear) continue;
      double span = 2 * kPi;
      if (shaft.extent.angular_span() < 2 * kPi - tol.angular || bore.extent.angular_span() < 2 * kPi - tol.angular)
        span = overlap(shaft.extent.angular, bore_angles_in(b, bore, shaft, tol.linear));
      if (span <= tol.angular) continue;
      const double rs = shaft.params.radius, rb = bore.params.radius;
      volume += 0.5 * span * (rs * rs - rb * rb) * (high - low);
      if (axes) axes->push_back(axis);
      found = true;
    }
  }
  return found;
}

// Points of a body's boundary: vertices, edge midpoints and a point inside
// each face. One of them inside the other body proves an overlap.
std::vector<gp_Pnt> boundary_samples(const TopoDS_Shape& shape) {
  std::vector<gp_Pnt> points;
  for (TopExp_Explorer v(shape, TopAbs_VERTEX); v.More(); v.Next())
    points.push_back(BRep_Tool::Pnt(TopoDS::Vertex(v.Current())));
  for (TopExp_Explorer e(shape, TopAbs_EDGE); e.More(); e.Next()) {
    const TopoDS_Edge& edge = TopoDS::Edge(e.Current());
    if (BRep_Tool::Degenerated(edge)) continue;
    BRepAdaptor_Curve curve(edge);
    points.push_back(curve.Value(0.5 * (curve.FirstParameter() + curve.LastParameter())));
  }
  for (TopExp_Explorer f(shape, TopAbs_FACE); f.More(); f.Next()) {
    const TopoDS_Face& face = TopoDS::Face(f.Current());
    BRepAdaptor_Surface surface(face);
    const gp_Pnt2d middle(0.5 * (surface.FirstUParameter() + surface.LastUParameter()),
                          0.5 * (surface.FirstVParameter() + surface.LastVParameter()));
    BRepTopAdaptor_FClass2d inside(face, Precision::PConfusion());
    if (inside.Perform(middle) == TopAbs_IN) points.push_back(surface.Value(middle.X(), middle.Y()));
  }
  return points;
}

// True when a boundary point of `from` lies inside `into` (deeper than the tolerance).
bool sample_inside(const TopoDS_Shape& from, const TopoDS_Shape& into, const Bnd_Box& into_box, double tolerance) {
  Bnd_Box inner = into_box;
  std::unique_ptr<BRepClass3d_SolidClassifier> classifier;
  for (const gp_Pnt& p : boundary_samples(from)) {
    double x0, y0, z0, x1, y1, z1;
    inner.Get(x0, y0, z0, x1, y1, z1);
    if (p.X() <= x0 + tolerance || p.X() >= x1 - tolerance || p.Y() <= y0 + tolerance || p.Y() >= y1 - tolerance ||
        p.Z() <= z0 + tolerance || p.Z() >= z1 - tolerance)
      continue;
    if (!classifier) classifier = std::make_unique<BRepClass3d_SolidClassifier>(into);
    classifier->Perform(p, tolerance);
    if (classifier->State() == TopAbs_IN) return true;
  }
  return false;
}

double shape_volume(const TopoDS_Shape& shape) {
  GProp_GProps props;
  BRepGProp::VolumeProperties(shape, props);
  return props.Mass();
}

// The volume of a common solid, integrated adaptively to 1e-7 relative: OCCT's
// fixed Gauss points miss on rational B-spline faces (a B-spline copy of a
// cylinder 5.05 in a bore 5: 8 % off the 15.79 mm3 ring).
double common_solid_volume(const TopoDS_Shape& shape) {
  GProp_GProps props;
  BRepGProp::VolumeProperties(shape, props, 1e-7);
  return props.Mass();
}

// Builds op, the Boolean common of a and b with the fuzzy value `tolerance`,
// serially. Arguments and tools set apart so the fuzzy value (coincident
// faces) applies; non-destructive: never grow the tolerances of the bodies'
// own edges and vertices (their boxes, and a second analysis of the same
// shapes, must not change).
void build_fuzzy_common(BRepAlgoAPI_Common& op, const TopoDS_Shape& a, const TopoDS_Shape& b, double tolerance) {
  TopTools_ListOfShape arguments, tools;
  arguments.Append(a);
  tools.Append(b);
  op.SetArguments(arguments);
  op.SetTools(tools);
  op.SetFuzzyValue(tolerance);
  op.SetNonDestructive(Standard_True);
  op.SetRunParallel(false);
  op.Build();
}

double common_volume(const TopoDS_Shape& a, const TopoDS_Shape& b, double tolerance) {
  BRepAlgoAPI_Common op;
  build_fuzzy_common(op, a, b, tolerance);
  if (!op.IsDone()) return -1;
  return common_solid_volume(op.Shape());
}

double box_volume(const Bnd_Box& box) {
  if (box.IsVoid()) return 0;
  double x0, y0, z0, x1, y1, z1;
  box.Get(x0, y0, z0, x1, y1, z1);
  return std::max(0.0, x1 - x0) * std::max(0.0, y1 - y0) * std::max(0.0, z1 - z0);
}

// The common box of two boxes grown by `grow` on every side (void when they miss).
Bnd_Box common_box(const Bnd_Box& a, const Bnd_Box& b, double grow) {
  Bnd_Box region;
  if (a.IsVoid() || b.IsVoid()) return region;
  double ax0, ay0, az0, ax1, ay1, az1, bx0, by0, bz0, bx1, by1, bz1;
  a.Get(ax0, ay0, az0, ax1, ay1, az1);
  b.Get(bx0, by0, bz0, bx1, by1, bz1);
  const double x0 = std::max(ax0, bx0) - grow, y0 = std::max(ay0, by0) - grow, z0 = std::max(az0, bz0) - grow;
  const double x1 = std::min(ax1, bx1) + grow, y1 = std::min(ay1, by1) + grow, z1 = std::min(az1, bz1) + grow;
  if (x1 <= x0 || y1 <= y0 || z1 <= z0) return region;
  region.Update(x0, y0, z0, x1, y1, z1);
  return region;
}

// `shape` cut down to the box: the Boolean common with it (empty shape when it fails).
TopoDS_Shape clipped(const TopoDS_Shape& shape, const Bnd_Box& box, double tolerance) {
  double x0, y0, z0, x1, y1, z1;
  box.Get(x0, y0, z0, x1, y1, z1);
  const TopoDS_Shape block = BRepPrimAPI_MakeBox(gp_Pnt(x0, y0, z0), gp_Pnt(x1, y1, z1)).Shape();
  BRepAlgoAPI_Common op;
  build_fuzzy_common(op, shape, block, tolerance);
  if (!op.IsDone() || op.HasErrors()) return TopoDS_Shape();
  return op.Shape();
}

// A region Boolean: the material two bodies share lies in the common box of
// their boxes, so A ^ B = (A ^ C) ^ (B ^ C') for any boxes C, C' holding that
// common box. When it is a small part of either body's box, each body is
// first cut down to it (a Boolean against six planes: the faces outside the
// region drop out before any face of one body meets a face of the other;
// never the whole of a body of B-spline faces against the whole of the
// other). B is cut by a box grown further than A's, so that the two cut
// faces never coincide. Otherwise, or when a cut fails, the whole solids.
// -1 when the Boolean fails.
constexpr double kRegionFraction = 0.25;  // region box below this share of a body's box: cut first

double region_common_volume(const TopoDS_Shape& a, const Bnd_Box& box_a, const TopoDS_Shape& b,
                            const Bnd_Box& box_b, double tolerance) {
  const double size = std::sqrt(std::max(box_a.SquareExtent(), box_b.SquareExtent()));
  const double grow = std::max(10 * tolerance, 1e-4 * size);
  const Bnd_Box region_a = common_box(box_a, box_b, grow);
  const Bnd_Box region_b = common_box(box_a, box_b, 2 * grow);
  if (region_a.IsVoid()) return 0;
  const double region = box_volume(region_b);
  if (region < kRegionFraction * box_volume(box_a) || region < kRegionFraction * box_volume(box_b)) {
    const TopoDS_Shape cut_a = clipped(a, region_a, tolerance);
    const TopoDS_Shape cut_b = cut_a.IsNull() ? TopoDS_Shape() : clipped(b, region_b, tolerance);
    if (!cut_a.IsNull() && !cut_b.IsNull()) {
      // Nothing of a body inside the region: nothing shared.
      if (TopExp_Explorer(cut_a, TopAbs_FACE).More() == Standard_False ||
          TopExp_Explorer(cut_b, TopAbs_FACE).More() == Standard_False)
        return 0;
      const double common = common_volume(cut_a, cut_b, tolerance);
      if (common >= 0) return common;
    }
  }
  return common_volume(a, b, tolerance);
}

// What the pass finds for one body pair.
struct PairOutcome {
  enum Kind { None, PressFit, Overlap, Failed } kind = None;
  double volume = 0;
  // Failed: the test itself failed (an OCCT exception or signal, `failure`
  // its text), or else the common volume of bodies that seem to overlap could not be computed.
  bool test_failed = false;
  std::string failure;
};

// What a failed outcome says, naming the pair's bodies.
std::string failure_message(const Assembly& assembly, int a, int b, const PairOutcome& outcome) {
  if (outcome.test_failed)
    return "interference test of '" + assembly.bodies[a].name + "' and '" + assembly.bodies[b].name +
           "' failed: " + outcome.failure;
  return "bodies '" + assembly.bodies[a].name + "' and '" + assembly.bodies[b].name +
         "' seem to overlap but their common volume could not be computed";
}

// A ball (one convex sphere partition) shares no material with a body whose
// boundary stays at least its radius (less the tolerance) from its centre,
// the centre outside that body: then no point of the body lies in the ball
// (a segment from the centre to it would cross the body's boundary inside
// the ball). One distance query, where the general test classifies samples
// and intersects a sphere with tori (balls in their raceways).
bool ball_apart(const BodyPartitions& ball, const TopoDS_Shape& other, const Tolerances& tol) {
  if (ball.partitions.size() != 1) return false;
  const Partition& sphere = ball.partitions.front();
  if (sphere.params.kind != SurfaceKind::Sphere || sphere.side != MaterialSide::Convex) return false;
  BRepExtrema_DistShapeShape distance(BRepBuilderAPI_MakeVertex(sphere.params.location).Vertex(), other);
  if (!distance.IsDone() || distance.NbSolution() == 0) return false;
  if (distance.InnerSolution() || distance.Value() < sphere.params.radius - tol.linear) return false;
  BRepClass3d_SolidClassifier centre(other, sphere.params.location, tol.linear);
  return centre.State() == TopAbs_OUT;
}

PairOutcome test_pair(const Assembly& assembly, const ContactsResult& result, int a, int b) {
  const BodyPartitions& pa = result.partitions[a];
  const BodyPartitions& pb = result.partitions[b];
  const Tolerances tol = pair_tolerances(pa, pb);
  PairOutcome out;
  double volume = 0;
  std::vector<gp_Ax1> axes;
  const bool shaft_in_b = press_fits(pa, pb, tol, volume, &axes);
  const bool shaft_in_a = press_fits(pb, pa, tol, volume, &axes);
  if (shaft_in_b || shaft_in_a) {
    // The ring proves the overlap (its volume is an estimate); what the
    // bodies share beyond the cylinders (a chamfer or counterbore at the
    // bore's mouth around the shaft: R08's 4848 mm3 ring is 5 % short of the
    // 5105 mm3 both solids share) is measured from the faces about the press
    // fit's axis when one body is a solid of revolution about it and the
    // other is one within its reach (coaxial_overlap.h, exact, no Boolean);
    // otherwise by the region Boolean. A failed Boolean leaves the ring (not a
    // bound either way: a cross hole through the bore takes material out of it).
    out.kind = PairOutcome::PressFit;
    for (const gp_Ax1& axis : axes)
      if (const std::optional<double> exact = coaxial_common_volume(pa, assembly.bodies[a].shape, pb,
                                                                    assembly.bodies[b].shape, axis, tol)) {
        out.volume = *exact;
        return out;
      }
    const double common = region_common_volume(assembly.bodies[a].shape, pa.box, assembly.bodies[b].shape, pb.box,
                                               tol.linear);
    out.volume = common >= 0 ? common : volume;
    return out;
  }
  // Instances hold no outlines of their own: their source's, same frames.
  const auto outlines = [&](int body) -> const BodyPartitions& {
    const int source = body < static_cast<int>(result.instance_of.size()) ? result.instance_of[body] : body;
    return result.partitions[source];
  };
  if (provably_apart(pa, outlines(a), pb, outlines(b), tol)) return out;
  const TopoDS_Shape& shape_a = assembly.bodies[a].shape;
  const TopoDS_Shape& shape_b = assembly.bodies[b].shape;
  if (ball_apart(pa, shape_b, tol) || ball_apart(pb, shape_a, tol)) return out;
  // No sample strictly inside: they share volume only if their boundaries
  // cross (boundary_crossing.h, complete for solids).
  if (!sample_inside(shape_a, shape_b, pb.box, tol.linear) && !sample_inside(shape_b, shape_a, pa.box, tol.linear) &&
      !boundaries_cross(shape_a, pa, shape_b, pb, tol))
    return out;
  const double common = region_common_volume(shape_a, pa.box, shape_b, pb.box, tol.linear);
  if (common < 0) {
    out.kind = PairOutcome::Failed;
    return out;
  }
  const double smaller = std::min(std::abs(shape_volume(shape_a)), std::abs(shape_volume(shape_b)));
  if (common > kMinRelativeVolume * smaller) {
    out.kind = PairOutcome::Overlap;
    out.volume = common;
  }
  return out;
}

}  // namespace

double press_fit_volume(const BodyPartitions& a, const BodyPartitions& b, const Tolerances& tol) {
  double volume = 0;
  press_fits(a, b, tol, volume);
  press_fits(b, a, tol, volume);
  return volume;
}

std::vector<Interference> whole_solid_interferences(const Assembly& assembly, const ContactsResult& result,
                                                    int threads) {
  const std::size_t n = assembly.bodies.size();
  std::vector<Bnd_Box> boxes(n);
  std::vector<double> volumes(n, 0);
  parallel_for(n, threads, nullptr, "interferences", [&](std::size_t i) {
    BRepBndLib::Add(assembly.bodies[i].shape, boxes[i]);
    volumes[i] = std::abs(shape_volume(assembly.bodies[i].shape));
  });
  std::vector<std::pair<int, int>> pairs;
  for (std::size_t a = 0; a < n; ++a) {
    if (box_thickness(boxes[a]) <= result.partitions[a].tolerances.linear) continue;  // holds no material
    for (std::size_t b = a + 1; b < n; ++b) {
      if (box_thickness(boxes[b]) <= result.partitions[b].tolerances.linear) continue;
      const double linear = pair_tolerances(result.partitions[a], result.partitions[b]).linear;
      if (box_overlap(boxes[a], boxes[b]) > linear) pairs.push_back({static_cast<int>(a), static_cast<int>(b)});
    }
  }
  std::vector<double> commons(pairs.size(), 0);
  const OcctGuard guard;
  parallel_for(pairs.size(), threads, nullptr, "interferences", [&](std::size_t k) {
    const int a = pairs[k].first, b = pairs[k].second;
    const double linear = pair_tolerances(result.partitions[a], result.partitions[b]).linear;
    std::string failure;
    if (!run_guarded([&] { commons[k] = common_volume(assembly.bodies[a].shape, assembly.bodies[b].shape, linear); },
                     failure))
      commons[k] = -1;
  });
  std::vector<Interference> found;
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const int a = pairs[k].first, b = pairs[k].second;
    if (commons[k] > kMinRelativeVolume * std::min(volumes[a], volumes[b]))
      found.push_back({a, b, commons[k], TopoDS_Shape()});
  }
  return found;
}

Status find_interferences(const Assembly& assembly, ContactsResult& result, Progress* progress, int threads) {
  const size_t n = assembly.bodies.size();
  std::vector<char> dropped(n, 0);  // zero-volume bodies and second copies: no contacts of their own

  for (size_t i = 0; i < n; ++i) {
    // A solid thinner than the tolerance holds no material (a zero-height box).
    if (box_thickness(result.partitions[i].box) <= result.partitions[i].tolerances.linear) {
      dropped[i] = 1;
      result.messages.push_back("body '" + assembly.bodies[i].name +
                                "' has no volume (thinner than the tolerance): its contacts are not counted");
    }
  }

  // Pairs whose boxes overlap deeper than the tolerance (the others at most
  // touch); copies in place found first, in order (a copy drops out of the
  // rest: its contacts repeat the first copy's).
  std::vector<std::pair<int, int>> deep;
  std::vector<Interference> copies;
  for (const auto& [a, b] : result.body_pairs) {
    if (dropped[a] || dropped[b]) continue;
    const BodyPartitions& pa = result.partitions[a];
    const BodyPartitions& pb = result.partitions[b];
    const double linear = pair_tolerances(pa, pb).linear;
    if (box_overlap(pa.box, pb.box) <= linear) continue;
    if (duplicates(pa, pb, linear)) {
      dropped[b] = 1;
      copies.push_back({a, b, -1, TopoDS_Shape()});
      result.messages.push_back("bodies '" + assembly.bodies[a].name + "' and '" + assembly.bodies[b].name +
                                "' are the same solid at the same place: an interference; the contacts of '" +
                                assembly.bodies[b].name + "' are not counted");
      continue;
    }
    deep.push_back({a, b});
  }
  deep.erase(std::remove_if(deep.begin(), deep.end(), [&](const auto& p) { return dropped[p.first] || dropped[p.second]; }),
             deep.end());

  // Pairs placed alike (pair_key.h: the same two shapes, the second placed
  // the same way relative to the first: a bolt in each of 5,000 plates)
  // share material alike: the first pair of each key is tested, the others
  // take its outcome (volumes are the same under a rigid motion).
  const auto source = [&result](int body) {
    return body < static_cast<int>(result.instance_of.size()) ? result.instance_of[body] : body;
  };
  const std::vector<std::size_t> representative = first_pairs_placed_alike(deep.size(), [&](std::size_t k) {
    const auto [a, b] = deep[k];
    const double linear = pair_tolerances(result.partitions[a], result.partitions[b]).linear;
    return pair_key(source(a), source(b), assembly.bodies[a], assembly.bodies[b], linear);
  });
  std::vector<std::size_t> tested;
  for (std::size_t k = 0; k < deep.size(); ++k)
    if (representative[k] == k) tested.push_back(k);
  std::vector<PairOutcome> outcomes(deep.size());
  // OCCT 7.6's Boolean common dereferences a null common block on some damaged
  // shapes (make fuzz, fuzz_brep): its signal handler makes that a failure of
  // the pair (OCC_CATCH_SIGNALS in each worker), not a crash.
  const OcctGuard guard;
  if (!parallel_for(tested.size(), threads, progress, "interferences", [&](std::size_t t) {
        const std::size_t k = tested[t];
        const auto a = deep[k].first, b = deep[k].second;  // not a structured binding: the lambda below captures them (clang 14)
        std::string failure;
        if (!run_guarded([&] { outcomes[k] = test_pair(assembly, result, a, b); }, failure)) {
          outcomes[k].kind = PairOutcome::Failed;
          outcomes[k].test_failed = true;
          outcomes[k].failure = failure;
        }
      }))
    return Status::failure(StatusCode::Cancelled, "cancelled");
  for (std::size_t k = 0; k < deep.size(); ++k)
    if (representative[k] != k) outcomes[k] = outcomes[representative[k]];
  std::vector<std::string> copy_failures(copies.size());
  if (!parallel_for(copies.size(), threads, progress, "interferences", [&](std::size_t k) {
        run_guarded([&] { copies[k].volume = std::abs(shape_volume(assembly.bodies[copies[k].body_a].shape)); },
                    copy_failures[k]);
      }))
    return Status::failure(StatusCode::Cancelled, "cancelled");
  for (std::size_t k = 0; k < copies.size(); ++k) {
    if (copy_failures[k].empty()) continue;
    copies[k].volume = 0;  // unknown: the copy is still reported
    result.messages.push_back("the volume of '" + assembly.bodies[copies[k].body_a].name +
                              "' could not be computed: " + copy_failures[k]);
  }

  for (const Interference& copy : copies) result.interferences.push_back(copy);
  for (std::size_t k = 0; k < deep.size(); ++k) {
    const PairOutcome& o = outcomes[k];
    if (o.kind == PairOutcome::Failed) result.messages.push_back(failure_message(assembly, deep[k].first, deep[k].second, o));
    if (o.kind != PairOutcome::PressFit && o.kind != PairOutcome::Overlap) continue;
    result.interferences.push_back({deep[k].first, deep[k].second, o.volume, TopoDS_Shape()});
  }
  std::sort(result.interferences.begin(), result.interferences.end(),
            [](const Interference& l, const Interference& r) {
              return std::tie(l.body_a, l.body_b) < std::tie(r.body_a, r.body_b);
            });

  // Empty bodies and second copies have no contacts of their own. A pair
  // whose material overlaps keeps every contact it has (a press-fitted
  // tongue on its slot's floor, a shoulder on its seat: the R08 press's 8
  // PLF + 7 CLJ): faces that touch with opposite normals are real contacts
  // however much the bodies overlap elsewhere; the interference is reported
  // beside them.
  result.contacts.erase(std::remove_if(result.contacts.begin(), result.contacts.end(),
                                       [&](const Contact& c) { return dropped[c.body_a] || dropped[c.body_b]; }),
                        result.contacts.end());
  result.higher_pairs.erase(std::remove_if(result.higher_pairs.begin(), result.higher_pairs.end(),
                                           [&](const HigherPair& h) { return dropped[h.body_a] || dropped[h.body_b]; }),
                            result.higher_pairs.end());
  return Status::success();
}

}  // namespace contactcore
