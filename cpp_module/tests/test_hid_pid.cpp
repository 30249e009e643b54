// HID force feedback (PID page) without hardware: a PID joystick's report
// descriptor written from the HID PID 1.0 specification, and a fake transport
// that captures every report the device layer sends.
#include <gtest/gtest.h>

#include <chrono>
#include <deque>
#include <memory>
#include <thread>

#include "contactcore/haptics/hid_pid_device.h"
#include "contactcore/haptics/servo_loop.h"
#include "contactcore/haptics/spacemouse.h"

using namespace contactcore::haptics;

namespace {

using Bytes = std::vector<std::uint8_t>;

// A two-axis force-feedback joystick, written from "USB Device Class
// Definition for Physical Interface Devices (PID)", version 1.0 (usb.org,
// 1999): usage IDs from its table 2 (page 0x0F), report structure after its
// section 5 (Set Effect, Set Constant Force, Effect Operation, PID Device
// Control, Device Gain, Create New Effect and Block Load). Report IDs: input 1,
// outputs 2 (Set Effect), 5 (Set Constant Force), 10 (Effect Operation), 12
// (Device Control), 13 (Device Gain); features 17 (Create New Effect), 18
// (Block Load), only with `device_allocates`.
Bytes pid_joystick_descriptor(bool device_allocates) {
  Bytes d = {
      0x05, 0x01,        // Usage Page (Generic Desktop)
      0x09, 0x04,        // Usage (Joystick)
      0xA1, 0x01,        // Collection (Application)
      0x85, 0x01,        //   Report ID (1)
      0x09, 0x30,        //   Usage (X)
      0x09, 0x31,        //   Usage (Y)
      0x16, 0x01, 0x80,  //   Logical Minimum (-32767)
      0x26, 0xFF, 0x7F,  //   Logical Maximum (32767)
      0x75, 0x10,        //   Report Size (16)
      0x95, 0x02,        //   Report Count (2)
      0x81, 0x02,        //   Input (Data, Var, Abs)
      0x05, 0x0F,        //   Usage Page (PID)
      // Set Effect Report
      0x09, 0x21, 0xA1, 0x02,  // Usage (Set Effect Report), Collection (Logical)
      0x85, 0x02,              //   Report ID (2)
      0x09, 0x22,              //   Usage (Effect Block Index)
      0x15, 0x01, 0x25, 0x28,  //   Logical 1..40
      0x75, 0x08, 0x95, 0x01,  //   8 bits x 1
      0x91, 0x02,              //   Output (Data, Var, Abs)
      0x09, 0x25, 0xA1, 0x02,  //   Usage (Effect Type), Collection (Logical)
      0x09, 0x26, 0x09, 0x27, 0x09, 0x30, 0x09, 0x31, 0x09, 0x40,  // ET Constant, Ramp, Square, Sine, Spring
      0x15, 0x01, 0x25, 0x05,  //     Logical 1..5
      0x75, 0x08, 0x95, 0x01,  //     8 bits x 1
      0x91, 0x00,              //     Output (Data, Array, Abs)
      0xC0,                    //   End Collection
      0x09, 0x50, 0x09, 0x54, 0x09, 0x51,  // Usage (Duration, Trigger Repeat Interval, Sample Period)
      0x15, 0x00, 0x26, 0xFF, 0x7F,        //   Logical 0..32767
      0x75, 0x10, 0x95, 0x03,              //   16 bits x 3
      0x91, 0x02,                          //   Output (Data, Var, Abs)
      0x09, 0x52,                          //   Usage (Gain)
      0x15, 0x00, 0x26, 0xFF, 0x00,        //   Logical 0..255
      0x75, 0x08, 0x95, 0x01, 0x91, 0x02,  //   8 bits x 1, Output
      0x09, 0x53,                          //   Usage (Trigger Button)
      0x15, 0x01, 0x25, 0x08,              //   Logical 1..8
      0x75, 0x08, 0x95, 0x01, 0x91, 0x02,  //   8 bits x 1, Output
      0x09, 0x55, 0xA1, 0x02,              //   Usage (Axes Enable), Collection (Logical)
      0x05, 0x01, 0x09, 0x30, 0x09, 0x31,  //     Generic Desktop X, Y
      0x15, 0x00, 0x25, 0x01,              //     Logical 0..1
      0x75, 0x01, 0x95, 0x02, 0x91, 0x02,  //     1 bit x 2, Output
      0xC0,                                //   End Collection
      0x05, 0x0F, 0x09, 0x56,              //   Usage (Direction Enable)
      0x95, 0x01, 0x91, 0x02,              //   1 bit x 1, Output
      0x95, 0x05, 0x91, 0x03,              //   5 bits padding (Output Const)
      0x09, 0x57, 0xA1, 0x02,              //   Usage (Direction), Collection (Logical)
      0x05, 0x0A, 0x09, 0x01, 0x09, 0x02,  //     Ordinal 1, 2
      0x15, 0x00, 0x26, 0xFF, 0x00,        //     Logical 0..255
      0x75, 0x08, 0x95, 0x02, 0x91, 0x02,  //     8 bits x 2, Output
      0xC0,                                //   End Collection
      0x05, 0x0F,                          //   Usage Page (PID)
      0xC0,                                // End Collection (Set Effect Report)
      // Set Constant Force Report
      0x09, 0x73, 0xA1, 0x02, 0x85, 0x05,
      0x09, 0x22, 0x15, 0x01, 0x25, 0x28, 0x75, 0x08, 0x95, 0x01, 0x91, 0x02,
      0x09, 0x70,                          //   Usage (Magnitude)
      0x16, 0xF0, 0xD8, 0x26, 0x10, 0x27,  //   Logical -10000..10000
      0x75, 0x10, 0x95, 0x01, 0x91, 0x02,  //   16 bits x 1, Output
      0xC0,
      // Effect Operation Report
      0x09, 0x77, 0xA1, 0x02, 0x85, 0x0A,
      0x09, 0x22, 0x15, 0x01, 0x25, 0x28, 0x75, 0x08, 0x95, 0x01, 0x91, 0x02,
      0x09, 0x78, 0xA1, 0x02,              //   Usage (Effect Operation), Collection (Logical)
      0x09, 0x79, 0x09, 0x7A, 0x09, 0x7B,  //     Op Effect Start, Start Solo, Stop
      0x15, 0x01, 0x25, 0x03, 0x75, 0x08, 0x95, 0x01, 0x91, 0x00,  // Output (Array)
      0xC0,
      0x09, 0x7C,                          //   Usage (Loop Count)
      0x15, 0x00, 0x26, 0xFF, 0x00, 0x75, 0x08, 0x95, 0x01, 0x91, 0x02,
      0xC0,
      // PID Device Control Report
      0x09, 0x95, 0xA1, 0x02, 0x85, 0x0C,
      0x09, 0x96, 0xA1, 0x02,              //   Usage (PID Device Control), Collection (Logical)
      0x09, 0x97, 0x09, 0x98, 0x09, 0x99, 0x09, 0x9A, 0x09, 0x9B, 0x09, 0x9C,  // Enable, Disable, Stop All, Reset, Pause, Continue
      0x15, 0x01, 0x25, 0x06, 0x75, 0x08, 0x95, 0x01, 0x91, 0x00,  // Output (Array)
      0xC0,
      0xC0,
      // Device Gain Report
      0x09, 0x7D, 0xA1, 0x02, 0x85, 0x0D,
      0x09, 0x7E, 0x15, 0x00, 0x26, 0xFF, 0x00, 0x75, 0x08, 0x95, 0x01, 0x91, 0x02,
      0xC0,
  };
  if (device_allocates) {
    const Bytes features = {
        // Create New Effect Report (feature 17): the effect type
        0x09, 0xAB, 0xA1, 0x02, 0x85, 0x11,
        0x09, 0x25, 0xA1, 0x02, 0x09, 0x26, 0x09, 0x27, 0x09, 0x30, 0x09, 0x31, 0x09, 0x40,
        0x15, 0x01, 0x25, 0x05, 0x75, 0x08, 0x95, 0x01, 0xB1, 0x00,  // Feature (Array)
        0xC0,
        0xC0,
        // Block Load Report (feature 18): the block given, and whether it worked
        0x09, 0x89, 0xA1, 0x02, 0x85, 0x12,
        0x09, 0x22, 0x15, 0x01, 0x25, 0x28, 0x75, 0x08, 0x95, 0x01, 0xB1, 0x02,
        0x09, 0x8B, 0xA1, 0x02, 0x09, 0x8C, 0x09, 0x8D, 0x09, 0x8E,  // Success, Full, Error
        0x15, 0x01, 0x25, 0x03, 0x75, 0x08, 0x95, 0x01, 0xB1, 0x00,
        0xC0,
        0xC0,
    };
    d.insert(d.end(), features.begin(), features.end());
  }
  d.push_back(0xC0);  // End Collection (Application)
  return d;
}

// The same joystick with conditions (PID 1.0 section 5.9): ET Damper added to
// the Set Effect types (spring is 5, damper 6) and a Set Condition Report
// (output 3): block, parameter block offset (the axis), CP offset and the two
// coefficients (-10000..10000, 16 bits), the two saturations (0..10000, 16
// bits), dead band (0..255, 8 bits): 14 bytes with the ID.
Bytes pid_joystick_with_conditions() {
  Bytes d = pid_joystick_descriptor(false);
  const Bytes types = {0x09, 0x40, 0x15, 0x01, 0x25, 0x05};
  auto at = std::search(d.begin(), d.end(), types.begin(), types.end());
  EXPECT_NE(at, d.end());
  const Bytes with_damper = {0x09, 0x40, 0x09, 0x41, 0x15, 0x01, 0x25, 0x06};
  at = d.erase(at, at + static_cast<std::ptrdiff_t>(types.size()));
  d.insert(at, with_damper.begin(), with_damper.end());
  const Bytes condition = {
      0x09, 0x5F, 0xA1, 0x02, 0x85, 0x03,                                // Set Condition Report (3)
      0x09, 0x22, 0x15, 0x01, 0x25, 0x28, 0x75, 0x08, 0x95, 0x01, 0x91, 0x02,  // Effect Block Index
      0x09, 0x23, 0x15, 0x00, 0x25, 0x01, 0x75, 0x08, 0x95, 0x01, 0x91, 0x02,  // Parameter Block Offset
      0x09, 0x60, 0x09, 0x61, 0x09, 0x62,                                // CP Offset, +/- Coefficient
      0x16, 0xF0, 0xD8, 0x26, 0x10, 0x27, 0x75, 0x10, 0x95, 0x03, 0x91, 0x02,
      0x09, 0x63, 0x09, 0x64, 0x15, 0x00, 0x26, 0x10, 0x27, 0x75, 0x10, 0x95, 0x02, 0x91, 0x02,  // saturations
      0x09, 0x65, 0x15, 0x00, 0x26, 0xFF, 0x00, 0x75, 0x08, 0x95, 0x01, 0x91, 0x02,              // Dead Band
      0xC0,
  };
  d.insert(d.end() - 1, condition.begin(), condition.end());  // before End Collection (Application)
  return d;
}

struct Sent {
  bool feature = false;
  Bytes bytes;
};

// Captures what the device layer sends; answers Block Load with `blocks`.
struct FakeLog {
  std::vector<Sent> sent;
  std::deque<Bytes> inputs;
  std::deque<int> blocks;
  int load_status = 1;  // 1: success, 2: full
  bool unplugged = false;
  std::vector<Bytes> outputs() const {
    std::vector<Bytes> out;
    for (const Sent& s : sent)
      if (!s.feature) out.push_back(s.bytes);
    return out;
  }
};

class FakeTransport : public HidTransport {
 public:
  explicit FakeTransport(std::shared_ptr<FakeLog> log) : log_(std::move(log)) {}
  bool write_output(const std::uint8_t* r, std::size_t n) override {
    if (log_->unplugged) return false;
    log_->sent.push_back(Sent{false, Bytes(r, r + n)});
    return true;
  }
  bool send_feature(const std::uint8_t* r, std::size_t n) override {
    if (log_->unplugged) return false;
    log_->sent.push_back(Sent{true, Bytes(r, r + n)});
    return true;
  }
  int get_feature(std::uint8_t* r, std::size_t n) override {
    if (log_->unplugged || r[0] != 18 || n < 3) return -1;
    r[1] = static_cast<std::uint8_t>(log_->blocks.empty() ? 1 : log_->blocks.front());
    if (!log_->blocks.empty()) log_->blocks.pop_front();
    r[2] = static_cast<std::uint8_t>(log_->load_status);
    return 3;
  }
  int read_input(std::uint8_t* buffer, std::size_t size) override {
    if (log_->unplugged) return -1;
    if (log_->inputs.empty()) return 0;
    const Bytes b = log_->inputs.front();
    log_->inputs.pop_front();
    const std::size_t n = std::min(size, b.size());
    std::copy(b.begin(), b.begin() + n, buffer);
    return static_cast<int>(n);
  }

