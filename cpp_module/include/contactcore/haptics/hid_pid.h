// HID force feedback (the PID usage page 0x0F, "USB Device Class Definition
// for Physical Interface Devices", version 1.0, usb.org, 1999): the layout of
// the effect reports read from a device's report descriptor, the reports
// themselves, and a Device that renders the servo loop's clamped force as one
// constant-force effect per device axis.
//
// The 1 kHz loop never writes to the device: write() stores the wrench in
// atomics and an I/O thread (or a test calling service()) sends Set Constant
// Force reports at a bounded rate, only for the axes whose magnitude changed.
// halt() (the watchdog: overrun, stale, unplugged, disabled) makes the next
// service send Device Control "Stop All Effects"; the next force after it
// re-enables the actuators and restarts the effects.
#pragma once

#include <array>
#include <atomic>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "contactcore/haptics/device.h"
#include "contactcore/haptics/hid_descriptor.h"

namespace contactcore::haptics {

// PID usages (page 0x0F) the output needs, from the PID 1.0 usage table.
namespace pid {
constexpr std::uint16_t kPage = 0x0F;
constexpr std::uint16_t kSetEffectReport = 0x21, kEffectBlockIndex = 0x22, kEffectType = 0x25,
                        kEtConstantForce = 0x26, kDuration = 0x50, kSamplePeriod = 0x51, kGain = 0x52,
                        kTriggerButton = 0x53, kTriggerRepeatInterval = 0x54, kAxesEnable = 0x55,
                        kDirectionEnable = 0x56, kDirection = 0x57, kMagnitude = 0x70,
                        kSetConstantForceReport = 0x73, kEffectOperationReport = 0x77, kEffectOperation = 0x78,
                        kOpEffectStart = 0x79, kOpEffectStop = 0x7B, kLoopCount = 0x7C,
                        kDeviceGainReport = 0x7D, kDeviceGain = 0x7E, kBlockLoadReport = 0x89,
                        kBlockLoadStatus = 0x8B, kBlockLoadSuccess = 0x8C, kDeviceControlReport = 0x95,
                        kDeviceControl = 0x96, kDcEnableActuators = 0x97, kDcDisableActuators = 0x98,
                        kDcStopAllEffects = 0x99, kStartDelay = 0xA7, kCreateNewEffectReport = 0xAB;
}  // namespace pid

// Element `index` of field `field` of the descriptor (-1: absent).
struct HidFieldRef {
  int field = -1;
  std::uint32_t index = 0;
  bool found() const { return field >= 0; }
};
// An array field and the value that selects one of its usages (logical
// minimum + the usage's position, as the Linux pidff driver computes it).
struct HidSelector {
  int field = -1;
  std::int32_t value = 0;
  bool found() const { return field >= 0; }
};
struct HidReportRef {
  bool present = false;
  HidReportKind kind = HidReportKind::Output;
  std::uint8_t id = 0;
  std::size_t size = 0;  // bytes, report ID included when the device uses IDs
};

struct PidLayout {
  HidReportDescriptor descriptor;
  HidReportRef set_effect, set_constant_force, effect_operation, device_control, device_gain,
      create_new_effect, block_load;
  // Set Effect
  HidFieldRef effect_block, duration, trigger_repeat, sample_period, gain, trigger_button, start_delay,
      direction_enable;
  HidSelector effect_type_constant;
  std::vector<HidFieldRef> axes_enable;  // per axis (Generic Desktop X, Y, ... in the Axes Enable collection)
  std::vector<HidFieldRef> direction;    // per axis, when present
  // Set Constant Force
  HidFieldRef constant_block, magnitude;
  // Effect Operation
  HidFieldRef operation_block, loop_count;
  HidSelector op_start, op_stop;
  // PID Device Control
  HidSelector enable_actuators, disable_actuators, stop_all;
  // Device Gain
  HidFieldRef device_gain_value;
  // Create New Effect / Block Load (features: the device allocates effect blocks)
  HidSelector create_constant;
  HidFieldRef load_block;
  HidSelector load_success;
  // Input axes (Generic Desktop X Y Z Rx Ry Rz) for a joystick's own input.
  std::array<HidFieldRef, 6> input_axes{};

