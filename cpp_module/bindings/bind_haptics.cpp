// Haptic trials: the SpaceMouse parser and device list, the trial scene, the
// headless scripted trial, and a live session (device + 1 kHz loop on its own
// thread) for the panel. The loop never touches Python: the session's
// methods exchange values with it through atomics and a snapshot.
// Results are classes (haptic_results.h/.cpp).
#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <utility>

#include "contactcore/haptics/joint_adapter.h"
#include "contactcore/haptics/pose_math.h"
#include "haptic_results.h"

namespace contactcore::bindings {

using namespace contactcore::haptics;

namespace {

Vec3 vec_from(const py::handle& value, const char* what) {
  auto seq = value.cast<std::vector<double>>();
  if (seq.size() != 3) raise_argument_error(std::string(what) + ": three numbers expected");
  return {seq[0], seq[1], seq[2]};
}

// The pose of an offset (translate mm, rotate_deg degrees about x, y, z)
// from the assembled placement, about `centre`.
Pose pose_from(const Vec3& translate, const Vec3& rotate_deg, const Vec3& centre) {
  return offset_pose(translate, Vec3(rad(rotate_deg.x()), rad(rotate_deg.y()), rad(rotate_deg.z())), centre);
}
Pose pose_from(const py::handle& translate, const py::handle& rotate_deg, const Vec3& centre) {
  return pose_from(vec_from(translate, "translate"), vec_from(rotate_deg, "rotate_deg"), centre);
}

ScriptKey key_from(const py::dict& d, bool timed) {
  ScriptKey k;
  if (timed) k.t = d.contains("t") ? d["t"].cast<double>() : 0.0;
  if (d.contains("translate")) k.translate = vec_from(d["translate"], "translate");
  if (d.contains("rotate_deg")) k.rotate_deg = vec_from(d["rotate_deg"], "rotate_deg");
  return k;
}

// (arrival s, bytes) pairs as recorded reports.
std::vector<RecordedReport> reports_from(const py::handle& pairs) {
  std::vector<RecordedReport> reports;
  for (const py::handle& item : pairs.cast<py::list>()) {
    auto pair = item.cast<py::tuple>();
    RecordedReport report;
    report.time = pair[0].cast<double>();
    const std::string b = pair[1].cast<py::bytes>();
    report.bytes.assign(b.begin(), b.end());
    reports.push_back(std::move(report));
  }
  return reports;
}

bool joint_of_pair(TrialScene& scene, const PairJoint& pair, JointState& joint) {
  if (!joint_state_from_pair(pair, scene.moving(), scene.centre(), scene.contacts().body_box(scene.moving()), joint))
    return false;
  scene.attach_collision_group(joint);
  return true;
}

py::object& device_unavailable_error() {
  static py::object error;
  return error;
}

// A failed device request as an exception: DeviceUnavailable carries the
// HID devices seen (`devices`, [HidDeviceSeen]), others go through raise_if_failed.
[[noreturn]] void raise_device_error(const DeviceResult& r) {
  if (r.device_missing) {
    py::object error = device_unavailable_error()(r.status.describe());
    error.attr("devices") = py::cast(r.seen);
    error.attr("reason") = r.message;
    PyErr_SetObject(device_unavailable_error().ptr(), error.ptr());
    throw py::error_already_set();
  }
  raise_if_failed(r.status);
  throw std::logic_error("raise_device_error on success");
}

HidRecording recording_from(const py::object& path) {
  HidRecording recording;
  const Status status = read_hid_recording(path.cast<std::string>(), recording);
  raise_if_failed(status);
  return recording;
}

// A device and the loop on its own thread, for the panel. The device comes
// from the factory (device_factory.h); without the hardware asked for, the
// simulated hand, and `message` says why.
class HapticSession {
 public:
  HapticSession(TrialScene& scene, const std::string& device, const Vec3& translate, const Vec3& rotate_deg,
                const ServoConfig& config, HidRecording replay)
      : scene_(scene) {
    const Vec3 c = scene.centre();
    start_ = pose_from(translate, rotate_deg, c);
    DeviceRequest request;
    request.kind = device;
    request.centre = c;
    request.start = start_;
    request.replay = std::move(replay);
    request.fall_back_to_simulated = true;
    DeviceResult opened;
    {
      py::gil_scoped_release release;
      opened = open_device(request);
    }
    if (!opened.status.ok()) raise_device_error(opened);
    device_ = std::move(opened.device);
    hand_ = opened.hand;
    message_ = opened.message;
    if (device == "sim") message_ = "Simulated hand (scripted, or driven from the panel).";
    ServoConfig cfg = config;
    cfg.centre = c;
    loop_ = std::make_unique<ServoLoop>(*device_, cfg, start_);
    loop_->set_joint_finder(&scene.finder());
    loop_->set_collision(&scene.collision());
  }
  ~HapticSession() { loop_->stop(); }

