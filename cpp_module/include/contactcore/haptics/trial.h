// A haptic trial on an assembly: the scene (partitions, real-time contacts,
// engagement, triangle models of the moving part and its neighbours) and the
// headless run of a scripted insertion with the simulated hand in lockstep
// (`contacts trial`). The panel uses the same scene with a live device.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "contactcore/bodies/bodies.h"
#include "contactcore/haptics/stage_collision.h"
#include "contactcore/haptics/realtime_contacts.h"
#include "contactcore/haptics/servo_loop.h"
#include "contactcore/haptics/simulated.h"

namespace contactcore::haptics {

struct SceneOptions {
  CaptureTolerances capture;
  double deflection = 0.01;  // mm, triangle models
  double angle = 0.2;        // rad
  // mm: the moving part's triangles no longer than this, so the collision
  // stage's overlap depth (its deepest vertex) sees a long face crossing
  // another body mid-way (a pin's side across a bore's rim); 0: no bound.
  double moving_max_edge = 1.0;
  // Closed-form contacts between analytic partitions in the loop's contact
  // query, the meshes for the rest (StageCollision::use_analytic). On by
  // default (docs/haptics.md, "Collision that fits the budget"); false: the
  // meshes alone (`bench_haptics --meshes-only`, the binding's
  // closed_forms=False), for comparison.
  bool analytic = true;
};

// Everything the loop needs about the assembly, built once (OCCT here only).
class TrialScene {
 public:
  static std::unique_ptr<TrialScene> build(const Assembly& assembly, const std::string& part,
                                           const SceneOptions& options, Status& status,
                                           Progress* progress = nullptr);
  int moving() const { return moving_; }
  const std::string& part_name() const { return part_name_; }
  const Vec3& centre() const { return centre_; }
  // The part's inertia about its centre of mass per unit mass (mm^2,
  // assembled frame): the proxy's mass metric.
  const Mat3& inertia_per_mass() const { return inertia_per_mass_; }
  RealtimeContacts& contacts() { return *contacts_; }
  ContactJointFinder& finder() { return *finder_; }
  StageCollision& collision() { return *collision_; }
  const std::vector<std::string>& body_names() const { return names_; }
  // Sets `joint.group` to the collision group of the part's surfaces on that
  // joint (a chosen joint, say from the joints stage): a cylinder or cone on
  // its axis, a sphere on its centre, a face on its plane; -1 when none. Of a
  // shaft's coaxial cylinders, the one in the joint's body's bore, whose
  // radius becomes `joint.radius` (the loop leaves out that bore's rim
  // contacts, as for a joint engagement finds).
  void attach_collision_group(JointState& joint) const;
  double setup_seconds() const { return setup_seconds_; }

 private:
  TrialScene() = default;
  int moving_ = 0;
  std::string part_name_;
  Vec3 centre_ = Vec3::Zero();
  Mat3 inertia_per_mass_ = Mat3::Zero();
  std::vector<std::string> names_;
  std::vector<BodyPartitions> partitions_;
  std::unique_ptr<RealtimeContacts> contacts_;
  CollisionGroups groups_;
  std::unique_ptr<ContactJointFinder> finder_;
  std::unique_ptr<StageCollision> collision_;
  double setup_seconds_ = 0;
};

// The trial script: the part's start offset from its assembled placement and
// the hand's target offsets over time (translate mm, rotate degrees about
// global axes through the part's centre of mass, applied x, then y, then z).
struct ScriptKey {
  double t = 0;
  Vec3 translate = Vec3::Zero();
  Vec3 rotate_deg = Vec3::Zero();
};
struct TrialScript {
  ScriptKey start;
  std::vector<ScriptKey> hand;
};

struct TrialOptions {
  ServoConfig servo;
  HandParameters hand;
  double settle = 1.5;     // s run after the last key
  int record_every = 10;   // ticks between recorded samples (0: no record)
  // Another device than the scripted simulated hand (device_factory.h: a
  // SpaceMouse, a HID force-feedback device, a replay); not owned. The run
  // lasts `duration` s (the script's keys do not drive it).
  Device* device = nullptr;
  double duration = 0;
  // A joint the part is held to from the first tick instead of the one
  // engagement finds (a joint chosen in the panel, joint_adapter.h, its
  // collision group attached); not owned, null: engagement.
  const JointState* hold = nullptr;
};

struct TrialSample {
  double t = 0;
  Vec3 translate = Vec3::Zero(), rotate_deg = Vec3::Zero();  // offset from the assembled placement
  Vec3 force = Vec3::Zero();                                 // N rendered to the hand
  bool engaged = false;
  double penetration = 0;
};

struct EngagedJoint {
  std::string with;   // body name
  std::string type;   // contact type of the joint (CLJ, SPF)
  std::string joint;  // joint kind (Cylindrical, Ball)
  double time = 0;
};

// Timing figures are measured from wall time only in realtime mode (the loop
// on its thread); in lockstep (a virtual clock) they mean nothing and the
// result says so (`realtime` false, the JSON's null), giving sim_time_s.
// status fails when the part is left inside another body (deeper than
// kLeftInsideMm at the end, e.g. a start overlap that could not be resolved).
struct TrialResult {
  Status status;
  bool realtime = false;            // "mode": "realtime" | "lockstep"
  bool realtime_priority = false;   // the loop thread got SCHED_FIFO
  std::uint64_t ticks = 0;
  double sim_time_s = 0;            // ticks x period
  double rate_hz = 0;               // realtime: 1 / mean period between tick starts
  double step_p50_us = 0, step_p99_us = 0, step_max_us = 0;  // realtime: tick compute time
  double jitter_p50_us = 0, jitter_p99_us = 0;               // realtime: |period - nominal|
  std::uint64_t overruns = 0;       // long steps + late wake-ups
  std::uint64_t long_steps = 0, late_wakeups = 0;
  double start_penetration_mm = 0;  // overlap at the start pose
  double final_penetration_mm = 0;  // at the end
  std::vector<EngagedJoint> joints_engaged;
  Vec3 final_translate = Vec3::Zero(), final_rotate_deg = Vec3::Zero();
  double max_penetration_mm = 0, max_force_n = 0;
  std::vector<TrialSample> path;
  double setup_seconds = 0;
  // Real-time hygiene of a realtime run (servo_loop.h): whether the
  // process' memory was locked (late wake-ups: above).
  bool memory_locked = false;
};

constexpr double kLeftInsideMm = 0.01;

// Runs the script with the simulated hand in lockstep (deterministic), or on
// the loop's own thread in real time when `realtime`.
TrialResult run_trial(TrialScene& scene, const TrialScript& script, const TrialOptions& options,
                      bool realtime = false);

}  // namespace contactcore::haptics