  int axis_count() const { return static_cast<int>(axes_enable.size()); }
  const HidField& field(const HidFieldRef& r) const { return descriptor.fields[r.field]; }
};

// Finds the constant-force output in `descriptor`; false with the reason when
// the device has no PID page or lacks a report the output needs.
bool find_pid_layout(const std::uint8_t* descriptor, std::size_t size, PidLayout& layout, std::string* why);

// The reports (report ID byte first, zero-filled, then the fields).
std::vector<std::uint8_t> pid_set_effect_report(const PidLayout& layout, int block, int axis);
std::vector<std::uint8_t> pid_constant_force_report(const PidLayout& layout, int block, std::int32_t magnitude);
std::vector<std::uint8_t> pid_effect_operation_report(const PidLayout& layout, int block, bool start);
std::vector<std::uint8_t> pid_device_control_report(const PidLayout& layout, const HidSelector& control);
std::vector<std::uint8_t> pid_device_gain_report(const PidLayout& layout, double gain);  // 0..1
std::vector<std::uint8_t> pid_create_effect_report(const PidLayout& layout);
// `force` in N against the device's full scale, as the Magnitude field's value
// (rounded, clamped to its logical range).
std::int32_t pid_magnitude(const PidLayout& layout, double force, double full_scale);

// Where the reports go: hidapi in use, a capturing fake in tests.
class HidTransport {
 public:
  virtual ~HidTransport() = default;
  virtual bool write_output(const std::uint8_t* report, std::size_t size) = 0;
  virtual bool send_feature(const std::uint8_t* report, std::size_t size) = 0;
  // `report[0]` holds the report ID on entry; returns the bytes read (< 0: error).
  virtual int get_feature(std::uint8_t* report, std::size_t size) = 0;
  // Non-blocking: bytes of one input report, 0 when none waits, < 0 when gone.
  virtual int read_input(std::uint8_t* buffer, std::size_t size) = 0;
};

struct PidForceConfig {
  std::string name = "HID force-feedback device";
  double full_scale_force = 3.0;  // N at the largest magnitude (PID devices do not say)
  double max_stiffness = 0.5;     // N/mm rendered stably
  double max_damping = 0.002;     // N s/mm
  double update_rate_hz = 250;    // effect updates per second at most
  double gain = 1.0;              // Device Gain, 0..1
  // World direction of each device axis: the force along it drives that axis.
  std::array<Vec3, 6> axis_directions{Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ(),
                                      Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()};
  bool start_thread = true;       // false: the caller runs service() (tests)
  // Opens the device again after an unplug (none: stays unplugged).
  std::function<std::unique_ptr<HidTransport>()> reopen;
};

// A HID device offering PID constant force: its own input axes (rate control,
// like a SpaceMouse) and the loop's force rendered per axis.
class HidPidDevice : public Device {
 public:
  HidPidDevice(std::unique_ptr<HidTransport> transport, PidLayout layout, PidForceConfig config);
  ~HidPidDevice() override;
  const DeviceCapabilities& capabilities() const override { return caps_; }
  DeviceSample read(double now) noexcept override;
  void write(const Wrench& wrench) noexcept override;
  void halt() noexcept override;

  // One pass of the I/O thread: input reports drained, then the effects
  // brought to the latest wrench (or stopped after a halt).
  void service();
  bool connected() const { return connected_.load(); }
  int effect_block(int axis) const { return blocks_[axis]; }
  std::string description() const;

 private:
  bool initialise();
  bool send(const std::vector<std::uint8_t>& report, HidReportKind kind);
  void run();

  std::unique_ptr<HidTransport> transport_;
  PidLayout layout_;
  PidForceConfig config_;
  DeviceCapabilities caps_;
  bool initialised_ = false, playing_ = false;
  std::array<int, 6> blocks_{};
  std::array<std::int32_t, 6> sent_{};
  std::vector<std::uint8_t> input_;
  // Loop -> I/O thread (seqlock), and the input axes back.
  std::atomic<std::uint32_t> force_sequence_{0};
  std::atomic<double> force_[3] = {};
  std::atomic<bool> halted_{true};
  std::atomic<double> axes_[6] = {};
  std::atomic<bool> connected_{false};
  std::atomic<bool> stop_{false};
  std::thread io_;
  mutable std::mutex description_mutex_;
  std::string description_;
};

// hidapi: the devices whose report descriptor offers PID constant force (the
// descriptor read from sysfs, /sys/class/hidraw/*/device/report_descriptor,
// since hidapi 0.13 cannot return it), and a transport on one of them.
struct HidPidFound {
  std::string name, path;
  std::uint16_t vendor = 0, product = 0;
  int axes = 0;
};
std::vector<HidPidFound> enumerate_hid_pid_devices();
std::unique_ptr<HidTransport> open_hidapi_transport(const std::string& path, std::string* why);
// The descriptor of a hidraw node (/dev/hidrawN), empty when unreadable.
std::vector<std::uint8_t> hidraw_report_descriptor(const std::string& path);

}  // namespace contactcore::haptics
