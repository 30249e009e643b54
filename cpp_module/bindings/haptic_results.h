// The haptics binding's results as plain values (what a Python result class
// holds): built by bind_haptics.cpp from the core's structs, registered with
// their documented fields and to_dict() in haptic_results.cpp, the one place
// that says what each result exposes.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "common.h"
#include "contactcore/haptics/device.h"
#include "contactcore/haptics/device_factory.h"
#include "contactcore/haptics/hid_pid_device.h"
#include "contactcore/haptics/hid_recording.h"
#include "contactcore/haptics/spacemouse.h"
#include "contactcore/haptics/trial.h"

namespace contactcore::bindings {

using Triple = std::array<double, 3>;

inline Triple triple(const haptics::Vec3& v) { return {v.x(), v.y(), v.z()}; }

// A displacement from the assembled placement about the part's centre.
struct Offset {
  Triple translate{};   // mm
  Triple rotate_deg{};  // degrees about x, y, z
};
Offset offset_from(const haptics::Pose& pose, const haptics::Vec3& centre);

struct SpaceMouseReport {
  bool understood = false;
  std::array<int, 6> raw{};
  std::array<double, 6> axes{};
  std::uint32_t buttons = 0;
  std::string model;
};

// What hid_pid_capabilities says of a report descriptor.
struct PidCapabilities {
  bool force_output = false;
  std::string why;  // empty when force_output
  std::optional<haptics::DeviceCapabilities> capabilities;
  int axes = 0;
};

// The joint the loop would hold the part to (TrialScene.joint_of_pair).
struct HeldJoint {
  std::string kind;
  Triple axis{}, point{};
  int stops = 0;
  int collision_group = -1;
};

struct LiveContactSeen {
  std::string type, with;
  double distance = 0;   // mm
  double angle_deg = 0;  // degrees
};

// One of the engaged joint's one-sided stops, on the part's reference point.
struct StopState {
  Triple normal{};
  double gap = 0;  // mm to the stop (<= 0: on or past it)
  bool active = false;
};

// HapticSession.snapshot(): the loop's latest state, with the joint's other
// bodies named and its stops measured from the part's reference point.
struct SessionSnapshot {
  haptics::ServoSnapshot loop;
  Offset offset, target;
  std::array<std::array<double, 4>, 4> matrix{};
  std::vector<std::string> joint_with;
  std::vector<StopState> stops;
  bool realtime_priority = false;
};

struct StepTimes {
  double p50 = 0, p99 = 0, max = 0;  // us
};
struct JitterTimes {
  double p50 = 0, p99 = 0;  // us
};

// run_trial's result: the core's TrialResult and the device it ran with.
struct TrialRun {
  haptics::TrialResult result;
  std::string device;
  std::string device_message;
};

// Registers the result classes in the haptics submodule (before any binding
// that returns one).
void bind_haptic_results(py::module_& m);

}  // namespace contactcore::bindings
