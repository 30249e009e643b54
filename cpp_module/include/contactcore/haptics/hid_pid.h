// HID force feedback (the PID usage page 0x0F, "USB Device Class Definition
// for Physical Interface Devices", version 1.0, usb.org, 1999): the layout of
// the effect reports read from a device's report descriptor, and the reports
// themselves. The device that sends them is in hid_pid_device.h.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "contactcore/haptics/hid_descriptor.h"
#include "contactcore/haptics/pose_math.h"

namespace contactcore::haptics {

// PID usages (page 0x0F) the output needs, from the PID 1.0 usage table.
namespace pid {
constexpr std::uint16_t kPage = 0x0F;
constexpr std::uint16_t kSetEffectReport = 0x21, kEffectBlockIndex = 0x22, kEffectType = 0x25,
                        kEtConstantForce = 0x26, kDuration = 0x50, kSamplePeriod = 0x51, kGain = 0x52,
                        kTriggerButton = 0x53, kTriggerRepeatInterval = 0x54, kAxesEnable = 0x55,
                        kDirectionEnable = 0x56, kDirection = 0x57, kMagnitude = 0x70,
                        kSetConstantForceReport = 0x73, kEffectOperationReport = 0x77, kEffectOperation = 0x78,
                        kOpEffectStart = 0x79, kOpEffectStop = 0x7B, kLoopCount = 0x7C,
                        kDeviceGainReport = 0x7D, kDeviceGain = 0x7E, kBlockLoadReport = 0x89,
                        kBlockLoadStatus = 0x8B, kBlockLoadSuccess = 0x8C, kDeviceControlReport = 0x95,
                        kDeviceControl = 0x96, kDcEnableActuators = 0x97, kDcDisableActuators = 0x98,
                        kDcStopAllEffects = 0x99, kStartDelay = 0xA7, kCreateNewEffectReport = 0xAB,
                        // Conditions (spring, damper): Set Condition Report and its parameters.
                        kParameterBlockOffset = 0x23, kEtSpring = 0x40, kEtDamper = 0x41,
                        kSetConditionReport = 0x5F, kCpOffset = 0x60, kPositiveCoefficient = 0x61,
                        kNegativeCoefficient = 0x62, kPositiveSaturation = 0x63, kNegativeSaturation = 0x64,
                        kDeadBand = 0x65;
}  // namespace pid

// Element `index` of field `field` of the descriptor (-1: absent).
struct HidFieldRef {
  int field = -1;
  std::uint32_t index = 0;
  bool found() const { return field >= 0; }
};
// An array field and the value that selects one of its usages (logical
// minimum + the usage's position, as the Linux pidff driver computes it).
struct HidSelector {
  int field = -1;
  std::int32_t value = 0;
  bool found() const { return field >= 0; }
};
struct HidReportRef {
  bool present = false;
  HidReportKind kind = HidReportKind::Output;
  std::uint8_t id = 0;
  std::size_t size = 0;  // bytes, report ID included when the device uses IDs
};

struct PidLayout {
  HidReportDescriptor descriptor;
  HidReportRef set_effect, set_constant_force, effect_operation, device_control, device_gain,
      create_new_effect, block_load, set_condition;
  // Set Effect
  HidFieldRef effect_block, duration, trigger_repeat, sample_period, gain, trigger_button, start_delay,
      direction_enable;
  HidSelector effect_type_constant;
  std::vector<HidFieldRef> axes_enable;  // per axis (Generic Desktop X, Y, ... in the Axes Enable collection)
  std::vector<HidFieldRef> direction;    // per axis, when present
  // Set Constant Force
  HidFieldRef constant_block, magnitude;
  // Effect Operation
  HidFieldRef operation_block, loop_count;
  HidSelector op_start, op_stop;
  // PID Device Control
  HidSelector enable_actuators, disable_actuators, stop_all;
  // Device Gain
  HidFieldRef device_gain_value;
  // Create New Effect / Block Load (features: the device allocates effect blocks)
  HidSelector create_constant;
  HidFieldRef load_block;
  HidSelector load_success;
  // Input axes (Generic Desktop X Y Z Rx Ry Rz) for a joystick's own input.
  std::array<HidFieldRef, 6> input_axes{};
  // Conditions (optional): spring and damper effect types, Set Condition.
  HidSelector effect_type_spring, effect_type_damper, create_spring, create_damper;
  HidFieldRef condition_block, parameter_offset, cp_offset, positive_coefficient, negative_coefficient,
      positive_saturation, negative_saturation, dead_band;

