#include "contactcore/haptics/realtime_contacts.h"

#include <algorithm>
#include <cmath>

namespace contactcore::haptics {

namespace {

using Vec2 = Eigen::Vector2d;
constexpr int kMaxLive = 256;

Vec3 to_vec(const gp_Pnt& p) { return {p.X(), p.Y(), p.Z()}; }
Vec3 to_vec(const gp_Dir& d) { return {d.X(), d.Y(), d.Z()}; }

Eigen::AlignedBox3d to_box(const Bnd_Box& b) {
  Eigen::AlignedBox3d box;
  if (b.IsVoid()) return box;
  double x0, y0, z0, x1, y1, z1;
  b.Get(x0, y0, z0, x1, y1, z1);
  box.extend(Vec3(x0, y0, z0));
  box.extend(Vec3(x1, y1, z1));
  return box;
}

Eigen::AlignedBox3d transformed(const Eigen::AlignedBox3d& box, const Pose& pose) {
  Eigen::AlignedBox3d out;
  if (box.isEmpty()) return out;
  for (int i = 0; i < 8; ++i)
    out.extend(pose * box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(i)));
  return out;
}


double line_distance(const Vec3& p, const Vec3& origin, const Vec3& axis) {
  const Vec3 r = p - origin;
  return (r - r.dot(axis) * axis).norm();
}

int kind_index(SurfaceKind k) { return static_cast<int>(k); }

// Radial band [r_min, r_max] of a planar outline about an axis line
// perpendicular to it: r_min is 0 when the axis pierces the material.
void radial_band(const std::vector<std::vector<Vec3>>& loops, const Pose& pose, const Vec3& point,
                 const Vec3& axis, double& r_min, double& r_max) {
  r_min = 1e300;
  r_max = 0;
  // Winding number of the axis point about the loops, in a frame normal to the axis.
  Vec3 x = axis.unitOrthogonal(), y = axis.cross(x);
  double winding = 0;
  for (const auto& loop : loops) {
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const Vec3 a = pose * loop[i] - point, b = pose * loop[(i + 1) % loop.size()] - point;
      const double ra = (a - a.dot(axis) * axis).norm();
      r_min = std::min(r_min, ra);
      r_max = std::max(r_max, ra);
      winding += std::atan2(a.dot(x) * b.dot(y) - a.dot(y) * b.dot(x), a.dot(x) * b.dot(x) + a.dot(y) * b.dot(y));
    }
  }
  if (std::abs(winding) > kPi) r_min = 0;
}

// Point-in-region by the even-odd rule over every loop (outer and holes),
// in the 2D frame (x, y) of a plane through `origin`.
bool inside(const Vec2& q, const std::vector<std::vector<Vec3>>& loops, const Pose& pose, const Vec3& origin,
            const Vec3& x, const Vec3& y) noexcept {
  bool in = false;
  for (const auto& loop : loops) {
    const std::size_t n = loop.size();
    for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
      const Vec3 pi = pose * loop[i] - origin, pj = pose * loop[j] - origin;
      const double xi = pi.dot(x), yi = pi.dot(y), xj = pj.dot(x), yj = pj.dot(y);
      if ((yi > q.y()) != (yj > q.y()) && q.x() < (xj - xi) * (q.y() - yi) / (yj - yi) + xi) in = !in;
    }
  }
  return in;
}

// Proper crossing of segments ab and cd (2D).
bool segments_cross(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) noexcept {
  auto orient = [](const Vec2& p, const Vec2& q, const Vec2& r) {
    return (q.x() - p.x()) * (r.y() - p.y()) - (q.y() - p.y()) * (r.x() - p.x());
  };
  const double d1 = orient(c, d, a), d2 = orient(c, d, b), d3 = orient(a, b, c), d4 = orient(a, b, d);
  return ((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0));
}

}  // namespace

