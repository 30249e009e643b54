// Device selection for trials and the panel, in one place: which device a
// name stands for (sim, sim-hid-ff, spacemouse, hid-ff, replay), opening it,
// recording its raw reports, and what to say when it is not there (the HID
// devices seen, possibly none). Errors as values: no device is a Status.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "contactcore/common/errors.h"
#include "contactcore/haptics/device.h"
#include "contactcore/haptics/hid_pid_device.h"
#include "contactcore/haptics/hid_recording.h"
#include "contactcore/haptics/simulated.h"

namespace contactcore::haptics {

// Every HID device hidapi lists (what "no device" reports).
struct HidDeviceSeen {
  std::string path, manufacturer, product;
  std::uint16_t vendor = 0, product_id = 0;
  std::uint16_t usage_page = 0, usage = 0;
};
std::vector<HidDeviceSeen> enumerate_hid_devices();
// "vendor:product name (path)" per device, or "no HID devices seen".
std::string describe_devices_seen(const std::vector<HidDeviceSeen>& seen);

struct DeviceRequest {
  // sim: the simulated hand (6 DOF, scripted or live); sim-hid-ff: the
  // simulated hand on a simulated HID PID device (the output path of real
  // force-feedback hardware); spacemouse, hid-ff: hardware through hidapi;
  // replay: a recording (HidRecording) through the live device's parser.
  std::string kind = "sim";
  Vec3 centre = Vec3::Zero();
  Pose start = Pose::Identity();
  HandScript script;
  HandParameters hand;
  HidRecording replay;              // kind "replay"
  bool record = false;              // spacemouse, hid-ff: keep the raw reports
  bool fall_back_to_simulated = false;  // no hardware: the simulated hand, and the message says why
  double first_scan_wait = 0.1;     // s for the SpaceMouse reader's first scan
  PidForceConfig pid;               // hid-ff, sim-hid-ff
};

struct DeviceResult {
  // InvalidInput with device_missing (and `seen`) when the hardware asked
  // for is not there; InvalidArgument for an unknown kind; InvalidInput for a bad replay.
  Status status;
  bool device_missing = false;
  std::unique_ptr<Device> device;
  SimulatedHand* hand = nullptr;    // the simulated hand, when one drives the trial
  std::shared_ptr<HidRecorder> recorder;
  std::string message;              // what was opened, or why not
  std::vector<HidDeviceSeen> seen;  // filled when the hardware asked for is missing
  bool simulated = false;
  bool fell_back = false;
};

DeviceResult open_device(const DeviceRequest& request);

}  // namespace contactcore::haptics
