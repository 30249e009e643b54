#include "contactcore/haptics/hid_pid_device.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>

#include <hidapi/hidapi.h>

namespace contactcore::haptics {

HidPidDevice::HidPidDevice(std::unique_ptr<HidTransport> transport, PidLayout layout, PidForceConfig config)
    : transport_(std::move(transport)), layout_(std::move(layout)), config_(std::move(config)) {
  caps_.name = config_.name;
  int inputs = 0;
  for (const auto& a : layout_.input_axes) inputs += a.found() ? 1 : 0;
  caps_.input_dof = inputs;
  caps_.control = ControlMode::Rate;
  caps_.force_output = true;
  caps_.torque_output = false;
  caps_.max_force = config_.full_scale_force;
  caps_.max_stiffness = config_.max_stiffness;
  caps_.max_damping = config_.max_damping;
  caps_.hid_force_feedback = true;
  std::size_t largest = 64;
  for (const HidField& f : layout_.descriptor.fields)
    if (f.kind == HidReportKind::Input)
      largest = std::max(largest, layout_.descriptor.report_size(HidReportKind::Input, f.report_id));
  input_.assign(largest, 0);
  description_ = config_.name;
  connected_ = transport_ != nullptr;
  if (config_.start_thread) io_ = std::thread([this] { run(); });
}

HidPidDevice::~HidPidDevice() {
  stop_ = true;
  if (io_.joinable()) io_.join();
  if (transport_ && initialised_) {
    // Leave the device silent.
    send(pid_device_control_report(layout_, layout_.stop_all), HidReportKind::Output);
    if (layout_.disable_actuators.found())
      send(pid_device_control_report(layout_, layout_.disable_actuators), HidReportKind::Output);
  }
}

std::string HidPidDevice::description() const {
  std::lock_guard<std::mutex> lock(description_mutex_);
  return description_;
}

DeviceSample HidPidDevice::read(double now) noexcept {
  DeviceSample s;
  s.connected = connected_.load(std::memory_order_acquire);
  for (int i = 0; i < 6; ++i) s.axes[i] = s.connected ? axes_[i].load(std::memory_order_relaxed) : 0.0;
  // Like a SpaceMouse, a resting joystick sends nothing: its last state holds.
  s.time = now;
  return s;
}

void HidPidDevice::write(const Wrench& wrench) noexcept {
  force_sequence_.fetch_add(1, std::memory_order_acq_rel);  // odd: writing
  for (int i = 0; i < 3; ++i) force_[i].store(wrench.force[i], std::memory_order_relaxed);
  force_sequence_.fetch_add(1, std::memory_order_acq_rel);
  halted_.store(false, std::memory_order_release);
}

void HidPidDevice::halt() noexcept {
  halted_.store(true, std::memory_order_release);
  force_sequence_.fetch_add(1, std::memory_order_acq_rel);
  for (int i = 0; i < 3; ++i) force_[i].store(0.0, std::memory_order_relaxed);
  force_sequence_.fetch_add(1, std::memory_order_acq_rel);
}

bool HidPidDevice::send(const std::vector<std::uint8_t>& report, HidReportKind kind) {
  if (!transport_ || report.empty()) return false;
  const bool ok = kind == HidReportKind::Feature ? transport_->send_feature(report.data(), report.size())
                                                 : transport_->write_output(report.data(), report.size());
  if (!ok) {
    // Unplugged: the loop sees "not connected" and its watchdog zeroes the force.
    connected_ = false;
    initialised_ = playing_ = false;
    transport_.reset();
    std::lock_guard<std::mutex> lock(description_mutex_);
    description_ = config_.name + ": unplugged";
  }
  return ok;
}

bool HidPidDevice::initialise() {
  using K = HidReportKind;
  if (layout_.enable_actuators.found() && !send(pid_device_control_report(layout_, layout_.enable_actuators), K::Output))
    return false;
  if (layout_.device_gain.present && !send(pid_device_gain_report(layout_, config_.gain), K::Output)) return false;
  for (int a = 0; a < layout_.axis_count(); ++a) {
    int block = a + 1;
    if (layout_.create_new_effect.present && layout_.create_constant.found() && layout_.block_load.present &&
        layout_.load_block.found()) {
      // The device allocates the block: Create New Effect, then read Block Load.
      if (!send(pid_create_effect_report(layout_), K::Feature)) return false;
      auto load = pid_blank_report(layout_, layout_.block_load);
      const int n = transport_->get_feature(load.data(), load.size());
      if (n <= 0) return false;
      const bool with_id = layout_.descriptor.uses_report_ids;
      if (layout_.load_success.found() &&
          get_field(load.data(), static_cast<std::size_t>(n), with_id, layout_.descriptor.fields[layout_.load_success.field], 0) !=
              layout_.load_success.value) {
        std::lock_guard<std::mutex> lock(description_mutex_);
        description_ = config_.name + ": the device has no free effect block";
        return false;
      }
      block = get_field(load.data(), static_cast<std::size_t>(n), with_id, layout_.field(layout_.load_block),
                        layout_.load_block.index);
    }
    blocks_[a] = block;
    if (!send(pid_set_effect_report(layout_, block, a), K::Output)) return false;
    if (!send(pid_constant_force_report(layout_, block, 0), K::Output)) return false;
    sent_[a] = 0;
  }
  initialised_ = true;
  playing_ = false;
  return true;
}

void HidPidDevice::service() {
  using K = HidReportKind;
  if (!transport_) {
    if (config_.reopen) transport_ = config_.reopen();
    if (!transport_) return;
    connected_ = true;
    std::lock_guard<std::mutex> lock(description_mutex_);
    description_ = config_.name;
  }
  // Input: drain what waits, keep the last axes.
  for (int guard = 0; guard < 64; ++guard) {
    const int n = transport_->read_input(input_.data(), input_.size());
    if (n < 0) {
      connected_ = false;
      initialised_ = playing_ = false;
      transport_.reset();
      return;
    }
    if (n == 0) break;
    const bool with_id = layout_.descriptor.uses_report_ids;
    for (int a = 0; a < 6; ++a) {
      const HidFieldRef& ref = layout_.input_axes[a];
      if (!ref.found()) continue;
      const HidField& f = layout_.field(ref);
      if (with_id && input_[0] != f.report_id) continue;
      const double v = get_field(input_.data(), static_cast<std::size_t>(n), with_id, f, ref.index);
      const double mid = 0.5 * (f.logical_min + static_cast<double>(f.logical_max));
      const double half = 0.5 * (static_cast<double>(f.logical_max) - f.logical_min);
      axes_[a].store(half > 0 ? std::clamp((v - mid) / half, -1.0, 1.0) : 0.0, std::memory_order_relaxed);
    }
  }
  if (!initialised_ && !initialise()) return;

  if (halted_.load(std::memory_order_acquire)) {
    if (playing_) {
      send(pid_device_control_report(layout_, layout_.stop_all), K::Output);
      playing_ = false;
      sent_.fill(0);
    }
    return;
  }
  Vec3 force;
  for (;;) {
    const std::uint32_t before = force_sequence_.load(std::memory_order_acquire);
    if (before & 1) continue;
    for (int i = 0; i < 3; ++i) force[i] = force_[i].load(std::memory_order_relaxed);
    std::atomic_thread_fence(std::memory_order_acquire);
    if (force_sequence_.load(std::memory_order_acquire) == before) break;
  }
  const bool restart = !playing_;
  if (restart && layout_.enable_actuators.found() &&
      !send(pid_device_control_report(layout_, layout_.enable_actuators), K::Output))
    return;
  for (int a = 0; a < layout_.axis_count(); ++a) {
    const std::int32_t m = pid_magnitude(layout_, force.dot(config_.axis_directions[a]), config_.full_scale_force);
    if (restart || m != sent_[a]) {
      if (!send(pid_constant_force_report(layout_, blocks_[a], m), K::Output)) return;
      sent_[a] = m;
    }
    if (restart && !send(pid_effect_operation_report(layout_, blocks_[a], true), K::Output)) return;
  }
  playing_ = true;
}

void HidPidDevice::run() {
  const auto period = std::chrono::duration<double>(1.0 / std::max(1.0, config_.update_rate_hz));
  auto next = std::chrono::steady_clock::now();
  while (!stop_.load()) {
    service();
    next += std::chrono::duration_cast<std::chrono::steady_clock::duration>(period);
    const auto now = std::chrono::steady_clock::now();
    if (now >= next) next = now;
    else std::this_thread::sleep_until(next);
  }
}

// ---- hidapi

namespace {

class HidapiTransport : public HidTransport {
 public:
  explicit HidapiTransport(hid_device* handle) : handle_(handle) { hid_set_nonblocking(handle_, 1); }
  ~HidapiTransport() override { hid_close(handle_); }
  bool write_output(const std::uint8_t* report, std::size_t size) override {
    return hid_write(handle_, report, size) >= 0;
  }
  bool send_feature(const std::uint8_t* report, std::size_t size) override {
    return hid_send_feature_report(handle_, report, size) >= 0;
  }
  int get_feature(std::uint8_t* report, std::size_t size) override {
    return hid_get_feature_report(handle_, report, size);
  }
  int read_input(std::uint8_t* buffer, std::size_t size) override { return hid_read(handle_, buffer, size); }

