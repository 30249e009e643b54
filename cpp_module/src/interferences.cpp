#include "contactcore/interferences.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include <BRepAlgoAPI_Common.hxx>
#include <BRepClass3d_SolidClassifier.hxx>
#include <BRepGProp.hxx>
#include <GProp_GProps.hxx>
#include <Standard_Failure.hxx>
#include <TopTools_ListOfShape.hxx>
#include <gp_Ax1.hxx>

namespace contactcore {

namespace {

// A common volume below this fraction of the smaller body is numerical noise.
constexpr double kMinRelativeVolume = 1e-6;

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

// A shaft coaxial with a bore of a smaller radius, over a common axial range:
// a press fit (what real interferences are; duplicates are found apart).
// `probe`: a point between the two radii, in the middle of the common range,
// which lies in both bodies when they really overlap there.
bool press_fit(const BodyPartitions& a, const BodyPartitions& b, const Tolerances& tol, std::vector<gp_Pnt>& probes) {
  for (const Partition& shaft : a.partitions) {
    if (shaft.params.kind != SurfaceKind::Cylinder || shaft.side != MaterialSide::Convex) continue;
    const gp_Ax1 axis(shaft.params.location, shaft.params.axis);
    for (const Partition& bore : b.partitions) {
      if (bore.params.kind != SurfaceKind::Cylinder || bore.side != MaterialSide::Concave) continue;
      if (shaft.params.radius <= bore.params.radius + tol.linear) continue;
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
      const double radius = 0.5 * (shaft.params.radius + bore.params.radius);
      const gp_Vec ref(shaft.extent.ref_dir);
      const gp_Vec binormal = direction.Crossed(ref);
      const double start = shaft.extent.angular.empty() ? 0 : shaft.extent.angular.front().start;
      const double span = shaft.extent.angular.empty() ? 2 * M_PI : shaft.extent.angular.front().span;
      for (double f : {0.5, 0.1, 0.9}) {
        const double angle = start + f * span;
        probes.push_back(axis.Location().Translated(direction * (0.5 * (low + high)) +
                                                    (ref * std::cos(angle) + binormal * std::sin(angle)) * radius));
      }
    }
  }
  return !probes.empty();
}

// A point classifier per body, made when first needed and kept: it caches
// the ray intersectors of the body's faces, the costly part on free-form
// faces, for the body's other pairs.
class Classifiers {
 public:
  explicit Classifiers(const Assembly& assembly) : assembly_(assembly), made_(assembly.bodies.size()) {}
  BRepClass3d_SolidClassifier& of(int body) {
    std::unique_ptr<BRepClass3d_SolidClassifier>& made = made_[body];
    if (!made) made = std::make_unique<BRepClass3d_SolidClassifier>(assembly_.bodies[body].shape);
    return *made;
  }

