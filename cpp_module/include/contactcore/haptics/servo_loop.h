// The 1 kHz servo loop of haptic trials. Each tick: read the device (never
// blocking), map its input to a commanded pose (position control for an arm,
// rate control for a SpaceMouse), capture or keep the joint (probed at the
// proxy's pose), move the proxy (god-object) toward the commanded pose as far
// as the constraints allow: the joint's free twists and one-sided stops and
// the non-penetration constraints of its contact set, solved as a small
// quadratic program in the part's mass metric (proxy_solver.h), the step
// checked against the collision stage (swept: conservative advancement), and
// render the virtual-coupling force and torque clamped to the device's limits. A
// watchdog zeroes the force on an overrun, a stale or unplugged device, or
// disable. Nothing inside a tick allocates, takes a lock, or calls Python or
// OCCT; the GUI reads a lock-free snapshot and writes atomics.
//
// Runs in its own thread on the steady clock (start/stop) or, for tests and
// headless trials, in lockstep (step_lockstep: a virtual clock of exact ticks).
#pragma once

#include <algorithm>
#include <array>
#include <atomic>
#include <cstdint>
#include <thread>
#include <vector>

#include "contactcore/haptics/constraints.h"
#include "contactcore/haptics/device.h"
#include "contactcore/haptics/triple_buffer.h"
#include "contactcore/haptics/proxy_solver.h"

namespace contactcore::haptics {

enum class Watchdog : int { None = 0, Disabled, Unplugged, Stale, Overrun };
const char* to_string(Watchdog reason);

struct ServoConfig {
  double rate_hz = 1000;
  Vec3 centre = Vec3::Zero();       // reference point: the part's centre of mass (assembled)
  double stiffness = 1.0;           // N/mm of the virtual coupling (clamped to the device)
  double angular_stiffness = 3000;  // N mm/rad
  double damping = 0.005;           // N s/mm
  double angular_damping = 5;       // N mm s/rad
  double max_speed = 150;           // mm/s the proxy may move
  double max_angular_speed = 2;     // rad/s
  double rate_speed = 40;           // mm/s at full deflection (rate control)
  double rate_angular_speed = 0.8;  // rad/s at full deflection
  Mat3 rate_frame = Mat3::Identity();  // device axes -> world (the view's orientation)
  double stale_after = 0.25;        // s without a device report
  double length_scale = 10;         // mm: weighs rotations against translations
  double breakaway_force = 8;       // N across the joint's free directions breaks away
  int collision_bisections = 10;    // last resort when the solve cannot clear a step
  // The proxy's mass metric: the part's inertia per unit mass about its centre
  // (mm^2, assembled frame); zero: length_scale^2 times the identity.
  Mat3 inertia_per_mass = Mat3::Zero();
  double contact_skin = 0.001;      // mm: the gap the contact constraints keep
  double penetration_tolerance = 0.002;  // mm: an end pose deeper than this (and than the start) is refused
  double max_pushout = 0.02;        // mm per tick: how fast a start overlap is pushed out
  int engaged_after_ticks = 50;     // a joint held this many consecutive ticks is reported engaged
  double joint_rim_band = 0.03;     // mm: three times the collision models' deflection (both sides chordal)
  bool lockstep = false;            // virtual clock; overruns counted, not acted on
  int realtime_priority = 0;        // > 0: ask for SCHED_FIFO at this priority (needs CAP_SYS_NICE)
  // Thread mode: lock the process' memory (mlockall) so no tick waits on a
  // page fault or swap-in; done only where it cannot make later allocations
  // fail (CAP_IPC_LOCK or an unlimited RLIMIT_MEMLOCK).
  bool lock_memory = true;
  double late_wakeup_us = 100;      // a wake-up this long after its deadline is late
  // Coulomb friction coefficient at the proxy's contacts (0: none): the part
  // sticks while the hand's pull along the surfaces is at most friction times
  // its push into them, and slides on the friction cone's edge beyond.
  double friction = 0;
};

// What the GUI (or a test) sees, published every tick.
struct ServoSnapshot {
  Pose proxy = Pose::Identity();    // the part's displacement from its assembled placement
  Pose target = Pose::Identity();   // the device's commanded pose
  Wrench wrench;                    // rendered (after clamping and watchdog)
  Wrench coupling;                  // before clamping
  JointState joint;
  bool engaged = false;
  bool held = false;                // the joint was chosen (hold_to), not found
  bool device_connected = false;
  bool enabled = false;
  Watchdog watchdog = Watchdog::None;
  bool blocked = false;             // a collision or stop held the last step
  std::uint64_t ticks = 0, overruns = 0;
  double time = 0;                  // s since start
  double rate_hz = 0, jitter_us = 0;
  double last_step_us = 0;
  double insertion_depth = 0;       // mm along the joint axis from where it engaged
  // mm: the deepest overlap of the part's collision model with another body
  // (the joint's own surfaces switched off), stop overshoot or distance off the joint.
  double penetration = 0;
  double max_penetration = 0, max_force = 0;
  double start_penetration = 0;     // mm: overlap at the first tick (a start inside another body)
  std::uint64_t engaged_ticks = 0;  // consecutive ticks on the current joint
  int contact_count = 0;            // constraints from the contact set this tick
  int deepest_body = -1;            // the body the part overlaps deepest (-1: none)
  std::uint64_t engagements = 0;
  Vec6 axes = Vec6::Zero();
  // Real-time hygiene (thread mode; 0 / false in lockstep).
  std::uint64_t late_wakeups = 0;   // woke more than late_wakeup_us after the deadline
  double max_wake_latency_us = 0;
  bool memory_locked = false;       // mlockall held while the loop runs
  bool realtime_priority = false;   // SCHED_FIFO granted
};

// One engagement, for reports.
struct EngagementEvent {
  double time = 0;
  JointState joint;
};

class ServoLoop {
 public:
  ServoLoop(Device& device, const ServoConfig& config, const Pose& initial_pose);
  ~ServoLoop();
  ServoLoop(const ServoLoop&) = delete;
  ServoLoop& operator=(const ServoLoop&) = delete;

