// A HID device offering PID constant force (hid_pid.h): its own input axes
// and the servo loop's clamped force rendered as one constant-force effect per
// device axis, over hidapi or any HidTransport.
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
#include "contactcore/haptics/hid_pid.h"

namespace contactcore::haptics {

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
