// The device layer of haptic trials, after CHAI3D's generic device: what a
// device can do (capabilities) and a non-blocking read / force write that the
// 1 kHz servo loop calls. Back-ends: the 3Dconnexion SpaceMouse family over
// hidapi (spacemouse.h), replayed HID reports, and a simulated hand
// (simulated.h). 6-DOF force devices (Force Dimension, Touch, Falcon, Haply)
// come through their own SDKs: they implement this same interface.
#pragma once

#include <cstdint>
#include <string>

#include "contactcore/haptics/pose_math.h"

namespace contactcore::haptics {

enum class ControlMode {
  Position,  // the device reports a pose (a haptic arm, the simulated hand)
  Rate,      // the device reports a velocity (a SpaceMouse: deflection -> speed)
};
const char* to_string(ControlMode mode);

struct DeviceCapabilities {
  std::string name;
  int input_dof = 6;
  bool force_output = false;   // renders a force (N)
  bool torque_output = false;  // renders a torque (N mm)
  ControlMode control = ControlMode::Position;
  double max_force = 0;               // N
  double max_torque = 0;              // N mm
  double max_stiffness = 0;           // N/mm the device renders stably
  double max_angular_stiffness = 0;   // N mm/rad
  double max_damping = 0;             // N s/mm
  double workspace_radius = 0;        // mm (position devices)
  bool hid_force_feedback = false;    // offers the HID PID usage page (effects only)
};

// One reading. Position devices fill `pose`/`velocity`; rate devices fill
// `axes` normalised to [-1, 1] (translation x y z, rotation x y z).
struct DeviceSample {
  bool connected = false;
  // s, on the loop's clock, when the device's last report ARRIVED (stamped by
  // the thread that received it, not by read): the stale watchdog's input.
  double time = 0;
  // The last report put the device at rest (a SpaceMouse or a joystick let
  // go: all axes zero). HID devices report on change only, so a device at
  // rest may stay silent without being stale.
  bool at_rest = false;
  Pose pose = Pose::Identity();
  Vec6 velocity = Vec6::Zero();  // mm/s at the reference point, rad/s
  Vec6 axes = Vec6::Zero();
  std::uint32_t buttons = 0;
};

// Force and torque to render, world frame (N, N mm at the reference point).
struct Wrench {
  Vec3 force = Vec3::Zero();
  Vec3 torque = Vec3::Zero();
  // The virtual coupling's gains behind the force (N/mm, N s/mm): a device
  // that renders springs itself (HID PID conditions) holds that stiffness
  // between its updates; others ignore them.
  double stiffness = 0, damping = 0;
};

class Device {
 public:
  virtual ~Device() = default;
  virtual const DeviceCapabilities& capabilities() const = 0;
  // Never blocks: returns the latest sample (held between device reports).
  // `now` is the loop's clock in seconds.
  virtual DeviceSample read(double now) noexcept = 0;
  // Renders `wrench` (already clamped to the limits) or does nothing on a
  // device without force output.
  virtual void write(const Wrench& wrench) noexcept = 0;
  // The watchdog tripped (overrun, stale, unplugged, disabled): render nothing
  // until the next write (a HID PID device sends "stop all effects").
  virtual void halt() noexcept { write(Wrench{}); }
};

// Limits a wrench to the device: force and torque norms clamped, directions kept.
Wrench clamp_to_device(const Wrench& wrench, const DeviceCapabilities& caps);

}  // namespace contactcore::haptics