  void set_joint_finder(JointFinder* finder) { finder_ = finder; }
  void set_collision(CollisionQuery* collision) {
    collision_ = collision;
    part_radius_ = collision ? collision->radius_about(config_.centre) : 0.0;
  }
  // Holds the part to a given joint (tests, or a joint chosen in the panel).
  // Call when the loop is stopped or from its thread; from another thread
  // (the GUI) while it runs, request_hold / request_release: applied at the
  // next tick through a lock-free mailbox.
  void hold_to(const JointState& joint);
  void release_joint();
  void request_hold(const JointState& joint);
  void request_release();

  // Thread mode on the steady clock.
  bool start();
  void stop();
  bool running() const { return thread_.joinable(); }

  // Lockstep: one tick at virtual time ticks * period (overruns counted, not acted on).
  void step_lockstep();

  // GUI side: lock-free.
  void set_enabled(bool enabled) { enabled_.store(enabled); }
  void set_friction(double mu) { friction_.store(mu > 0 ? mu : 0.0); }
  double friction() const { return friction_.load(std::memory_order_relaxed); }
  void set_stiffness(double linear, double angular) {
    stiffness_.store(linear);
    angular_stiffness_.store(angular);
  }
  void set_damping(double linear, double angular) {
    damping_.store(linear);
    angular_damping_.store(angular);
  }
  ServoSnapshot snapshot() { return snapshots_.read(); }

  // Statistics (call when stopped or from the loop's thread).
  std::uint64_t ticks() const { return ticks_; }
  // Ticks whose step took longer than the period plus ticks that woke up late
  // (more than config.late_wakeup_us after their absolute deadline; thread mode only).
  std::uint64_t overruns() const { return overruns_; }
  std::uint64_t long_steps() const { return long_steps_; }
  // Steps whose end-pose contact query was not made: the step moved no point
  // of the part further than the allowed depth left room for (move_proxy).
  std::uint64_t end_checks_skipped() const { return end_checks_skipped_; }
  double step_percentile_us(double p) const;  // from a 0.25 us histogram
  double step_max_us() const { return step_max_us_; }
  // Measured from wall time between tick starts (thread mode); 0 in lockstep.
  double rate_hz() const;
  double jitter_us() const;                   // standard deviation of the period
  // |period - nominal| percentile (us), thread mode; 0 in lockstep.
  double jitter_percentile_us(double p) const;
  double sim_time_s() const { return static_cast<double>(ticks_) * period_; }
  const Pose& proxy() const { return proxy_; }
  const ServoSnapshot& last() const { return last_; }
  const std::vector<EngagementEvent>& engagement_events() const { return events_; }
  const ServoConfig& config() const { return config_; }
  bool got_realtime_priority() const { return got_priority_.load(); }
  // Real-time hygiene (thread mode): memory locked, late wake-ups (woke more
  // than config.late_wakeup_us after the absolute deadline), and the latency.
  bool memory_locked() const { return memory_locked_.load(); }
  // The loop thread's timer slack (ns) once it runs: 1 (asked for), or -1
  // before the thread starts or where prctl refused.
  long timer_slack_ns() const { return timer_slack_ns_.load(); }
  std::uint64_t late_wakeups() const { return late_wakeups_; }
  double wake_latency_max_us() const { return wake_latency_max_us_; }
  double wake_latency_mean_us() const { return wake_count_ ? wake_latency_sum_us_ / wake_count_ : 0.0; }

