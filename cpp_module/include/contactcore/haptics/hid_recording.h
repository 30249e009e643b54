// Raw HID reports recorded with their arrival times (`contacts trial
// --record-hid FILE`) and read back for replay (`--device replay --hid-file
// FILE`), which feeds them through the same parser as the live device.
//
// File format (text, one item a line; '#' starts a comment):
//   contacts-hid-recording 1
//   device <spacemouse|hid-ff> <vendor hex> <product hex> <name...>
//   descriptor <hex bytes>          (hid-ff: the report descriptor, for its input layout)
//   <arrival s> <hex bytes>         (one report, report ID first)
//   <arrival s> unplug              (the device went away; the next report is a plug-in)
// Arrival times are seconds from the start of the recording, not decreasing.
#pragma once

#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

#include "contactcore/common/errors.h"

namespace contactcore::haptics {

struct RecordedReport {
  double time = 0;                  // s: arrival (on the loop's clock when replayed)
  std::vector<std::uint8_t> bytes;  // empty: an unplug (or the plug-in after one)
};

struct HidRecording {
  std::string kind = "spacemouse";  // "spacemouse" or "hid-ff"
  std::uint16_t vendor = 0, product = 0;
  std::string name;
  std::vector<std::uint8_t> descriptor;  // hid-ff
  std::vector<RecordedReport> reports;
};

// Collects reports from a device's reader thread (never the loop's: it
// locks and allocates). Times are taken relative to `origin` (steady seconds).
class HidRecorder {
 public:
  explicit HidRecorder(double origin);
  void set_device(const std::string& kind, std::uint16_t vendor, std::uint16_t product, const std::string& name,
                  std::vector<std::uint8_t> descriptor);
  void report(double arrival, const std::uint8_t* data, std::size_t size);
  void unplugged(double arrival);
  HidRecording recording() const;
  std::size_t size() const;

 private:
  double origin_;
  mutable std::mutex mutex_;
  HidRecording recording_;
};

Status write_hid_recording(const HidRecording& recording, const std::string& path);
// The recording in `path`; errors name the file and line.
Status read_hid_recording(const std::string& path, HidRecording& recording);

}  // namespace contactcore::haptics
