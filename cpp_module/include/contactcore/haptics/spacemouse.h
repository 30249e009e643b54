// The 3Dconnexion SpaceMouse family over HID (what hidapi sees): the report
// parser, the per-model axis table (signs and swaps as spacenavd keeps them),
// a hidapi back-end with hot-plug, and a replay of recorded reports.
//
// Report formats (report ID in byte 0, int16 little-endian values):
//  - older devices (vendor 0x046d): report 1 = Tx Ty Tz (7 bytes), report 2 =
//    Rx Ry Rz (7 bytes);
//  - newer devices (vendor 0x256f): report 1 = Tx Ty Tz Rx Ry Rz (13 bytes);
//  - both: report 3 = button bitmap (little-endian, 1 to 4 bytes).
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "contactcore/haptics/device.h"
#include "contactcore/haptics/hid_pid_device.h"
#include "contactcore/haptics/hid_recording.h"
#include "contactcore/haptics/triple_buffer.h"

namespace contactcore::haptics {

enum class ReportFormat {
  TwoReports,  // translation in report 1, rotation in report 2
  SixAxes,     // all six axes in report 1
};

struct SpaceMouseModel {
  std::uint16_t vendor = 0, product = 0;
  const char* name = "";
  ReportFormat format = ReportFormat::TwoReports;
  bool swap_yz = false;    // spacenavd DF_SWAPYZ: HID y/z are screen z/y
  bool invert_yz = false;  // spacenavd DF_INVYZ
  double full_scale = 350; // raw value of a full deflection
};

// The known 6-DOF models; nullptr for anything else (CadMouse and other
// non-6-DOF 3Dconnexion products included). An unknown product of vendor
// 0x046d or 0x256f gets a generic entry from `generic_model`.
const SpaceMouseModel* find_model(std::uint16_t vendor, std::uint16_t product);
bool is_spacemouse_vendor(std::uint16_t vendor);
bool is_excluded_product(std::uint16_t vendor, std::uint16_t product);  // CadMouse, ...
SpaceMouseModel generic_model(std::uint16_t vendor, std::uint16_t product);
const std::vector<SpaceMouseModel>& known_models();

// Parsed state: raw values as sent, and axes in spacenavd's frame (x right,
// y up, z towards the user; rotations about those) normalised to [-1, 1].
struct SpaceMouseState {
  std::int16_t raw[6] = {0, 0, 0, 0, 0, 0};
  Vec6 axes = Vec6::Zero();
  std::uint32_t buttons = 0;
  int reports = 0;  // reports understood so far
};

// Applies one input report (report ID first). Returns false for a report it
// does not understand (too short, unknown ID), leaving `state` unchanged.
bool parse_report(const std::uint8_t* data, std::size_t size, const SpaceMouseModel& model,
                  SpaceMouseState& state);

// True when a HID report descriptor declares the PID (force feedback) usage
// page 0x0F: such a device can play HID effects (constant force, spring).
bool descriptor_has_pid_page(const std::uint8_t* descriptor, std::size_t size);

// A SpaceMouse through hidapi. A reader thread polls the device (reports come
// at 60-250 Hz) and holds the last sample for the loop; when the device goes
// away it is closed and looked for again every `rescan_period` seconds
// (hot-plug). Never throws: with no device, read() says not connected.
class HidSpaceMouse : public Device {
 public:
  // `recorder`: every raw report (and unplug) with its arrival time, when given.
  explicit HidSpaceMouse(std::shared_ptr<HidRecorder> recorder = nullptr);
  ~HidSpaceMouse() override;
  const DeviceCapabilities& capabilities() const override { return caps_; }
  DeviceSample read(double now) noexcept override;
  void write(const Wrench&) noexcept override {}  // no force output (rate device)
  bool connected() const { return connected_.load(); }
  std::string description() const;  // model and path, or why nothing is open

  // The 6-DOF devices hidapi lists now (name, vendor, product, path).
  struct Found {
    std::string name, path;
    std::uint16_t vendor = 0, product = 0;
  };
  static std::vector<Found> enumerate();

 private:
  void run();
  DeviceCapabilities caps_;
  std::thread reader_;
  std::atomic<bool> stop_{false};
  std::atomic<bool> connected_{false};
  mutable std::mutex description_mutex_;
  std::string description_;
  std::shared_ptr<HidRecorder> recorder_;
  // Last state, written by the reader thread, read by the loop: a triple
  // buffer, so the loop never retries (a seqlock reader spins while the
  // writer is preempted mid-write).
  struct Reading {
    Vec6 axes = Vec6::Zero();
    std::uint32_t buttons = 0;
    double arrival = 0;  // steady_seconds() when the report arrived
  };
  TripleBuffer<Reading> readings_;
};

// Recorded reports (hid_recording.h) played back on the loop's clock through
// the same parser as the live device: (time, bytes) in order; an empty report
// marks an unplug, the next one a plug-in. A report's time is its arrival:
// the stale watchdog sees the recorded gaps.
class ReplayDevice : public Device {
 public:
  ReplayDevice(SpaceMouseModel model, std::vector<RecordedReport> reports);
  // A HID PID device's input reports, through its descriptor's layout (the
  // parser HidPidDevice uses), mapped as `config` says (rate or position).
  ReplayDevice(PidLayout layout, const PidForceConfig& config, std::vector<RecordedReport> reports);
  const DeviceCapabilities& capabilities() const override { return caps_; }
  DeviceSample read(double now) noexcept override;
  void write(const Wrench&) noexcept override {}
  const SpaceMouseState& state() const { return state_; }

 private:
  DeviceCapabilities caps_;
  SpaceMouseModel model_;
  bool pid_ = false;
  PidLayout layout_;
  PidForceConfig pid_config_;
  Vec6 pid_axes_ = Vec6::Zero(), pid_velocity_ = Vec6::Zero();
  std::vector<RecordedReport> reports_;
  std::size_t next_ = 0;
  SpaceMouseState state_;
  bool connected_ = true;
  double last_report_ = 0;
  bool reported_ = false;
};

// Capabilities of a SpaceMouse: 6 DOF input, rate control, no force output.
DeviceCapabilities spacemouse_capabilities(const std::string& name);

// Seconds on CLOCK_MONOTONIC (the loop's clock outside lockstep tests).
double steady_seconds();

}  // namespace contactcore::haptics