bool outlines_overlap(const SurfaceProxy& m, const Pose& pose, const SurfaceProxy& o) noexcept {
  if (m.loops.empty() || o.loops.empty()) return true;  // no outline known: the boxes decided
  const Vec3 x = o.axis.unitOrthogonal(), y = o.axis.cross(x), origin = o.location;
  const Pose identity = Pose::Identity();
  auto flat = [&](const Vec3& p) { return Vec2((p - origin).dot(x), (p - origin).dot(y)); };
  // A vertex of one strictly inside the other: the regions share area near it.
  for (const auto& loop : m.loops)
    for (const Vec3& p : loop)
      if (inside(flat(pose * p), o.loops, identity, origin, x, y)) return true;
  for (const auto& loop : o.loops)
    for (const Vec3& p : loop)
      if (inside(flat(p), m.loops, pose, origin, x, y)) return true;
  // Boundaries crossing (two overlapping rectangles in a cross).
  for (const auto& lm : m.loops)
    for (std::size_t i = 0; i < lm.size(); ++i) {
      const Vec2 a = flat(pose * lm[i]), b = flat(pose * lm[(i + 1) % lm.size()]);
      for (const auto& lo : o.loops)
        for (std::size_t j = 0; j < lo.size(); ++j)
          if (segments_cross(a, b, flat(lo[j]), flat(lo[(j + 1) % lo.size()]))) return true;
    }
  return false;
}

bool cone_bands_overlap(const SurfaceProxy& a, const SurfaceProxy& b) noexcept {
  return std::min(a.axial_max, b.axial_max) - std::max(a.axial_min, b.axial_min) > 1e-3;
}

RealtimeContacts::RealtimeContacts(const std::vector<BodyPartitions>& partitions, int moving,
                                   const CaptureTolerances& tolerances)
    : bodies_(partitions.size()), moving_(moving), tolerances_(tolerances) {
  for (std::size_t b = 0; b < partitions.size(); ++b) {
    BodySurfaces& body = bodies_[b];
    for (const Partition& p : partitions[b].partitions) {
      if (p.params.kind == SurfaceKind::Other || p.params.kind == SurfaceKind::Torus) continue;
      SurfaceProxy s;
      s.body = static_cast<int>(b);
      s.partition = p.id;
      s.kind = p.params.kind;
      s.side = p.side;
      s.location = to_vec(p.params.location);
      s.axis = to_vec(p.params.axis);
      s.radius = p.params.radius;
      s.half_angle = p.params.half_angle;
      s.axial_min = p.extent.axial_min;
      s.axial_max = p.extent.axial_max;
      s.box = to_box(p.box);
      if (s.kind == SurfaceKind::Plane) {
        const Vec3 xdir = to_vec(p.extent.ref_dir), ydir = s.axis.cross(xdir);
        for (const Polygon2& loop : p.extent.outline) {
          std::vector<Vec3> points;
          points.reserve(loop.size());
          for (const Point2& q : loop) points.push_back(s.location + q.x * xdir + q.y * ydir);
          s.loops.push_back(std::move(points));
        }
      }
      body.surfaces.push_back(std::move(s));
    }
    body.box = to_box(partitions[b].box);
    for (int k = 0; k < 6; ++k) {
      for (int i = 0; i < static_cast<int>(body.surfaces.size()); ++i)
        if (kind_index(body.surfaces[i].kind) == k) body.by_radius[k].push_back(i);
      std::sort(body.by_radius[k].begin(), body.by_radius[k].end(),
                [&](int a, int c) { return body.surfaces[a].radius < body.surfaces[c].radius; });
    }
  }
}

int RealtimeContacts::near_bodies(const Pose& pose, int* out, int capacity) const noexcept {
  Eigen::AlignedBox3d box = transformed(bodies_[moving_].box, pose);
  if (box.isEmpty()) return 0;
  const Vec3 pad = Vec3::Constant(tolerances_.distance);
  box.min() -= pad;
  box.max() += pad;
  int n = 0;
  for (int b = 0; b < static_cast<int>(bodies_.size()) && n < capacity; ++b)
    if (b != moving_ && !bodies_[b].box.isEmpty() && box.intersects(bodies_[b].box)) out[n++] = b;
  return n;
}

