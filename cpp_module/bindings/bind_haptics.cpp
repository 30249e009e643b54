// Haptic trials: the SpaceMouse parser and device list, the trial scene, the
// headless scripted trial, and a live session (device + 1 kHz loop on its own
// thread) for the panel. The loop never touches Python: the session's
// methods exchange values with it through atomics and a snapshot.
#include "common.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <memory>

#include "contactcore/haptics/device_factory.h"
#include "contactcore/haptics/hid_pid_device.h"
#include "contactcore/haptics/hid_recording.h"
#include "contactcore/haptics/joint_adapter.h"
#include "contactcore/haptics/spacemouse.h"
#include "contactcore/haptics/trial.h"

namespace contactcore::bindings {

using namespace contactcore::haptics;

namespace {

py::list vec(const Vec3& v) {
  py::list out;
  for (int i = 0; i < 3; ++i) out.append(v[i]);
  return out;
}

Vec3 vec_from(const py::handle& value, const char* what) {
  auto seq = value.cast<std::vector<double>>();
  if (seq.size() != 3) raise_argument_error(std::string(what) + ": three numbers expected");
  return {seq[0], seq[1], seq[2]};
}

ScriptKey key_from(const py::dict& d, bool timed) {
  ScriptKey k;
  if (timed) k.t = d.contains("t") ? d["t"].cast<double>() : 0.0;
  if (d.contains("translate")) k.translate = vec_from(d["translate"], "translate");
  if (d.contains("rotate_deg")) k.rotate_deg = vec_from(d["rotate_deg"], "rotate_deg");
  return k;
}

py::dict offset_dict(const Pose& pose, const Vec3& centre) {
  Vec3 t, r;
  offset_of(pose, centre, t, r);
  py::dict d;
  d["translate"] = vec(t);
  d["rotate_deg"] = vec(Vec3(deg(r.x()), deg(r.y()), deg(r.z())));
  return d;
}

py::list matrix_rows(const Pose& pose) {
  py::list rows;
  for (int i = 0; i < 4; ++i) {
    py::list row;
    for (int j = 0; j < 4; ++j) row.append(pose.matrix()(i, j));
    rows.append(row);
  }
  return rows;
}

py::dict capabilities_dict(const DeviceCapabilities& c) {
  py::dict d;
  d["name"] = c.name;
  d["input_dof"] = c.input_dof;
  d["force_output"] = c.force_output;
  d["torque_output"] = c.torque_output;
  d["control"] = to_string(c.control);
  d["max_force"] = c.max_force;
  d["max_torque"] = c.max_torque;
  d["max_stiffness"] = c.max_stiffness;
  d["max_angular_stiffness"] = c.max_angular_stiffness;
  d["max_damping"] = c.max_damping;
  d["hid_force_feedback"] = c.hid_force_feedback;
  return d;
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

py::list devices_seen_list(const std::vector<HidDeviceSeen>& seen) {
  py::list out;
  for (const HidDeviceSeen& s : seen) {
    py::dict d;
    d["path"] = s.path;
    d["manufacturer"] = s.manufacturer;
    d["product"] = s.product;
    d["vendor"] = s.vendor;
    d["product_id"] = s.product_id;
    d["usage_page"] = s.usage_page;
    d["usage"] = s.usage;
    out.append(d);
  }
  return out;
}

// A failed device request as an exception: DeviceUnavailable carries the
// HID devices seen (`devices`), others go through raise_if_failed.
[[noreturn]] void raise_device_error(const DeviceResult& r) {
  if (r.device_missing) {
    py::object error = device_unavailable_error()(r.status.describe());
    error.attr("devices") = devices_seen_list(r.seen);
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
    start_ = offset_pose(translate, Vec3(rad(rotate_deg.x()), rad(rotate_deg.y()), rad(rotate_deg.z())), c);
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
    hand_->set_live_target(offset_pose(t, Vec3(rad(r_deg.x()), rad(r_deg.y()), rad(r_deg.z())), scene_.centre()));
  }

  py::dict snapshot() {
    const ServoSnapshot s = loop_->snapshot();
    return snapshot_dict(s);
  }
  py::dict snapshot_dict(const ServoSnapshot& s) {
    const Vec3 c = scene_.centre();
    py::dict d = offset_dict(s.proxy, c);
    d["matrix"] = matrix_rows(s.proxy);
    d["target"] = offset_dict(s.target, c);
    d["force"] = vec(s.wrench.force);
    d["torque"] = vec(s.wrench.torque);
    d["force_n"] = s.wrench.force.norm();
    d["engaged"] = s.engaged;
    d["held"] = s.held;
    d["joint"] = s.engaged ? to_string(s.joint.kind) : "Free";
    d["joint_axis"] = vec(s.joint.axis);
    d["joint_point"] = vec(s.joint.point);
    py::list with;
    for (int k = 0; s.engaged && k < s.joint.body_count; ++k) with.append(scene_.body_names()[s.joint.bodies[k]]);
    d["joint_with"] = with;
    // The joint's one-sided stops (n . c <= limit on the reference point),
    // active when the part is on them (within 1 um): the panel's readout.
    py::list stops;
    const Vec3 reference = s.proxy * c;
    for (int k = 0; s.engaged && k < s.joint.stop_count; ++k) {
      py::dict stop;
      stop["normal"] = vec(s.joint.stops[k].normal);
      stop["gap"] = s.joint.stops[k].limit - s.joint.stops[k].normal.dot(reference);
      stop["active"] = s.joint.stops[k].limit - s.joint.stops[k].normal.dot(reference) < 1e-3;
      stops.append(stop);
    }
    d["stops"] = stops;
    d["insertion_depth"] = s.insertion_depth;
    d["penetration"] = s.penetration;
    d["max_penetration"] = s.max_penetration;
    d["max_force"] = s.max_force;
    d["rate_hz"] = s.rate_hz;
    d["jitter_us"] = s.jitter_us;
    d["step_us"] = s.last_step_us;
    d["ticks"] = s.ticks;
    d["overruns"] = s.overruns;
    d["watchdog"] = to_string(s.watchdog);
    d["connected"] = s.device_connected;
    d["enabled"] = s.enabled;
    d["blocked"] = s.blocked;
    py::list axes;
    for (int i = 0; i < 6; ++i) axes.append(s.axes[i]);
    d["axes"] = axes;
    d["time"] = s.time;
    d["realtime_priority"] = loop_->got_realtime_priority();
    d["late_wakeups"] = s.late_wakeups;
    d["max_wake_latency_us"] = s.max_wake_latency_us;
    d["memory_locked"] = s.memory_locked;
    return d;
  }

  TrialScene& scene_;
  Pose start_;
  std::unique_ptr<Device> device_;
  SimulatedHand* hand_ = nullptr;
  std::unique_ptr<ServoLoop> loop_;
  std::string message_;
};

// The servo loop's keyword options, each checked by name: a misspelt one is
// an ArgumentError naming it, never silently the default.
ServoConfig config_from(const py::kwargs& kw) {
  static const char* const kOptions[] = {"stiffness", "angular_stiffness", "damping", "angular_damping",
                                         "max_speed", "breakaway_force",   "rate_hz", "realtime_priority",
                                         "friction"};
  for (const auto& item : kw) {
    const std::string key = py::str(item.first);
    if (std::none_of(std::begin(kOptions), std::end(kOptions), [&](const char* option) { return key == option; })) {
      std::string known;
      for (const char* option : kOptions) known += (known.empty() ? "" : ", ") + std::string(option);
      raise_argument_error("unknown keyword option '" + key + "' (the options: " + known + ")");
    }
  }
  ServoConfig c;
  if (kw.contains("stiffness")) c.stiffness = kw["stiffness"].cast<double>();
  if (kw.contains("angular_stiffness")) c.angular_stiffness = kw["angular_stiffness"].cast<double>();
  if (kw.contains("damping")) c.damping = kw["damping"].cast<double>();
  if (kw.contains("angular_damping")) c.angular_damping = kw["angular_damping"].cast<double>();
  if (kw.contains("max_speed")) c.max_speed = kw["max_speed"].cast<double>();
  if (kw.contains("breakaway_force")) c.breakaway_force = kw["breakaway_force"].cast<double>();
  if (kw.contains("rate_hz")) c.rate_hz = kw["rate_hz"].cast<double>();
  if (kw.contains("realtime_priority")) c.realtime_priority = kw["realtime_priority"].cast<int>();
  if (kw.contains("lock_memory")) c.lock_memory = kw["lock_memory"].cast<bool>();
  if (kw.contains("friction")) {
    c.friction = kw["friction"].cast<double>();
    if (!(c.friction >= 0) || !std::isfinite(c.friction))
      raise_argument_error("friction must be a finite number >= 0 (Coulomb's coefficient), got " +
                           std::to_string(c.friction));
  }
  return c;
}

}  // namespace

void bind_haptics(py::module_& root) {
  py::module_ m = root.def_submodule("haptics", "Haptic trials: devices, the 1 kHz servo loop, real-time contacts");

  m.def(
      "parse_spacemouse_report",
      [](std::uint16_t vendor, std::uint16_t product, const py::bytes& report) {
        const SpaceMouseModel* known = find_model(vendor, product);
        const SpaceMouseModel model = known ? *known : generic_model(vendor, product);
        const std::string data = report;
        SpaceMouseState state;
        py::dict d;
        d["understood"] = parse_report(reinterpret_cast<const std::uint8_t*>(data.data()), data.size(), model, state);
        py::list raw, axes;
        for (int i = 0; i < 6; ++i) {
          raw.append(state.raw[i]);
          axes.append(state.axes[i]);
        }
        d["raw"] = raw;
        d["axes"] = axes;
        d["buttons"] = state.buttons;
        d["model"] = model.name;
        return d;
      },
      py::arg("vendor"), py::arg("product"), py::arg("report"),
      "Parses one SpaceMouse HID input report (report ID first) from a fresh state.");

  m.def("spacemouse_devices", [] {
    py::list out;
    std::vector<HidSpaceMouse::Found> found;
    {
      py::gil_scoped_release release;
      found = HidSpaceMouse::enumerate();
    }
    for (const auto& f : found) {
      py::dict d;
      d["name"] = f.name;
      d["path"] = f.path;
      d["vendor"] = f.vendor;
      d["product"] = f.product;
      out.append(d);
    }
    return out;
  }, "The 3Dconnexion 6-DOF devices hidapi sees now (empty without hardware).");

  m.def("hid_force_feedback_devices", [] {
    py::list out;
    std::vector<HidPidFound> found;
    {
      py::gil_scoped_release release;
      found = enumerate_hid_pid_devices();
    }
    for (const auto& f : found) {
      py::dict d;
      d["name"] = f.name;
      d["path"] = f.path;
      d["vendor"] = f.vendor;
      d["product"] = f.product;
      d["axes"] = f.axes;
      out.append(d);
    }
    return out;
  }, "HID devices whose report descriptor offers PID constant force (empty without hardware).");

  m.def(
      "hid_pid_capabilities",
      [](const py::bytes& descriptor, double full_scale_force) {
        const std::string data = descriptor;
        PidLayout layout;
        std::string why;
        py::dict d;
        if (!find_pid_layout(reinterpret_cast<const std::uint8_t*>(data.data()), data.size(), layout, &why)) {
          d["force_output"] = false;
          d["why"] = why;
          return d;
        }
        PidForceConfig config;
        config.full_scale_force = full_scale_force;
        config.start_thread = false;
        HidPidDevice device(nullptr, layout, config);
        d = capabilities_dict(device.capabilities());
        d["axes"] = layout.axis_count();
        return d;
      },
      py::arg("descriptor"), py::arg("full_scale_force") = 3.0,
      "What a device with this HID report descriptor can render (force output through the PID page or why not).");

  m.def("simulated_capabilities", [] { return capabilities_dict(simulated_capabilities()); });

  device_unavailable_error() = py::reinterpret_borrow<py::object>(py::handle(PyErr_NewException(
      "contactcore.haptics.DeviceUnavailable", root.attr("ContactsError").ptr(), nullptr)));
  m.attr("DeviceUnavailable") = device_unavailable_error();

  m.def("hid_devices_seen", [] {
    std::vector<HidDeviceSeen> seen;
    {
      py::gil_scoped_release release;
      seen = enumerate_hid_devices();
    }
    return devices_seen_list(seen);
  }, "Every HID device hidapi lists now (path, manufacturer, product, vendor, product_id, usage_page, usage).");

  m.def(
      "read_hid_recording",
      [](const std::string& path) {
        const HidRecording r = recording_from(py::str(path));
        py::dict d;
        d["kind"] = r.kind;
        d["vendor"] = r.vendor;
        d["product"] = r.product;
        d["name"] = r.name;
        d["descriptor"] = py::bytes(reinterpret_cast<const char*>(r.descriptor.data()), r.descriptor.size());
        py::list reports;
        for (const RecordedReport& report : r.reports)
          reports.append(py::make_tuple(report.time, py::bytes(reinterpret_cast<const char*>(report.bytes.data()),
                                                               report.bytes.size())));
        d["reports"] = reports;
        return d;
      },
      py::arg("path"), "A HID recording (--record-hid): device kind, ids, descriptor and (arrival s, bytes) reports.");

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
        for (const py::handle& item : reports) {
          auto pair = item.cast<py::tuple>();
          RecordedReport report;
          report.time = pair[0].cast<double>();
          const std::string b = pair[1].cast<py::bytes>();
          report.bytes.assign(b.begin(), b.end());
          r.reports.push_back(std::move(report));
        }
        raise_if_failed(write_hid_recording(r, path));
      },
      py::arg("path"), py::arg("kind"), py::arg("vendor"), py::arg("product"), py::arg("name"), py::arg("reports"),
      py::arg("descriptor") = py::bytes(), "Writes a HID recording file (the format --record-hid writes).");

