// What the servo loop asks of the assembly, as small abstract interfaces: the
// joint the part is held to (its free twists and one-sided stops), where a
// joint captures the part (engagement), and whether a pose collides with the
// neighbours (the joint's own partitions switched off). The trial fills them
// from the contacts (realtime_contacts.h) and the triangle models
// (stage_collision.h, on the collision stage); tests fill them by hand.
#pragma once

#include <array>

#include "contactcore/haptics/pose_math.h"

namespace contactcore::haptics {

// Planar: a face on a plane (axis: the plane's normal, out of the material the
// part rests on; part_axis: the part's face normal). It slides in the plane,
// turns about the normal and may lift off (a one-sided stop keeps it out).
// HigherPair: point and line contacts (a ball or a wheel on a plane, a roller
// or a cone lying on one, a ball in a V): every twist is free but for the
// one-sided stops, each on a point of the part (a ball's centre, points of a
// roller's axis), so the part slides, turns and rolls on the surfaces and
// lifts off them, never sinks into them.
enum class JointKind { Free, Cylindrical, Revolute, Prismatic, Spherical, Fixed, Planar, HigherPair };
const char* to_string(JointKind kind);

// A one-sided stop: the reference point c of the part keeps normal . c <= limit
// (a shoulder on a bore's face, the bottom of a blind hole); with
// on_part_point, the part's point part_point (its assembled frame) does
// instead (a ball's centre above the plane it rolls on).
struct Stop {
  Vec3 normal = Vec3::UnitZ();
  double limit = 0;
  bool on_part_point = false;
  Vec3 part_point = Vec3::Zero();
};

// Where stop `s` holds the part at `pose` (c: its reference point, assembled).
inline Vec3 stop_point(const Stop& s, const Pose& pose, const Vec3& c) {
  return s.on_part_point ? Vec3(pose * s.part_point) : Vec3(pose * c);
}

constexpr int kMaxStops = 8;
constexpr int kMaxJointBodies = 8;

struct JointState {
  JointKind kind = JointKind::Free;
  Vec3 point = Vec3::Zero();   // on the axis line (world), or the centre (Spherical)
  Vec3 axis = Vec3::UnitZ();   // unit
  // The part's own axis (or centre), in its assembled frame: snapping aligns it.
  Vec3 part_point = Vec3::Zero();
  Vec3 part_axis = Vec3::UnitZ();
  double part_axial_min = 0, part_axial_max = 0;  // extent along part_axis from part_point
  double radius = 0;  // the bore's radius (a shaft in a bore), 0 when not one
  std::array<Stop, kMaxStops> stops{};
  int stop_count = 0;
  int group = -1;  // which collision partitions to switch off (-1: none)
  // The bodies this joint is with, and the contact type, for reports.
  std::array<int, kMaxJointBodies> bodies{};
  int body_count = 0;
  int contact_type = 0;  // contactcore::ContactType as int
  // A shaft captured at its bore's mouth (the lead-in: coaxial, its end
  // within the capture distance outside the bore), not yet inside it.
  bool at_mouth = false;

  bool add_stop(const Vec3& normal, double limit) {
    if (stop_count >= kMaxStops) return false;
    stops[stop_count++] = Stop{normal, limit};
    return true;
  }
};

// Free twists of `joint` at the part's reference point `c` (world), as the
// columns of `basis` (6 x n, n returned): (velocity of c, angular velocity).
int free_twists(const JointState& joint, const Vec3& c, Eigen::Matrix<double, 6, 6>& basis);

// `pose` moved the least onto the joint: the part's axis made the joint's axis
// (sign kept), its point put on the line (Cylindrical, Revolute, Prismatic),
// its centre on the centre (Spherical); for Planar, the part's face turned
// parallel to the plane (about the face's point; the normal stays free).
Pose snap_to_joint(const JointState& joint, const Pose& pose);

// Largest distance from the joint's axis line of the part's axis over its
// extent (mm): how far the pose is from the joint (0 when snapped). Planar:
// how far the face's rim (radius part_axial_max) is off parallel.
double joint_deviation(const JointState& joint, const Pose& pose);

// Engagement: the joint near `pose` within the capture distance and angle.
class JointFinder {
 public:
  virtual ~JointFinder() = default;
  // True and `joint` filled when a joint captures the part at `pose`.
  virtual bool capture(const Pose& pose, JointState& joint) noexcept = 0;
  // False once the part has left the joint (no common extent left). For a
  // shaft in a bore, `entered` (when given) says whether it shares an axial
  // band with a bore on the joint's axis (false: only at a bore's mouth).
  virtual bool still_engaged(const Pose& pose, const JointState& joint, bool* entered) noexcept = 0;
};

// One contact of the part with another body, as the proxy's solver uses it:
// the gap along `normal` at `point` must not close (a non-penetration
// constraint, linearised about the pose it was measured at).
struct ContactPoint {
  Vec3 point = Vec3::Zero();   // on the part's surface (world)
  Vec3 normal = Vec3::UnitZ(); // unit, from the other body towards the part: the way out
  double gap = 0;              // mm: > 0 apart, < 0 overlapping (minus the depth)
  int body = -1;               // the other body
};

constexpr int kMaxContacts = 16;

class CollisionQuery {
 public:
  virtual ~CollisionQuery() = default;
  // True when the part at `pose` overlaps a neighbour; the partitions of
  // collision group `group` (a joint's own surfaces) are switched off.
  virtual bool collides(const Pose& pose, int group) noexcept = 0;
  // The part's contacts at `pose` with every neighbour nearer than `reach`
  // (mm): per neighbour its closest pair when apart, its deepest point (depth
  // and the direction out) when overlapping. At most `capacity` written;
  // returns how many. Allocation-free after set-up.
  virtual int contacts(const Pose& pose, int group, double reach, ContactPoint* out, int capacity) noexcept = 0;
  // Largest distance of the part's surface from `centre` (its assembled
  // frame): bounds how far any point moves for a given twist.
  virtual double radius_about(const Vec3& centre) const noexcept = 0;
};

}  // namespace contactcore::haptics