 private:
  // `wall_clock`: the tick runs on the thread's real clock, where an overrun
  // trips the watchdog; on a virtual clock (step_lockstep) it is only counted.
  void tick(double now, bool wall_clock);
  void run();
  // Thread mode, at each tick's start: the period since the last tick
  // (statistics only; late wake-ups are counted where the loop wakes).
  void note_period(double now);
  void engage(const JointState& joint);
  Pose interpolate(const Pose& a, const Pose& b, double s) const;
  // `spent` (mm of the centre, rad): motion this tick already made (a snap at
  // a bore's mouth), taken off the speed limits.
  Pose move_proxy(const Pose& target, double dt, double spent_lin = 0, double spent_ang = 0);
  // The contact set at `pose` (reach mm) merged with the last ticks' contacts
  // carried on the part; returns the deepest overlap (mm, >= 0).
  double gather_contacts(const Pose& pose, double reach);
  // The deepest overlap at `pose` with collision group `group` off; its
  // contacts are left in probe_ (probe_count_).
  double depth_at(const Pose& pose, const JointState* joint);
  // A contact on the rim of a bore joint's own surfaces (its point within
  // joint_rim_band of the bore's cylinder): where a line-to-line shaft passes
  // its bore's edges the tessellations touch, the solids do not.
  bool on_joint_rim(const ContactPoint& contact, const JointState* joint) const;
  void carry_contacts(const Pose& measured_at);
  Mat3 metric_rotation() const;
  double min_gap_of_measured() const {
    double gap = 0;
    for (int i = 0; i < measured_count_; ++i) gap = std::min(gap, measured_[i].gap);
    return gap;
  }

  Device& device_;
  ServoConfig config_;
  DeviceCapabilities caps_;
  double period_;
  JointFinder* finder_ = nullptr;
  CollisionQuery* collision_ = nullptr;

  Pose proxy_;
  Pose anchor_ = Pose::Identity();  // device pose -> commanded pose (re-set on enable)
  bool was_enabled_ = false;
  JointState joint_;
  bool engaged_ = false;
  bool held_ = false;               // joint set by hold_to: never released by the finder
  bool rearm_ = true;               // after a break-away: no capture until out of reach
  double engaged_axial_ = 0;        // axial position where it engaged
  Vec6 proxy_velocity_ = Vec6::Zero();
  bool overrun_pending_ = false;

  std::atomic<bool> enabled_{true};
  std::atomic<double> stiffness_, angular_stiffness_, damping_, angular_damping_;
  std::atomic<double> friction_{0.0};
  std::atomic<bool> stop_{false};
  std::atomic<bool> got_priority_{false};
  std::atomic<bool> memory_locked_{false};
  std::atomic<long> timer_slack_ns_{-1};
  std::thread thread_;

  std::uint64_t ticks_ = 0, overruns_ = 0, long_steps_ = 0, end_checks_skipped_ = 0;
  std::uint64_t late_wakeups_ = 0, wake_count_ = 0;
  double wake_latency_max_us_ = 0, wake_latency_sum_us_ = 0;
  std::vector<std::uint32_t> step_histogram_;  // allocated once: 0.25 us bins
  std::vector<std::uint32_t> jitter_histogram_;  // |period - nominal|, 0.25 us bins
  double step_max_us_ = 0;
  double start_time_ = 0, last_tick_start_ = 0;
  double period_mean_ = 0, period_m2_ = 0;
  std::uint64_t period_count_ = 0;
  double max_penetration_ = 0, max_force_ = 0, start_penetration_ = 0;
  double part_radius_ = 0;          // from the collision query, at set_collision
  std::uint64_t engagements_ = 0, engaged_ticks_ = 0;
  double engaged_at_ = 0;
  bool event_logged_ = false;
  // The contact set: measured this tick, and carried from the last ticks
  // (point in the part's frame, the other body's point and normal in world).
  struct CarriedContact {
    Vec3 local = Vec3::Zero(), anchor = Vec3::Zero(), normal = Vec3::UnitZ();
    int age = 0, body = -1;
  };
  std::array<CarriedContact, kMaxContacts> carried_{};
  int carried_count_ = 0;
  std::array<ContactPoint, kMaxContacts> measured_{};
  std::array<ContactPoint, 2 * kMaxContacts> constraint_set_{};
  int constraint_count_ = 0;
  std::array<ContactPoint, kMaxContacts> probe_{};
  int probe_count_ = 0, deepest_body_ = -1, measured_count_ = 0, carried_used_ = 0;
  // Bodies the last query answered on the engaged joint's rim only: the joint
  // guides the part along them, so their carried contacts no longer hold.
  std::array<int, kMaxContacts> guided_bodies_{};
  int guided_count_ = 0;
  std::vector<EngagementEvent> events_;  // reserved up front; full: later ones dropped
  ServoSnapshot last_;
  TripleBuffer<ServoSnapshot> snapshots_;
  struct HoldRequest {
    std::uint64_t serial = 0;  // 0: none yet
    bool hold = false;
    JointState joint;
  };
  TripleBuffer<HoldRequest> hold_requests_;
  std::uint64_t request_serial_ = 0;  // writer's (GUI)
  std::uint64_t applied_serial_ = 0;  // loop's
};

}  // namespace contactcore::haptics