bool RealtimeContacts::match(const SurfaceProxy& m, const SurfaceProxy& local, const Pose& pose, const SurfaceProxy& o,
                             LiveContact& c, double lead_in) const noexcept {
  const double cos_tol = std::cos(tolerances_.angle);
  switch (m.kind) {
    case SurfaceKind::Cylinder: {
      if (!contactcore::convex_against_concave(m.side, o.side)) return false;
      // A shaft (convex) in a bore (concave): line to line within the radius
      // tolerance, or a clearance fit up to `clearance` larger.
      const double gap = m.side == MaterialSide::Convex ? o.radius - m.radius : m.radius - o.radius;
      if (gap < -tolerances_.radius || gap > tolerances_.radius + tolerances_.clearance) return false;
      const double clearance = std::max(0.0, gap);
      const double dot = std::abs(m.axis.dot(o.axis));
      if (dot < cos_tol) return false;
      const Vec3 p1 = m.location + m.axial_min * m.axis, p2 = m.location + m.axial_max * m.axis;
      const double d = std::max(line_distance(p1, o.location, o.axis), line_distance(p2, o.location, o.axis));
      if (d > tolerances_.distance + clearance) return false;
      const double s1 = (p1 - o.location).dot(o.axis), s2 = (p2 - o.location).dot(o.axis);
      const double lo = std::max(std::min(s1, s2), o.axial_min), hi = std::min(std::max(s1, s2), o.axial_max);
      // Sharing an axial band, or (lead-in) about to: the shaft's end
      // outside the bore's mouth by at most `lead_in`.
      const bool inside = hi - lo >= 1e-3;
      if (!inside && (lead_in <= 0 || lo - hi > lead_in)) return false;
      c.mouth_gap = inside ? 0.0 : std::max(lo - hi, 1e-9);
      c.type = ContactType::CLJ;
      c.distance = d;
      c.angle = std::acos(std::min(1.0, dot));
      c.clearance = clearance;
      return true;
    }
    case SurfaceKind::Cone: {
      if (!contactcore::convex_against_concave(m.side, o.side) || std::abs(m.half_angle - o.half_angle) > tolerances_.angle) return false;
      const double dot = m.axis.dot(o.axis);
      const double d = (m.location - o.location).norm();
      if (dot < cos_tol || d > tolerances_.distance) return false;
      // One surface, not two chamfers of one angle: their bands must meet.
      if (!cone_bands_overlap(m, o)) return false;
      c.type = ContactType::CJU;
      c.distance = d;
      c.angle = std::acos(std::min(1.0, dot));
      return true;
    }
    case SurfaceKind::Sphere: {
      if (!contactcore::convex_against_concave(m.side, o.side) || std::abs(m.radius - o.radius) > tolerances_.radius) return false;
      const double d = (m.location - o.location).norm();
      if (d > tolerances_.distance) return false;
      c.type = ContactType::SPF;
      c.distance = d;
      c.angle = 0;
      return true;
    }
    case SurfaceKind::Plane: {
      const double dot = m.axis.dot(o.axis);
      if (dot > -cos_tol) return false;
      const double d = std::abs((m.location - o.location).dot(o.axis));
      if (d > tolerances_.distance) return false;
      Eigen::AlignedBox3d box = m.box;
      const Vec3 pad = Vec3::Constant(tolerances_.distance);
      box.min() -= pad;
      box.max() += pad;
      if (!box.intersects(o.box)) return false;
      // The real outlines must share area, not just their boxes (an L-shaped
      // face's box covers what lies beside it).
      if (!outlines_overlap(local, pose, o)) return false;
      c.type = ContactType::PLF;
      c.distance = d;
      c.angle = std::acos(std::min(1.0, -dot));
      return true;
    }
    default:
      return false;
  }
}

