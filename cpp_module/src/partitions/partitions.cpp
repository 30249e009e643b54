// Stage 2: partitions. Each face typed (face_typing.cpp, free-form faces
// recognised by surface_fitting.cpp, plane outlines by outlines.cpp), then
// adjacent faces on the same surface merged into maximal partitions
// (partition_merging.cpp; paper, section 3). Here: the stage's entry, its
// tolerances, and the angular interval sets and surface comparison the
// other files share.
#include "contactcore/partitions/partitions.h"
#include "contactcore/common/out_of_memory.h"

#include "partitions/face_typing.h"
#include "partitions/partition_merging.h"
#include "partitions/surface_fitting.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <BRepBndLib.hxx>
#include <Standard_Failure.hxx>
#include <TopExp.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>

namespace contactcore {

using detail::kAngularJoinGap;
using detail::wrap_angle;

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

Status body_tolerances(const Bnd_Box& body_box, std::optional<double> linear, std::optional<double> angular,
                       Tolerances& out) {
  if (!body_box.IsVoid()) {
    double x0, y0, z0, x1, y1, z1;
    body_box.Get(x0, y0, z0, x1, y1, z1);
    for (double v : {x0, y0, z0, x1, y1, z1})
      if (!std::isfinite(v))
        return Status::failure(StatusCode::InvalidInput, "the body's extent is not finite (a coordinate of " +
                                                             std::to_string(v) + " mm)");
  }
  out = resolve_tolerances(body_box, linear, angular);
  return Status::success();
}

Status body_tolerances(const TopoDS_Shape& shape, std::optional<double> linear, std::optional<double> angular,
                       Tolerances& out) {
  Bnd_Box box;
  if (!shape.IsNull()) BRepBndLib::Add(shape, box, false);
  return body_tolerances(box, linear, angular, out);
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
    return detail::distance_to_axis(p.XYZ(), origin.XYZ(), axis.XYZ());
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

BodyPartitions partition_shape(const TopoDS_Shape& shape, const Tolerances& tol) {
  BodyPartitions result;
  result.tolerances = tol;
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

    result.partitions = detail::merge_faces(shape, face_map, result.faces, tol);
  } CONTACTS_PASS_OUT_OF_MEMORY catch (const Standard_Failure& failure) {
    result.status = Status::failure(StatusCode::GeometryError,
                                    std::string("OCCT failed while partitioning: ") + failure.GetMessageString());
  } catch (const std::exception& error) {
    result.status = Status::failure(StatusCode::GeometryError, std::string("partitioning failed: ") + error.what());
  }
  return result;
}

}  // namespace contactcore