 private:
  hid_device* handle_;
};

}  // namespace

std::vector<std::uint8_t> hidraw_report_descriptor(const std::string& path) {
  const std::string prefix = "/dev/";
  if (path.rfind(prefix, 0) != 0) return {};
  std::ifstream in("/sys/class/hidraw/" + path.substr(prefix.size()) + "/device/report_descriptor", std::ios::binary);
  if (!in) return {};
  return std::vector<std::uint8_t>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::vector<HidPidFound> enumerate_hid_pid_devices() {
  std::vector<HidPidFound> found;
  if (hid_init() != 0) return found;
  hid_device_info* list = hid_enumerate(0, 0);
  for (hid_device_info* d = list; d; d = d->next) {
    if (!d->path) continue;
    const auto descriptor = hidraw_report_descriptor(d->path);
    PidLayout layout;
    if (descriptor.empty() || !find_pid_layout(descriptor.data(), descriptor.size(), layout, nullptr)) continue;
    HidPidFound f;
    f.path = d->path;
    f.vendor = d->vendor_id;
    f.product = d->product_id;
    f.axes = layout.axis_count();
    if (d->product_string) {
      const std::wstring w = d->product_string;
      f.name.assign(w.begin(), w.end());  // product names are ASCII in practice
    }
    if (f.name.empty()) f.name = "HID force-feedback device";
    found.push_back(std::move(f));
  }
  hid_free_enumeration(list);
  return found;
}

std::unique_ptr<HidTransport> open_hidapi_transport(const std::string& path, std::string* why) {
  if (hid_init() != 0) {
    if (why) *why = "hidapi could not start";
    return nullptr;
  }
  hid_device* handle = hid_open_path(path.c_str());
  if (!handle) {
    if (why) *why = "cannot open " + path + " (permissions: add a udev rule)";
    return nullptr;
  }
  return std::make_unique<HidapiTransport>(handle);
}

}  // namespace contactcore::haptics