int RealtimeContacts::update(const Pose& pose, LiveContact* out, int capacity, double lead_in) const noexcept {
  int near[kMaxLive];
  const int near_count = near_bodies(pose, near, kMaxLive);
  int n = 0;
  const auto& moving = bodies_[moving_].surfaces;
  for (int mi = 0; mi < static_cast<int>(moving.size()); ++mi) {
    const SurfaceProxy& local = moving[mi];
    // The moving partition at this pose (outline loops are not needed here).
    SurfaceProxy m;
    m.kind = local.kind;
    m.side = local.side;
    m.location = pose * local.location;
    m.axis = pose.linear() * local.axis;
    m.radius = local.radius;
    m.half_angle = local.half_angle;
    m.axial_min = local.axial_min;
    m.axial_max = local.axial_max;
    m.box = transformed(local.box, pose);
    for (int k = 0; k < near_count; ++k) {
      const BodySurfaces& body = bodies_[near[k]];
      if (!m.box.isEmpty()) {
        Eigen::AlignedBox3d padded = body.box;
        padded.min() -= Vec3::Constant(tolerances_.distance);
        padded.max() += Vec3::Constant(tolerances_.distance);
        if (!padded.intersects(m.box)) continue;
      }
      const std::vector<int>& list = body.by_radius[kind_index(m.kind)];
      auto first = list.begin();
      // Radii that may match: the tolerance, and for cylinders a clearance fit either way.
      const double slack = tolerances_.radius + (m.kind == SurfaceKind::Cylinder ? tolerances_.clearance : 0.0);
      if (m.kind != SurfaceKind::Plane && m.kind != SurfaceKind::Cone)
        first = std::lower_bound(list.begin(), list.end(), m.radius - slack,
                                 [&](int i, double r) { return body.surfaces[i].radius < r; });
      for (auto it = first; it != list.end(); ++it) {
        const SurfaceProxy& o = body.surfaces[*it];
        if (m.kind != SurfaceKind::Plane && m.kind != SurfaceKind::Cone && o.radius > m.radius + slack) break;
        LiveContact c;
        if (!match(m, local, pose, o, c, lead_in)) continue;
        if (n >= capacity) return n;
        c.body = near[k];
        c.moving_partition = local.partition;
        c.other_partition = o.partition;
        c.other_index = *it;
        c.moving_index = mi;
        out[n++] = c;
      }
    }
  }
  return n;
}

// ---- engagement

ContactJointFinder::ContactJointFinder(const RealtimeContacts& contacts, std::vector<int> partition_groups,
                                       const Vec3& centre)
    : contacts_(contacts), groups_(std::move(partition_groups)), centre_(centre), live_(kMaxLive) {}

bool ContactJointFinder::capture(const Pose& pose, JointState& joint) noexcept {
  const int n = contacts_.update(pose, live_.data(), kMaxLive, contacts_.tolerances().distance);
  // The nearest contact of a type (a shaft inside its bore before one at a mouth).
  auto nearest = [&](ContactType type) -> const LiveContact* {
    const LiveContact* best = nullptr;
    for (int i = 0; i < n; ++i) {
      const LiveContact& c = live_[i];
      if (c.type != type) continue;
      if (!best || (c.mouth_gap > 0) < (best->mouth_gap > 0) ||
          ((c.mouth_gap > 0) == (best->mouth_gap > 0) && c.distance < best->distance))
        best = &c;
    }
    return best;
  };
  // What fixes more first: a shaft in a bore, a cone in its seat, a ball in a cup, a face on a plane.
  if (const LiveContact* clj = nearest(ContactType::CLJ)) {
    fill_axial(*clj, n, joint);
    joint.at_mouth = clj->mouth_gap > 0;
    add_stops(pose, joint);
    return true;
  }
  if (cone_seat(pose, joint, nullptr)) {
    add_stops(pose, joint);
    return true;
  }
  if (const LiveContact* spf = nearest(ContactType::SPF)) {
    fill_axial(*spf, n, joint);
    return true;
  }
  // Planes: the nearest face that is not tilted past the capture angle.
  const LiveContact* plf = nearest(ContactType::PLF);
  return plf && plane_joint(pose, *plf, joint);
}

void ContactJointFinder::fill_axial(const LiveContact& best, int n, JointState& joint) const noexcept {
  const SurfaceProxy& o = contacts_.surfaces(best.body)[best.other_index];
  const SurfaceProxy& m = contacts_.moving_surfaces()[best.moving_index];
  joint = JointState{};
  joint.kind = best.type == ContactType::CLJ ? JointKind::Cylindrical : JointKind::Spherical;
  joint.point = o.location;
  joint.axis = o.axis.normalized();
  joint.part_point = m.location;
  joint.part_axis = m.axis.normalized();
  joint.part_axial_min = m.axial_min;
  joint.part_axial_max = m.axial_max;
  joint.radius = best.type == ContactType::CLJ ? o.radius : 0.0;
  joint.contact_type = static_cast<int>(best.type);
  const int partition = best.moving_partition;
  joint.group = partition >= 0 && partition < static_cast<int>(groups_.size()) ? groups_[partition] : -1;
  // Every body holding the part on this same axis (all the bores of a shaft).
  for (int i = 0; i < n; ++i) {
    const LiveContact& c = live_[i];
    if (c.type != best.type) continue;
    if (c.mouth_gap > 0 && best.mouth_gap == 0) continue;  // not entered yet: not a body it is in
    const SurfaceProxy& oc = contacts_.surfaces(c.body)[c.other_index];
    const bool same = joint.kind == JointKind::Spherical
                          ? (oc.location - o.location).norm() < contacts_.tolerances().distance
                          : std::abs(oc.axis.dot(joint.axis)) > std::cos(contacts_.tolerances().angle) &&
                                line_distance(oc.location, joint.point, joint.axis) < contacts_.tolerances().radius * 10;
    if (!same) continue;
    bool listed = false;
    for (int k = 0; k < joint.body_count; ++k) listed |= joint.bodies[k] == c.body;
    if (!listed && joint.body_count < kMaxJointBodies) joint.bodies[joint.body_count++] = c.body;
  }
}

