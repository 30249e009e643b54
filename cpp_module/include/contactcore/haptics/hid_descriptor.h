// A HID report descriptor parsed into fields (HID 1.11, section 6.2.2): for
// each Input, Output and Feature main item, its report ID, bit offset and size,
// usages, logical range and the collections around it. Device-agnostic: the
// SpaceMouse reader, the PID force output (hid_pid.h) and generic joystick
// axes all read their layout from here instead of hard-coding a device.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace contactcore::haptics {

enum class HidReportKind : std::uint8_t { Input = 0, Output = 1, Feature = 2 };

// A usage with its page: (page << 16) | id.
constexpr std::uint32_t hid_usage(std::uint16_t page, std::uint16_t id) {
  return (std::uint32_t(page) << 16) | id;
}

struct HidField {
  HidReportKind kind = HidReportKind::Input;
  std::uint8_t report_id = 0;
  std::uint32_t bit_offset = 0;  // from the first byte after the report ID
  std::uint32_t bit_size = 0, count = 0;
  std::uint32_t flags = 0;       // the main item's data bits (0: constant, 1: variable, ...)
  std::int32_t logical_min = 0, logical_max = 0;
  std::vector<std::uint32_t> usages;       // per element (variable) or the selectable usages (array)
  std::vector<std::uint32_t> collections;  // usages of the enclosing collections, outermost first

  bool constant() const { return flags & 1; }
  bool variable() const { return flags & 2; }
  // Usage of element `i` of a variable field (the last usage repeats, HID 6.2.2.8).
  std::uint32_t usage(std::uint32_t i) const;
  bool in_collection(std::uint32_t usage) const;
};

struct HidReportDescriptor {
  std::vector<HidField> fields;
  bool uses_report_ids = false;
  // Bytes of report `id` of `kind`, report ID byte included when IDs are used.
  std::size_t report_size(HidReportKind kind, std::uint8_t id) const;
};

// Parses `data`; false with a message (item offset) on a malformed descriptor.
bool parse_hid_descriptor(const std::uint8_t* data, std::size_t size, HidReportDescriptor& out,
                          std::string* error = nullptr);

// Writes element `index` of `field` into `report` (report ID byte first when
// IDs are used), bits little-endian; `value` is clamped to the logical range
// unless `clamp` is false (a null value: all bits set means "infinite").
void put_field(std::uint8_t* report, bool with_id, const HidField& field, std::uint32_t index,
               std::int32_t value, bool clamp = true);
// Reads element `index` (sign-extended when the logical minimum is negative).
std::int32_t get_field(const std::uint8_t* report, std::size_t size, bool with_id, const HidField& field,
                       std::uint32_t index);

}  // namespace contactcore::haptics
