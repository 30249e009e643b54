#include "contactcore/haptics/device_factory.h"

#include <chrono>
#include <cstdio>
#include <thread>

#include <hidapi/hidapi.h>

#include "contactcore/haptics/simulated_pid.h"
#include "contactcore/haptics/spacemouse.h"

namespace contactcore::haptics {

namespace {

std::string narrow(const wchar_t* text) {
  std::string out;
  for (; text && *text; ++text) out.push_back(*text < 128 ? static_cast<char>(*text) : '?');
  return out;
}

DeviceResult unavailable(const std::string& what) {
  DeviceResult r;
  r.seen = enumerate_hid_devices();
  r.status = Status::failure(StatusCode::InvalidInput, what + "; HID devices seen: " + describe_devices_seen(r.seen));
  r.device_missing = true;
  r.message = what;
  return r;
}

void use_simulated_hand(const DeviceRequest& q, DeviceResult& r) {
  auto hand = std::make_unique<SimulatedHand>(q.script, q.hand, q.centre, q.start);
  r.hand = hand.get();
  r.device = std::move(hand);
  r.simulated = true;
}

}  // namespace

std::vector<HidDeviceSeen> enumerate_hid_devices() {
  std::vector<HidDeviceSeen> seen;
  if (hid_init() != 0) return seen;
  hid_device_info* list = hid_enumerate(0, 0);
  for (hid_device_info* d = list; d; d = d->next) {
    HidDeviceSeen s;
    s.path = d->path ? d->path : "";
    s.manufacturer = narrow(d->manufacturer_string);
    s.product = narrow(d->product_string);
    s.vendor = d->vendor_id;
    s.product_id = d->product_id;
    s.usage_page = d->usage_page;
    s.usage = d->usage;
    seen.push_back(std::move(s));
  }
  hid_free_enumeration(list);
  return seen;
}

std::string describe_devices_seen(const std::vector<HidDeviceSeen>& seen) {
  if (seen.empty()) return "no HID devices seen";
  std::string out;
  char ids[16];
  for (const HidDeviceSeen& s : seen) {
    std::snprintf(ids, sizeof ids, "%04x:%04x", s.vendor, s.product_id);
    if (!out.empty()) out += "; ";
    out += ids;
    const std::string name = (s.manufacturer + " " + s.product);
    if (name != " ") out += " " + name;
    out += " (" + s.path + ")";
  }
  return out;
}

DeviceResult open_device(const DeviceRequest& q) {
  DeviceResult r;
  if (q.kind == "sim") {
    use_simulated_hand(q, r);
    r.message = "Simulated hand.";
  } else if (q.kind == "sim-hid-ff") {
    auto device = std::make_unique<SimulatedPidDevice>(q.script, q.hand, q.centre, q.start, q.pid);
    r.hand = &device->hand();
    r.device = std::move(device);
    r.simulated = true;
    r.message = "Simulated hand on a HID force-feedback (PID) device.";
  } else if (q.kind == "spacemouse") {
    if (q.record) r.recorder = std::make_shared<HidRecorder>(steady_seconds());
    auto mouse = std::make_unique<HidSpaceMouse>(r.recorder);
    // The reader thread needs a moment for its first scan.
    std::this_thread::sleep_for(std::chrono::duration<double>(q.first_scan_wait));
    if (mouse->connected()) {
      r.message = mouse->description();
      r.device = std::move(mouse);
    } else {
      const std::string why = "no SpaceMouse (" + mouse->description() + ")";
      if (!q.fall_back_to_simulated) return unavailable(why);
      r.recorder.reset();
      use_simulated_hand(q, r);
      r.fell_back = true;
      r.message = "No SpaceMouse found (" + mouse->description() + "): using the simulated hand.";
    }
  } else if (q.kind == "hid-ff") {
    // The first HID device whose descriptor offers PID constant force.
    const auto found = enumerate_hid_pid_devices();
    std::string why = "no HID device offers force feedback (PID page)";
    if (!found.empty()) {
      auto transport = open_hidapi_transport(found.front().path, &why);
      PidLayout layout;
      const auto descriptor = hidraw_report_descriptor(found.front().path);
      if (transport && find_pid_layout(descriptor.data(), descriptor.size(), layout, &why)) {
        PidForceConfig pid = q.pid;
        pid.name = found.front().name;
        const std::string path = found.front().path;
        pid.reopen = [path] { return open_hidapi_transport(path, nullptr); };
        if (q.record) {
          r.recorder = std::make_shared<HidRecorder>(steady_seconds());
          pid.recorder = r.recorder;
        }
        r.device = std::make_unique<HidPidDevice>(std::move(transport), std::move(layout), pid);
        if (r.recorder)
          r.recorder->set_device("hid-ff", found.front().vendor, found.front().product, found.front().name, descriptor);
        r.message = found.front().name + " at " + path + " (HID force feedback)";
      }
    }
    if (!r.device) {
      if (!q.fall_back_to_simulated) return unavailable(why);
      use_simulated_hand(q, r);
      r.fell_back = true;
      r.message = "No force-feedback device (" + why + "): using the simulated hand.";
    }
  } else if (q.kind == "replay") {
    const HidRecording& rec = q.replay;
    if (rec.kind == "spacemouse") {
      const SpaceMouseModel* model = find_model(rec.vendor, rec.product);
      r.device = std::make_unique<ReplayDevice>(model ? *model : generic_model(rec.vendor, rec.product), rec.reports);
    } else if (rec.kind == "hid-ff") {
      PidLayout layout;
      std::string why;
      if (!find_pid_layout(rec.descriptor.data(), rec.descriptor.size(), layout, &why)) {
        r.status = Status::failure(StatusCode::InvalidInput, "the recording's descriptor: " + why);
        return r;
      }
      r.device = std::make_unique<ReplayDevice>(std::move(layout), q.pid, rec.reports);
    } else {
      r.status = Status::failure(StatusCode::InvalidInput, "a recording of an unknown device kind '" + rec.kind + "'");
      return r;
    }
    r.message = "Replaying " + std::to_string(rec.reports.size()) + " recorded reports of " +
                (rec.name.empty() ? rec.kind : rec.name) + ".";
  } else {
    r.status = Status::failure(StatusCode::InvalidArgument,
                               "unknown device '" + q.kind + "' (sim, sim-hid-ff, spacemouse, hid-ff, replay)");
    return r;
  }
  r.status = Status::success();
  return r;
}

}  // namespace contactcore::haptics