 private:
  std::shared_ptr<FakeLog> log_;
};

PidLayout layout_of(const Bytes& descriptor) {
  PidLayout layout;
  std::string why;
  EXPECT_TRUE(find_pid_layout(descriptor.data(), descriptor.size(), layout, &why)) << why;
  return layout;
}

std::unique_ptr<HidPidDevice> make_device(const std::shared_ptr<FakeLog>& log, bool device_allocates = false,
                                          bool thread = false) {
  PidForceConfig config;
  config.name = "PID joystick";
  config.full_scale_force = 3.0;  // N at magnitude 10000
  config.start_thread = thread;
  config.max_force_rate = 0;      // these tests check one update's bytes; the limit has its own test
  return std::make_unique<HidPidDevice>(std::make_unique<FakeTransport>(log),
                                        layout_of(pid_joystick_descriptor(device_allocates)), config);
}

// Set Constant Force (ID 5): block, magnitude int16 little-endian.
Bytes constant_force(int block, int magnitude) {
  const auto m = static_cast<std::uint16_t>(static_cast<std::int16_t>(magnitude));
  return {5, static_cast<std::uint8_t>(block), static_cast<std::uint8_t>(m & 0xFF), static_cast<std::uint8_t>(m >> 8)};
}
const Bytes kEnableActuators = {12, 1};  // Device Control: first usage (0x97), logical minimum 1
const Bytes kStopAll = {12, 3};          // 0x99, third
Bytes start_effect(int block) { return {10, static_cast<std::uint8_t>(block), 1, 1}; }  // Op Effect Start, loop 1

}  // namespace

