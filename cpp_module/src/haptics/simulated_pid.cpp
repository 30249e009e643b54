#include "contactcore/haptics/simulated_pid.h"

#include <algorithm>
#include <cmath>

namespace contactcore::haptics {

const std::vector<std::uint8_t>& simulated_pid_descriptor() {
  // Written after the HID PID 1.0 specification (usb.org, 1999), usage IDs
  // from its table 2; the structure of its section 5 reports.
  static const std::vector<std::uint8_t> d = {
      0x05, 0x01, 0x09, 0x04, 0xA1, 0x01,  // Generic Desktop, Joystick, Collection (Application)
      0x85, 0x01,                          //   Report ID (1): input X Y Z
      0x09, 0x30, 0x09, 0x31, 0x09, 0x32, 0x16, 0x01, 0x80, 0x26, 0xFF, 0x7F, 0x75, 0x10, 0x95, 0x03, 0x81, 0x02,
      0x05, 0x0F,                          //   Usage Page (PID)
      // Set Effect (2): block, type (constant, spring, damper), duration, gain, axes X Y Z, direction enable
      0x09, 0x21, 0xA1, 0x02, 0x85, 0x02,
      0x09, 0x22, 0x15, 0x01, 0x25, 0x28, 0x75, 0x08, 0x95, 0x01, 0x91, 0x02,
      0x09, 0x25, 0xA1, 0x02, 0x09, 0x26, 0x09, 0x40, 0x09, 0x41, 0x15, 0x01, 0x25, 0x03, 0x75, 0x08, 0x95, 0x01,
      0x91, 0x00, 0xC0,
      0x09, 0x50, 0x15, 0x00, 0x26, 0xFF, 0x7F, 0x75, 0x10, 0x95, 0x01, 0x91, 0x02,
      0x09, 0x52, 0x15, 0x00, 0x26, 0xFF, 0x00, 0x75, 0x08, 0x95, 0x01, 0x91, 0x02,
      0x09, 0x55, 0xA1, 0x02, 0x05, 0x01, 0x09, 0x30, 0x09, 0x31, 0x09, 0x32, 0x15, 0x00, 0x25, 0x01, 0x75, 0x01,
      0x95, 0x03, 0x91, 0x02, 0xC0,
      0x05, 0x0F, 0x09, 0x56, 0x95, 0x01, 0x91, 0x02,
      0x95, 0x04, 0x91, 0x03,              //   padding to the byte
      0xC0,
      // Set Condition (3): block, parameter block offset (axis), CP offset, +/- coefficients, saturations, dead band
      0x09, 0x5F, 0xA1, 0x02, 0x85, 0x03,
      0x09, 0x22, 0x15, 0x01, 0x25, 0x28, 0x75, 0x08, 0x95, 0x01, 0x91, 0x02,
      0x09, 0x23, 0x15, 0x00, 0x25, 0x02, 0x75, 0x08, 0x95, 0x01, 0x91, 0x02,
      0x09, 0x60, 0x09, 0x61, 0x09, 0x62, 0x16, 0xF0, 0xD8, 0x26, 0x10, 0x27, 0x75, 0x10, 0x95, 0x03, 0x91, 0x02,
      0x09, 0x63, 0x09, 0x64, 0x15, 0x00, 0x26, 0x10, 0x27, 0x75, 0x10, 0x95, 0x02, 0x91, 0x02,
      0x09, 0x65, 0x15, 0x00, 0x26, 0xFF, 0x00, 0x75, 0x08, 0x95, 0x01, 0x91, 0x02,
      0xC0,
      // Set Constant Force (5): block, magnitude
      0x09, 0x73, 0xA1, 0x02, 0x85, 0x05,
      0x09, 0x22, 0x15, 0x01, 0x25, 0x28, 0x75, 0x08, 0x95, 0x01, 0x91, 0x02,
      0x09, 0x70, 0x16, 0xF0, 0xD8, 0x26, 0x10, 0x27, 0x75, 0x10, 0x95, 0x01, 0x91, 0x02,
      0xC0,
      // Effect Operation (10): block, start / start solo / stop, loop count
      0x09, 0x77, 0xA1, 0x02, 0x85, 0x0A,
      0x09, 0x22, 0x15, 0x01, 0x25, 0x28, 0x75, 0x08, 0x95, 0x01, 0x91, 0x02,
      0x09, 0x78, 0xA1, 0x02, 0x09, 0x79, 0x09, 0x7A, 0x09, 0x7B, 0x15, 0x01, 0x25, 0x03, 0x75, 0x08, 0x95, 0x01,
      0x91, 0x00, 0xC0,
      0x09, 0x7C, 0x15, 0x00, 0x26, 0xFF, 0x00, 0x75, 0x08, 0x95, 0x01, 0x91, 0x02,
      0xC0,
      // PID Device Control (12): enable, disable, stop all
      0x09, 0x95, 0xA1, 0x02, 0x85, 0x0C,
      0x09, 0x96, 0xA1, 0x02, 0x09, 0x97, 0x09, 0x98, 0x09, 0x99, 0x15, 0x01, 0x25, 0x03, 0x75, 0x08, 0x95, 0x01,
      0x91, 0x00, 0xC0,
      0xC0,
      // Device Gain (13)
      0x09, 0x7D, 0xA1, 0x02, 0x85, 0x0D,
      0x09, 0x7E, 0x15, 0x00, 0x26, 0xFF, 0x00, 0x75, 0x08, 0x95, 0x01, 0x91, 0x02,
      0xC0,
      0xC0,
  };
  return d;
}

namespace {

PidLayout simulated_layout() {
  PidLayout layout;
  const auto& d = simulated_pid_descriptor();
  find_pid_layout(d.data(), d.size(), layout, nullptr);  // a fixed descriptor: checked by the tests
  return layout;
}

std::int32_t value(const PidLayout& layout, const std::uint8_t* r, std::size_t n, const HidFieldRef& ref) {
  return ref.found() ? get_field(r, n, layout.descriptor.uses_report_ids, layout.field(ref), ref.index) : 0;
}

std::int32_t selected(const PidLayout& layout, const std::uint8_t* r, std::size_t n, const HidSelector& sel) {
  return sel.found() ? get_field(r, n, layout.descriptor.uses_report_ids, layout.descriptor.fields[sel.field], 0) : -1;
}

double top(const PidLayout& layout, const HidFieldRef& ref) {
  if (!ref.found()) return 1;
  const HidField& f = layout.field(ref);
  return std::max(std::abs(static_cast<double>(f.logical_max)), std::abs(static_cast<double>(f.logical_min)));
}

}  // namespace

PidFirmware::PidFirmware(const PidLayout& layout) : layout_(layout) {}

bool PidFirmware::write_output(const std::uint8_t* r, std::size_t n) {
  ++received_;
  if (n == 0) return true;
  const std::uint8_t id = r[0];
  const PidLayout& L = layout_;
  if (L.set_effect.present && id == L.set_effect.id) {
    Effect& e = effects_[value(L, r, n, L.effect_block)];
    e.type = selected(L, r, n, L.effect_type_constant);  // the type field holds the selector's value
    for (int a = 0; a < L.axis_count(); ++a) e.axes[a] = value(L, r, n, L.axes_enable[a]) != 0;
  } else if (L.set_constant_force.present && id == L.set_constant_force.id) {
    effects_[value(L, r, n, L.constant_block)].magnitude = value(L, r, n, L.magnitude) / top(L, L.magnitude);
  } else if (L.set_condition.present && id == L.set_condition.id) {
    Effect& e = effects_[value(L, r, n, L.condition_block)];
    const int axis = std::clamp(value(L, r, n, L.parameter_offset), 0, 5);
    PidCondition& c = e.conditions[axis];
    c.cp_offset = value(L, r, n, L.cp_offset);
    c.positive_coefficient = value(L, r, n, L.positive_coefficient);
    c.negative_coefficient = value(L, r, n, L.negative_coefficient);
    c.positive_saturation = value(L, r, n, L.positive_saturation);
    c.negative_saturation = value(L, r, n, L.negative_saturation);
    c.dead_band = value(L, r, n, L.dead_band);
  } else if (L.effect_operation.present && id == L.effect_operation.id) {
    Effect& e = effects_[value(L, r, n, L.operation_block)];
    const std::int32_t op = selected(L, r, n, L.op_start);
    if (op == L.op_start.value) e.playing = true;
    else if (L.op_stop.found() && op == L.op_stop.value) e.playing = false;
  } else if (L.device_control.present && id == L.device_control.id) {
    const std::int32_t op = selected(L, r, n, L.stop_all);
    if (op == L.stop_all.value)
      for (auto& [block, e] : effects_) e.playing = false;
    else if (L.enable_actuators.found() && op == L.enable_actuators.value) actuators_ = true;
    else if (L.disable_actuators.found() && op == L.disable_actuators.value) actuators_ = false;
  } else if (L.device_gain.present && id == L.device_gain.id) {
    gain_ = value(L, r, n, L.device_gain_value) / top(L, L.device_gain_value);
  }
  return true;
}

int PidFirmware::read_input(std::uint8_t* buffer, std::size_t size) {
  if (inputs_.empty()) return 0;
  const auto report = inputs_.front();
  inputs_.erase(inputs_.begin());
  const std::size_t n = std::min(size, report.size());
  std::copy(report.begin(), report.begin() + static_cast<std::ptrdiff_t>(n), buffer);
  return static_cast<int>(n);
}

void PidFirmware::report_position(const Vec3& axes) {
  std::vector<std::uint8_t> report(1 + 6, 0);
  report[0] = 1;
  for (int a = 0; a < 3; ++a) {
    const HidFieldRef& ref = layout_.input_axes[a];
    if (!ref.found()) continue;
    const HidField& f = layout_.field(ref);
    put_field(report.data(), true, f, ref.index, static_cast<std::int32_t>(std::lround(std::clamp(axes[a], -1.0, 1.0) * f.logical_max)));
  }
  inputs_.push_back(std::move(report));
}

int PidFirmware::playing_effects() const {
  int n = 0;
  for (const auto& [block, e] : effects_) n += e.playing ? 1 : 0;
  return n;
}

Vec3 PidFirmware::force(const Vec3& x, const Vec3& v) const {
  Vec3 f = Vec3::Zero();
  if (!actuators_) return f;
  const PidLayout& L = layout_;
  const double cp_top = top(L, L.cp_offset), k_top = top(L, L.positive_coefficient),
               sat_top = top(L, L.positive_saturation);
  for (const auto& [block, e] : effects_) {
    if (!e.playing) continue;
    for (int a = 0; a < 3 && a < L.axis_count(); ++a) {
      if (!e.axes[a]) continue;
      if (e.type == L.effect_type_constant.value) {
        f[a] += e.magnitude;
        continue;
      }
      const PidCondition& c = e.conditions[a];
      double term = 0;
      if (e.type == L.effect_type_spring.value) {
        // PID 1.0, section 5.9: the force opposes the displacement from the
        // centre, with the coefficient of the side it is on.
        const double d = x[a] - c.cp_offset / cp_top;
        term = -(d > 0 ? c.positive_coefficient : c.negative_coefficient) / k_top * d;
      } else if (e.type == L.effect_type_damper.value) {
        term = -(v[a] > 0 ? c.positive_coefficient : c.negative_coefficient) / k_top * v[a];
      }
      const double limit = (term > 0 ? c.positive_saturation : c.negative_saturation) / sat_top;
      f[a] += std::clamp(term, -limit, limit);
    }
  }
  return f * gain_;
}

SimulatedPidDevice::SimulatedPidDevice(HandScript script, const HandParameters& params, const Vec3& centre,
                                       const Pose& initial_pose, PidForceConfig config)
    : layout_(simulated_layout()),
      config_(std::move(config)),
      hand_(std::move(script), params, centre, initial_pose),
      origin_(initial_pose * centre) {
  auto firmware = std::make_unique<PidFirmware>(layout_);
  firmware_ = firmware.get();
  config_.control = ControlMode::Position;
  config_.start_thread = false;  // serviced from read(): deterministic in lockstep
  if (config_.name == PidForceConfig{}.name) config_.name = "simulated hand on a HID PID device";
  config_.clock = [this] { return now_; };
  pid_ = std::make_unique<HidPidDevice>(std::move(firmware), layout_, config_);
}

DeviceSample SimulatedPidDevice::read(double now) noexcept {
  now_ = now;
  const double w = config_.workspace_mm;
  auto position = [&] {
    Vec3 x;
    for (int a = 0; a < 3; ++a) x[a] = config_.axis_directions[a].dot(hand_.reference_point() - origin_) / w;
    return x;
  };
  // The device's effects at its position and speed push the hand over the
  // next step (the firmware's force, decoded from the reports it got).
  Vec3 v;
  for (int a = 0; a < 3; ++a) v[a] = config_.axis_directions[a].dot(hand_.velocity().head<3>()) / w;
  const Vec3 f = firmware_->force(position(), v) * config_.full_scale_force;
  felt_.force = Vec3::Zero();
  for (int a = 0; a < 3; ++a) felt_.force += f[a] * config_.axis_directions[a];
  hand_.write(felt_);
  hand_.read(now_);  // integrates the hand up to now
  firmware_->report_position(position());
  if (now_ + 1e-12 >= next_service_) {
    pid_->service();
    next_service_ = now_ + 1.0 / std::max(1.0, config_.update_rate_hz);
  }
  return pid_->read(now_);
}

}  // namespace contactcore::haptics