  py::class_<TrialScene>(m, "TrialScene", "Partitions, real-time contacts and collision models for one moving part.")
      .def(py::init([](const Assembly& assembly, const std::string& part, double capture_distance,
                       double capture_angle_deg, double deflection, py::object progress) {
             std::unique_ptr<PythonProgress> reporter;
             if (!progress.is_none()) reporter = std::make_unique<PythonProgress>(progress);
             SceneOptions options;
             options.capture.distance = capture_distance;
             options.capture.angle = rad(capture_angle_deg);
             options.deflection = deflection;
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
           py::arg("capture_angle_deg") = 2.0, py::arg("deflection") = 0.01, py::arg("progress") = py::none())
      .def_property_readonly("part", &TrialScene::part_name)
      .def_property_readonly("moving", &TrialScene::moving, "Index of the moving part in the assembly.")
      .def(
          "joint_of_pair",
          [](TrialScene& s, const PairJoint& pair) -> py::object {
            JointState j;
            if (!joint_of_pair(s, pair, j)) return py::none();
            py::dict d;
            d["kind"] = to_string(j.kind);
            d["axis"] = vec(j.axis);
            d["point"] = vec(j.point);
            d["stops"] = j.stop_count;
            d["collision_group"] = j.group;
            return d;
          },
          py::arg("pair"),
          "The joint the loop would hold the part to for this assembled pair (kind, axis, point, stops), "
          "or None when the pair does not involve the part or the loop cannot hold its type.")
      .def_property_readonly("centre", [](const TrialScene& s) { return vec(s.centre()); })
      .def_property_readonly("body_names", &TrialScene::body_names)
      .def_property_readonly("setup_seconds", &TrialScene::setup_seconds)
      .def_property_readonly("triangles", [](TrialScene& s) { return s.collision().triangle_count(); })
      .def(
          "contacts_at",
          [](TrialScene& s, const std::vector<double>& translate, const std::vector<double>& rotate_deg) {
            const Pose pose = offset_pose(Vec3(translate[0], translate[1], translate[2]),
                                          Vec3(rad(rotate_deg[0]), rad(rotate_deg[1]), rad(rotate_deg[2])), s.centre());
            std::vector<LiveContact> live(256);
            const int n = s.contacts().update(pose, live.data(), 256);
            py::list out;
            for (int i = 0; i < n; ++i) {
              py::dict d;
              d["type"] = to_string(live[i].type);
              d["with"] = s.body_names()[live[i].body];
              d["distance"] = live[i].distance;
              d["angle_deg"] = deg(live[i].angle);
              out.append(d);
            }
            return out;
          },
          py::arg("translate"), py::arg("rotate_deg"),
          "Real-time contacts of the part displaced by (translate mm, rotate_deg) from its placement.")
      .def(
          "collides",
          [](TrialScene& s, const std::vector<double>& translate, const std::vector<double>& rotate_deg) {
            const Pose pose = offset_pose(Vec3(translate[0], translate[1], translate[2]),
                                          Vec3(rad(rotate_deg[0]), rad(rotate_deg[1]), rad(rotate_deg[2])), s.centre());
            return s.collision().collides(pose, -1);
          },
          py::arg("translate"), py::arg("rotate_deg"));

  m.def(
      "run_trial",
      [](TrialScene& scene, const py::dict& script, bool realtime, int record_every, double settle,
         const std::string& device, py::object hid_file, py::object record_hid, py::object duration,
         const py::kwargs& kw) {
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
          const ScriptKey& k = s.start;
          request.start = offset_pose(k.translate, Vec3(rad(k.rotate_deg.x()), rad(k.rotate_deg.y()), rad(k.rotate_deg.z())),
                                      scene.centre());
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
        const TrialResult r = call_guarded([&] { return run_trial(scene, s, options, realtime); });
        if (opened.recorder) {
          opened.device.reset();  // the reader thread stops: the recording is complete
          raise_if_failed(write_hid_recording(opened.recorder->recording(), record_hid.cast<std::string>()));
        }
        py::dict out;
        // Timing from wall time in realtime mode only; null in lockstep.
        out["mode"] = r.realtime ? "realtime" : "lockstep";
        out["ticks"] = r.ticks;
        out["sim_time_s"] = r.sim_time_s;
        if (r.realtime) {
          out["rate_hz"] = r.rate_hz;
          py::dict step;
          step["p50"] = r.step_p50_us;
          step["p99"] = r.step_p99_us;
          step["max"] = r.step_max_us;
          out["step_us"] = step;
          py::dict jitter;
          jitter["p50"] = r.jitter_p50_us;
          jitter["p99"] = r.jitter_p99_us;
          out["jitter_us"] = jitter;
        } else {
          out["rate_hz"] = py::none();
          out["step_us"] = py::none();
          out["jitter_us"] = py::none();
        }
        out["overruns"] = r.overruns;
        out["long_steps"] = r.long_steps;
        out["late_wakeups"] = r.late_wakeups;
        out["realtime_priority"] = r.realtime_priority;
        out["success"] = r.status.ok();
        out["failure"] = r.status.ok() ? py::object(py::none()) : py::object(py::str(r.status.message));
        out["memory_locked"] = r.memory_locked;
        out["device"] = device;
        out["device_message"] = opened.message.empty() ? std::string("Simulated hand.") : opened.message;
        py::list joints;
        for (const auto& j : r.joints_engaged) {
          py::dict d;
          d["with"] = j.with;
          d["type"] = j.type;
          d["joint"] = j.joint;
          d["t"] = j.time;
          joints.append(d);
        }
        out["joints_engaged"] = joints;
        py::dict final_offset;
        final_offset["translate"] = vec(r.final_translate);
        final_offset["rotate_deg"] = vec(r.final_rotate_deg);
        out["final"] = final_offset;
        out["max_penetration_mm"] = r.max_penetration_mm;
        out["start_penetration_mm"] = r.start_penetration_mm;
        out["final_penetration_mm"] = r.final_penetration_mm;
        out["max_force_n"] = r.max_force_n;
        py::list path;
        for (const auto& p : r.path) {
          py::dict d;
          d["t"] = p.t;
          d["translate"] = vec(p.translate);
          d["rotate_deg"] = vec(p.rotate_deg);
          d["force"] = vec(p.force);
          d["engaged"] = p.engaged;
          d["penetration"] = p.penetration;
          path.append(d);
        }
        out["path"] = path;
        return out;
      },
      py::arg("scene"), py::arg("script"), py::arg("realtime") = false, py::arg("record_every") = 10,
      py::arg("settle") = 1.5, py::arg("device") = "sim", py::arg("hid_file") = py::none(),
      py::arg("record_hid") = py::none(), py::arg("duration") = py::none(),
      "Runs a trial: the scripted simulated hand (device 'sim', lockstep unless realtime), or a device from "
      "the factory: 'spacemouse', 'hid-ff' (real time; record_hid=FILE keeps their raw reports), 'replay' "
      "(hid_file=FILE, lockstep), 'sim-hid-ff'. Raises DeviceUnavailable (with .devices) when the hardware "
      "is not there. Keyword options: "
      "stiffness, angular_stiffness, damping, angular_damping, max_speed, breakaway_force, rate_hz, "
      "realtime_priority (SCHED_FIFO priority of the loop thread when permitted), friction (Coulomb's "
      "coefficient at the part's contacts, 0: none).");

  py::class_<HapticSession>(m, "HapticSession", "A device and the 1 kHz loop on its own thread.")
      .def(py::init([](TrialScene& scene, const std::string& device, const std::vector<double>& translate,
                       const std::vector<double>& rotate_deg, py::object replay, int vendor, int product,
                       py::object hid_file, const py::kwargs& kw) {
             // A replay: a recording file, or (time, bytes) pairs of a SpaceMouse (vendor, product).
             HidRecording recording;
             if (!hid_file.is_none()) {
               recording = recording_from(hid_file);
             } else if (!replay.is_none()) {
               recording.kind = "spacemouse";
               recording.vendor = static_cast<std::uint16_t>(vendor);
               recording.product = static_cast<std::uint16_t>(product);
               for (const py::handle& item : replay.cast<py::list>()) {
                 auto pair = item.cast<py::tuple>();
                 RecordedReport r;
                 r.time = pair[0].cast<double>();
                 const std::string b = pair[1].cast<py::bytes>();
                 r.bytes.assign(b.begin(), b.end());
                 recording.reports.push_back(std::move(r));
               }
             }
             return std::make_unique<HapticSession>(scene, device, Vec3(translate[0], translate[1], translate[2]),
                                                    Vec3(rotate_deg[0], rotate_deg[1], rotate_deg[2]), config_from(kw),
                                                    std::move(recording));
           }),
           py::arg("scene"), py::arg("device") = "sim", py::arg("translate") = std::vector<double>{0, 0, 0},
           py::arg("rotate_deg") = std::vector<double>{0, 0, 0}, py::arg("replay") = py::none(),
           py::arg("vendor") = 0x256f, py::arg("product") = 0xc635, py::arg("hid_file") = py::none(),
           py::keep_alive<1, 2>())
      .def_property_readonly("message", [](const HapticSession& s) { return s.message_; })
      .def_property_readonly("capabilities", [](const HapticSession& s) { return capabilities_dict(s.device_->capabilities()); })
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
      .def("set_hand_target", [](HapticSession& s, const std::vector<double>& t, const std::vector<double>& r) {
        s.set_hand_target(Vec3(t[0], t[1], t[2]), Vec3(r[0], r[1], r[2]));
      }, py::arg("translate"), py::arg("rotate_deg"))
      .def("snapshot", &HapticSession::snapshot, "The loop's latest state (lock-free).")
      .def("hold_to_pair", &HapticSession::hold_to_pair, py::arg("pair"),
           "Holds the part to this assembled pair's joint (a PairJoint of find_joints) instead of the one "
           "engagement finds; False when the loop cannot hold its type.")
      .def("release_joint", [](HapticSession& s) { s.loop_->request_release(); },
           "Back to the joint engagement finds.");
}

}  // namespace contactcore::bindings