bool ContactJointFinder::cone_seat(const Pose& pose, JointState& joint, const JointState* same) const noexcept {
  const CaptureTolerances& tol = contacts_.tolerances();
  const double cos_tol = std::cos(tol.angle);
  int near[kMaxLive];
  const int near_count = contacts_.near_bodies(pose, near, kMaxLive);
  double best_lateral = 1e300;
  bool found = false;
  const auto& moving = contacts_.moving_surfaces();
  for (int mi = 0; mi < static_cast<int>(moving.size()); ++mi) {
    const SurfaceProxy& m = moving[mi];
    if (m.kind != SurfaceKind::Cone) continue;
    const Vec3 apex = pose * m.location, axis = pose.linear() * m.axis;
    // The male cone's apex stays on the opening side of the female's: sign +1
    // when the moving cone is the male (convex), -1 when it is the seat.
    const double sign = m.side == MaterialSide::Convex ? 1.0 : -1.0;
    for (int k = 0; k < near_count; ++k) {
      const auto& others = contacts_.surfaces(near[k]);
      for (int oi = 0; oi < static_cast<int>(others.size()); ++oi) {
        const SurfaceProxy& o = others[oi];
        if (o.kind != SurfaceKind::Cone || !contactcore::convex_against_concave(m.side, o.side)) continue;
        if (std::abs(m.half_angle - o.half_angle) > tol.angle || axis.dot(o.axis) < cos_tol) continue;
        const double lateral = line_distance(apex, o.location, o.axis);
        const double axial = sign * (apex - o.location).dot(o.axis);
        // Within reach: near the axis, not past the seat, not beyond the other cone's length.
        if (lateral > tol.distance || axial < -tol.distance || axial > o.axial_max - o.axial_min + tol.distance)
          continue;
        // Seated (apexes met), the two cones must share a band of surface:
        // two chamfers of one angle at different radii are no seat.
        if (!cone_bands_overlap(m, o)) continue;
        if (same && (std::abs(o.axis.dot(same->axis)) < cos_tol ||
                     line_distance(o.location, same->point, same->axis) > tol.distance))
          continue;
        if (lateral >= best_lateral) continue;
        best_lateral = lateral;
        found = true;
        JointState j;
        j.kind = JointKind::Cylindrical;
        j.point = o.location;
        j.axis = o.axis.normalized();
        j.part_point = m.location;
        j.part_axis = m.axis.normalized();
        j.part_axial_min = m.axial_min;
        j.part_axial_max = m.axial_max;
        j.contact_type = static_cast<int>(ContactType::CJU);
        j.group = m.partition >= 0 && m.partition < static_cast<int>(groups_.size()) ? groups_[m.partition] : -1;
        j.bodies[0] = near[k];
        j.body_count = 1;
        // The seat: sign * (apex - o.apex) . u >= 0 with apex - c fixed on the
        // snapped part (it slides and turns about u): -sign u . c <= sign (k - o.apex . u).
        const Pose snapped = snap_to_joint(j, pose);
        const Vec3 u = j.axis;
        const double offset = (snapped * m.location - snapped * centre_).dot(u);
        j.add_stop(-sign * u, sign * (offset - o.location.dot(u)));
        joint = j;
      }
    }
  }
  return found;
}

