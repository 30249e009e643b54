#include "contactcore/haptics/spacemouse.h"

#include <chrono>
#include <cstring>

#include <time.h>

#include <hidapi/hidapi.h>

namespace contactcore::haptics {

namespace {

constexpr ReportFormat kTwo = ReportFormat::TwoReports;
constexpr ReportFormat kSix = ReportFormat::SixAxes;

// spacenavd's table (dev.c): every HID 6-DOF model but the oldest two has its
// y and z swapped and inverted relative to spacenavd's frame.
const std::vector<SpaceMouseModel>& model_table() {
  static const std::vector<SpaceMouseModel> table = {
      {0x046d, 0xc603, "SpaceMouse Plus XT", kTwo, false, false},
      {0x046d, 0xc605, "CadMan", kTwo, true, true},
      {0x046d, 0xc606, "SpaceMouse Classic", kTwo, false, false},
      {0x046d, 0xc621, "SpaceBall 5000", kTwo, true, true},
      {0x046d, 0xc623, "SpaceTraveller", kTwo, true, true},
      {0x046d, 0xc625, "SpacePilot", kTwo, true, true},
      {0x046d, 0xc626, "SpaceNavigator", kTwo, true, true},
      {0x046d, 0xc627, "SpaceExplorer", kTwo, true, true},
      {0x046d, 0xc628, "SpaceNavigator for Notebooks", kTwo, true, true},
      {0x046d, 0xc629, "SpacePilot Pro", kTwo, true, true},
      {0x046d, 0xc62b, "SpaceMouse Pro", kTwo, true, true},
      {0x256f, 0xc62e, "SpaceMouse Wireless (cable)", kSix, true, true},
      {0x256f, 0xc62f, "SpaceMouse Wireless (receiver)", kSix, true, true},
      {0x256f, 0xc631, "SpaceMouse Pro Wireless (cable)", kSix, true, true},
      {0x256f, 0xc632, "SpaceMouse Pro Wireless (receiver)", kSix, true, true},
      {0x256f, 0xc633, "SpaceMouse Enterprise", kSix, true, true},
      {0x256f, 0xc635, "SpaceMouse Compact", kSix, true, true},
      {0x256f, 0xc636, "SpaceMouse Module", kSix, true, true},
      {0x256f, 0xc638, "SpaceMouse Pro Wireless", kSix, true, true},
      {0x256f, 0xc63a, "SpaceMouse Wireless", kSix, true, true},
      {0x256f, 0xc652, "3Dconnexion Universal Receiver", kSix, true, true},
  };
  return table;
}

std::int16_t le16(const std::uint8_t* p) {
  return static_cast<std::int16_t>(static_cast<std::uint16_t>(p[0]) |
                                   (static_cast<std::uint16_t>(p[1]) << 8));
}

// Raw HID axes (X Y Z Rx Ry Rz) to spacenavd's frame, normalised.
void map_axes(const SpaceMouseModel& model, SpaceMouseState& state) {
  double v[6];
  for (int i = 0; i < 6; ++i) v[i] = state.raw[i] / model.full_scale;
  if (model.swap_yz) {
    std::swap(v[1], v[2]);
    std::swap(v[4], v[5]);
  }
  if (model.invert_yz) {
    v[1] = -v[1];
    v[2] = -v[2];
    v[4] = -v[4];
    v[5] = -v[5];
  }
  for (int i = 0; i < 6; ++i) state.axes[i] = std::clamp(v[i], -1.0, 1.0);
}

}  // namespace

const std::vector<SpaceMouseModel>& known_models() { return model_table(); }

bool is_spacemouse_vendor(std::uint16_t vendor) { return vendor == 0x046d || vendor == 0x256f; }

bool is_excluded_product(std::uint16_t vendor, std::uint16_t product) {
  if (vendor != 0x256f) return false;
  switch (product) {
    case 0xc650: case 0xc651: case 0xc654: case 0xc655: case 0xc656: case 0xc657:
    case 0xc658: case 0xc62c: case 0xc641:
      return true;
    default:
      return false;
  }
}

const SpaceMouseModel* find_model(std::uint16_t vendor, std::uint16_t product) {
  for (const auto& m : model_table())
    if (m.vendor == vendor && m.product == product) return &m;
  return nullptr;
}

SpaceMouseModel generic_model(std::uint16_t vendor, std::uint16_t product) {
  SpaceMouseModel m;
  m.vendor = vendor;
  m.product = product;
  m.name = "3Dconnexion device";
  m.format = vendor == 0x256f ? kSix : kTwo;
  m.swap_yz = m.invert_yz = true;
  return m;
}

bool parse_report(const std::uint8_t* data, std::size_t size, const SpaceMouseModel& model,
                  SpaceMouseState& state) {
  if (!data || size < 2) return false;
  switch (data[0]) {
    case 1:
      if (size >= 13 && model.format == ReportFormat::SixAxes) {
        for (int i = 0; i < 6; ++i) state.raw[i] = le16(data + 1 + 2 * i);
      } else if (size >= 7) {
        for (int i = 0; i < 3; ++i) state.raw[i] = le16(data + 1 + 2 * i);
      } else {
        return false;
      }
      break;
    case 2:
      if (size < 7) return false;
      for (int i = 0; i < 3; ++i) state.raw[3 + i] = le16(data + 1 + 2 * i);
      break;
    case 3: {
      std::uint32_t bits = 0;
      for (std::size_t i = 1; i < size && i <= 4; ++i) bits |= std::uint32_t(data[i]) << (8 * (i - 1));
      state.buttons = bits;
      break;
    }
    default:
      return false;
  }
  map_axes(model, state);
  ++state.reports;
  return true;
}

bool descriptor_has_pid_page(const std::uint8_t* d, std::size_t size) {
  // HID short items: prefix bSize (bits 0-1: 0,1,2,4 bytes), bType (2-3), bTag (4-7).
  std::size_t i = 0;
  while (i < size) {
    const std::uint8_t prefix = d[i];
    if (prefix == 0xFE) {  // long item: size in the next byte
      if (i + 1 >= size) return false;
      i += 3 + d[i + 1];
      continue;
    }
    const std::size_t n = (prefix & 3) == 3 ? 4 : (prefix & 3);
    if (i + n >= size) return false;
    if ((prefix & 0xFC) == 0x04) {  // global item, tag 0: Usage Page
      std::uint32_t page = 0;
      for (std::size_t k = 0; k < n; ++k) page |= std::uint32_t(d[i + 1 + k]) << (8 * k);
      if (page == 0x0F) return true;
    }
    i += 1 + n;
  }
  return false;
}

double steady_seconds() {
  timespec t{};
  clock_gettime(CLOCK_MONOTONIC, &t);  // the clock the loop's absolute deadlines use
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

DeviceCapabilities spacemouse_capabilities(const std::string& name) {
  DeviceCapabilities caps;
  caps.name = name;
  caps.input_dof = 6;
  caps.control = ControlMode::Rate;
  return caps;
}

// ---- hidapi back-end

std::vector<HidSpaceMouse::Found> HidSpaceMouse::enumerate() {
  std::vector<Found> found;
  if (hid_init() != 0) return found;
  for (std::uint16_t vendor : {std::uint16_t(0x046d), std::uint16_t(0x256f)}) {
    hid_device_info* list = hid_enumerate(vendor, 0);
    for (hid_device_info* d = list; d; d = d->next) {
      if (is_excluded_product(d->vendor_id, d->product_id)) continue;
      const SpaceMouseModel* model = find_model(d->vendor_id, d->product_id);
      // Logitech (0x046d) makes much else: only its known 3Dconnexion products.
      if (!model && d->vendor_id == 0x046d) continue;
      Found f;
      f.name = model ? model->name : "3Dconnexion device";
      f.path = d->path ? d->path : "";
      f.vendor = d->vendor_id;
      f.product = d->product_id;
      found.push_back(std::move(f));
    }
    hid_free_enumeration(list);
  }
  return found;
}

HidSpaceMouse::HidSpaceMouse(std::shared_ptr<HidRecorder> recorder)
    : caps_(spacemouse_capabilities("SpaceMouse (hidapi)")), recorder_(std::move(recorder)) {
  description_ = "no 3Dconnexion 6-DOF device found";
  reader_ = std::thread([this] { run(); });
}

HidSpaceMouse::~HidSpaceMouse() {
  stop_ = true;
  if (reader_.joinable()) reader_.join();
}

std::string HidSpaceMouse::description() const {
  std::lock_guard<std::mutex> lock(description_mutex_);
  return description_;
}

void HidSpaceMouse::run() {
  const double rescan_period = 0.5;
  double next_scan = 0;
  hid_device* handle = nullptr;
  SpaceMouseModel model;
  SpaceMouseState state;
  std::uint8_t buffer[64];
  auto publish = [&](double t) {
    Reading r;
    r.axes = state.axes;
    r.buttons = state.buttons;
    r.arrival = t;
    readings_.write(r);
  };
  while (!stop_) {
    if (!handle) {
      const double now = steady_seconds();
      if (now < next_scan) {
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
        continue;
      }
      next_scan = now + rescan_period;
      auto found = enumerate();
      if (found.empty()) continue;
      handle = hid_open_path(found.front().path.c_str());
      if (!handle) {
        std::lock_guard<std::mutex> lock(description_mutex_);
        description_ = "cannot open " + found.front().path + " (permissions: add a udev rule)";
        continue;
      }
      const SpaceMouseModel* known = find_model(found.front().vendor, found.front().product);
      model = known ? *known : generic_model(found.front().vendor, found.front().product);
      state = SpaceMouseState{};
      if (recorder_) recorder_->set_device("spacemouse", model.vendor, model.product, model.name, {});
      {
        std::lock_guard<std::mutex> lock(description_mutex_);
        description_ = std::string(model.name) + " at " + found.front().path;
      }
      publish(steady_seconds());
      connected_ = true;
    }
    const int n = hid_read_timeout(handle, buffer, sizeof buffer, 50);
    if (n < 0) {  // unplugged
      if (recorder_) recorder_->unplugged(steady_seconds());
      hid_close(handle);
      handle = nullptr;
      connected_ = false;
      state = SpaceMouseState{};
      publish(steady_seconds());
      std::lock_guard<std::mutex> lock(description_mutex_);
      description_ = "device unplugged; waiting for it";
      continue;
    }
    if (n > 0) {
      const double arrival = steady_seconds();
      if (recorder_) recorder_->report(arrival, buffer, static_cast<std::size_t>(n));
      if (parse_report(buffer, static_cast<std::size_t>(n), model, state)) publish(arrival);
    }
  }
  if (handle) hid_close(handle);
  hid_exit();
}

DeviceSample HidSpaceMouse::read(double now) noexcept {
  DeviceSample s;
  const Reading& r = readings_.read();  // wait-free: no retry on the loop's thread
  s.axes = r.axes;
  s.buttons = r.buttons;
  s.connected = connected_.load(std::memory_order_acquire);
  // The report's arrival on the loop's clock (its age is what the watchdog judges).
  s.time = now - std::max(0.0, steady_seconds() - r.arrival);
  // A SpaceMouse sends reports while deflected and falls silent at rest.
  s.at_rest = s.axes.isZero(0.0);
  return s;
}

// ---- replay

ReplayDevice::ReplayDevice(SpaceMouseModel model, std::vector<RecordedReport> reports)
    : caps_(spacemouse_capabilities(std::string("replay of ") + model.name)),
      model_(model),
      reports_(std::move(reports)) {}

ReplayDevice::ReplayDevice(PidLayout layout, const PidForceConfig& config, std::vector<RecordedReport> reports)
    : model_(generic_model(0, 0)),
      pid_(true),
      layout_(std::move(layout)),
      pid_config_(config),
      reports_(std::move(reports)) {
  caps_.name = "replay of " + config.name;
  caps_.control = config.control;
  caps_.input_dof = 0;
  for (int a = 0; a < (config.control == ControlMode::Position ? 3 : 6); ++a)
    caps_.input_dof += layout_.input_axes[a].found() ? 1 : 0;
  caps_.workspace_radius = config.control == ControlMode::Position ? config.workspace_mm : 0;
}

DeviceSample ReplayDevice::read(double now) noexcept {
  while (next_ < reports_.size() && reports_[next_].time <= now) {
    const auto& r = reports_[next_++];
    if (r.bytes.empty()) {
      connected_ = !connected_;
      if (!connected_) {
        state_ = SpaceMouseState{};
        pid_axes_.setZero();
        pid_velocity_.setZero();
        reported_ = false;
      }
    } else if (connected_ && pid_) {
      Vec6 axes = pid_axes_;
      if (parse_pid_input(layout_, r.bytes.data(), r.bytes.size(), axes)) {
        const double dt = r.time - last_report_;
        if (reported_ && dt > 1e-6) pid_velocity_ = (axes - pid_axes_) / dt;
        pid_axes_ = axes;
        reported_ = true;
      }
    } else if (connected_) {
      parse_report(r.bytes.data(), r.bytes.size(), model_, state_);
    }
    last_report_ = r.time;
  }
  DeviceSample s;
  s.connected = connected_;
  s.time = last_report_;  // arrival, as recorded: the watchdog sees the recorded gaps
  if (pid_ && pid_config_.control == ControlMode::Position) {
    for (int a = 0; a < 3; ++a) {
      s.pose.translation() += pid_axes_[a] * pid_config_.workspace_mm * pid_config_.axis_directions[a];
      s.velocity.head<3>() += pid_velocity_[a] * pid_config_.workspace_mm * pid_config_.axis_directions[a];
    }
    return s;
  }
  s.axes = pid_ ? pid_axes_ : state_.axes;
  s.buttons = state_.buttons;
  s.at_rest = s.axes.isZero(0.0);
  return s;
}

}  // namespace contactcore::haptics
