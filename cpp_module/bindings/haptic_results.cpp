// The haptics binding's result classes: each field a read-only property with
// its unit in the docstring, and to_dict() from the same list (result_class.h).
// A new field of a result is one `.field(...)` line here.
#include "haptic_results.h"

#include "contactcore/haptics/pose_math.h"
#include "result_class.h"

namespace contactcore::bindings {

using namespace contactcore::haptics;

Offset offset_from(const Pose& pose, const Vec3& centre) {
  Vec3 t, r;
  offset_of(pose, centre, t, r);
  return {triple(t), {deg(r.x()), deg(r.y()), deg(r.z())}};
}

namespace {

void bind_device_results(py::module_& m) {
  ResultClass<SpaceMouseReport>(m, "SpaceMouseReport", "One SpaceMouse HID input report, parsed.")
      .field("understood", &SpaceMouseReport::understood, "False: too short or an unknown report ID")
      .field("raw", &SpaceMouseReport::raw, "[6] the values as sent (translation x y z, rotation x y z)")
      .field("axes", &SpaceMouseReport::axes, "[6] in spacenavd's frame, normalised to [-1, 1]")
      .field("buttons", &SpaceMouseReport::buttons, "bit mask of the buttons held")
      .field("model", &SpaceMouseReport::model, "the model's name (or a generic one)")
      .done();

  ResultClass<HidSpaceMouse::Found>(m, "SpaceMouseFound", "A 3Dconnexion 6-DOF device hidapi sees.")
      .field("name", &HidSpaceMouse::Found::name, "model name")
      .field("path", &HidSpaceMouse::Found::path, "hidapi path")
      .field("vendor", &HidSpaceMouse::Found::vendor, "USB vendor id")
      .field("product", &HidSpaceMouse::Found::product, "USB product id")
      .done();

  ResultClass<HidPidFound>(m, "HidPidFound", "A HID device whose report descriptor offers PID constant force.")
      .field("name", &HidPidFound::name, "product name")
      .field("path", &HidPidFound::path, "hidapi path")
      .field("vendor", &HidPidFound::vendor, "USB vendor id")
      .field("product", &HidPidFound::product, "USB product id")
      .field("axes", &HidPidFound::axes, "force axes of the PID page")
      .done();

  ResultClass<HidDeviceSeen>(m, "HidDeviceSeen", "A HID device hidapi lists (what 'no device' reports).")
      .field("path", &HidDeviceSeen::path, "hidapi path")
      .field("manufacturer", &HidDeviceSeen::manufacturer, "manufacturer string")
      .field("product", &HidDeviceSeen::product, "product string")
      .field("vendor", &HidDeviceSeen::vendor, "USB vendor id")
      .field("product_id", &HidDeviceSeen::product_id, "USB product id")
      .field("usage_page", &HidDeviceSeen::usage_page, "HID usage page")
      .field("usage", &HidDeviceSeen::usage, "HID usage")
      .done();

  ResultClass<DeviceCapabilities>(m, "DeviceCapabilities", "What a device can sense and render.")
      .field("name", &DeviceCapabilities::name, "device name")
      .field("input_dof", &DeviceCapabilities::input_dof, "degrees of freedom it senses")
      .field("force_output", &DeviceCapabilities::force_output, "renders a force")
      .field("torque_output", &DeviceCapabilities::torque_output, "renders a torque")
      .field("control", [](const DeviceCapabilities& c) { return std::string(to_string(c.control)); },
             "'position' or 'rate' control")
      .field("max_force", &DeviceCapabilities::max_force, "N")
      .field("max_torque", &DeviceCapabilities::max_torque, "N mm")
      .field("max_stiffness", &DeviceCapabilities::max_stiffness, "N/mm it renders stably")
      .field("max_angular_stiffness", &DeviceCapabilities::max_angular_stiffness, "N mm/rad")
      .field("max_damping", &DeviceCapabilities::max_damping, "N s/mm")
      .field("hid_force_feedback", &DeviceCapabilities::hid_force_feedback, "offers the HID PID usage page")
      .done();

  ResultClass<PidCapabilities>(m, "PidCapabilities", "What a device with a given HID report descriptor can render.")
      .field("force_output", &PidCapabilities::force_output, "the descriptor offers PID constant force")
      .field("why", [](const PidCapabilities& c) { return c.force_output ? py::object(py::none()) : py::object(py::str(c.why)); },
             "why not (None when force_output)")
      .field("capabilities", &PidCapabilities::capabilities,
             "DeviceCapabilities of the device built on it (None without force output)")
      .field("axes", &PidCapabilities::axes, "force axes of the PID page (0 without force output)")
      .done();

  ResultClass<HidRecording>(m, "HidRecording", "A HID recording (--record-hid): the device and its raw reports.")
      .field("kind", &HidRecording::kind, "'spacemouse' or 'hid-ff'")
      .field("vendor", &HidRecording::vendor, "USB vendor id")
      .field("product", &HidRecording::product, "USB product id")
      .field("name", &HidRecording::name, "device name")
      .field("descriptor", [](const HidRecording& r) {
               return py::bytes(reinterpret_cast<const char*>(r.descriptor.data()), r.descriptor.size());
             }, "the report descriptor (hid-ff; empty otherwise)")
      .field("reports", [](const HidRecording& r) {
               py::list reports;
               for (const RecordedReport& report : r.reports)
                 reports.append(py::make_tuple(report.time, py::bytes(reinterpret_cast<const char*>(report.bytes.data()),
                                                                      report.bytes.size())));
               return reports;
             }, "[(arrival s, bytes)]; empty bytes: an unplug")
      .done();
}

void bind_scene_results(py::module_& m) {
  ResultClass<Offset>(m, "Offset", "A displacement from the assembled placement, about the part's centre.")
      .field("translate", &Offset::translate, "[x, y, z] mm")
      .field("rotate_deg", &Offset::rotate_deg, "[rx, ry, rz] degrees about x, y, z")
      .done();

  ResultClass<HeldJoint>(m, "HeldJoint", "The joint the servo loop holds the part to.")
      .field("kind", &HeldJoint::kind, "'Cylindrical', 'Prismatic', 'Planar', 'Spherical', ...")
      .field("axis", &HeldJoint::axis, "unit [x, y, z] (world)")
      .field("point", &HeldJoint::point, "[x, y, z] mm on the axis (world), the centre of a spherical joint")
      .field("stops", &HeldJoint::stops, "how many one-sided stops it has")
      .field("collision_group", &HeldJoint::collision_group, "the collision group its surfaces are switched off in")
      .done();

  ResultClass<LiveContactSeen>(m, "LiveContact", "A real-time contact of the moving part.")
      .field("type", &LiveContactSeen::type, "contact type code (PLF, CLJ, ...)")
      .field("with_body", "with", [](const LiveContactSeen& c) { return c.with; }, "the other body's name ('with' in to_dict())")
      .field("distance", &LiveContactSeen::distance, "mm between the surfaces")
      .field("angle_deg", &LiveContactSeen::angle_deg, "degrees between their normals or axes")
      .done();

  ResultClass<StopState>(m, "StopState", "A one-sided stop of the engaged joint (n . c <= limit on the reference point).")
      .field("normal", &StopState::normal, "unit [x, y, z] (world)")
      .field("gap", &StopState::gap, "mm left before the stop")
      .field("active", &StopState::active, "the part is on it (gap below 1 um)")
      .done();

  using S = SessionSnapshot;
  ResultClass<S>(m, "SessionSnapshot", "The servo loop's latest state (HapticSession.snapshot()).")
      .field("translate", [](const S& s) { return s.offset.translate; }, "[x, y, z] mm: the part's offset")
      .field("rotate_deg", [](const S& s) { return s.offset.rotate_deg; }, "[rx, ry, rz] degrees: the part's rotation")
      .field("matrix", &S::matrix, "4x4 rows: the part's displacement from its assembled placement (mm)")
      .field("target", &S::target, "Offset: the device's commanded pose")
      .field("force", [](const S& s) { return triple(s.loop.wrench.force); }, "[x, y, z] N rendered")
      .field("torque", [](const S& s) { return triple(s.loop.wrench.torque); }, "[x, y, z] N mm rendered")
      .field("force_n", [](const S& s) { return s.loop.wrench.force.norm(); }, "N: |force|")
      .field("engaged", [](const S& s) { return s.loop.engaged; }, "held to a joint")
      .field("held", [](const S& s) { return s.loop.held; }, "the joint was chosen (hold_to_pair), not found")
      .field("joint", [](const S& s) { return std::string(s.loop.engaged ? to_string(s.loop.joint.kind) : "Free"); },
             "joint kind, 'Free' when not engaged")
      .field("joint_axis", [](const S& s) { return triple(s.loop.joint.axis); }, "unit [x, y, z] (world)")
      .field("joint_point", [](const S& s) { return triple(s.loop.joint.point); }, "[x, y, z] mm (world)")
      .field("joint_with", &S::joint_with, "names of the bodies the joint is with")
      .field("stops", &S::stops, "[StopState] of the engaged joint")
      .field("insertion_depth", [](const S& s) { return s.loop.insertion_depth; },
             "mm along the joint axis from where it engaged")
      .field("penetration", [](const S& s) { return s.loop.penetration; }, "mm: the deepest overlap now")
      .field("max_penetration", [](const S& s) { return s.loop.max_penetration; }, "mm: the deepest overlap so far")
      .field("max_force", [](const S& s) { return s.loop.max_force; }, "N: the largest force so far")
      .field("rate_hz", [](const S& s) { return s.loop.rate_hz; }, "Hz: the loop's measured rate")
      .field("jitter_us", [](const S& s) { return s.loop.jitter_us; }, "us: |period - nominal|")
      .field("step_us", [](const S& s) { return s.loop.last_step_us; }, "us: the last tick's compute time")
      .field("ticks", [](const S& s) { return s.loop.ticks; }, "ticks since start")
      .field("overruns", [](const S& s) { return s.loop.overruns; }, "long steps + late wake-ups")
      .field("watchdog", [](const S& s) { return std::string(to_string(s.loop.watchdog)); },
             "why the force was zeroed ('none': it was not)")
      .field("connected", [](const S& s) { return s.loop.device_connected; }, "the device answers")
      .field("enabled", [](const S& s) { return s.loop.enabled; }, "force output enabled")
      .field("blocked", [](const S& s) { return s.loop.blocked; }, "a collision or stop held the last step")
      .field("axes", [](const S& s) {
               std::array<double, 6> axes{};
               for (int i = 0; i < 6; ++i) axes[i] = s.loop.axes[i];
               return axes;
             }, "[6] the device's axes (rate devices), in [-1, 1]")
      .field("time", [](const S& s) { return s.loop.time; }, "s since start")
      .field("realtime_priority", &S::realtime_priority, "the loop thread got SCHED_FIFO")
      .field("late_wakeups", [](const S& s) { return s.loop.late_wakeups; }, "wake-ups later than allowed")
      .field("max_wake_latency_us", [](const S& s) { return s.loop.max_wake_latency_us; }, "us")
      .field("memory_locked", [](const S& s) { return s.loop.memory_locked; }, "mlockall held while the loop runs")
      .done();
}

void bind_trial_results(py::module_& m) {
  ResultClass<StepTimes>(m, "StepTimes", "A realtime trial's tick compute times.")
      .field("p50", &StepTimes::p50, "us, median")
      .field("p99", &StepTimes::p99, "us, 99th percentile")
      .field("max", &StepTimes::max, "us")
      .done();

  ResultClass<JitterTimes>(m, "JitterTimes", "A realtime trial's |period - nominal|.")
      .field("p50", &JitterTimes::p50, "us, median")
      .field("p99", &JitterTimes::p99, "us, 99th percentile")
      .done();

  ResultClass<EngagedJoint>(m, "EngagedJoint", "A joint the part engaged during a trial.")
      .field("with_body", "with", [](const EngagedJoint& j) { return j.with; }, "the other body's name ('with' in to_dict())")
      .field("type", &EngagedJoint::type, "contact type of the joint (CLJ, SPF, ...)")
      .field("joint", &EngagedJoint::joint, "joint kind (Cylindrical, Ball, ...)")
      .field("t", &EngagedJoint::time, "s since the start")
      .done();

  ResultClass<TrialSample>(m, "TrialSample", "A recorded sample of a trial's path.")
      .field("t", &TrialSample::t, "s since the start")
      .field("translate", [](const TrialSample& p) { return triple(p.translate); }, "[x, y, z] mm offset")
      .field("rotate_deg", [](const TrialSample& p) { return triple(p.rotate_deg); }, "[rx, ry, rz] degrees")
      .field("force", [](const TrialSample& p) { return triple(p.force); }, "[x, y, z] N rendered to the hand")
      .field("engaged", &TrialSample::engaged, "held to a joint")
      .field("penetration", &TrialSample::penetration, "mm: the deepest overlap")
      .done();

  // The order of the fields is the order of `contacts trial --json`'s keys
  // (the CLI picks its keys from to_dict()).
  using T = TrialRun;
  auto realtime_only = [](const T& t, auto value) { return t.result.realtime ? py::cast(value) : py::object(py::none()); };
  ResultClass<T>(m, "TrialResult", "What a trial did (run_trial).")
      .field("mode", [](const T& t) { return std::string(t.result.realtime ? "realtime" : "lockstep"); },
             "'realtime' (wall clock) or 'lockstep' (simulated time)")
      .field("ticks", [](const T& t) { return t.result.ticks; }, "servo ticks run")
      .field("sim_time_s", [](const T& t) { return t.result.sim_time_s; }, "s: ticks x period")
      .field("rate_hz", [=](const T& t) { return realtime_only(t, t.result.rate_hz); },
             "Hz: 1 / mean period (realtime; None in lockstep)")
      .field("step_us", [=](const T& t) {
               return realtime_only(t, StepTimes{t.result.step_p50_us, t.result.step_p99_us, t.result.step_max_us});
             }, "StepTimes: tick compute time (realtime; None in lockstep)")
      .field("jitter_us", [=](const T& t) {
               return realtime_only(t, JitterTimes{t.result.jitter_p50_us, t.result.jitter_p99_us});
             }, "JitterTimes: |period - nominal| (realtime; None in lockstep)")
      .field("overruns", [](const T& t) { return t.result.overruns; }, "long steps + late wake-ups")
      .field("long_steps", [](const T& t) { return t.result.long_steps; }, "ticks that computed past their deadline")
      .field("late_wakeups", [](const T& t) { return t.result.late_wakeups; }, "wake-ups later than allowed")
      .field("realtime_priority", [](const T& t) { return t.result.realtime_priority; }, "the loop thread got SCHED_FIFO")
      .field("success", [](const T& t) { return t.result.status.ok(); }, "the path is acceptable")
      .field("failure", [](const T& t) {
               return t.result.status.ok() ? py::object(py::none()) : py::object(py::str(t.result.status.message));
             }, "why not (None on success)")
      .field("memory_locked", [](const T& t) { return t.result.memory_locked; }, "mlockall held while the loop ran")
      .field("device", &T::device, "the device asked for ('sim', 'spacemouse', 'hid-ff', 'replay', ...)")
      .field("device_message", &T::device_message, "what the device factory said of it")
      .field("joints_engaged", [](const T& t) { return t.result.joints_engaged; }, "[EngagedJoint] in order")
      .field("final", [](const T& t) { return Offset{triple(t.result.final_translate), triple(t.result.final_rotate_deg)}; },
             "Offset: where the part ended")
      .field("max_penetration_mm", [](const T& t) { return t.result.max_penetration_mm; }, "mm: deepest overlap")
      .field("start_penetration_mm", [](const T& t) { return t.result.start_penetration_mm; }, "mm: overlap at the start")
      .field("final_penetration_mm", [](const T& t) { return t.result.final_penetration_mm; }, "mm: overlap at the end")
      .field("max_force_n", [](const T& t) { return t.result.max_force_n; }, "N: the largest force rendered")
      .field("path", [](const T& t) { return t.result.path; }, "[TrialSample] every record_every ticks")
      .done();
}

}  // namespace

void bind_haptic_results(py::module_& m) {
  bind_device_results(m);
  bind_scene_results(m);
  bind_trial_results(m);
}

}  // namespace contactcore::bindings