  // The loop holds the part to the joint of an assembled pair (from the joints
  // stage) instead of the joint engagement finds; false when the loop cannot
  // hold that type.
  bool hold_to_pair(const PairJoint& pair) {
    JointState joint;
    if (!joint_of_pair(scene_, pair, joint)) return false;
    loop_->request_hold(joint);
    return true;
  }

  void set_hand_target(const Vec3& t, const Vec3& r_deg) {
    if (!hand_) return;
    hand_->set_live_target(pose_from(t, r_deg, scene_.centre()));
  }

  SessionSnapshot snapshot() const {
    SessionSnapshot out;
    const ServoSnapshot& s = out.loop = loop_->snapshot();
    const Vec3 c = scene_.centre();
    out.offset = offset_from(s.proxy, c);
    out.target = offset_from(s.target, c);
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) out.matrix[i][j] = s.proxy.matrix()(i, j);
    for (int k = 0; s.engaged && k < s.joint.body_count; ++k) out.joint_with.push_back(scene_.body_names()[s.joint.bodies[k]]);
    // The joint's one-sided stops (n . p <= limit on the reference point, or
    // on the stop's own point of the part), active when the part is on them
    // (within 1 um): the panel's readout.
    for (int k = 0; s.engaged && k < s.joint.stop_count; ++k) {
      const double gap = s.joint.stops[k].limit - s.joint.stops[k].normal.dot(stop_point(s.joint.stops[k], s.proxy, c));
      out.stops.push_back({triple(s.joint.stops[k].normal), gap, gap < 1e-3});
    }
    out.realtime_priority = loop_->got_realtime_priority();
    return out;
  }

