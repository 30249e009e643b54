// Clearance fits: a convex and a concave surface of the same type on the same
// axis (or centre) whose radii differ by a gap smaller than the user's, e.g. a
// nut on its bolt. Reported beside contacts, never as contacts.
#include "contactcore/common/angles.h"
#include "contactcore/contacts/clearances.h"

#include "contacts/common_area.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

namespace contactcore {

namespace {

constexpr double kNotAFit = std::numeric_limits<double>::quiet_NaN();

// The radial gap of a convex/concave pair of partitions on the same axis or
// centre (negative: the convex one is the larger, they overlap), or NaN when
// they do not form a fit.
double fit_gap(const Partition& a, const Partition& b, const Tolerances& tol) {
  const SurfaceParams& pa = a.params;
  const SurfaceParams& pb = b.params;
  if (pa.kind != pb.kind) return kNotAFit;
  if (a.side == b.side || a.side == MaterialSide::Outward) return kNotAFit;
  const Partition& inner = a.side == MaterialSide::Convex ? a : b;
  const Partition& outer = a.side == MaterialSide::Convex ? b : a;
  if (pa.kind == SurfaceKind::Cylinder) {
    if (pa.axis.Angle(pb.axis) > tol.angular && kPi - pa.axis.Angle(pb.axis) > tol.angular) return kNotAFit;
    if (distance_to_line(pb.location, pa.location, pa.axis) > tol.linear) return kNotAFit;
    // The two must overlap along the axis.
    const gp_Vec shift(pa.location, pb.location);
    const double offset = shift.Dot(gp_Vec(pa.axis));
    const double sign = pa.axis.Dot(pb.axis) > 0 ? 1.0 : -1.0;
    double b_min = offset + sign * b.extent.axial_min, b_max = offset + sign * b.extent.axial_max;
    if (b_min > b_max) std::swap(b_min, b_max);
    if (std::min(a.extent.axial_max, b_max) - std::max(a.extent.axial_min, b_min) <= tol.linear) return kNotAFit;
  } else if (pa.kind == SurfaceKind::Sphere) {
    if (pa.location.Distance(pb.location) > tol.linear) return kNotAFit;
  } else {
    return kNotAFit;
  }
  return outer.params.radius - inner.params.radius;
}

// Facing parallel planes (opposite outward normals) a small distance apart,
// whose outlines overlap seen along the normal: the normal gap, else NaN.
double plane_gap(const BodyPartitions& body_a, const Partition& a, const BodyPartitions& body_b,
                 const Partition& b, const Tolerances& tol) {
  const SurfaceParams& pa = a.params;
  const SurfaceParams& pb = b.params;
  if (pa.kind != SurfaceKind::Plane || pb.kind != SurfaceKind::Plane) return kNotAFit;
  if (pa.axis.Dot(pb.axis) > -std::cos(tol.angular)) return kNotAFit;
  const double gap = gp_Vec(pa.location, pb.location).Dot(gp_Vec(pa.axis));
  if (gap <= tol.linear) return kNotAFit;
  const gp_Dir x = a.extent.ref_dir;
  const gp_Dir y = pa.axis.Crossed(x);
  for (int fa : a.faces) {
    const auto loops_a = outline_in(body_a.faces[fa - 1], pa.location, x, y);
    for (int fb : b.faces) {
      const auto loops_b = outline_in(body_b.faces[fb - 1], pa.location, x, y);
      if (common_area(loops_a, loops_b, tol.linear) > tol.linear * tol.linear) return gap;
    }
  }
  return kNotAFit;
}

}  // namespace

std::vector<Clearance> find_clearances(const std::vector<BodyPartitions>& partitions, double max_gap) {
  std::vector<Clearance> out;
  if (max_gap <= 0) return out;
  std::vector<Bnd_Box> boxes;
  for (const BodyPartitions& body : partitions) boxes.push_back(body.box);
  for (const auto& [i, j] : broad_phase(boxes, max_gap).pairs) {
    const int a = std::min(i, j), b = std::max(i, j);
    if (a < 0 || b >= static_cast<int>(partitions.size())) continue;
    const Tolerances tol = pair_tolerances(partitions[a], partitions[b]);
    for (const Partition& pa : partitions[a].partitions) {
      if (pa.params.kind == SurfaceKind::Cone || pa.params.kind == SurfaceKind::Torus ||
          pa.params.kind == SurfaceKind::Other)
        continue;
      for (const Partition& pb : partitions[b].partitions) {
        if (!boxes_meet(pa.box, pb.box, max_gap)) continue;
        const double gap = pa.params.kind == SurfaceKind::Plane
                               ? plane_gap(partitions[a], pa, partitions[b], pb, tol)
                               : fit_gap(pa, pb, tol);
        // Same radius is a contact, not a clearance. A convex surface larger than its coaxial
        // concave one by less than the gap is an overlap (a press fit drawn oversize): negative.
        if (std::isnan(gap) || std::abs(gap) <= tol.linear || std::abs(gap) >= max_gap) continue;
        if (gap < 0 && pa.params.kind == SurfaceKind::Plane) continue;
        out.push_back({a, b, pa.id, pb.id, pa.params.kind, gap});
      }
    }
  }
  std::sort(out.begin(), out.end(), [](const Clearance& x, const Clearance& y) {
    return std::tie(x.body_a, x.body_b, x.partition_a, x.partition_b) <
           std::tie(y.body_a, y.body_b, y.partition_a, y.partition_b);
  });
  return out;
}

}  // namespace contactcore
