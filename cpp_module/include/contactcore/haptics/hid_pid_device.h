// A HID device offering PID constant force (hid_pid.h): its own input axes
// and the servo loop's clamped force rendered as one constant-force effect per
// device axis, over hidapi or any HidTransport.
//
// The 1 kHz loop never writes to the device: write() stores the wrench in a
// triple buffer and an I/O thread (or a test calling service()) sends Set
// Constant Force reports at a bounded rate, only for the axes whose magnitude
// changed; each axis' force changes at most `max_force_rate` N/s. A position
// device whose descriptor offers conditions renders the coupling locally:
// a spring (Set Condition: centre where the spring gives the loop's force at
// the device's last position, coefficient = the coupling's stiffness) and a
// damper (the coupling's damping), so the stiffness holds between updates.
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
#include "contactcore/haptics/hid_recording.h"
#include "contactcore/haptics/triple_buffer.h"

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
  double max_force_rate = 200;    // N/s per axis the rendered force may change (0: no limit)
  // Position: the input axes X Y Z are a position, +-workspace_mm at full
  // deflection along axis_directions (an arm, a force-feedback joystick
  // used as a position device); Rate: a deflection -> speed (like a SpaceMouse).
  ControlMode control = ControlMode::Rate;
  double workspace_mm = 50;
  bool use_conditions = true;     // position devices: spring + damper conditions where offered
  // The clock arrival times are stamped with (none: steady seconds; the
  // simulated device and tests give their own). Called without allocating.
  std::function<double()> clock;
  std::shared_ptr<HidRecorder> recorder;  // raw input reports with their arrival times
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
  int spring_block() const { return spring_block_; }
  int damper_block() const { return damper_block_; }
  bool renders_conditions() const { return conditions_; }
  // The force per device axis the last service rendered (after the rate limit), N.
  double rendered_force(int axis) const { return rendered_[axis]; }
  std::string description() const;

 private:
  bool initialise();
  bool allocate(const HidSelector& create_type, int fallback, int& block);
  bool send(const std::vector<std::uint8_t>& report, HidReportKind kind);
  bool render_conditions(double stiffness, double damping, bool restart);
  void run();
  double clock() const;

  struct Command {
    Vec3 force = Vec3::Zero();
    double stiffness = 0, damping = 0;  // the coupling's gains (N/mm, N s/mm)
  };
  struct Reading {
    Vec6 axes = Vec6::Zero();
    Vec6 velocity = Vec6::Zero();  // normalised units per second
    double arrival = 0;            // clock() when the report arrived
    bool reported = false;         // a report came (velocities need two)
  };

  std::unique_ptr<HidTransport> transport_;
  PidLayout layout_;
  PidForceConfig config_;
  DeviceCapabilities caps_;
  bool initialised_ = false, playing_ = false;
  bool conditions_ = false;  // spring and damper played (position device with conditions)
  std::array<int, 6> blocks_{};
  int spring_block_ = 0, damper_block_ = 0;
  std::array<std::int32_t, 6> sent_{};
  std::array<PidCondition, 6> sent_spring_{}, sent_damper_{};
  std::array<double, 6> rendered_{};  // N per axis after the rate limit
  double last_service_ = -1;
  Reading reading_;                   // I/O thread's own copy
  std::vector<std::uint8_t> input_;
  // Loop -> I/O thread and the input back: triple buffers (no side retries).
  TripleBuffer<Command> commands_;
  std::atomic<bool> halted_{true};
  TripleBuffer<Reading> readings_;
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