  TrialScene& scene_;
  Pose start_;
  std::unique_ptr<Device> device_;
  SimulatedHand* hand_ = nullptr;
  std::unique_ptr<ServoLoop> loop_;
  std::string message_;
};

// The servo loop's keyword options, each read by name from one table: a
// misspelt one is an ArgumentError naming it, never silently the default.
template <class Value>
std::pair<const char*, std::function<void(ServoConfig&, const py::handle&)>> option(const char* name,
                                                                                    Value ServoConfig::*member) {
  return {name, [member](ServoConfig& c, const py::handle& value) { c.*member = value.cast<Value>(); }};
}

ServoConfig config_from(const py::kwargs& kw) {
  static const std::vector<std::pair<const char*, std::function<void(ServoConfig&, const py::handle&)>>> kOptions = {
      option("stiffness", &ServoConfig::stiffness),         option("angular_stiffness", &ServoConfig::angular_stiffness),
      option("damping", &ServoConfig::damping),             option("angular_damping", &ServoConfig::angular_damping),
      option("max_speed", &ServoConfig::max_speed),         option("breakaway_force", &ServoConfig::breakaway_force),
      option("rate_hz", &ServoConfig::rate_hz),             option("realtime_priority", &ServoConfig::realtime_priority),
      option("friction", &ServoConfig::friction)};
  ServoConfig c;
  for (const auto& item : kw) {
    const std::string key = py::str(item.first);
    const auto known = std::find_if(kOptions.begin(), kOptions.end(), [&](const auto& o) { return key == o.first; });
    if (known == kOptions.end()) {
      std::string names;
      for (const auto& o : kOptions) names += (names.empty() ? "" : ", ") + std::string(o.first);
      raise_argument_error("unknown keyword option '" + key + "' (the options: " + names + ")");
    }
    known->second(c, item.second);
  }
  if (!(c.friction >= 0) || !std::isfinite(c.friction))
    raise_argument_error("friction must be a finite number >= 0 (Coulomb's coefficient), got " +
                         std::to_string(c.friction));
  return c;
}

// run_trial: the scripted simulated hand, or a device from the factory.
TrialRun run_trial_binding(TrialScene& scene, const py::dict& script, bool realtime, int record_every, double settle,
                           const std::string& device, const py::object& hid_file, const py::object& record_hid,
                           const py::object& duration, const py::kwargs& kw) {
  TrialScript s;
  if (script.contains("start")) s.start = key_from(script["start"].cast<py::dict>(), false);
  const bool scripted_hand = device == "sim";
  if (scripted_hand && !script.contains("hand")) raise_argument_error("script: 'hand' (a list of keys) is missing");
  if (script.contains("hand"))
    for (const py::handle& k : script["hand"].cast<py::list>()) s.hand.push_back(key_from(k.cast<py::dict>(), true));
  if (scripted_hand && s.hand.empty()) raise_argument_error("script: 'hand' is empty");
  TrialOptions options;
  options.servo = config_from(kw);
  options.record_every = record_every;
  options.settle = settle;
  // Any other device comes from the factory; the run lasts `duration`
  // (a replay: its last report + settle; a live device: the script's
  // keys + settle, or 10 s).
  DeviceResult opened;
  if (!scripted_hand) {
    DeviceRequest request;
    request.kind = device;
    request.centre = scene.centre();
    request.start = pose_from(s.start.translate, s.start.rotate_deg, scene.centre());
    if (device == "replay") {
      if (hid_file.is_none()) raise_argument_error("--device replay needs a recording (hid_file)");
      request.replay = recording_from(hid_file);
    }
    request.record = !record_hid.is_none();
    {
      py::gil_scoped_release release;
      opened = open_device(request);
    }
    if (!opened.status.ok()) raise_device_error(opened);
    options.device = opened.device.get();
    if (!duration.is_none()) options.duration = duration.cast<double>();
    else if (device == "replay" && !request.replay.reports.empty())
      options.duration = request.replay.reports.back().time + settle;
    else options.duration = (s.hand.empty() ? 10.0 : s.hand.back().t + settle);
    if (options.duration <= 0) raise_argument_error("duration must be > 0 s");
    // Hardware runs on the wall clock; a replay is deterministic in lockstep.
    if (device == "spacemouse" || device == "hid-ff") realtime = true;
  } else if (!record_hid.is_none()) {
    raise_argument_error("--record-hid records a HID device (spacemouse, hid-ff), not the simulated hand");
  }
  TrialRun run;
  run.result = call_guarded([&] { return run_trial(scene, s, options, realtime); });
  if (opened.recorder) {
    opened.device.reset();  // the reader thread stops: the recording is complete
    raise_if_failed(write_hid_recording(opened.recorder->recording(), record_hid.cast<std::string>()));
  }
  run.device = device;
  run.device_message = opened.message.empty() ? std::string("Simulated hand.") : opened.message;
  return run;
}

}  // namespace

