// A simulated hand holding a haptic arm: a mass-spring-damper driven towards
// a script of target poses (or pushed by scripted forces), feeling the force
// the loop renders. Position-controlled, 6 DOF, force and torque output: the
// device of headless trials and tests, and the fallback with no hardware.
#pragma once

#include <atomic>
#include <vector>

#include "contactcore/haptics/device.h"
#include "contactcore/haptics/servo_loop.h"

namespace contactcore::haptics {

// One key of the script: at time t the hand aims at `pose` (its displacement
// from the part's assembled placement) and/or pushes with force/torque.
struct HandKey {
  double t = 0;
  Pose pose = Pose::Identity();
  Vec3 force = Vec3::Zero();   // N, added to the hand
  Vec3 torque = Vec3::Zero();  // N mm
};

struct HandParameters {
  double mass = 0.3;             // kg
  double inertia = 300;          // kg mm^2 about the reference point
  double stiffness = 1.0;        // N/mm pulling the hand to the scripted pose (0: passive)
  double angular_stiffness = 3000;  // N mm/rad
  double damping = 0.04;         // N s/mm (critical for 1 N/mm and 0.3 kg is ~0.035)
  double angular_damping = 60;   // N mm s/rad
};

// Piecewise linear between keys (slerp for rotations), held after the last.
class HandScript {
 public:
  HandScript() = default;
  explicit HandScript(std::vector<HandKey> keys);
  HandKey at(double t, const Vec3& centre) const;
  double duration() const { return keys_.empty() ? 0 : keys_.back().t; }
  bool empty() const { return keys_.empty(); }

 private:
  std::vector<HandKey> keys_;
};

class SimulatedHand : public Device {
 public:
  SimulatedHand(HandScript script, const HandParameters& params, const Vec3& centre,
                const Pose& initial_pose);
  const DeviceCapabilities& capabilities() const override { return caps_; }
  DeviceSample read(double now) noexcept override;  // integrates the hand up to `now`
  void write(const Wrench& wrench) noexcept override { applied_ = wrench; }

  // Live target (the mouse in the 3D view, from the GUI thread): replaces the
  // script's pose from the next tick on. Lock-free.
  void set_live_target(const Pose& pose) {
    live_target_.write(pose);
    live_.store(true);
  }
  void clear_live_target() { live_.store(false); }

  // Test hooks: pull the cable, give the hand a push, read its state.
  void set_connected(bool connected) { connected_ = connected; }
  void set_velocity(const Vec6& v) { velocity_ = v; }
  const Pose& pose() const { return pose_; }
  Vec3 reference_point() const { return pose_ * centre_; }
  const Vec6& velocity() const { return velocity_; }
  const Wrench& applied() const { return applied_; }
  // Kinetic energy of the hand, N mm (= mJ).
  double kinetic_energy() const;
  DeviceCapabilities& mutable_capabilities() { return caps_; }

 private:
  void integrate(double dt) noexcept;
  DeviceCapabilities caps_;
  HandScript script_;
  HandParameters params_;
  Vec3 centre_;
  Pose pose_;
  Vec6 velocity_ = Vec6::Zero();  // mm/s of the reference point, rad/s
  Wrench applied_;
  double time_ = 0;
  bool started_ = false;
  std::atomic<bool> connected_{true};
  std::atomic<bool> live_{false};
  TripleBuffer<Pose> live_target_;
};

// The simulated device's capabilities: a desktop 6-DOF arm's order of size.
DeviceCapabilities simulated_capabilities();

}  // namespace contactcore::haptics