bool ContactJointFinder::plane_joint(const Pose& pose, const LiveContact& contact, JointState& joint) const noexcept {
  const SurfaceProxy& o = contacts_.surfaces(contact.body)[contact.other_index];
  const SurfaceProxy& m = contacts_.moving_surfaces()[contact.moving_index];
  JointState j;
  j.kind = JointKind::Planar;
  j.point = o.location;
  j.axis = o.axis.normalized();  // out of the other body's material, towards the part
  j.part_point = m.location;
  j.part_axis = m.axis.normalized();
  // The face's size about its point: how far its rim goes when it tilts.
  double rim = 0;
  for (const auto& loop : m.loops)
    for (const Vec3& p : loop) rim = std::max(rim, (p - m.location).norm());
  j.part_axial_min = 0;
  j.part_axial_max = rim;
  j.contact_type = static_cast<int>(ContactType::PLF);
  j.group = m.partition >= 0 && m.partition < static_cast<int>(groups_.size()) ? groups_[m.partition] : -1;
  j.bodies[0] = contact.body;
  j.body_count = 1;
  // One-sided: the face stays on its side of the plane. Its point's height
  // above the plane less the centre's is fixed under the joint's motions.
  const Pose snapped = snap_to_joint(j, pose);
  const double offset = (snapped * m.location - snapped * centre_).dot(j.axis);
  j.add_stop(-j.axis, offset - o.location.dot(j.axis));
  joint = j;
  return true;
}

void ContactJointFinder::add_stops(const Pose& pose, JointState& joint) const noexcept {
  const Pose snapped = snap_to_joint(joint, pose);
  const Vec3 c = snapped * centre_;
  const double cos_tol = std::cos(contacts_.tolerances().angle);
  const double tol = contacts_.tolerances().distance;
  for (const SurfaceProxy& m : contacts_.moving_surfaces()) {
    if (m.kind != SurfaceKind::Plane || m.loops.empty()) continue;
    const Vec3 n = snapped.linear() * m.axis;
    if (std::abs(n.dot(joint.axis)) < cos_tol) continue;
    double m_min, m_max;
    radial_band(m.loops, snapped, joint.point, joint.axis, m_min, m_max);
    const Vec3 pm = snapped * m.location;
    for (int b = 0; b < contacts_.body_count(); ++b) {
      if (b == contacts_.moving()) continue;
      for (const SurfaceProxy& o : contacts_.surfaces(b)) {
        if (o.kind != SurfaceKind::Plane || o.loops.empty() || n.dot(o.axis) > -cos_tol) continue;
        const double gap = n.dot(o.location - pm);
        if (gap < -tol) continue;  // behind the face: not in the way
        double o_min, o_max;
        radial_band(o.loops, Pose::Identity(), joint.point, joint.axis, o_min, o_max);
        if (std::min(m_max, o_max) - std::max(m_min, o_min) < 1e-6) continue;
        // Keep the nearest stop per direction.
        const double limit = n.dot(c) + gap;
        bool merged = false;
        for (int k = 0; k < joint.stop_count; ++k) {
          if (joint.stops[k].normal.dot(n) > cos_tol) {
            joint.stops[k].limit = std::min(joint.stops[k].limit, limit);
            merged = true;
          }
        }
        if (!merged) joint.add_stop(n, limit);
      }
    }
  }
}

bool ContactJointFinder::still_engaged(const Pose& pose, const JointState& joint, bool* entered) noexcept {
  const double cos_tol = std::cos(contacts_.tolerances().angle);
  if (entered) *entered = true;
  if (joint.contact_type == static_cast<int>(ContactType::CJU)) {
    JointState again;
    return cone_seat(pose, again, &joint);
  }
  // With the capture's lead-in: a shaft captured at its bore's mouth stays
  // held there, and a shaft pulled out is let go only beyond the capture
  // distance, where it could not be captured again (no capture, release,
  // capture again at each tick).
  const int n = contacts_.update(pose, live_.data(), kMaxLive, contacts_.tolerances().distance);
  bool held = false, inside = false;
  for (int i = 0; i < n; ++i) {
    const LiveContact& c = live_[i];
    const SurfaceProxy& o = contacts_.surfaces(c.body)[c.other_index];
    if (joint.kind == JointKind::Cylindrical && c.type == ContactType::CLJ &&
        std::abs(o.axis.dot(joint.axis)) > cos_tol &&
        line_distance(o.location, joint.point, joint.axis) < contacts_.tolerances().distance) {
      held = true;
      inside = inside || c.mouth_gap == 0;
      continue;
    }
    if (joint.kind == JointKind::Spherical && c.type == ContactType::SPF &&
        (o.location - joint.point).norm() < contacts_.tolerances().distance)
      return true;
    // A face stays on its plane while within the capture distance of it.
    if (joint.kind == JointKind::Planar && c.type == ContactType::PLF && o.axis.dot(joint.axis) > cos_tol &&
        std::abs((o.location - joint.point).dot(joint.axis)) < contacts_.tolerances().radius * 10)
      return true;
  }
  if (entered) *entered = inside;
  return held;
}