  int axis_count() const { return static_cast<int>(axes_enable.size()); }
  // Spring and damper conditions can be played (Set Condition with its
  // centre and coefficients, both effect types).
  bool has_conditions() const {
    return set_condition.present && condition_block.found() && cp_offset.found() && positive_coefficient.found() &&
           effect_type_spring.found() && effect_type_damper.found();
  }
  const HidField& field(const HidFieldRef& r) const { return descriptor.fields[r.field]; }
};

// Finds the constant-force output in `descriptor`; false with the reason when
// the device has no PID page or lacks a report the output needs.
bool find_pid_layout(const std::uint8_t* descriptor, std::size_t size, PidLayout& layout, std::string* why);

// A zero-filled report with its ID byte (when the device uses IDs): what the
// builders below fill, and the buffer a Block Load feature is read into.
std::vector<std::uint8_t> pid_blank_report(const PidLayout& layout, const HidReportRef& report);
// The reports (report ID byte first, zero-filled, then the fields).
std::vector<std::uint8_t> pid_set_effect_report(const PidLayout& layout, int block, int axis);
std::vector<std::uint8_t> pid_constant_force_report(const PidLayout& layout, int block, std::int32_t magnitude);
std::vector<std::uint8_t> pid_effect_operation_report(const PidLayout& layout, int block, bool start);
std::vector<std::uint8_t> pid_device_control_report(const PidLayout& layout, const HidSelector& control);
std::vector<std::uint8_t> pid_device_gain_report(const PidLayout& layout, double gain);  // 0..1
std::vector<std::uint8_t> pid_create_effect_report(const PidLayout& layout);
// Create New Effect of a given type (layout.create_spring, create_damper).
std::vector<std::uint8_t> pid_create_effect_report(const PidLayout& layout, const HidSelector& type);
// Set Effect for a condition (`type`: layout.effect_type_spring or _damper):
// every axis enabled, no direction (one parameter block per axis), infinite.
std::vector<std::uint8_t> pid_set_condition_effect_report(const PidLayout& layout, int block, const HidSelector& type);
// One axis' parameter block of a condition; values in the fields' logical
// units (centre in [-max, max] of CP Offset, coefficients, saturations).
struct PidCondition {
  std::int32_t cp_offset = 0, positive_coefficient = 0, negative_coefficient = 0;
  std::int32_t positive_saturation = 0, negative_saturation = 0, dead_band = 0;
  bool operator==(const PidCondition& o) const {
    return cp_offset == o.cp_offset && positive_coefficient == o.positive_coefficient &&
           negative_coefficient == o.negative_coefficient && positive_saturation == o.positive_saturation &&
           negative_saturation == o.negative_saturation && dead_band == o.dead_band;
  }
  bool operator!=(const PidCondition& o) const { return !(*this == o); }
};
std::vector<std::uint8_t> pid_set_condition_report(const PidLayout& layout, int block, int axis,
                                                   const PidCondition& condition);
// `fraction` in [-1, 1] of a field's largest magnitude, rounded and clamped.
std::int32_t pid_scaled(const PidLayout& layout, const HidFieldRef& field, double fraction);
// A device's input report through its descriptor: the Generic Desktop axes
// normalised to [-1, 1] (the ones the report carries are set; false when the
// report holds none of them).
bool parse_pid_input(const PidLayout& layout, const std::uint8_t* report, std::size_t size, Vec6& axes);
// `force` in N against the device's full scale, as the Magnitude field's value
// (rounded, clamped to its logical range).
std::int32_t pid_magnitude(const PidLayout& layout, double force, double full_scale);

}  // namespace contactcore::haptics
