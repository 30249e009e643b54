// Contacts in real time (the paper's second configuration): while one part
// moves, its contacts with the other bodies are found again at every pose
// from the partitions alone: a broad phase on the moving part's box only,
// then partitions of the same kind and radius (sorted per body) whose
// parameters match within a capture tolerance. No OCCT call after set-up, no
// allocation per update. Engagement (JointFinder) builds on it: near a
// shaft-in-bore contact the part is captured by a cylindrical joint on the
// bore's axis, with one-sided stops from the facing planes along that axis.
#pragma once

#include <string>
#include <vector>

#include "contactcore/contacts/contacts.h"
#include "contactcore/haptics/constraints.h"

namespace contactcore::haptics {

// A partition as plain numbers (global frame; for the moving part, its
// assembled placement).
struct SurfaceProxy {
  int body = 0, partition = 0;
  SurfaceKind kind = SurfaceKind::Other;
  MaterialSide side = MaterialSide::Outward;
  Vec3 location = Vec3::Zero(), axis = Vec3::UnitZ();
  double radius = 0, half_angle = 0;
  double axial_min = 0, axial_max = 0;  // revolution surfaces, along axis from location
  Eigen::AlignedBox3d box;
  std::vector<std::vector<Vec3>> loops; // planes: outline loops (outer CCW, holes CW about axis)
};

struct CaptureTolerances {
  double distance = 0.5;   // mm: axis lines, plane distances, centres
  double angle = 0.035;    // rad (2 degrees)
  double radius = 0.005;   // mm: radii must agree this well to be one surface
  // mm: a shaft in a bore up to this much larger in radius is a clearance
  // fit (CLJ), recognised anywhere within its gap (axes up to the gap plus
  // the capture distance apart).
  double clearance = 0.1;
};

struct LiveContact {
  ContactType type = ContactType::PLF;
  int body = 0;                 // the other body
  int moving_partition = 0, other_partition = 0;
  int other_index = 0;          // into surfaces(body)
  int moving_index = 0;         // into moving_surfaces()
  double distance = 0, angle = 0;
  double clearance = 0;         // CLJ: bore radius - shaft radius (0 for a line-to-line fit)
  // CLJ: mm from the shaft's end to its bore's mouth along the axis when
  // matched by the lead-in only (no axial band in common yet); 0 inside.
  double mouth_gap = 0;
};

class RealtimeContacts {
 public:
  // Set-up (allocates): partitions of every body of the assembly, body boxes.
  RealtimeContacts(const std::vector<BodyPartitions>& partitions, int moving,
                   const CaptureTolerances& tolerances);
  // The contacts of the moving part at `pose` (its displacement from the
  // assembled placement), at most `capacity`, written to `out`. Allocation-free.
  // `lead_in` (mm, engagement only): a coaxial shaft whose end is up to this
  // far outside its bore's mouth counts as a CLJ contact (`mouth_gap` > 0).
  int update(const Pose& pose, LiveContact* out, int capacity, double lead_in = 0) const noexcept;
  // Bodies whose box meets the moving part's box at `pose` (inflated by the
  // capture distance); returns how many were written.
  int near_bodies(const Pose& pose, int* out, int capacity) const noexcept;

  int moving() const { return moving_; }
  int body_count() const { return static_cast<int>(bodies_.size()); }
  const std::vector<SurfaceProxy>& moving_surfaces() const { return bodies_[moving_].surfaces; }
  const std::vector<SurfaceProxy>& surfaces(int body) const { return bodies_[body].surfaces; }
  const Eigen::AlignedBox3d& body_box(int body) const { return bodies_[body].box; }
  const CaptureTolerances& tolerances() const { return tolerances_; }

 private:
  struct BodySurfaces {
    std::vector<SurfaceProxy> surfaces;
    std::vector<int> by_radius[6];  // per SurfaceKind: indices sorted by radius (planes: all)
    Eigen::AlignedBox3d box;
  };
  // `m` is the moving partition at `pose` (no outline); `local` the same at
  // its assembled placement (with its outline, for planes).
  bool match(const SurfaceProxy& m, const SurfaceProxy& local, const Pose& pose, const SurfaceProxy& o,
             LiveContact& c, double lead_in) const noexcept;
  std::vector<BodySurfaces> bodies_;
  int moving_ = 0;
  CaptureTolerances tolerances_;
};

// Engagement from the real-time contacts, in this order: a shaft-in-bore (CLJ)
// contact within capture captures the part on the bore's axis (Cylindrical),
// a shaft inside its bore first, else one coaxial at its bore's mouth (its end
// within the capture distance outside: a line-to-line shaft's tessellation
// would catch on the mouth's rim before it could enter; the joint then holds
// while the end stays within that distance, so capture and release agree); a
// cone in a cone of the same angle (a conical seat: axes within the capture
// angle and distance, the part's cone inside the other's axial range, not past
// its apex) on the common axis, with a one-sided stop where the apexes meet
// (the seat); a ball in a cup (SPF) on its centre (Ball); a face on a plane
// (PLF within the capture distance and angle) turned parallel (Planar: slides
// in the plane, turns about its normal, a one-sided stop on the plane). Stops
// on an axis come from planes of the part facing planes of the partners along
// it, over a common radial band.
class ContactJointFinder : public JointFinder {
 public:
  // `partition_groups[i]` is the collision group of moving partition i (-1:
  // none); `centre` the part's reference point (stops are written on it).
  ContactJointFinder(const RealtimeContacts& contacts, std::vector<int> partition_groups,
                     const Vec3& centre);
  bool capture(const Pose& pose, JointState& joint) noexcept override;
  bool still_engaged(const Pose& pose, const JointState& joint, bool* entered) noexcept override;

 private:
  void add_stops(const Pose& pose, JointState& joint) const noexcept;
  void fill_axial(const LiveContact& best, int live_count, JointState& joint) const noexcept;
  // A conical seat near `pose` (the one on `same`'s axis when given).
  bool cone_seat(const Pose& pose, JointState& joint, const JointState* same) const noexcept;
  bool plane_joint(const Pose& pose, const LiveContact& contact, JointState& joint) const noexcept;
  const RealtimeContacts& contacts_;
  std::vector<int> groups_;
  Vec3 centre_;
  std::vector<LiveContact> live_;  // scratch, sized once
};

// Whether two parallel planar outlines share area once projected on the plane
// of `o` (the moving one `m`'s loops placed by `pose`): a vertex of one inside
// the other (even-odd, so holes count) or two edges crossing. Allocation-free.
bool outlines_overlap(const SurfaceProxy& m, const Pose& pose, const SurfaceProxy& o) noexcept;

// Whether two cones of one angle share a band of their surface once their
// apexes meet: their axial ranges from the apex overlap (chamfers of one
// angle at different radii do not).
bool cone_bands_overlap(const SurfaceProxy& a, const SurfaceProxy& b) noexcept;

// Groups of the moving part's revolution partitions lying on one surface that
// some other body has a same-radius, opposite-side partition for: the surfaces
// a joint switches off in collision. Returns per moving partition its group
// (-1: none), and per group and body the other partitions switched off.
struct CollisionGroups {
  std::vector<int> moving_group;                          // per moving partition
  std::vector<std::vector<std::vector<int>>> switched_off;  // [group][body] -> partition ids
  int count() const { return static_cast<int>(switched_off.size()); }
};
CollisionGroups collision_groups(const RealtimeContacts& contacts);

}  // namespace contactcore::haptics