TEST(HidDescriptor, FieldsOffsetsAndSizes) {
  const Bytes d = pid_joystick_descriptor(false);
  HidReportDescriptor parsed;
  std::string error;
  ASSERT_TRUE(parse_hid_descriptor(d.data(), d.size(), parsed, &error)) << error;
  EXPECT_TRUE(parsed.uses_report_ids);
  // Set Effect: block 8 + type 8 + 3 x 16 + gain 8 + trigger 8 + axes 2 + direction enable 1 + pad 5 + 2 x 8 bits.
  EXPECT_EQ(parsed.report_size(HidReportKind::Output, 2), 1u + 13u);
  EXPECT_EQ(parsed.report_size(HidReportKind::Output, 5), 4u);
  EXPECT_EQ(parsed.report_size(HidReportKind::Input, 1), 5u);
  // The magnitude: signed range, 16 bits at bit 8 of report 5.
  const HidField* magnitude = nullptr;
  for (const HidField& f : parsed.fields)
    if (f.report_id == 5 && f.usage(0) == hid_usage(0x0F, 0x70)) magnitude = &f;
  ASSERT_NE(magnitude, nullptr);
  EXPECT_EQ(magnitude->bit_offset, 8u);
  EXPECT_EQ(magnitude->logical_min, -10000);
  EXPECT_EQ(magnitude->logical_max, 10000);
  EXPECT_TRUE(magnitude->in_collection(hid_usage(0x0F, 0x73)));
  // Round trip of a negative value.
  Bytes report(4, 0);
  report[0] = 5;
  put_field(report.data(), true, *magnitude, 0, -2500);
  EXPECT_EQ(report, (Bytes{5, 0, 0x3C, 0xF6}));
  EXPECT_EQ(get_field(report.data(), report.size(), true, *magnitude, 0), -2500);
  // Malformed: an unclosed collection, a truncated item.
  Bytes truncated(d.begin(), d.end() - 1);
  EXPECT_FALSE(parse_hid_descriptor(truncated.data(), truncated.size(), parsed, &error));
  EXPECT_NE(error.find("unclosed collection"), std::string::npos);
  const Bytes cut = {0x05, 0x01, 0x26, 0xFF};
  EXPECT_FALSE(parse_hid_descriptor(cut.data(), cut.size(), parsed, &error));
  EXPECT_NE(error.find("byte 2"), std::string::npos) << error;
}