 private:
  const Assembly& assembly_;
  std::vector<std::unique_ptr<BRepClass3d_SolidClassifier>> made_;
};

// True when one of the points lies inside both bodies.
bool inside_both(const std::vector<gp_Pnt>& points, BRepClass3d_SolidClassifier& in_a,
                 BRepClass3d_SolidClassifier& in_b, double tolerance) {
  for (const gp_Pnt& p : points) {
    in_b.Perform(p, tolerance);
    if (in_b.State() != TopAbs_IN) continue;
    in_a.Perform(p, tolerance);
    if (in_a.State() == TopAbs_IN) return true;
  }
  return false;
}

double shape_volume(const TopoDS_Shape& shape) {
  GProp_GProps props;
  BRepGProp::VolumeProperties(shape, props);
  return props.Mass();
}

double common_volume(const TopoDS_Shape& a, const TopoDS_Shape& b, double tolerance) {
  // Arguments and tools set apart so the fuzzy value (coincident faces) applies.
  TopTools_ListOfShape arguments, tools;
  arguments.Append(a);
  tools.Append(b);
  BRepAlgoAPI_Common op;
  op.SetArguments(arguments);
  op.SetTools(tools);
  op.SetFuzzyValue(tolerance);
  // Never grow the tolerances of the bodies' own edges and vertices: their
  // boxes, and a second analysis of the same shapes, must not change.
  op.SetNonDestructive(Standard_True);
  op.SetRunParallel(false);
  op.Build();
  if (!op.IsDone()) return -1;
  return shape_volume(op.Shape());
}

}  // namespace

Status find_interferences(const Assembly& assembly, ContactsResult& result, Progress* progress) {
  const size_t n = assembly.bodies.size();
  const Tolerances& tol = result.tolerances;
  std::vector<char> dropped(n, 0);  // zero-volume bodies and second copies: no contacts of their own
  Classifiers classifiers(assembly);

  for (size_t i = 0; i < n; ++i) {
    // A solid thinner than the tolerance holds no material (a zero-height box).
    if (box_thickness(result.partitions[i].box) <= tol.linear) {
      dropped[i] = 1;
      result.messages.push_back("body '" + assembly.bodies[i].name +
                                "' has no volume (thinner than the tolerance): its contacts are not counted");
    }
  }

  for (size_t k = 0; k < result.body_pairs.size(); ++k) {
    if (progress && k % 256 == 0 &&
        !progress->report("interferences", static_cast<double>(k) / result.body_pairs.size()))
      return Status::failure(StatusCode::Cancelled, "cancelled");
    const auto [a, b] = result.body_pairs[k];
    if (dropped[a] || dropped[b]) continue;
    const BodyPartitions& pa = result.partitions[a];
    const BodyPartitions& pb = result.partitions[b];
    if (box_overlap(pa.box, pb.box) <= tol.linear) continue;  // at most touching
    const TopoDS_Shape& shape_a = assembly.bodies[a].shape;
    const TopoDS_Shape& shape_b = assembly.bodies[b].shape;
    try {
      if (duplicates(pa, pb, tol.linear)) {
        // Its contacts with third bodies repeat the first copy's.
        dropped[b] = 1;
        result.interferences.push_back({a, b, std::abs(shape_volume(shape_a))});
        result.messages.push_back("bodies '" + assembly.bodies[a].name + "' and '" + assembly.bodies[b].name +
                                  "' are the same solid at the same place: an interference; the contacts of '" +
                                  assembly.bodies[b].name + "' are not counted");
        continue;
      }
      std::vector<gp_Pnt> probes;
      press_fit(pa, pb, tol, probes);
      press_fit(pb, pa, tol, probes);
      if (probes.empty() || !inside_both(probes, classifiers.of(a), classifiers.of(b), tol.linear)) continue;
      const double volume = common_volume(shape_a, shape_b, tol.linear);
      if (volume < 0) {
        result.messages.push_back("bodies '" + assembly.bodies[a].name + "' and '" + assembly.bodies[b].name +
                                  "' seem to overlap but their common volume could not be computed");
        continue;
      }
      const double smaller = std::min(std::abs(shape_volume(shape_a)), std::abs(shape_volume(shape_b)));
      if (volume > kMinRelativeVolume * smaller) result.interferences.push_back({a, b, volume});
    } catch (const Standard_Failure& failure) {
      result.messages.push_back("interference test of '" + assembly.bodies[a].name + "' and '" +
                                assembly.bodies[b].name + "' failed: " + failure.GetMessageString());
    }
  }

  // Empty bodies and second copies have no contacts. A press-fitted pair keeps
  // its real ones (a shoulder on its seat: the R08 press's 8 PLF + 7 CLJ).
  result.contacts.erase(std::remove_if(result.contacts.begin(), result.contacts.end(),
                                       [&](const Contact& c) { return dropped[c.body_a] || dropped[c.body_b]; }),
                        result.contacts.end());
  return Status::success();
}

}  // namespace contactcore