CollisionGroups collision_groups(const RealtimeContacts& contacts) {
  CollisionGroups groups;
  const auto& moving = contacts.moving_surfaces();
  int max_partition = -1;
  for (const auto& s : moving) max_partition = std::max(max_partition, s.partition);
  groups.moving_group.assign(max_partition + 1, -1);
  const double rtol = contacts.tolerances().radius;
  const double cos_tol = std::cos(contacts.tolerances().angle);
  std::vector<const SurfaceProxy*> representatives;  // one per group
  for (const SurfaceProxy& m : moving) {
    // Partners: cylinders and spheres of the same radius anywhere (opposite
    // side); cones and planes only where they meet at the assembled placement
    // (same angle and coaxial; coplanar and facing), since cones of one angle
    // (chamfers) and planes are everywhere.
    std::vector<std::vector<int>> partners(contacts.body_count());
    bool any = false;
    for (int b = 0; b < contacts.body_count(); ++b) {
      if (b == contacts.moving()) continue;
      for (const SurfaceProxy& o : contacts.surfaces(b)) {
        if (o.kind != m.kind) continue;
        if (m.kind == SurfaceKind::Cylinder || m.kind == SurfaceKind::Sphere) {
          if (!contactcore::convex_against_concave(m.side, o.side) || std::abs(o.radius - m.radius) > rtol) continue;
        } else if (m.kind == SurfaceKind::Cone) {
          if (!contactcore::convex_against_concave(m.side, o.side) || std::abs(o.half_angle - m.half_angle) > contacts.tolerances().angle ||
              m.axis.dot(o.axis) < cos_tol || (m.location - o.location).norm() > contacts.tolerances().distance)
            continue;
        } else if (m.kind == SurfaceKind::Plane) {
          Eigen::AlignedBox3d box = m.box;
          box.min() -= Vec3::Constant(rtol * 10);
          box.max() += Vec3::Constant(rtol * 10);
          if (m.axis.dot(o.axis) > -cos_tol || std::abs((m.location - o.location).dot(o.axis)) > rtol * 10 ||
              !box.intersects(o.box))
            continue;
        } else {
          continue;
        }
        partners[b].push_back(o.partition);
        any = true;
      }
    }
    if (!any) continue;
    // Same surface as an earlier group: join it.
    int group = -1;
    for (int g = 0; g < static_cast<int>(representatives.size()); ++g) {
      const SurfaceProxy& r = *representatives[g];
      if (r.kind != m.kind) continue;
      if (m.kind == SurfaceKind::Plane) {
        if (r.axis.dot(m.axis) > cos_tol && std::abs((m.location - r.location).dot(r.axis)) < rtol * 10) group = g;
      } else if (m.kind == SurfaceKind::Cone) {
        if (std::abs(r.half_angle - m.half_angle) <= contacts.tolerances().angle && r.axis.dot(m.axis) > cos_tol &&
            (m.location - r.location).norm() < rtol * 10)
          group = g;
      } else if (std::abs(r.radius - m.radius) <= rtol && std::abs(r.axis.dot(m.axis)) > cos_tol &&
                 line_distance(m.location, r.location, r.axis) < rtol * 10 &&
                 (m.kind != SurfaceKind::Sphere || (m.location - r.location).norm() < rtol * 10)) {
        group = g;
      }
    }
    if (group < 0) {
      group = static_cast<int>(representatives.size());
      representatives.push_back(&m);
      groups.switched_off.emplace_back(contacts.body_count());
    }
    groups.moving_group[m.partition] = group;
    for (int b = 0; b < contacts.body_count(); ++b)
      for (int p : partners[b]) {
        auto& list = groups.switched_off[group][b];
        if (std::find(list.begin(), list.end(), p) == list.end()) list.push_back(p);
      }
  }
  return groups;
}

}  // namespace contactcore::haptics