TEST(HidPid, LayoutFromTheDescriptor) {
  const Bytes d = pid_joystick_descriptor(false);
  const PidLayout layout = layout_of(d);
  EXPECT_EQ(layout.axis_count(), 2);
  EXPECT_EQ(layout.set_effect.id, 2);
  EXPECT_EQ(layout.set_constant_force.id, 5);
  EXPECT_EQ(layout.effect_operation.id, 10);
  EXPECT_EQ(layout.device_control.id, 12);
  EXPECT_EQ(layout.device_gain.id, 13);
  EXPECT_EQ(layout.effect_type_constant.value, 1);
  EXPECT_EQ(layout.op_start.value, 1);
  EXPECT_EQ(layout.op_stop.value, 3);
  EXPECT_EQ(layout.enable_actuators.value, 1);
  EXPECT_EQ(layout.stop_all.value, 3);
  EXPECT_EQ(layout.direction.size(), 2u);
  EXPECT_TRUE(layout.input_axes[0].found() && layout.input_axes[1].found());
  EXPECT_FALSE(layout.input_axes[2].found());
  EXPECT_FALSE(layout.create_new_effect.present);

  // A SpaceMouse-like descriptor (no PID page) offers no force output, and says so.
  const Bytes plain = {0x05, 0x01, 0x09, 0x08, 0xA1, 0x01, 0x85, 0x01, 0x09, 0x30, 0x16, 0xA2, 0xFE,
                       0x26, 0x5E, 0x01, 0x75, 0x10, 0x95, 0x01, 0x81, 0x02, 0xC0};
  PidLayout none;
  std::string why;
  EXPECT_FALSE(find_pid_layout(plain.data(), plain.size(), none, &why));
  EXPECT_EQ(why, "no PID usage page (0x0F): no force feedback");
}

