#include "contactcore/haptics/hid_pid.h"

#include <algorithm>
#include <cmath>

#include "contactcore/haptics/spacemouse.h"

namespace contactcore::haptics {

namespace {

constexpr std::uint32_t pid_usage(std::uint16_t id) { return hid_usage(pid::kPage, id); }
constexpr std::uint32_t desktop_usage(std::uint16_t id) { return hid_usage(0x01, id); }

HidReportRef find_report(const HidReportDescriptor& d, HidReportKind kind, std::uint16_t collection) {
  HidReportRef r;
  for (const HidField& f : d.fields)
    if (f.kind == kind && f.in_collection(pid_usage(collection))) {
      r.present = true;
      r.kind = kind;
      r.id = f.report_id;
      r.size = d.report_size(kind, f.report_id);
      break;
    }
  return r;
}

// The element of report `report` (kind, ID) whose usage is `usage`, inside
// collection `parent` when given.
HidFieldRef find_element(const HidReportDescriptor& d, const HidReportRef& report, std::uint32_t usage,
                         std::uint16_t parent = 0) {
  HidFieldRef r;
  if (!report.present) return r;
  for (std::size_t k = 0; k < d.fields.size(); ++k) {
    const HidField& f = d.fields[k];
    if (f.kind != report.kind || f.report_id != report.id || f.constant() || !f.variable()) continue;
    if (parent && !f.in_collection(pid_usage(parent))) continue;
    for (std::uint32_t i = 0; i < f.count; ++i)
      if (f.usage(i) == usage) return HidFieldRef{static_cast<int>(k), i};
  }
  return r;
}

// The array field of `report` inside collection `parent` offering `usage`.
HidSelector find_selector(const HidReportDescriptor& d, const HidReportRef& report, std::uint16_t parent,
                          std::uint16_t usage) {
  HidSelector s;
  if (!report.present) return s;
  for (std::size_t k = 0; k < d.fields.size(); ++k) {
    const HidField& f = d.fields[k];
    if (f.kind != report.kind || f.report_id != report.id || f.constant() || f.variable()) continue;
    if (!f.in_collection(pid_usage(parent))) continue;
    const auto it = std::find(f.usages.begin(), f.usages.end(), pid_usage(usage));
    if (it != f.usages.end()) return HidSelector{static_cast<int>(k), f.logical_min + static_cast<std::int32_t>(it - f.usages.begin())};
  }
  return s;
}

// Every element of `report` inside collection `parent`, in order (axes).
std::vector<HidFieldRef> elements_in(const HidReportDescriptor& d, const HidReportRef& report, std::uint16_t parent) {
  std::vector<HidFieldRef> out;
  if (!report.present) return out;
  for (std::size_t k = 0; k < d.fields.size(); ++k) {
    const HidField& f = d.fields[k];
    if (f.kind != report.kind || f.report_id != report.id || f.constant() || !f.variable()) continue;
    if (!f.in_collection(pid_usage(parent))) continue;
    for (std::uint32_t i = 0; i < f.count; ++i) out.push_back(HidFieldRef{static_cast<int>(k), i});
  }
  return out;
}

// The elements and selectors find_pid_layout looks up, as data: where each
// goes in PidLayout, the report it is in, its PID usage (and, for a selector,
// the collection of the array field offering it).
struct ElementLookup {
  HidFieldRef PidLayout::*element;
  HidReportRef PidLayout::*report;
  std::uint16_t usage;
};
struct SelectorLookup {
  HidSelector PidLayout::*selector;
  HidReportRef PidLayout::*report;
  std::uint16_t collection, usage;
};
const ElementLookup kElementLookups[] = {
    {&PidLayout::effect_block, &PidLayout::set_effect, pid::kEffectBlockIndex},
    {&PidLayout::duration, &PidLayout::set_effect, pid::kDuration},
    {&PidLayout::trigger_repeat, &PidLayout::set_effect, pid::kTriggerRepeatInterval},
    {&PidLayout::sample_period, &PidLayout::set_effect, pid::kSamplePeriod},
    {&PidLayout::gain, &PidLayout::set_effect, pid::kGain},
    {&PidLayout::trigger_button, &PidLayout::set_effect, pid::kTriggerButton},
    {&PidLayout::start_delay, &PidLayout::set_effect, pid::kStartDelay},
    {&PidLayout::direction_enable, &PidLayout::set_effect, pid::kDirectionEnable},
    {&PidLayout::constant_block, &PidLayout::set_constant_force, pid::kEffectBlockIndex},
    {&PidLayout::magnitude, &PidLayout::set_constant_force, pid::kMagnitude},
    {&PidLayout::operation_block, &PidLayout::effect_operation, pid::kEffectBlockIndex},
    {&PidLayout::loop_count, &PidLayout::effect_operation, pid::kLoopCount},
    {&PidLayout::device_gain_value, &PidLayout::device_gain, pid::kDeviceGain},
    {&PidLayout::load_block, &PidLayout::block_load, pid::kEffectBlockIndex},
    {&PidLayout::condition_block, &PidLayout::set_condition, pid::kEffectBlockIndex},
    {&PidLayout::parameter_offset, &PidLayout::set_condition, pid::kParameterBlockOffset},
    {&PidLayout::cp_offset, &PidLayout::set_condition, pid::kCpOffset},
    {&PidLayout::positive_coefficient, &PidLayout::set_condition, pid::kPositiveCoefficient},
    {&PidLayout::negative_coefficient, &PidLayout::set_condition, pid::kNegativeCoefficient},
    {&PidLayout::positive_saturation, &PidLayout::set_condition, pid::kPositiveSaturation},
    {&PidLayout::negative_saturation, &PidLayout::set_condition, pid::kNegativeSaturation},
    {&PidLayout::dead_band, &PidLayout::set_condition, pid::kDeadBand},
};
const SelectorLookup kSelectorLookups[] = {
    {&PidLayout::effect_type_constant, &PidLayout::set_effect, pid::kEffectType, pid::kEtConstantForce},
    {&PidLayout::op_start, &PidLayout::effect_operation, pid::kEffectOperation, pid::kOpEffectStart},
    {&PidLayout::op_stop, &PidLayout::effect_operation, pid::kEffectOperation, pid::kOpEffectStop},
    {&PidLayout::enable_actuators, &PidLayout::device_control, pid::kDeviceControl, pid::kDcEnableActuators},
    {&PidLayout::disable_actuators, &PidLayout::device_control, pid::kDeviceControl, pid::kDcDisableActuators},
    {&PidLayout::stop_all, &PidLayout::device_control, pid::kDeviceControl, pid::kDcStopAllEffects},
    {&PidLayout::create_constant, &PidLayout::create_new_effect, pid::kEffectType, pid::kEtConstantForce},
    {&PidLayout::load_success, &PidLayout::block_load, pid::kBlockLoadStatus, pid::kBlockLoadSuccess},
    {&PidLayout::effect_type_spring, &PidLayout::set_effect, pid::kEffectType, pid::kEtSpring},
    {&PidLayout::effect_type_damper, &PidLayout::set_effect, pid::kEffectType, pid::kEtDamper},
    {&PidLayout::create_spring, &PidLayout::create_new_effect, pid::kEffectType, pid::kEtSpring},
    {&PidLayout::create_damper, &PidLayout::create_new_effect, pid::kEffectType, pid::kEtDamper},
};

std::vector<std::uint8_t> blank(const PidLayout& layout, const HidReportRef& report) {
  std::vector<std::uint8_t> out(report.size, 0);
  if (layout.descriptor.uses_report_ids && !out.empty()) out[0] = report.id;
  return out;
}

void put(const PidLayout& layout, std::vector<std::uint8_t>& report, const HidFieldRef& ref, std::int32_t value,
         bool clamp = true) {
  if (ref.found())
    put_field(report.data(), layout.descriptor.uses_report_ids, layout.field(ref), ref.index, value, clamp);
}

void put(const PidLayout& layout, std::vector<std::uint8_t>& report, const HidSelector& sel) {
  if (sel.found())
    put_field(report.data(), layout.descriptor.uses_report_ids, layout.descriptor.fields[sel.field], 0, sel.value);
}

std::int32_t field_max(const PidLayout& layout, const HidFieldRef& ref) {
  return ref.found() ? layout.field(ref).logical_max : 0;
}

}  // namespace

bool find_pid_layout(const std::uint8_t* data, std::size_t size, PidLayout& layout, std::string* why) {
  layout = PidLayout{};
  std::string error;
  if (!parse_hid_descriptor(data, size, layout.descriptor, &error)) {
    if (why) *why = error;
    return false;
  }
  const HidReportDescriptor& d = layout.descriptor;
  using K = HidReportKind;
  layout.set_effect = find_report(d, K::Output, pid::kSetEffectReport);
  layout.set_constant_force = find_report(d, K::Output, pid::kSetConstantForceReport);
  layout.effect_operation = find_report(d, K::Output, pid::kEffectOperationReport);
  layout.device_control = find_report(d, K::Output, pid::kDeviceControl);
  layout.device_gain = find_report(d, K::Output, pid::kDeviceGainReport);
  layout.create_new_effect = find_report(d, K::Feature, pid::kCreateNewEffectReport);
  layout.block_load = find_report(d, K::Feature, pid::kBlockLoadReport);
  layout.set_condition = find_report(d, K::Output, pid::kSetConditionReport);

  for (const ElementLookup& e : kElementLookups)
    layout.*e.element = find_element(d, layout.*e.report, pid_usage(e.usage));
  for (const SelectorLookup& e : kSelectorLookups)
    layout.*e.selector = find_selector(d, layout.*e.report, e.collection, e.usage);
  layout.axes_enable = elements_in(d, layout.set_effect, pid::kAxesEnable);
  layout.direction = elements_in(d, layout.set_effect, pid::kDirection);

  for (std::size_t k = 0; k < d.fields.size(); ++k) {
    const HidField& f = d.fields[k];
    if (f.kind != K::Input || f.constant() || !f.variable()) continue;
    for (std::uint32_t i = 0; i < f.count; ++i)
      for (int a = 0; a < 6; ++a)
        if (f.usage(i) == desktop_usage(static_cast<std::uint16_t>(0x30 + a)) && !layout.input_axes[a].found())
          layout.input_axes[a] = HidFieldRef{static_cast<int>(k), i};
  }

  const char* missing = nullptr;
  if (!descriptor_has_pid_page(data, size)) missing = "no PID usage page (0x0F): no force feedback";
  else if (!layout.set_effect.present || !layout.effect_block.found()) missing = "no Set Effect report";
  else if (!layout.effect_type_constant.found()) missing = "no constant-force effect type";
  else if (layout.axes_enable.empty()) missing = "no axes in the Set Effect report";
  else if (!layout.set_constant_force.present || !layout.magnitude.found() || !layout.constant_block.found())
    missing = "no Set Constant Force report";
  else if (!layout.effect_operation.present || !layout.op_start.found()) missing = "no Effect Operation report";
  else if (!layout.device_control.present || !layout.stop_all.found()) missing = "no Device Control (stop all)";
  if (missing) {
    if (why) *why = missing;
    return false;
  }
  if (layout.axes_enable.size() > 6) layout.axes_enable.resize(6);
  return true;
}

std::vector<std::uint8_t> pid_blank_report(const PidLayout& layout, const HidReportRef& report) {
  return blank(layout, report);
}

std::vector<std::uint8_t> pid_set_effect_report(const PidLayout& layout, int block, int axis) {
  auto r = blank(layout, layout.set_effect);
  put(layout, r, layout.effect_block, block);
  put(layout, r, layout.effect_type_constant);
  // Infinite duration and no trigger button: all bits set (the null value,
  // what the Linux pidff driver sends for FF_INFINITE) and 0.
  put(layout, r, layout.duration, -1, false);
  put(layout, r, layout.trigger_button, 0, false);
  put(layout, r, layout.trigger_repeat, 0);
  put(layout, r, layout.sample_period, 0);
  put(layout, r, layout.start_delay, 0);
  put(layout, r, layout.gain, field_max(layout, layout.gain));
  // One axis, no direction: the signed magnitude acts along that axis alone.
  for (int a = 0; a < layout.axis_count(); ++a) put(layout, r, layout.axes_enable[a], a == axis ? 1 : 0);
  put(layout, r, layout.direction_enable, 0);
  for (const HidFieldRef& ref : layout.direction) put(layout, r, ref, 0);
  return r;
}

std::vector<std::uint8_t> pid_constant_force_report(const PidLayout& layout, int block, std::int32_t magnitude) {
  auto r = blank(layout, layout.set_constant_force);
  put(layout, r, layout.constant_block, block);
  put(layout, r, layout.magnitude, magnitude);
  return r;
}

std::vector<std::uint8_t> pid_effect_operation_report(const PidLayout& layout, int block, bool start) {
  auto r = blank(layout, layout.effect_operation);
  put(layout, r, layout.operation_block, block);
  put(layout, r, start ? layout.op_start : layout.op_stop);
  put(layout, r, layout.loop_count, 1);
  return r;
}

std::vector<std::uint8_t> pid_device_control_report(const PidLayout& layout, const HidSelector& control) {
  auto r = blank(layout, layout.device_control);
  put(layout, r, control);
  return r;
}

std::vector<std::uint8_t> pid_device_gain_report(const PidLayout& layout, double gain) {
  auto r = blank(layout, layout.device_gain);
  const std::int32_t top = field_max(layout, layout.device_gain_value);
  put(layout, r, layout.device_gain_value, static_cast<std::int32_t>(std::lround(std::clamp(gain, 0.0, 1.0) * top)));
  return r;
}

std::vector<std::uint8_t> pid_create_effect_report(const PidLayout& layout) {
  auto r = blank(layout, layout.create_new_effect);
  put(layout, r, layout.create_constant);
  return r;
}

std::vector<std::uint8_t> pid_create_effect_report(const PidLayout& layout, const HidSelector& type) {
  auto r = blank(layout, layout.create_new_effect);
  put(layout, r, type);
  return r;
}

std::vector<std::uint8_t> pid_set_condition_effect_report(const PidLayout& layout, int block, const HidSelector& type) {
  auto r = blank(layout, layout.set_effect);
  put(layout, r, layout.effect_block, block);
  put(layout, r, type);
  put(layout, r, layout.duration, -1, false);  // infinite (the null value)
  put(layout, r, layout.trigger_button, 0, false);
  put(layout, r, layout.trigger_repeat, 0);
  put(layout, r, layout.sample_period, 0);
  put(layout, r, layout.start_delay, 0);
  put(layout, r, layout.gain, field_max(layout, layout.gain));
  // Every axis, no direction: one Set Condition parameter block per axis.
  for (int a = 0; a < layout.axis_count(); ++a) put(layout, r, layout.axes_enable[a], 1);
  put(layout, r, layout.direction_enable, 0);
  for (const HidFieldRef& ref : layout.direction) put(layout, r, ref, 0);
  return r;
}

std::vector<std::uint8_t> pid_set_condition_report(const PidLayout& layout, int block, int axis,
                                                   const PidCondition& c) {
  auto r = blank(layout, layout.set_condition);
  put(layout, r, layout.condition_block, block);
  put(layout, r, layout.parameter_offset, axis);
  put(layout, r, layout.cp_offset, c.cp_offset);
  put(layout, r, layout.positive_coefficient, c.positive_coefficient);
  put(layout, r, layout.negative_coefficient, c.negative_coefficient);
  put(layout, r, layout.positive_saturation, c.positive_saturation);
  put(layout, r, layout.negative_saturation, c.negative_saturation);
  put(layout, r, layout.dead_band, c.dead_band);
  return r;
}

std::int32_t pid_scaled(const PidLayout& layout, const HidFieldRef& ref, double fraction) {
  if (!ref.found()) return 0;
  const HidField& f = layout.field(ref);
  const double top = std::max(std::abs(static_cast<double>(f.logical_max)), std::abs(static_cast<double>(f.logical_min)));
  const double value = std::clamp(fraction * top, static_cast<double>(f.logical_min), static_cast<double>(f.logical_max));
  return static_cast<std::int32_t>(std::lround(value));
}

bool parse_pid_input(const PidLayout& layout, const std::uint8_t* report, std::size_t size, Vec6& axes) {
  if (!report || size == 0) return false;
  const bool with_id = layout.descriptor.uses_report_ids;
  bool any = false;
  for (int a = 0; a < 6; ++a) {
    const HidFieldRef& ref = layout.input_axes[a];
    if (!ref.found()) continue;
    const HidField& f = layout.field(ref);
    if (with_id && report[0] != f.report_id) continue;
    const std::size_t needed = (with_id ? 1 : 0) + (f.bit_offset + f.bit_size * (ref.index + 1) + 7) / 8;
    if (size < needed) continue;
    const double v = get_field(report, size, with_id, f, ref.index);
    const double mid = 0.5 * (f.logical_min + static_cast<double>(f.logical_max));
    const double half = 0.5 * (static_cast<double>(f.logical_max) - f.logical_min);
    axes[a] = half > 0 ? std::clamp((v - mid) / half, -1.0, 1.0) : 0.0;
    any = true;
  }
  return any;
}

std::int32_t pid_magnitude(const PidLayout& layout, double force, double full_scale) {
  const HidField& f = layout.field(layout.magnitude);
  const double top = std::max(std::abs(static_cast<double>(f.logical_max)), std::abs(static_cast<double>(f.logical_min)));
  const double value = full_scale > 0 ? force / full_scale * top : 0.0;
  const double clamped = std::clamp(value, static_cast<double>(f.logical_min), static_cast<double>(f.logical_max));
  return static_cast<std::int32_t>(std::lround(clamped));
}

}  // namespace contactcore::haptics
