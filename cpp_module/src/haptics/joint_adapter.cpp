#include "contactcore/haptics/joint_adapter.h"

#include <algorithm>
#include <cmath>

namespace contactcore::haptics {

namespace {
Vec3 vec(const gp_Pnt& p) { return {p.X(), p.Y(), p.Z()}; }
Vec3 vec(const gp_Dir& d) { return {d.X(), d.Y(), d.Z()}; }
// Point and line contacts only (a ball or a wheel on a plane, a roller or a
// cone lying on one, a ball in a V): every twist free, each contact point a
// one-sided stop on the part's point there (TrialScene::attach_collision_group
// moves it to the centre of the part's surface: a ball's centre, a roller's
// axis). Circle contacts give planar or revolute joints: the switch below.
bool higher_pair_state(const PairJoint& pair, int moving, const Vec3& centre, JointState& out) {
  if (pair.stops.empty() || pair.stops.size() > static_cast<size_t>(kMaxStops)) return false;
  JointState j;
  j.kind = JointKind::HigherPair;
  j.point = centre;
  j.part_point = centre;
  Vec3 lift = Vec3::Zero();
  for (const OneSidedStop& stop : pair.stops) {
    if (stop.higher_pair < 0) return false;
    const Vec3 n = vec(stop.normal);
    const Vec3 blocked = moving == pair.body_b ? Vec3(-n) : n;
    const Vec3 at = vec(stop.point);
    j.add_stop(blocked, blocked.dot(at));
    j.stops[j.stop_count - 1].on_part_point = true;
    j.stops[j.stop_count - 1].part_point = at;
    lift -= blocked;
  }
  // The axis: the way off the surfaces (the lift-off normal, or their mean).
  j.axis = lift.norm() > 1e-9 ? Vec3(lift.normalized()) : Vec3(-j.stops[0].normal);
  j.part_axis = j.axis;
  j.bodies[0] = moving == pair.body_a ? pair.body_b : pair.body_a;
  j.body_count = 1;
  j.contact_type = static_cast<int>(ContactType::PLF);  // reports only: the surface it rests on
  out = j;
  return true;
}

}  // namespace

bool joint_state_from_pair(const PairJoint& pair, int moving, const Vec3& centre,
                           const Eigen::AlignedBox3d& part_box, JointState& out) {
  if (moving != pair.body_a && moving != pair.body_b) return false;
  if (pair.contacts.empty() && !pair.higher_pairs.empty() &&
      (pair.type == JointType::SpherePlane || pair.type == JointType::CylinderPlane || pair.type == JointType::General))
    return higher_pair_state(pair, moving, centre, out);
  JointState j;
  switch (pair.type) {
    case JointType::Rigid:
      j.kind = JointKind::Fixed;
      j.point = centre;
      break;
    case JointType::Revolute:
    case JointType::Cylindrical:
      if (pair.rotations.empty()) return false;
      j.kind = pair.type == JointType::Revolute ? JointKind::Revolute : JointKind::Cylindrical;
      j.point = vec(pair.rotations[0].point);
      j.axis = vec(pair.rotations[0].direction);
      break;
    case JointType::Prismatic:
      if (pair.translations.empty()) return false;
      j.kind = JointKind::Prismatic;
      j.point = centre;
      j.axis = vec(pair.translations[0]);
      break;
    case JointType::Spherical:
      if (pair.rotations.empty()) return false;
      j.kind = JointKind::Spherical;
      j.point = vec(pair.rotations[0].point);
      break;
    case JointType::Planar: {
      if (pair.rotations.empty()) return false;
      j.kind = JointKind::Planar;
      j.point = vec(pair.rotations[0].point);
      j.axis = vec(pair.rotations[0].direction);
      // The plane's normal out of the other body, towards the moving part: the
      // side a stop lets it leave by (b may move with u . n >= 0).
      for (const OneSidedStop& stop : pair.stops) {
        Vec3 free = vec(stop.normal);
        if (moving == pair.body_a) free = -free;
        if (std::abs(free.dot(j.axis)) > 1 - 1e-6) {
          j.axis = free.dot(j.axis) > 0 ? j.axis : Vec3(-j.axis);
          break;
        }
      }
      break;
    }
    default:
      return false;
  }
  // The joints stage counts one-sided contacts as holding both ways (a bearing
  // seated in its bore is Revolute); the loop lets the part leave through them:
  // an axial stop on a revolute joint makes it cylindrical with that stop.
  if (j.kind == JointKind::Revolute)
    for (const OneSidedStop& stop : pair.stops)
      if (std::abs(vec(stop.normal).dot(j.axis)) > 1 - 1e-6) j.kind = JointKind::Cylindrical;
  // Assembled: the part's own axis is the joint's (a face faces its plane).
  j.part_point = j.point;
  j.part_axis = j.kind == JointKind::Planar ? Vec3(-j.axis) : j.axis;
  double lo = 0, hi = 0;
  if (!part_box.isEmpty()) {
    lo = 1e300;
    hi = -1e300;
    for (int i = 0; i < 8; ++i) {
      const double s = (part_box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(i)) - j.point).dot(j.axis);
      lo = std::min(lo, s);
      hi = std::max(hi, s);
    }
  }
  j.part_axial_min = lo;
  j.part_axial_max = hi;
  if (j.kind == JointKind::Planar) {  // the face's reach when it tilts: the part's half-diagonal
    j.part_axial_min = 0;
    j.part_axial_max = part_box.isEmpty() ? 0.0 : 0.5 * part_box.diagonal().norm();
  }
  // Stops: b may move with u . n >= 0 at the stop; the moving part's reference
  // point keeps normal . c <= limit, written at the assembled placement.
  for (const OneSidedStop& stop : pair.stops) {
    const Vec3 n = vec(stop.normal);
    const Vec3 blocked = moving == pair.body_b ? Vec3(-n) : n;
    bool merged = false;
    for (int k = 0; k < j.stop_count; ++k) merged |= j.stops[k].normal.dot(blocked) > 1 - 1e-9;
    if (!merged) j.add_stop(blocked, blocked.dot(centre));
  }
  j.bodies[0] = moving == pair.body_a ? pair.body_b : pair.body_a;
  j.body_count = 1;
  j.contact_type = static_cast<int>(pair.type == JointType::Spherical ? ContactType::SPF
                                    : pair.type == JointType::Planar  ? ContactType::PLF
                                                                      : ContactType::CLJ);
  out = j;
  return true;
}

}  // namespace contactcore::haptics