TEST(HidPid, ReportsByteForByte) {
  const PidLayout layout = layout_of(pid_joystick_descriptor(false));
  // Set Effect, block 2 on axis 1 (Y): constant force (1), infinite duration
  // (0xFFFF), no repeat or sample period, gain 255, no trigger button, axes
  // enable bit 1 only, direction enable 0, directions 0.
  EXPECT_EQ(pid_set_effect_report(layout, 2, 1),
            (Bytes{2, 2, 1, 0xFF, 0xFF, 0, 0, 0, 0, 0xFF, 0, 0b010, 0, 0}));
  EXPECT_EQ(pid_constant_force_report(layout, 1, 5000), constant_force(1, 5000));
  EXPECT_EQ(pid_effect_operation_report(layout, 2, true), start_effect(2));
  EXPECT_EQ(pid_effect_operation_report(layout, 2, false), (Bytes{10, 2, 3, 1}));
  EXPECT_EQ(pid_device_control_report(layout, layout.stop_all), kStopAll);
  EXPECT_EQ(pid_device_gain_report(layout, 0.5), (Bytes{13, 128}));
  // Magnitudes: 3 N is full scale (10000); beyond it the device's limit holds.
  EXPECT_EQ(pid_magnitude(layout, 1.5, 3.0), 5000);
  EXPECT_EQ(pid_magnitude(layout, -0.75, 3.0), -2500);
  EXPECT_EQ(pid_magnitude(layout, 10.0, 3.0), 10000);
  EXPECT_EQ(pid_magnitude(layout, -7.0, 3.0), -10000);
}

TEST(HidPid, CapabilitiesSayForceOutput) {
  auto log = std::make_shared<FakeLog>();
  auto device = make_device(log);
  const DeviceCapabilities& caps = device->capabilities();
  EXPECT_TRUE(caps.force_output);
  EXPECT_TRUE(caps.hid_force_feedback);
  EXPECT_FALSE(caps.torque_output);
  EXPECT_EQ(caps.input_dof, 2);
  EXPECT_EQ(caps.control, ControlMode::Rate);
  EXPECT_DOUBLE_EQ(caps.max_force, 3.0);
}

TEST(HidPid, InitialisesThenRendersAKnownForce) {
  auto log = std::make_shared<FakeLog>();
  auto device = make_device(log);
  device->service();  // halted from the start: set up, nothing played
  EXPECT_EQ(log->outputs(), (std::vector<Bytes>{kEnableActuators, Bytes{13, 255},
                                                pid_set_effect_report(layout_of(pid_joystick_descriptor(false)), 1, 0),
                                                constant_force(1, 0),
                                                Bytes{2, 2, 1, 0xFF, 0xFF, 0, 0, 0, 0, 0xFF, 0, 0b010, 0, 0},
                                                constant_force(2, 0)}));
  log->sent.clear();
  Wrench w;
  w.force = Vec3(1.5, -0.75, 0.4);  // z: no such axis on this device
  device->write(w);
  device->service();
  EXPECT_EQ(log->outputs(), (std::vector<Bytes>{kEnableActuators, constant_force(1, 5000), start_effect(1),
                                                constant_force(2, -2500), start_effect(2)}));
  // Same force again: nothing sent; x alone changes: one report.
  log->sent.clear();
  device->write(w);
  device->service();
  EXPECT_TRUE(log->sent.empty());
  w.force.x() = 0.3;
  device->write(w);
  device->service();
  EXPECT_EQ(log->outputs(), (std::vector<Bytes>{constant_force(1, 1000)}));
  // Beyond the device's limit: full scale, not more.
  log->sent.clear();
  w.force = Vec3(10, -20, 0);
  device->write(w);
  device->service();
  EXPECT_EQ(log->outputs(), (std::vector<Bytes>{constant_force(1, 10000), constant_force(2, -10000)}));
  // Halt: one Stop All, then silence until the next force restarts the effects.
  log->sent.clear();
  device->halt();
  device->service();
  device->service();
  EXPECT_EQ(log->outputs(), (std::vector<Bytes>{kStopAll}));
}

