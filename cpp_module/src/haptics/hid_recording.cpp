#include "contactcore/haptics/hid_recording.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

namespace contactcore::haptics {

namespace {

std::string hex(const std::vector<std::uint8_t>& bytes) {
  static const char* digits = "0123456789abcdef";
  std::string out;
  out.reserve(bytes.size() * 2);
  for (std::uint8_t b : bytes) {
    out.push_back(digits[b >> 4]);
    out.push_back(digits[b & 15]);
  }
  return out;
}

bool from_hex(const std::string& text, std::vector<std::uint8_t>& out) {
  if (text.size() % 2) return false;
  out.clear();
  for (std::size_t i = 0; i < text.size(); i += 2) {
    unsigned value = 0;
    for (int k = 0; k < 2; ++k) {
      const char c = text[i + k];
      unsigned d;
      if (c >= '0' && c <= '9') d = c - '0';
      else if (c >= 'a' && c <= 'f') d = c - 'a' + 10;
      else if (c >= 'A' && c <= 'F') d = c - 'A' + 10;
      else return false;
      value = value * 16 + d;
    }
    out.push_back(static_cast<std::uint8_t>(value));
  }
  return true;
}

Status file_error(const std::string& path, int line, const std::string& what) {
  Status s = Status::failure(StatusCode::ReadError,
                             line > 0 ? "line " + std::to_string(line) + ": " + what : what);
  s.file = path;
  return s;
}

}  // namespace

HidRecorder::HidRecorder(double origin) : origin_(origin) {}

void HidRecorder::set_device(const std::string& kind, std::uint16_t vendor, std::uint16_t product,
                             const std::string& name, std::vector<std::uint8_t> descriptor) {
  std::lock_guard<std::mutex> lock(mutex_);
  recording_.kind = kind;
  recording_.vendor = vendor;
  recording_.product = product;
  recording_.name = name;
  recording_.descriptor = std::move(descriptor);
}

void HidRecorder::report(double arrival, const std::uint8_t* data, std::size_t size) {
  if (!data || size == 0) return;
  std::lock_guard<std::mutex> lock(mutex_);
  recording_.reports.push_back(RecordedReport{std::max(0.0, arrival - origin_), {data, data + size}});
}

void HidRecorder::unplugged(double arrival) {
  std::lock_guard<std::mutex> lock(mutex_);
  recording_.reports.push_back(RecordedReport{std::max(0.0, arrival - origin_), {}});
}

HidRecording HidRecorder::recording() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return recording_;
}

std::size_t HidRecorder::size() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return recording_.reports.size();
}

Status write_hid_recording(const HidRecording& r, const std::string& path) {
  std::ofstream out(path);
  if (!out) return file_error(path, 0, std::string("cannot write: ") + std::strerror(errno));
  char ids[32];
  std::snprintf(ids, sizeof ids, "%04x %04x", r.vendor, r.product);
  out << "contacts-hid-recording 1\n";
  out << "device " << r.kind << ' ' << ids << ' ' << (r.name.empty() ? "unnamed" : r.name) << '\n';
  if (!r.descriptor.empty()) out << "descriptor " << hex(r.descriptor) << '\n';
  char t[32];
  for (const RecordedReport& report : r.reports) {
    std::snprintf(t, sizeof t, "%.6f", report.time);
    out << t << ' ' << (report.bytes.empty() ? std::string("unplug") : hex(report.bytes)) << '\n';
  }
  out.flush();
  if (!out) return file_error(path, 0, std::string("cannot write: ") + std::strerror(errno));
  return Status::success();
}

Status read_hid_recording(const std::string& path, HidRecording& r) {
  r = HidRecording{};
  std::ifstream in(path);
  if (!in) return file_error(path, 0, std::string("cannot read: ") + std::strerror(errno));
  std::string line;
  int number = 0;
  bool header = false, device = false;
  double last = 0;
  while (std::getline(in, line)) {
    ++number;
    if (const auto hash = line.find('#'); hash != std::string::npos) line.erase(hash);
    std::istringstream words(line);
    std::string first;
    if (!(words >> first)) continue;
    if (!header) {
      int version = 0;
      if (first != "contacts-hid-recording" || !(words >> version))
        return file_error(path, number, "not a HID recording (expected 'contacts-hid-recording 1')");
      if (version != 1) return file_error(path, number, "unsupported version " + std::to_string(version));
      header = true;
      continue;
    }
    if (first == "device") {
      std::string vendor, product;
      if (!(words >> r.kind >> vendor >> product) || (r.kind != "spacemouse" && r.kind != "hid-ff"))
        return file_error(path, number, "expected 'device <spacemouse|hid-ff> <vendor hex> <product hex> <name>'");
      try {
        r.vendor = static_cast<std::uint16_t>(std::stoul(vendor, nullptr, 16));
        r.product = static_cast<std::uint16_t>(std::stoul(product, nullptr, 16));
      } catch (const std::exception&) {
        return file_error(path, number, "vendor and product must be hexadecimal");
      }
      std::getline(words >> std::ws, r.name);
      device = true;
      continue;
    }
    if (first == "descriptor") {
      std::string bytes;
      if (!(words >> bytes) || !from_hex(bytes, r.descriptor))
        return file_error(path, number, "the descriptor must be hexadecimal bytes");
      continue;
    }
    double t = 0;
    try {
      std::size_t used = 0;
      t = std::stod(first, &used);
      if (used != first.size()) throw std::invalid_argument(first);
    } catch (const std::exception&) {
      return file_error(path, number, "expected '<arrival s> <hex bytes|unplug>', got '" + first + "'");
    }
    if (!std::isfinite(t) || t < last)
      return file_error(path, number, "arrival times must be finite and not decrease");
    last = t;
    std::string bytes;
    if (!(words >> bytes)) return file_error(path, number, "a report needs its bytes (hex) or 'unplug'");
    RecordedReport report;
    report.time = t;
    if (bytes != "unplug" && (!from_hex(bytes, report.bytes) || report.bytes.empty()))
      return file_error(path, number, "report bytes must be hexadecimal");
    r.reports.push_back(std::move(report));
  }
  if (!header) return file_error(path, 0, "empty file: not a HID recording");
  if (!device) return file_error(path, 0, "no 'device' line: which parser replays it is unknown");
  if (r.kind == "hid-ff" && r.descriptor.empty())
    return file_error(path, 0, "a hid-ff recording needs its 'descriptor' line");
  return Status::success();
}

}  // namespace contactcore::haptics