void bind_haptics(py::module_& root) {
  py::module_ m = root.def_submodule("haptics", "Haptic trials: devices, the 1 kHz servo loop, real-time contacts");
  bind_haptic_results(m);

  m.def(
      "parse_spacemouse_report",
      [](std::uint16_t vendor, std::uint16_t product, const py::bytes& report) {
        const SpaceMouseModel* known = find_model(vendor, product);
        const SpaceMouseModel model = known ? *known : generic_model(vendor, product);
        const std::string data = report;
        SpaceMouseState state;
        SpaceMouseReport out;
        out.understood = parse_report(reinterpret_cast<const std::uint8_t*>(data.data()), data.size(), model, state);
        for (int i = 0; i < 6; ++i) {
          out.raw[i] = state.raw[i];
          out.axes[i] = state.axes[i];
        }
        out.buttons = state.buttons;
        out.model = model.name;
        return out;
      },
      py::arg("vendor"), py::arg("product"), py::arg("report"),
      "Parses one SpaceMouse HID input report (report ID first) from a fresh state: a SpaceMouseReport.");

  m.def("spacemouse_devices", [] {
    py::gil_scoped_release release;
    return HidSpaceMouse::enumerate();
  }, "The 3Dconnexion 6-DOF devices hidapi sees now ([SpaceMouseFound], empty without hardware).");

  m.def("hid_force_feedback_devices", [] {
    py::gil_scoped_release release;
    return enumerate_hid_pid_devices();
  }, "HID devices whose report descriptor offers PID constant force ([HidPidFound], empty without hardware).");

  m.def(
      "hid_pid_capabilities",
      [](const py::bytes& descriptor, double full_scale_force) {
        const std::string data = descriptor;
        PidLayout layout;
        PidCapabilities out;
        if (!find_pid_layout(reinterpret_cast<const std::uint8_t*>(data.data()), data.size(), layout, &out.why))
          return out;
        PidForceConfig config;
        config.full_scale_force = full_scale_force;
        config.start_thread = false;
        HidPidDevice device(nullptr, layout, config);
        out.capabilities = device.capabilities();
        out.force_output = out.capabilities->force_output;
        out.axes = layout.axis_count();
        return out;
      },
      py::arg("descriptor"), py::arg("full_scale_force") = 3.0,
      "What a device with this HID report descriptor can render (PidCapabilities: force output through the "
      "PID page, or why not).");

  m.def("simulated_capabilities", [] { return simulated_capabilities(); }, "The simulated hand's DeviceCapabilities.");

  device_unavailable_error() = py::reinterpret_borrow<py::object>(py::handle(PyErr_NewException(
      "contactcore.haptics.DeviceUnavailable", root.attr("ContactsError").ptr(), nullptr)));
  m.attr("DeviceUnavailable") = device_unavailable_error();

  m.def("hid_devices_seen", [] {
    py::gil_scoped_release release;
    return enumerate_hid_devices();
  }, "Every HID device hidapi lists now ([HidDeviceSeen]).");

  m.def("read_hid_recording", [](const std::string& path) { return recording_from(py::str(path)); }, py::arg("path"),
        "A HID recording (--record-hid): a HidRecording (device kind, ids, descriptor and (arrival s, bytes) reports).");

  m.def(
      "write_hid_recording",
      [](const std::string& path, const std::string& kind, int vendor, int product, const std::string& name,
         const py::list& reports, const py::bytes& descriptor) {
        HidRecording r;
        r.kind = kind;
        r.vendor = static_cast<std::uint16_t>(vendor);
        r.product = static_cast<std::uint16_t>(product);
        r.name = name;
        const std::string desc = descriptor;
        r.descriptor.assign(desc.begin(), desc.end());
        r.reports = reports_from(reports);
        raise_if_failed(write_hid_recording(r, path));
      },
      py::arg("path"), py::arg("kind"), py::arg("vendor"), py::arg("product"), py::arg("name"), py::arg("reports"),
      py::arg("descriptor") = py::bytes(), "Writes a HID recording file (the format --record-hid writes).");

  py::class_<TrialScene>(m, "TrialScene", "Partitions, real-time contacts and collision models for one moving part.")
      .def(py::init([](const Assembly& assembly, const std::string& part, double capture_distance,
                       double capture_angle_deg, double deflection, py::object progress, bool closed_forms) {
             std::unique_ptr<PythonProgress> reporter;
             if (!progress.is_none()) reporter = std::make_unique<PythonProgress>(progress);
             SceneOptions options;
             options.capture.distance = capture_distance;
             options.capture.angle = rad(capture_angle_deg);
             options.deflection = deflection;
             options.analytic = closed_forms;
             std::unique_ptr<TrialScene> scene;
             const Status status = guarded([&] {
               Status built;
               scene = TrialScene::build(assembly, part, options, built, reporter.get());
               return built;
             });
             if (reporter) reporter->rethrow_if_raised();  // the callback's own exception, as raised
             raise_if_failed(status);
             return scene;
           }),
           py::arg("assembly"), py::arg("part"), py::arg("capture_distance") = 0.5,
           py::arg("capture_angle_deg") = 2.0, py::arg("deflection") = 0.01, py::arg("progress") = py::none(),
           py::arg("closed_forms") = true,
           "closed_forms: contacts between analytic partitions in closed form, the meshes for the rest (False: "
           "the meshes alone, for comparison).")
      .def_property_readonly("part", &TrialScene::part_name)
      .def_property_readonly("moving", &TrialScene::moving, "Index of the moving part in the assembly.")
      .def(
          "joint_of_pair",
          [](TrialScene& s, const PairJoint& pair) -> std::optional<HeldJoint> {
            JointState j;
            if (!joint_of_pair(s, pair, j)) return std::nullopt;
            return HeldJoint{to_string(j.kind), triple(j.axis), triple(j.point), j.stop_count, j.group};
          },
          py::arg("pair"),
          "The joint the loop would hold the part to for this assembled pair (a HeldJoint), "
          "or None when the pair does not involve the part or the loop cannot hold its type.")
      .def_property_readonly("centre", [](const TrialScene& s) { return triple(s.centre()); })
      .def_property_readonly("body_names", &TrialScene::body_names)
      .def_property_readonly("setup_seconds", &TrialScene::setup_seconds)
      .def_property_readonly("triangles", [](TrialScene& s) { return s.collision().triangle_count(); })
      .def(
          "contacts_at",
          [](TrialScene& s, const py::object& translate, const py::object& rotate_deg) {
            std::vector<LiveContact> live(256);
            const int n = s.contacts().update(pose_from(translate, rotate_deg, s.centre()), live.data(), 256);
            std::vector<LiveContactSeen> out;
            for (int i = 0; i < n; ++i)
              out.push_back({to_string(live[i].type), s.body_names()[live[i].body], live[i].distance, deg(live[i].angle)});
            return out;
          },
          py::arg("translate"), py::arg("rotate_deg"),
          "Real-time contacts ([LiveContact]) of the part displaced by (translate mm, rotate_deg) from its placement.")
      .def(
          "collides",
          [](TrialScene& s, const py::object& translate, const py::object& rotate_deg) {
            return s.collision().collides(pose_from(translate, rotate_deg, s.centre()), -1);
          },
          py::arg("translate"), py::arg("rotate_deg"));

  m.def("run_trial", &run_trial_binding, py::arg("scene"), py::arg("script"), py::arg("realtime") = false,
        py::arg("record_every") = 10, py::arg("settle") = 1.5, py::arg("device") = "sim",
        py::arg("hid_file") = py::none(), py::arg("record_hid") = py::none(), py::arg("duration") = py::none(),
        "Runs a trial: the scripted simulated hand (device 'sim', lockstep unless realtime), or a device from "
        "the factory: 'spacemouse', 'hid-ff' (real time; record_hid=FILE keeps their raw reports), 'replay' "
        "(hid_file=FILE, lockstep), 'sim-hid-ff'. Returns a TrialResult. Raises DeviceUnavailable (with "
        ".devices) when the hardware is not there. Keyword options: "
        "stiffness, angular_stiffness, damping, angular_damping, max_speed, breakaway_force, rate_hz, "
        "realtime_priority (SCHED_FIFO priority of the loop thread when permitted), friction (Coulomb's "
        "coefficient at the part's contacts, 0: none).");

  py::class_<HapticSession>(m, "HapticSession", "A device and the 1 kHz loop on its own thread.")
      .def(py::init([](TrialScene& scene, const std::string& device, const py::object& translate,
                       const py::object& rotate_deg, py::object replay, int vendor, int product,
                       py::object hid_file, const py::kwargs& kw) {
             // A replay: a recording file, or (time, bytes) pairs of a SpaceMouse (vendor, product).
             HidRecording recording;
             if (!hid_file.is_none()) {
               recording = recording_from(hid_file);
             } else if (!replay.is_none()) {
               recording.kind = "spacemouse";
               recording.vendor = static_cast<std::uint16_t>(vendor);
               recording.product = static_cast<std::uint16_t>(product);
               recording.reports = reports_from(replay);
             }
             return std::make_unique<HapticSession>(scene, device, vec_from(translate, "translate"),
                                                    vec_from(rotate_deg, "rotate_deg"), config_from(kw),
                                                    std::move(recording));
           }),
           py::arg("scene"), py::arg("device") = "sim", py::arg("translate") = std::vector<double>{0, 0, 0},
           py::arg("rotate_deg") = std::vector<double>{0, 0, 0}, py::arg("replay") = py::none(),
           py::arg("vendor") = 0x256f, py::arg("product") = 0xc635, py::arg("hid_file") = py::none(),
           py::keep_alive<1, 2>())
      .def_property_readonly("message", [](const HapticSession& s) { return s.message_; })
      .def_property_readonly("capabilities", [](const HapticSession& s) { return s.device_->capabilities(); },
                             "The device's DeviceCapabilities.")
      .def("start", [](HapticSession& s) { return s.loop_->start(); })
      .def("stop", [](HapticSession& s) {
        py::gil_scoped_release release;
        s.loop_->stop();
      })
      .def_property_readonly("running", [](const HapticSession& s) { return s.loop_->running(); })
      .def("step", [](HapticSession& s, int ticks) {
        if (s.loop_->running()) raise_argument_error("the loop is running on its thread");
        py::gil_scoped_release release;
        for (int i = 0; i < ticks; ++i) s.loop_->step_lockstep();
      }, py::arg("ticks"), "Lockstep ticks (with the thread stopped).")
      .def("set_enabled", [](HapticSession& s, bool on) { s.loop_->set_enabled(on); })
      .def("set_stiffness", [](HapticSession& s, double k, double kr) { s.loop_->set_stiffness(k, kr); })
      .def("set_damping", [](HapticSession& s, double b, double br) { s.loop_->set_damping(b, br); })
      .def("set_friction", [](HapticSession& s, double mu) {
        if (!(mu >= 0) || !std::isfinite(mu)) raise_argument_error("friction must be a finite number >= 0");
        s.loop_->set_friction(mu);
      }, py::arg("mu"), "Coulomb friction coefficient at the part's contacts (0: none).")
      .def("set_hand_target", [](HapticSession& s, const py::object& t, const py::object& r) {
        s.set_hand_target(vec_from(t, "translate"), vec_from(r, "rotate_deg"));
      }, py::arg("translate"), py::arg("rotate_deg"))
      .def("snapshot", &HapticSession::snapshot, "The loop's latest state (lock-free): a SessionSnapshot.")
      .def("hold_to_pair", &HapticSession::hold_to_pair, py::arg("pair"),
           "Holds the part to this assembled pair's joint (a PairJoint of find_joints) instead of the one "
           "engagement finds; False when the loop cannot hold its type.")
      .def("release_joint", [](HapticSession& s) { s.loop_->request_release(); },
           "Back to the joint engagement finds.");
}

}  // namespace contactcore::bindings
