#include "contactcore/haptics/hid_descriptor.h"

#include <algorithm>

namespace contactcore::haptics {

std::uint32_t HidField::usage(std::uint32_t i) const {
  if (usages.empty()) return 0;
  return usages[std::min<std::size_t>(i, usages.size() - 1)];
}

bool HidField::in_collection(std::uint32_t u) const {
  return std::find(collections.begin(), collections.end(), u) != collections.end();
}

std::size_t HidReportDescriptor::report_size(HidReportKind kind, std::uint8_t id) const {
  std::uint32_t bits = 0;
  for (const HidField& f : fields)
    if (f.kind == kind && f.report_id == id) bits = std::max(bits, f.bit_offset + f.bit_size * f.count);
  return (bits + 7) / 8 + (uses_report_ids ? 1 : 0);
}

namespace {

struct Globals {
  std::uint16_t usage_page = 0;
  std::int32_t logical_min = 0;
  std::uint32_t logical_max_raw = 0;
  int logical_max_bytes = 0;
  std::uint32_t report_size = 0, report_count = 0;
  std::uint8_t report_id = 0;
};

std::uint32_t unsigned_value(const std::uint8_t* p, int n) {
  std::uint32_t v = 0;
  for (int k = 0; k < n; ++k) v |= std::uint32_t(p[k]) << (8 * k);
  return v;
}

std::int32_t signed_value(std::uint32_t v, int n) {
  if (n == 1) return static_cast<std::int8_t>(v);
  if (n == 2) return static_cast<std::int16_t>(v);
  return static_cast<std::int32_t>(v);
}

bool fail(std::string* error, std::size_t offset, const char* what) {
  if (error) *error = "HID report descriptor, byte " + std::to_string(offset) + ": " + what;
  return false;
}

}  // namespace

bool parse_hid_descriptor(const std::uint8_t* d, std::size_t size, HidReportDescriptor& out, std::string* error) {
  out = HidReportDescriptor{};
  constexpr std::size_t kMaxUsages = 4096;  // a malformed Usage Maximum must not explode
  Globals g;
  std::vector<Globals> stack;
  std::vector<std::uint32_t> usages, collections;
  bool have_min = false;
  std::uint32_t usage_min = 0;
  // Next free bit per (kind, report ID).
  std::vector<std::uint32_t> next_bit(3 * 256, 0);
  std::size_t i = 0;
  while (i < size) {
    const std::uint8_t prefix = d[i];
    if (prefix == 0xFE) {  // long item: skipped (none defined)
      if (i + 2 >= size) return fail(error, i, "truncated long item");
      i += 3 + d[i + 1];
      continue;
    }
    const int n = (prefix & 3) == 3 ? 4 : (prefix & 3);
    if (i + 1 + n > size) return fail(error, i, "truncated item");
    const std::uint32_t raw = unsigned_value(d + i + 1, n);
    const int type = (prefix >> 2) & 3, tag = prefix >> 4;
    if (type == 0) {  // main
      if (tag == 8 || tag == 9 || tag == 0xB) {
        HidField f;
        f.kind = tag == 8 ? HidReportKind::Input : tag == 9 ? HidReportKind::Output : HidReportKind::Feature;
        f.report_id = g.report_id;
        f.bit_size = g.report_size;
        f.count = g.report_count;
        f.flags = raw;
        f.logical_min = g.logical_min;
        const std::int32_t max_signed = signed_value(g.logical_max_raw, g.logical_max_bytes);
        // HID 6.2.2.7: with a non-negative minimum the maximum is read unsigned.
        f.logical_max = g.logical_min >= 0 && max_signed < 0 ? static_cast<std::int32_t>(g.logical_max_raw) : max_signed;
        f.usages = usages;
        f.collections = collections;
        std::uint32_t& bit = next_bit[static_cast<int>(f.kind) * 256 + f.report_id];
        f.bit_offset = bit;
        const std::uint64_t bits = std::uint64_t(f.bit_size) * f.count;
        if (bits > 8 * 4096) return fail(error, i, "report larger than 4096 bytes");
        bit += static_cast<std::uint32_t>(bits);
        out.fields.push_back(std::move(f));
      } else if (tag == 0xA) {  // Collection
        collections.push_back(usages.empty() ? 0 : usages.front());
      } else if (tag == 0xC) {  // End Collection
        if (collections.empty()) return fail(error, i, "End Collection without Collection");
        collections.pop_back();
      }
      usages.clear();
      have_min = false;
    } else if (type == 1) {  // global
      switch (tag) {
        case 0: g.usage_page = static_cast<std::uint16_t>(raw); break;
        case 1: g.logical_min = signed_value(raw, n); break;
        case 2: g.logical_max_raw = raw; g.logical_max_bytes = n; break;
        case 7: g.report_size = raw; break;
        case 8:
          if (raw == 0 || raw > 255) return fail(error, i, "report ID out of range");
          g.report_id = static_cast<std::uint8_t>(raw);
          out.uses_report_ids = true;
          break;
        case 9: g.report_count = raw; break;
        case 0xA: stack.push_back(g); break;
        case 0xB:
          if (stack.empty()) return fail(error, i, "Pop without Push");
          g = stack.back();
          stack.pop_back();
          break;
        default: break;
      }
      if (g.report_size > 32) return fail(error, i, "report size above 32 bits");
    } else if (type == 2) {  // local
      const std::uint32_t u = n == 4 ? raw : hid_usage(g.usage_page, static_cast<std::uint16_t>(raw));
      if (tag == 0) {
        if (usages.size() < kMaxUsages) usages.push_back(u);
      } else if (tag == 1) {
        usage_min = u;
        have_min = true;
      } else if (tag == 2 && have_min) {
        for (std::uint32_t v = usage_min; v <= u && usages.size() < kMaxUsages; ++v) usages.push_back(v);
        have_min = false;
      }
    }
    i += 1 + n;
  }
  if (!collections.empty()) return fail(error, size, "unclosed collection");
  return true;
}

void put_field(std::uint8_t* report, bool with_id, const HidField& f, std::uint32_t index, std::int32_t value,
               bool clamp) {
  if (clamp) value = std::clamp(value, f.logical_min, std::max(f.logical_min, f.logical_max));
  std::uint8_t* data = report + (with_id ? 1 : 0);
  const std::uint32_t start = f.bit_offset + index * f.bit_size;
  const std::uint32_t bits = static_cast<std::uint32_t>(value);
  for (std::uint32_t b = 0; b < f.bit_size; ++b) {
    const std::uint32_t at = start + b;
    const std::uint8_t mask = std::uint8_t(1u << (at % 8));
    if ((bits >> b) & 1u) data[at / 8] |= mask;
    else data[at / 8] &= std::uint8_t(~mask);
  }
}

std::int32_t get_field(const std::uint8_t* report, std::size_t size, bool with_id, const HidField& f,
                       std::uint32_t index) {
  const std::uint8_t* data = report + (with_id ? 1 : 0);
  const std::size_t data_bytes = size - (with_id ? 1 : 0);
  const std::uint32_t start = f.bit_offset + index * f.bit_size;
  std::uint32_t v = 0;
  for (std::uint32_t b = 0; b < f.bit_size; ++b) {
    const std::uint32_t at = start + b;
    if (at / 8 >= data_bytes) break;
    if ((data[at / 8] >> (at % 8)) & 1u) v |= 1u << b;
  }
  if (f.logical_min < 0 && f.bit_size < 32 && (v >> (f.bit_size - 1)) & 1u) v |= ~0u << f.bit_size;
  return static_cast<std::int32_t>(v);
}

}  // namespace contactcore::haptics