TEST(HidPid, DeviceAllocatedBlocks) {
  auto log = std::make_shared<FakeLog>();
  log->blocks = {7, 9};
  auto device = make_device(log, true);
  device->service();
  ASSERT_EQ(log->sent.size(), 2u + 2u * 3u);
  EXPECT_TRUE(log->sent[2].feature);
  EXPECT_EQ(log->sent[2].bytes, (Bytes{17, 1}));  // Create New Effect: constant force
  EXPECT_EQ(device->effect_block(0), 7);
  EXPECT_EQ(device->effect_block(1), 9);
  EXPECT_EQ(log->sent[3].bytes[1], 7);  // Set Effect for block 7
  EXPECT_EQ(log->sent[4].bytes, constant_force(7, 0));

  // A device with no free block: nothing is played, and it says why.
  auto full_log = std::make_shared<FakeLog>();
  full_log->load_status = 2;
  auto full = make_device(full_log, true);
  full->service();
  EXPECT_NE(full->description().find("no free effect block"), std::string::npos);
  Wrench w;
  w.force = Vec3(1, 0, 0);
  full->write(w);
  full->service();
  for (const Sent& s : full_log->sent) EXPECT_NE(s.bytes[0], 5) << "no force on an unallocated effect";
}

TEST(HidPid, InputAxesFromTheDescriptor) {
  auto log = std::make_shared<FakeLog>();
  auto device = make_device(log);
  // X = 32767 (full right), Y = -16384 (half forward).
  log->inputs.push_back(Bytes{1, 0xFF, 0x7F, 0x00, 0xC0});
  device->service();
  const DeviceSample s = device->read(1.0);
  EXPECT_TRUE(s.connected);
  EXPECT_DOUBLE_EQ(s.axes[0], 1.0);
  EXPECT_NEAR(s.axes[1], -16384.0 / 32767.0, 1e-12);
  EXPECT_EQ(s.axes[2], 0.0);
}

// The servo loop drives the device: a known coupling force reaches the device
// as magnitudes; the watchdog (disable, unplug) stops all effects.
TEST(HidPid, ServoLoopForceAndWatchdog) {
  auto log = std::make_shared<FakeLog>();
  auto device = make_device(log);
  ServoConfig config;
  config.lockstep = true;
  config.stiffness = 0.5;  // N/mm, the device's stable limit
  config.damping = 0;
  config.rate_speed = 40;  // mm/s at full deflection
  ServoLoop loop(*device, config, Pose::Identity());
  JointState fixed;
  fixed.kind = JointKind::Fixed;
  loop.hold_to(fixed);  // the part cannot move: the coupling force is K * (proxy - target)
  log->inputs.push_back(Bytes{1, 0xFF, 0x7F, 0, 0});  // full deflection along x
  device->service();
  log->sent.clear();
  loop.step_lockstep();
  // target = proxy + 40 mm/s * 1 ms along x; F = 0.5 N/mm * (-0.04 mm) = -0.02 N -> -0.02 / 3 * 10000.
  EXPECT_NEAR(loop.last().wrench.force.x(), -0.02, 1e-12);
  device->service();
  EXPECT_EQ(log->outputs(), (std::vector<Bytes>{kEnableActuators, constant_force(1, -67), start_effect(1),
                                                constant_force(2, 0), start_effect(2)}));
  // Disable: the watchdog halts the device, which stops every effect.
  log->sent.clear();
  loop.set_enabled(false);
  loop.step_lockstep();
  EXPECT_EQ(loop.last().watchdog, Watchdog::Disabled);
  device->service();
  EXPECT_EQ(log->outputs(), (std::vector<Bytes>{kStopAll}));
  // Enabled again: the effects restart.
  log->sent.clear();
  loop.set_enabled(true);
  loop.step_lockstep();
  device->service();
  ASSERT_FALSE(log->outputs().empty());
  EXPECT_EQ(log->outputs().front(), kEnableActuators);
  // Unplugged: the device reads "not connected", the loop trips its watchdog.
  log->unplugged = true;
  device->service();
  EXPECT_FALSE(device->connected());
  loop.step_lockstep();
  EXPECT_EQ(loop.last().watchdog, Watchdog::Unplugged);
  EXPECT_EQ(loop.last().wrench.force.norm(), 0.0);
}

