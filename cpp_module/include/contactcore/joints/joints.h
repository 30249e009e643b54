// Stage 4: joints and mobility. Each contact is a set of constraint wrenches;
// a body pair's free twists are the null space of its stacked wrenches (SVD
// with a tolerance), named as an ISO 3952 kinematic pair. The assembly's
// mobility solves every body's twist at once with one part grounded, reduced
// first by rigid groups (union-find) and solved per connected component.
//
// Conventions, used by every value below (all global coordinates, mm):
//  - A twist is (omega, v): angular velocity, then the linear velocity of the
//    body point that is at the global origin. A rotation about the line
//    (p, d) is (d, p x d); a translation along d is (0, d).
//  - A pair's twists are the motion of body `b` relative to body `a`.
//  - A one-sided stop (point p, normal n) lets b move relative to a with
//    velocity u at p only when u . n >= 0 (n points out of a's material).
#pragma once

#include <array>
#include <string>
#include <vector>

#include <gp_Dir.hxx>
#include <gp_Pnt.hxx>

#include "contactcore/contacts/contacts.h"

namespace contactcore {

using Twist = std::array<double, 6>;  // wx, wy, wz, vx, vy, vz (v at the global origin)

enum class JointType {
  Rigid,           // 0 DOF
  Revolute,        // 1: rotation about a line
  Prismatic,       // 1: translation
  Helical,         // 1: screw motion (never from these surfaces)
  Cylindrical,     // 2: rotation about and translation along one line
  Spherical,       // 3: rotations about a point
  Planar,          // 3: rotation about a normal, translations in the plane
  SphereCylinder,  // 4: ball in a bore (rotations about a point, translation along the axis)
  SpherePlane,     // 5: rotations about a point, translations in a plane
  CylinderPlane,   // 4: a line contact (a cylinder lying on a plane): rotations
                   //    about the line and the normal, translations in the plane
  General,         // anything else (see dof)
};
// ISO 3952 type strings: "rigid", "revolute", ..., "sphere_cylinder",
// "sphere_plane", "cylinder_plane", "general".
const char* to_string(JointType type);

struct FreeRotation {
  gp_Pnt point;   // a point of the axis line (the one nearest the contacts' centre)
  gp_Dir direction;
};

struct OneSidedStop {
  int contact = -1;  // index into ContactsResult::contacts (-1: a higher pair's)
  gp_Pnt point;      // where the unilateral force acts
  gp_Dir normal;     // out of a's material: b may move with u . normal >= 0 at point
  int higher_pair = -1;  // index into ContactsResult::higher_pairs (-1: a contact's)
};

// What two bodies in contact allow each other (b relative to a).
struct PairJoint {
  int body_a = 0, body_b = 0;     // body_a < body_b, indices into Assembly::bodies
  std::vector<int> contacts;      // indices into ContactsResult::contacts
  std::vector<int> higher_pairs;  // indices into ContactsResult::higher_pairs (point, line contacts)
  // Held rigid by an annotated contact (a press fit, a bond): type Rigid, no
  // free twist, stop or free direction, whatever the surfaces allow.
  bool annotated_rigid = false;
  JointType type = JointType::Rigid;
  int dof = 0;                    // = free_twists.size()
  std::vector<Twist> free_twists; // orthonormal basis of the free twists (in a
                                  // frame at the contacts' centre), expressed globally
  std::vector<FreeRotation> rotations;  // one per rotational DOF
  std::vector<gp_Dir> translations;     // one per translational DOF
  double pitch = 0;                     // helical only, mm per radian
  std::vector<OneSidedStop> stops;      // unilateral contacts (planes, cones, partial cylinders)
  // Generators of the cone of translation directions in which b can leave a
  // (unit vectors d with d . n >= 0 for every stop normal, within the
  // bilateral constraints). Empty: b cannot translate away from a at all. A
  // whole line or plane of free directions appears as both signs of its basis.
  std::vector<gp_Dir> free_directions;
  // The frame the null space was taken in (centre of the contacts, size in
  // mm): invariant under a rigid motion of the assembly.
  gp_Pnt frame_centre;
  double frame_length = 1;
};

// The designer's intent for a contact (a fit or a bond the CAD model cannot
// show: parts drawn at nominal size read as sliding fits). Interference,
// transition and bonded contacts hold their pair rigid; ignored ones are
// left out; clearance (and unspecified) ones are what the surfaces allow.
// Threaded: a screw tightened in its thread (often drawn as a plain bore): rigid like a bond in the
// joints, but a fastener a mechanic undoes (the disassembly unscrews it); a bonded contact (glued,
// welded, staked) is never undone: its parts come out together or stay together.
enum class ContactIntent { Unspecified, Clearance, Transition, Interference, Bonded, Ignored, Threaded };
// "", "clearance", "transition", "interference", "bonded", "ignored", "threaded".
const char* to_string(ContactIntent intent);
// The intent named `text` (one of the strings above but ""); false when unknown.
bool parse_intent(const std::string& text, ContactIntent& intent);
inline bool holds_rigid(ContactIntent intent) {
  return intent == ContactIntent::Interference || intent == ContactIntent::Transition ||
         intent == ContactIntent::Bonded || intent == ContactIntent::Threaded;
}

struct JointOptions {
  // Singular values below this ratio of the largest count as zero (rows are
  // scaled to the pair's size, so the ratio does not depend on units).
  double rank_tolerance = 1e-6;
  int cone_samples = 12;  // stop normals sampled around a full cone
  // The designer's annotations, per contact (indices of ContactsResult::
  // contacts) and per higher pair; empty or shorter: unspecified.
  std::vector<ContactIntent> contact_intents;
  std::vector<ContactIntent> higher_pair_intents;
};

struct JointsResult {
  Status status;
  std::vector<PairJoint> joints;  // one per body pair with at least one contact, sorted (a, b)
};

// Joints of every body pair in contact (surface contacts or higher pairs). `contacts` must come from find_contacts
// on `assembly` (its partitions give the material sides and angular spans).
JointsResult find_joints(const Assembly& assembly, const ContactsResult& contacts,
                         const JointOptions& options = {});

// The free twists of one set of contacts between two bodies (b relative to a):
// the same computation as find_joints for a single pair.
PairJoint joint_of_pair(const ContactsResult& contacts, int body_a, int body_b,
                        const std::vector<int>& contact_indices, const JointOptions& options = {},
                        const std::vector<int>& higher_pair_indices = {});

// Generators of the cone of translation directions in which `body` can
// leave, every neighbour it touches held still (all its contacts at once,
// stops oriented for `body`): what a disassembly planner asks of each part.
// Empty: the body cannot translate out at all.
std::vector<gp_Dir> body_free_directions(const ContactsResult& contacts, const JointsResult& joints, int body,
                                         const JointOptions& options = {});

// Names a space of free twists (any basis) and gives its axes: the kernel of
// the classification, exposed for the assembly's group motions and for tests.
// `centre` is the point nearest which rotation axes of a free point are placed
// (planar joints); `length` the scale of the problem (mm).
struct TwistSpace {
  JointType type = JointType::Rigid;
  int dof = 0;
  std::vector<Twist> basis;  // orthonormal (at `centre`, lengths divided by `length`)
  std::vector<FreeRotation> rotations;
  std::vector<gp_Dir> translations;
  double pitch = 0;
};
TwistSpace classify_twists(const std::vector<Twist>& twists, const gp_Pnt& centre, double length,
                           double tolerance = 1e-6);

// A rotation a body can make alone, every neighbour held still, about the axis
// of one of its revolution or sphere contacts: a screw turning in its hole, a
// ball spinning in its socket. It moves nothing else, so it is reported apart.
struct PassiveSpin {
  int body = 0;
  FreeRotation axis;
};

// How a rigid group moves relative to the ground (its passive spins aside).
struct GroupMotion {
  int group = 0;
  JointType type = JointType::Rigid;
  int dof = 0;
  std::vector<FreeRotation> rotations;
  std::vector<gp_Dir> translations;
  double pitch = 0;
  std::vector<PassiveSpin> passive_spins;  // of the group's bodies
};

struct MobilityOptions {
  int ground = -1;  // body index held still; -1: the largest by volume
  double rank_tolerance = 1e-6;
};

// Rule (docs/joints.md): every pair's bilateral constraints together, the
// ground held still. Two bodies belong to one rigid group when, in every
// motion the constraints allow, their relative twist is made of their own
// passive spins only. `dof` counts every free motion, passive spins included;
// `passive` counts the passive spins; a part connected to nothing (or a
// component without the ground) floats with 6 DOF.
struct MobilityResult {
  Status status;
  int ground = -1;
  int dof = 0;
  int passive = 0;
  std::vector<std::vector<int>> groups;  // body indices; groups[0] holds the ground
  std::vector<int> group_of_body;        // per body
  std::vector<GroupMotion> group_motions;  // one per group, same order
  std::vector<PassiveSpin> passive_spins;
  std::vector<std::vector<int>> components;  // connected components (body indices)
};

MobilityResult assembly_mobility(const Assembly& assembly, const ContactsResult& contacts,
                                 const JointsResult& joints, const MobilityOptions& options = {},
                                 Progress* progress = nullptr);

// The liaison graph in Graphviz DOT: bodies as nodes, joints as edges
// labelled "type (dof)", rigid groups as clusters. `mobility` may be null.
std::string liaison_graph_dot(const Assembly& assembly, const JointsResult& joints,
                              const MobilityResult* mobility);

}  // namespace contactcore
