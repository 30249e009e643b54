#include "contactcore/haptics/simulated.h"

#include <algorithm>

namespace contactcore::haptics {

DeviceCapabilities simulated_capabilities() {
  DeviceCapabilities caps;
  caps.name = "simulated hand";
  caps.input_dof = 6;
  caps.force_output = caps.torque_output = true;
  caps.control = ControlMode::Position;
  caps.max_force = 12;             // N
  caps.max_torque = 400;           // N mm
  caps.max_stiffness = 2.0;        // N/mm
  caps.max_angular_stiffness = 4000;  // N mm/rad
  caps.max_damping = 0.02;         // N s/mm
  caps.workspace_radius = 200;
  return caps;
}

HandScript::HandScript(std::vector<HandKey> keys) : keys_(std::move(keys)) {
  std::stable_sort(keys_.begin(), keys_.end(), [](const HandKey& a, const HandKey& b) { return a.t < b.t; });
}

HandKey HandScript::at(double t, const Vec3& centre) const {
  if (keys_.empty()) return HandKey{};
  if (t <= keys_.front().t) return keys_.front();
  if (t >= keys_.back().t) return keys_.back();
  auto next = std::upper_bound(keys_.begin(), keys_.end(), t,
                               [](double v, const HandKey& k) { return v < k.t; });
  const HandKey& b = *next;
  const HandKey& a = *(next - 1);
  const double s = b.t > a.t ? (t - a.t) / (b.t - a.t) : 1.0;
  HandKey k;
  k.t = t;
  const Eigen::Quaterniond qa(a.pose.linear()), qb(b.pose.linear());
  const Vec3 ca = a.pose * centre, cb = b.pose * centre;
  k.pose.linear() = qa.slerp(s, qb).toRotationMatrix();
  k.pose.translation() = ca + s * (cb - ca) - k.pose.linear() * centre;
  k.force = a.force + s * (b.force - a.force);
  k.torque = a.torque + s * (b.torque - a.torque);
  return k;
}

SimulatedHand::SimulatedHand(HandScript script, const HandParameters& params, const Vec3& centre,
                             const Pose& initial_pose)
    : caps_(simulated_capabilities()),
      script_(std::move(script)),
      params_(params),
      centre_(centre),
      pose_(initial_pose) {}

double SimulatedHand::kinetic_energy() const {
  // v in mm/s: 0.5 m v^2 / 1000 in N mm; 0.5 I w^2 / 1000 with I in kg mm^2.
  return 0.5 * params_.mass * velocity_.head<3>().squaredNorm() / 1000.0 +
         0.5 * params_.inertia * velocity_.tail<3>().squaredNorm() / 1000.0;
}

// Semi-implicit Euler with the damping taken implicitly (dissipative for any step).
void SimulatedHand::integrate(double dt) noexcept {
  HandKey key = script_.at(time_ + dt, centre_);
  const bool live = live_.load(std::memory_order_relaxed);
  if (live) key.pose = live_target_.read();
  const Vec3 c = pose_ * centre_;
  Vec3 force = applied_.force + key.force;
  Vec3 torque = applied_.torque + key.torque;
  if (!script_.empty() || live) {
    force += params_.stiffness * (key.pose * centre_ - c);
    torque += params_.angular_stiffness * rotation_vector(key.pose.linear() * pose_.linear().transpose());
  }
  const double m = params_.mass / 1000.0;    // N s^2/mm
  const double inertia = params_.inertia / 1000.0;  // N mm s^2
  Vec3 v = velocity_.head<3>(), w = velocity_.tail<3>();
  v = (v + dt * force / m) / (1.0 + dt * params_.damping / m);
  w = (w + dt * torque / inertia) / (1.0 + dt * params_.angular_damping / inertia);
  velocity_.head<3>() = v;
  velocity_.tail<3>() = w;
  Vec6 step;
  step.head<3>() = v * dt;
  step.tail<3>() = w * dt;
  pose_ = apply_twist(pose_, step, centre_);
  time_ += dt;
}

DeviceSample SimulatedHand::read(double now) noexcept {
  if (!started_) {
    time_ = now;
    started_ = true;
  }
  // Fixed sub-steps of at most 1 ms, so the hand does not depend on the caller's rate.
  while (now - time_ > 1e-12) integrate(std::min(1e-3, now - time_));
  DeviceSample s;
  s.connected = connected_.load(std::memory_order_relaxed);
  s.time = s.connected ? now : 0;
  s.pose = pose_;
  s.velocity = velocity_;
  return s;
}

}  // namespace contactcore::haptics