// The I/O thread sends at a bounded rate, never from the loop's tick; on
// destruction the device is left silent.
TEST(HidPid, WriterThread) {
  auto log = std::make_shared<FakeLog>();
  {
    auto device = make_device(log, false, true);
    Wrench w;
    w.force = Vec3(0.3, 0, 0);
    for (int i = 0; i < 20; ++i) {  // 20 writes at 1 kHz
      device->write(w);
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  const auto out = log->outputs();
  int forces = 0;
  for (const Bytes& b : out) forces += b == constant_force(1, 1000) ? 1 : 0;
  EXPECT_EQ(forces, 1) << "one report per change, not one per loop tick";
  ASSERT_GE(out.size(), 2u);
  EXPECT_EQ(out[out.size() - 1], (Bytes{12, 2}));  // Disable Actuators
  EXPECT_EQ(out[out.size() - 2], kStopAll);
}

// ---- conditions (spring, damper), position devices, the force-rate limit

namespace {

struct FakeClock {
  static double now;
  static double read() { return now; }
};
double FakeClock::now = 0;

Bytes condition(int block, int axis, int cp, int k, int saturation) {
  auto le = [](int v) {
    const auto u = static_cast<std::uint16_t>(static_cast<std::int16_t>(v));
    return std::pair<std::uint8_t, std::uint8_t>(u & 0xFF, u >> 8);
  };
  const auto c = le(cp), kk = le(k), s = le(saturation);
  return {3, static_cast<std::uint8_t>(block), static_cast<std::uint8_t>(axis), c.first, c.second, kk.first, kk.second,
          kk.first, kk.second, s.first, s.second, s.first, s.second, 0};
}

}  // namespace

TEST(HidPid, ConditionReportsByteForByte) {
  const PidLayout layout = layout_of(pid_joystick_with_conditions());
  ASSERT_TRUE(layout.has_conditions());
  EXPECT_EQ(layout.set_condition.id, 3);
  EXPECT_EQ(layout.set_condition.size, 14u);
  EXPECT_EQ(layout.effect_type_spring.value, 5);
  EXPECT_EQ(layout.effect_type_damper.value, 6);
  EXPECT_FALSE(layout_of(pid_joystick_descriptor(false)).has_conditions());
  // Spring on block 3, every axis: type 5, infinite, gain 255, axes X and Y.
  EXPECT_EQ(pid_set_condition_effect_report(layout, 3, layout.effect_type_spring),
            (Bytes{2, 3, 5, 0xFF, 0xFF, 0, 0, 0, 0, 0xFF, 0, 0b011, 0, 0}));
  PidCondition c;
  c.cp_offset = -2000;
  c.positive_coefficient = c.negative_coefficient = 5000;
  c.positive_saturation = c.negative_saturation = 10000;
  EXPECT_EQ(pid_set_condition_report(layout, 3, 1, c), condition(3, 1, -2000, 5000, 10000));
  EXPECT_EQ(condition(3, 1, -2000, 5000, 10000),
            (Bytes{3, 3, 1, 0x30, 0xF8, 0x88, 0x13, 0x88, 0x13, 0x10, 0x27, 0x10, 0x27, 0}));
  // Out of range values are clamped to the fields' logical ranges.
  c.cp_offset = 20000;
  c.positive_saturation = -5;
  const Bytes clamped = pid_set_condition_report(layout, 3, 0, c);
  EXPECT_EQ(clamped[3], 0x10);  // 10000
  EXPECT_EQ(clamped[4], 0x27);
  EXPECT_EQ(clamped[9], 0);
  EXPECT_EQ(clamped[10], 0);
}

// A position device renders the loop's coupling as a spring centred where it
// gives the loop's force at the device's last position (plus a damper), so
// the stiffness holds between the device's updates.
TEST(HidPid, PositionDeviceRendersTheCouplingAsSpringAndDamper) {
  auto log = std::make_shared<FakeLog>();
  PidForceConfig config;
  config.full_scale_force = 3.0;
  config.control = ControlMode::Position;
  config.workspace_mm = 10;  // full deflection = 10 mm
  config.max_force_rate = 0;
  config.start_thread = false;
  config.clock = FakeClock::read;
  FakeClock::now = 1.0;
  HidPidDevice device(std::make_unique<FakeTransport>(log), layout_of(pid_joystick_with_conditions()), config);
  EXPECT_EQ(device.capabilities().control, ControlMode::Position);
  EXPECT_EQ(device.capabilities().input_dof, 2);
  device.service();  // set-up: constant forces on blocks 1, 2; spring 3, damper 4 (zero parameters)
  ASSERT_TRUE(device.renders_conditions());
  EXPECT_EQ(device.spring_block(), 3);
  EXPECT_EQ(device.damper_block(), 4);
  const auto setup = log->outputs();
  ASSERT_EQ(setup.size(), 2u + 4u + 2u + 4u);
  EXPECT_EQ(setup[6], (Bytes{2, 3, 5, 0xFF, 0xFF, 0, 0, 0, 0, 0xFF, 0, 0b011, 0, 0}));
  EXPECT_EQ(setup[7], (Bytes{2, 4, 6, 0xFF, 0xFF, 0, 0, 0, 0, 0xFF, 0, 0b011, 0, 0}));
  EXPECT_EQ(setup[8], condition(3, 0, 0, 0, 0));
  EXPECT_EQ(setup[11], condition(4, 1, 0, 0, 0));

  // The device at X = 16384 / 32767 of its range (5.0002 mm), Y = 0.
  log->inputs.push_back(Bytes{1, 0x00, 0x40, 0x00, 0x00});
  FakeClock::now = 1.004;
  device.service();
  const DeviceSample s = device.read(7.0);
  EXPECT_NEAR(s.pose.translation().x(), 10.0 * 16384 / 32767, 1e-12);
  EXPECT_DOUBLE_EQ(s.time, 7.0);  // the report arrived just now (clock unchanged since)
  EXPECT_FALSE(s.at_rest);
  log->sent.clear();
  Wrench w;
  w.force = Vec3(0.6, -0.3, 0);
  w.stiffness = 0.15;  // N/mm: 0.15 x 10 mm / 3 N = half the coefficient's range, 5000
  w.damping = 0.003;   // N s/mm: 0.01 of the range, 100
  device.write(w);
  device.service();
  // Spring centres: x + F / k = 0.50002 + 0.2 / 0.5 -> 9000; 0 - 0.1 / 0.5 -> -2000.
  Bytes damper_x = condition(4, 0, 0, 100, 10000), damper_y = condition(4, 1, 0, 100, 10000);
  EXPECT_EQ(log->outputs(), (std::vector<Bytes>{kEnableActuators, condition(3, 0, 9000, 5000, 10000), damper_x,
                                                condition(3, 1, -2000, 5000, 10000), damper_y, constant_force(1, 0),
                                                start_effect(1), constant_force(2, 0), start_effect(2),
                                                start_effect(3), start_effect(4)}));
  // The device moved to X = 0 (0.01 s later): the damper term enters the
  // centre, x + (F + b v) / k with v = -50 000 / 32767 ranges per second.
  log->sent.clear();
  log->inputs.push_back(Bytes{1, 0x00, 0x00, 0x00, 0x00});
  FakeClock::now = 1.014;
  device.service();
  const double v = (0.0 - 16384.0 / 32767.0) / 0.01;
  const int cp = static_cast<int>(std::lround((0.0 + (0.2 + 0.01 * v) / 0.5) * 10000));
  EXPECT_EQ(log->outputs(), (std::vector<Bytes>{condition(3, 0, cp, 5000, 10000)}));
  // Halt: Stop All once.
  log->sent.clear();
  device.halt();
  device.service();
  EXPECT_EQ(log->outputs(), (std::vector<Bytes>{kStopAll}));
}

// The rendered force moves towards the loop's at most max_force_rate N/s.
TEST(HidPid, ForceRateLimit) {
  auto log = std::make_shared<FakeLog>();
  PidForceConfig config;
  config.full_scale_force = 3.0;
  config.max_force_rate = 100;  // N/s: 0.4 N per 4 ms update
  config.start_thread = false;
  config.clock = FakeClock::read;
  FakeClock::now = 0;
  HidPidDevice device(std::make_unique<FakeTransport>(log), layout_of(pid_joystick_descriptor(false)), config);
  device.service();
  Wrench w;
  w.force = Vec3(1.5, 0, 0);
  device.write(w);
  std::vector<std::vector<Bytes>> passes;
  for (int i = 1; i <= 5; ++i) {
    log->sent.clear();
    FakeClock::now = 0.004 * i;
    device.service();
    passes.push_back(log->outputs());
  }
  EXPECT_EQ(passes[0], (std::vector<Bytes>{kEnableActuators, constant_force(1, 1333), start_effect(1),
                                           constant_force(2, 0), start_effect(2)}));  // 0.4 N
  EXPECT_EQ(passes[1], (std::vector<Bytes>{constant_force(1, 2667)}));  // 0.8 N
  EXPECT_EQ(passes[2], (std::vector<Bytes>{constant_force(1, 4000)}));  // 1.2 N
  EXPECT_EQ(passes[3], (std::vector<Bytes>{constant_force(1, 5000)}));  // 1.5 N reached
  EXPECT_TRUE(passes[4].empty());
  EXPECT_NEAR(device.rendered_force(0), 1.5, 1e-12);
  // Down again just as slowly, never a jump.
  w.force = Vec3(-1.5, 0, 0);
  device.write(w);
  log->sent.clear();
  FakeClock::now = 0.024;
  device.service();
  EXPECT_EQ(log->outputs(), (std::vector<Bytes>{constant_force(1, 3667)}));  // 1.1 N
}
