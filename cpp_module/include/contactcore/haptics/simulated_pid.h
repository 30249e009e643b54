// The simulated hand behind a HID PID force-feedback device: the loop's force
// goes through the same output path as real hardware (HidPidDevice builds the
// reports: constant force, spring and damper conditions, the force-rate
// limit) to a simulated device firmware that decodes the bytes with the
// descriptor's layout and pushes the hand with the force they describe; the
// hand's position comes back as input reports through the same parser.
#pragma once

#include <array>
#include <map>
#include <memory>
#include <vector>

#include "contactcore/haptics/hid_pid_device.h"
#include "contactcore/haptics/simulated.h"

namespace contactcore::haptics {

// A three-axis (X Y Z) position device with PID constant force, spring and
// damper: its report descriptor (host-allocated effect blocks; report IDs:
// input 1, Set Effect 2, Set Condition 3, Set Constant Force 5, Effect
// Operation 10, Device Control 12, Device Gain 13).
const std::vector<std::uint8_t>& simulated_pid_descriptor();

// What a PID device does with the reports it gets: effect blocks, their
// parameters, start/stop, actuators and gain; the force they render at a
// given position and speed (normalised axes), as fractions of full scale.
class PidFirmware : public HidTransport {
 public:
  explicit PidFirmware(const PidLayout& layout);
  bool write_output(const std::uint8_t* report, std::size_t size) override;
  bool send_feature(const std::uint8_t*, std::size_t) override { return false; }
  int get_feature(std::uint8_t*, std::size_t) override { return -1; }
  int read_input(std::uint8_t* buffer, std::size_t size) override;

  // Queues an input report for axes in [-1, 1] (X Y Z).
  void report_position(const Vec3& axes);
  // Force per axis (fraction of full scale) at `axes` moving at `speed` (per s).
  Vec3 force(const Vec3& axes, const Vec3& speed) const;
  bool actuators_enabled() const { return actuators_; }
  int playing_effects() const;
  std::size_t reports_received() const { return received_; }

 private:
  struct Effect {
    int type = 0;  // the Effect Type selector value
    std::array<bool, 6> axes{};
    bool playing = false;
    double magnitude = 0;               // constant force, fraction
    std::array<PidCondition, 6> conditions{};
  };
  const PidLayout& layout_;
  std::map<int, Effect> effects_;
  bool actuators_ = false;
  double gain_ = 1;
  std::vector<std::vector<std::uint8_t>> inputs_;
  std::size_t received_ = 0;
};

// The simulated hand holding a PID force-feedback device in position mode.
class SimulatedPidDevice : public Device {
 public:
  SimulatedPidDevice(HandScript script, const HandParameters& params, const Vec3& centre, const Pose& initial_pose,
                     PidForceConfig config = {});
  const DeviceCapabilities& capabilities() const override { return pid_->capabilities(); }
  DeviceSample read(double now) noexcept override;
  void write(const Wrench& wrench) noexcept override { pid_->write(wrench); }
  void halt() noexcept override { pid_->halt(); }

  SimulatedHand& hand() { return hand_; }
  HidPidDevice& pid() { return *pid_; }
  const PidFirmware& firmware() const { return *firmware_; }
  const Wrench& felt() const { return felt_; }  // what the firmware pushes the hand with

 private:
  PidLayout layout_;
  PidForceConfig config_;
  SimulatedHand hand_;
  PidFirmware* firmware_ = nullptr;  // owned by pid_
  std::unique_ptr<HidPidDevice> pid_;
  Vec3 origin_;  // the hand's reference point at the start: the device's centre
  double now_ = 0, next_service_ = 0;
  Wrench felt_;
};

}  // namespace contactcore::haptics
