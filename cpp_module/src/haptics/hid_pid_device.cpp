#include "contactcore/haptics/hid_pid_device.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>

#include <hidapi/hidapi.h>

#include "contactcore/haptics/spacemouse.h"

namespace contactcore::haptics {

HidPidDevice::HidPidDevice(std::unique_ptr<HidTransport> transport, PidLayout layout, PidForceConfig config)
    : transport_(std::move(transport)), layout_(std::move(layout)), config_(std::move(config)) {
  caps_.name = config_.name;
  int inputs = 0;
  for (const auto& a : layout_.input_axes) inputs += a.found() ? 1 : 0;
  caps_.input_dof = inputs;
  caps_.control = config_.control;
  if (config_.control == ControlMode::Position) {
    caps_.input_dof = 0;
    for (int a = 0; a < 3; ++a) caps_.input_dof += layout_.input_axes[a].found() ? 1 : 0;
    caps_.workspace_radius = config_.workspace_mm;
  }
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
  reading_.arrival = clock();
  readings_.write(reading_);
  if (config_.recorder)
    config_.recorder->set_device("hid-ff", 0, 0, config_.name, {});  // vendor/product set by the factory
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

double HidPidDevice::clock() const { return config_.clock ? config_.clock() : steady_seconds(); }

DeviceSample HidPidDevice::read(double now) noexcept {
  DeviceSample s;
  s.connected = connected_.load(std::memory_order_acquire);
  const Reading& r = readings_.read();  // wait-free on the loop's side
  const Vec6 axes = s.connected ? r.axes : Vec6::Zero();
  // The last report's arrival on the loop's clock: the stale watchdog's input.
  s.time = now - std::max(0.0, clock() - r.arrival);
  if (config_.control == ControlMode::Position) {
    // An arm is never "at rest": silence while a force is rendered is stale.
    for (int a = 0; a < 3; ++a) {
      s.pose.translation() += axes[a] * config_.workspace_mm * config_.axis_directions[a];
      s.velocity.head<3>() += r.velocity[a] * config_.workspace_mm * config_.axis_directions[a];
    }
  } else {
    s.axes = axes;
    s.at_rest = axes.isZero(0.0);  // a joystick let go falls silent
  }
  return s;
}

void HidPidDevice::write(const Wrench& wrench) noexcept {
  Command c;
  c.force = wrench.force;
  c.stiffness = wrench.stiffness;
  c.damping = wrench.damping;
  commands_.write(c);
  halted_.store(false, std::memory_order_release);
}

void HidPidDevice::halt() noexcept {
  commands_.write(Command{});
  halted_.store(true, std::memory_order_release);
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

bool HidPidDevice::allocate(const HidSelector& create_type, int fallback, int& block) {
  block = fallback;
  if (!(layout_.create_new_effect.present && create_type.found() && layout_.block_load.present &&
        layout_.load_block.found()))
    return true;
  // The device allocates the block: Create New Effect, then read Block Load.
  if (!send(pid_create_effect_report(layout_, create_type), HidReportKind::Feature)) return false;
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
  return true;
}

bool HidPidDevice::initialise() {
  using K = HidReportKind;
  if (layout_.enable_actuators.found() && !send(pid_device_control_report(layout_, layout_.enable_actuators), K::Output))
    return false;
  if (layout_.device_gain.present && !send(pid_device_gain_report(layout_, config_.gain), K::Output)) return false;
  for (int a = 0; a < layout_.axis_count(); ++a) {
    int block = a + 1;
    if (!allocate(layout_.create_constant, a + 1, block)) return false;
    blocks_[a] = block;
    if (!send(pid_set_effect_report(layout_, block, a), K::Output)) return false;
    if (!send(pid_constant_force_report(layout_, block, 0), K::Output)) return false;
    sent_[a] = 0;
  }
  conditions_ = config_.control == ControlMode::Position && config_.use_conditions && layout_.has_conditions();
  if (conditions_) {
    // A spring and a damper over every axis, silent until the first force.
    const int next = layout_.axis_count() + 1;
    if (!allocate(layout_.create_spring, next, spring_block_)) return false;
    if (!allocate(layout_.create_damper, next + 1, damper_block_)) return false;
    if (!send(pid_set_condition_effect_report(layout_, spring_block_, layout_.effect_type_spring), K::Output)) return false;
    if (!send(pid_set_condition_effect_report(layout_, damper_block_, layout_.effect_type_damper), K::Output)) return false;
    for (int a = 0; a < layout_.axis_count(); ++a) {
      sent_spring_[a] = sent_damper_[a] = PidCondition{};
      if (!send(pid_set_condition_report(layout_, spring_block_, a, PidCondition{}), K::Output)) return false;
      if (!send(pid_set_condition_report(layout_, damper_block_, a, PidCondition{}), K::Output)) return false;
    }
  }
  rendered_.fill(0.0);
  initialised_ = true;
  playing_ = false;
  return true;
}

bool HidPidDevice::render_conditions(double stiffness, double damping, bool restart) {
  using K = HidReportKind;
  // Logical units: positions normalised to [-1, 1] (+-workspace), a
  // coefficient of full scale gives the full-scale force at a full
  // normalised deflection (or speed of one workspace per second).
  const double to_fraction_k = config_.workspace_mm / config_.full_scale_force;
  const double kf = std::clamp(stiffness * to_fraction_k, 0.0, 1.0);
  const double bf = std::clamp(damping * to_fraction_k, 0.0, 1.0);
  const std::int32_t k = pid_scaled(layout_, layout_.positive_coefficient, kf);
  const std::int32_t b = pid_scaled(layout_, layout_.positive_coefficient, bf);
  const std::int32_t saturation = pid_scaled(layout_, layout_.positive_saturation, 1.0);
  for (int a = 0; a < layout_.axis_count() && a < 3; ++a) {
    const double x = reading_.axes[a], v = reading_.velocity[a];
    // The spring (+ the damper at the device's speed) gives the rate-limited
    // force at the device's last position: centre = x + (F + b v) / k.
    const double f = rendered_[a] / config_.full_scale_force;  // fraction of full scale
    PidCondition spring;
    if (k > 0) {
      const double k_used = static_cast<double>(k) / pid_scaled(layout_, layout_.positive_coefficient, 1.0);
      const double b_used = static_cast<double>(b) / pid_scaled(layout_, layout_.positive_coefficient, 1.0);
      spring.cp_offset = pid_scaled(layout_, layout_.cp_offset, x + (f + b_used * v) / k_used);
      spring.positive_coefficient = spring.negative_coefficient = k;
      spring.positive_saturation = spring.negative_saturation = saturation;
    }
    PidCondition damper;
    damper.positive_coefficient = damper.negative_coefficient = k > 0 ? b : 0;
    damper.positive_saturation = damper.negative_saturation = saturation;
    if (restart || spring != sent_spring_[a]) {
      if (!send(pid_set_condition_report(layout_, spring_block_, a, spring), K::Output)) return false;
      sent_spring_[a] = spring;
    }
    if (restart || damper != sent_damper_[a]) {
      if (!send(pid_set_condition_report(layout_, damper_block_, a, damper), K::Output)) return false;
      sent_damper_[a] = damper;
    }
  }
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
  // Input: drain what waits, keep the last axes and when they arrived.
  for (int guard = 0; guard < 64; ++guard) {
    const int n = transport_->read_input(input_.data(), input_.size());
    if (n < 0) {
      connected_ = false;
      initialised_ = playing_ = false;
      transport_.reset();
      if (config_.recorder) config_.recorder->unplugged(clock());
      return;
    }
    if (n == 0) break;
    const double arrival = clock();
    if (config_.recorder) config_.recorder->report(arrival, input_.data(), static_cast<std::size_t>(n));
    Vec6 axes = reading_.axes;
    if (parse_pid_input(layout_, input_.data(), static_cast<std::size_t>(n), axes)) {
      const double dt = arrival - reading_.arrival;
      if (reading_.reported && dt > 1e-6) reading_.velocity = (axes - reading_.axes) / dt;
      reading_.reported = true;
      reading_.axes = axes;
      reading_.arrival = arrival;
      readings_.write(reading_);
    }
  }
  if (!initialised_ && !initialise()) return;

  const double now = clock();
  // HID devices report on change: a device silent for a while is not moving.
  if (now - reading_.arrival > 0.05 && !reading_.velocity.isZero(0.0)) {
    reading_.velocity.setZero();
    readings_.write(reading_);
  }
  const double dt = last_service_ < 0 ? 0.0 : std::max(0.0, now - last_service_);
  last_service_ = now;
  if (halted_.load(std::memory_order_acquire)) {
    if (playing_) {
      send(pid_device_control_report(layout_, layout_.stop_all), K::Output);
      playing_ = false;
      sent_.fill(0);
    }
    rendered_.fill(0.0);
    return;
  }
  const Command command = commands_.read();
  const bool restart = !playing_;
  if (restart && layout_.enable_actuators.found() &&
      !send(pid_device_control_report(layout_, layout_.enable_actuators), K::Output))
    return;
  // The force-rate limit: each axis moves towards the loop's force by at
  // most max_force_rate * dt (the device's own updates are the steps).
  const double step = config_.max_force_rate > 0 ? config_.max_force_rate * dt : 1e300;
  for (int a = 0; a < layout_.axis_count(); ++a) {
    const double wanted = command.force.dot(config_.axis_directions[a]);
    rendered_[a] += std::clamp(wanted - rendered_[a], -step, step);
  }
  const bool springs = conditions_ && command.stiffness > 0;
  if (conditions_ && !render_conditions(springs ? command.stiffness : 0.0, command.damping, restart))
    return;
  for (int a = 0; a < layout_.axis_count(); ++a) {
    // With a spring rendering the force, the constant force stays at zero.
    const std::int32_t m = springs ? 0 : pid_magnitude(layout_, rendered_[a], config_.full_scale_force);
    if (restart || m != sent_[a]) {
      if (!send(pid_constant_force_report(layout_, blocks_[a], m), K::Output)) return;
      sent_[a] = m;
    }
    if (restart && !send(pid_effect_operation_report(layout_, blocks_[a], true), K::Output)) return;
  }
  if (restart && conditions_) {
    if (!send(pid_effect_operation_report(layout_, spring_block_, true), K::Output)) return;
    if (!send(pid_effect_operation_report(layout_, damper_block_, true), K::Output)) return;
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
