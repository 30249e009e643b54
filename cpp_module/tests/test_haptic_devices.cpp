// Device front ends and real-time hygiene without hardware: the stale
// watchdog driven by report arrival times (fake devices whose reports stop),
// the loop's thread mode (absolute deadlines, late wake-ups, memory lock),
// HID recordings, the device factory, replay through the live parsers, and
// the simulated hand on a simulated HID PID device.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <thread>

#include <unistd.h>

#include "contactcore/haptics/device_factory.h"
#include "contactcore/haptics/hid_recording.h"
#include "contactcore/haptics/servo_loop.h"
#include "contactcore/haptics/simulated_pid.h"
#include "contactcore/haptics/spacemouse.h"

using namespace contactcore;
using namespace contactcore::haptics;

namespace {

// A rate device (a SpaceMouse's shape) whose reports the test sends: read()
// holds the last one and says when it ARRIVED, as a real device must.
class ReportingDevice : public Device {
 public:
  ReportingDevice() {
    caps_ = spacemouse_capabilities("reporting fake");
    caps_.force_output = true;  // a rate device with force output (a PID joystick's shape)
    caps_.max_force = 10;
  }
  const DeviceCapabilities& capabilities() const override { return caps_; }
  void report(double arrival, const Vec6& axes) {
    arrival_ = arrival;
    axes_ = axes;
  }
  DeviceSample read(double) noexcept override {
    DeviceSample s;
    s.connected = true;
    s.axes = axes_;
    s.time = arrival_;
    s.at_rest = axes_.isZero(0.0);
    return s;
  }
  void write(const Wrench& w) noexcept override {
    last = w;
    ++writes;
  }
  void halt() noexcept override {
    last = Wrench{};
    ++halts;
  }
  Wrench last;
  int writes = 0, halts = 0;

 private:
  DeviceCapabilities caps_;
  double arrival_ = 0;
  Vec6 axes_ = Vec6::Zero();
};

// The same with a reader thread stamping arrivals on the steady clock (the
// shape of HidSpaceMouse), for the loop's thread mode.
class ThreadedReportingDevice : public Device {
 public:
  ThreadedReportingDevice() {
    caps_ = spacemouse_capabilities("threaded fake");
    caps_.force_output = true;
    caps_.max_force = 10;
  }
  ~ThreadedReportingDevice() override { stop(); }
  const DeviceCapabilities& capabilities() const override { return caps_; }
  // Sends a deflected report every 5 ms for `seconds`, then falls silent.
  void start(double seconds) {
    reader_ = std::thread([this, seconds] {
      const double end = steady_seconds() + seconds;
      while (steady_seconds() < end && !stop_) {
        Reading r;
        r.axes[0] = 0.5;
        r.arrival = steady_seconds();
        readings_.write(r);
        last_arrival_ = r.arrival;
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
      }
    });
  }
  void stop() {
    stop_ = true;
    if (reader_.joinable()) reader_.join();
  }
  DeviceSample read(double now) noexcept override {
    const Reading& r = readings_.read();
    DeviceSample s;
    s.connected = true;
    s.axes = r.axes;
    s.time = now - std::max(0.0, steady_seconds() - r.arrival);
    s.at_rest = r.axes.isZero(0.0);
    return s;
  }
  void write(const Wrench& w) noexcept override { force_.store(w.force.norm()); }
  void halt() noexcept override { force_.store(0.0); }
  double force() const { return force_.load(); }
  double last_arrival() const { return last_arrival_.load(); }

 private:
  struct Reading {
    Vec6 axes = Vec6::Zero();
    double arrival = 0;
  };
  DeviceCapabilities caps_;
  TripleBuffer<Reading> readings_;
  std::thread reader_;
  std::atomic<bool> stop_{false};
  std::atomic<double> force_{0}, last_arrival_{0};
};

ServoConfig lockstep() {
  ServoConfig c;
  c.lockstep = true;
  c.stiffness = 1.0;
  c.damping = 0;
  return c;
}

JointState fixed_joint() {
  JointState j;
  j.kind = JointKind::Fixed;
  return j;
}

std::string temp_path(const char* name) {
  return "/tmp/contacts_test_" + std::to_string(getpid()) + "_" + name;
}

}  // namespace

// Reports every 10 ms with the device deflected, the last one arriving at
// 0.2005 s: the watchdog trips at the first tick more than 0.25 s after that
// arrival (t = 0.451 s), zeroes the force and halts the device; a device
// whose last report put it at rest may stay silent.
TEST(RealtimeHygiene, StaleWatchdogFromArrivalTimes) {
  ReportingDevice device;
  ServoLoop loop(device, lockstep(), Pose::Identity());
  loop.hold_to(fixed_joint());  // the part cannot follow: the coupling pulls
  Vec6 deflected = Vec6::Zero();
  deflected[0] = 0.5;
  for (int tick = 0; tick <= 600; ++tick) {
    const double t = tick * 1e-3;
    if (tick % 10 == 0 && t < 0.2) device.report(t + 0.0005, deflected);
    if (tick == 200) device.report(0.2005, deflected);
    loop.step_lockstep();
    const ServoSnapshot& s = loop.last();
    if (tick <= 450) {
      ASSERT_EQ(s.watchdog, Watchdog::None) << "tick " << tick;
      ASSERT_GT(s.wrench.force.norm(), 0.0) << "tick " << tick;
    } else {
      ASSERT_EQ(s.watchdog, Watchdog::Stale) << "tick " << tick;
      ASSERT_EQ(s.wrench.force.norm(), 0.0);
      ASSERT_EQ(device.last.force.norm(), 0.0);
    }
  }
  EXPECT_EQ(device.halts, 150);  // ticks 451..600
  // A fresh report: the watchdog lets go at once.
  device.report(0.6005, deflected);
  loop.step_lockstep();
  EXPECT_EQ(loop.last().watchdog, Watchdog::None);

  // At rest (all axes zero), silence is not staleness: a SpaceMouse let go sends nothing.
  ReportingDevice resting;
  ServoLoop quiet(resting, lockstep(), Pose::Identity());
  resting.report(0.0, Vec6::Zero());
  for (int tick = 0; tick < 2000; ++tick) quiet.step_lockstep();
  EXPECT_EQ(quiet.last().watchdog, Watchdog::None);
  EXPECT_EQ(resting.halts, 0);
}

// Replayed reports carry their recorded arrival: a recording that stops while
// deflected trips the watchdog 0.25 s after its last report.
TEST(RealtimeHygiene, ReplayedSilenceTripsTheWatchdog) {
  std::vector<RecordedReport> reports;
  for (int i = 0; i < 10; ++i)  // newer format: Tx = 175 (half), report 1 of 13 bytes
    reports.push_back(RecordedReport{0.01 * i + 0.0005, {1, 175, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0}});
  ReplayDevice replay(*find_model(0x256f, 0xc635), reports);  // last report at 0.0905 s
  ServoLoop loop(replay, lockstep(), Pose::Identity());
  loop.hold_to(fixed_joint());
  int first_stale = -1;
  for (int tick = 0; tick < 500; ++tick) {
    loop.step_lockstep();
    if (first_stale < 0 && loop.last().watchdog == Watchdog::Stale) first_stale = tick;
  }
  EXPECT_EQ(first_stale, 341);  // 0.341 - 0.0905 > 0.25 first
  EXPECT_EQ(loop.last().wrench.force.norm(), 0.0);
}

// Thread mode on CLOCK_MONOTONIC with absolute deadlines: a device reporting
// from its own thread, then silent; the watchdog zeroes the force within its
// timeout (judged on the loop's clock); late wake-ups are counted.
TEST(RealtimeHygiene, ThreadModeWatchdogAndStatistics) {
  ThreadedReportingDevice device;
  ServoConfig config;
  config.stiffness = 1.0;
  config.damping = 0;
  config.late_wakeup_us = -1;  // every wake-up counts as late: the counter is exercised
  ServoLoop loop(device, config, Pose::Identity());
  loop.hold_to(fixed_joint());
  device.start(0.15);
  ASSERT_TRUE(loop.start());
  // The device reports for 0.15 s: the force is rendered.
  bool rendered = false;
  for (int i = 0; i < 300 && !rendered; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
    rendered = device.force() > 0;
  }
  EXPECT_TRUE(rendered);
  ServoSnapshot s;
  bool stale = false;
  for (int i = 0; i < 500 && !stale; ++i) {  // up to 5 s on a busy machine
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    s = loop.snapshot();
    stale = s.watchdog == Watchdog::Stale;
  }
  const bool locked = loop.memory_locked();
  const long slack_ns = loop.timer_slack_ns();
  loop.stop();
  device.stop();
  ASSERT_TRUE(stale) << "the watchdog never fired after the reports stopped";
  EXPECT_EQ(device.force(), 0.0);
  EXPECT_EQ(s.wrench.force.norm(), 0.0);
  EXPECT_GT(loop.late_wakeups(), 0u);
  EXPECT_EQ(s.late_wakeups > 0, true);
  EXPECT_GE(loop.wake_latency_max_us(), 0.0);
  // mlockall is attempted only where it cannot make later allocations fail;
  // as root (CAP_IPC_LOCK) it is granted. Released on stop.
  if (geteuid() == 0) EXPECT_TRUE(locked);
  EXPECT_EQ(s.memory_locked, locked);
  EXPECT_FALSE(loop.memory_locked());
  // The loop thread sleeps with 1 ns of timer slack, not a normal thread's 50 us.
  EXPECT_EQ(slack_ns, 1);
  std::printf("[ measured ] thread mode: %llu ticks, rate %.1f Hz, jitter %.1f us, wake latency mean %.1f us max %.1f us, "
              "memory locked %s\n",
              static_cast<unsigned long long>(loop.ticks()), loop.rate_hz(), loop.jitter_us(),
              loop.wake_latency_mean_us(), loop.wake_latency_max_us(), locked ? "yes" : "no");

  // With a generous threshold nothing is late.
  ServoConfig lenient = config;
  lenient.late_wakeup_us = 1e9;
  lenient.lock_memory = false;
  ReportingDevice quiet;
  ServoLoop relaxed(quiet, lenient, Pose::Identity());
  relaxed.start();
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  relaxed.stop();
  EXPECT_GT(relaxed.ticks(), 0u);
  EXPECT_EQ(relaxed.late_wakeups(), 0u);
  EXPECT_FALSE(relaxed.snapshot().memory_locked);
}

TEST(HidRecording, RoundTripAndErrors) {
  HidRecording r;
  r.kind = "hid-ff";
  r.vendor = 0x1234;
  r.product = 0xabcd;
  r.name = "PID stick 2";
  r.descriptor = {0x05, 0x01, 0xC0};
  r.reports = {{0.0125, {1, 0xFF, 0x7F}}, {0.5, {}}, {0.75, {}}, {1.000001, {1, 0, 0}}};
  const std::string path = temp_path("rec.hid");
  ASSERT_TRUE(write_hid_recording(r, path).ok());
  std::ifstream in(path);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text,
            "contacts-hid-recording 1\n"
            "device hid-ff 1234 abcd PID stick 2\n"
            "descriptor 0501c0\n"
            "0.012500 01ff7f\n"
            "0.500000 unplug\n"
            "0.750000 unplug\n"
            "1.000001 010000\n");
  HidRecording back;
  ASSERT_TRUE(read_hid_recording(path, back).ok());
  EXPECT_EQ(back.kind, "hid-ff");
  EXPECT_EQ(back.vendor, 0x1234);
  EXPECT_EQ(back.product, 0xabcd);
  EXPECT_EQ(back.name, "PID stick 2");
  EXPECT_EQ(back.descriptor, r.descriptor);
  ASSERT_EQ(back.reports.size(), 4u);
  EXPECT_DOUBLE_EQ(back.reports[0].time, 0.0125);
  EXPECT_EQ(back.reports[0].bytes, (std::vector<std::uint8_t>{1, 0xFF, 0x7F}));
  EXPECT_TRUE(back.reports[1].bytes.empty());
  EXPECT_DOUBLE_EQ(back.reports[3].time, 1.000001);

  auto error_of = [&](const std::string& content) {
    std::ofstream(path) << content;
    HidRecording ignored;
    return read_hid_recording(path, ignored).describe();
  };
  EXPECT_EQ(error_of("contacts-hid-recording 1\ndevice spacemouse 256f c635 x\n0.5 01\n0.4 01\n"),
            "line 4: arrival times must be finite and not decrease (file '" + path + "')");
  EXPECT_EQ(error_of("contacts-hid-recording 1\ndevice spacemouse 256f c635 x\n0.5 0g\n"),
            "line 3: report bytes must be hexadecimal (file '" + path + "')");
  EXPECT_EQ(error_of("hello\n"), "line 1: not a HID recording (expected 'contacts-hid-recording 1') (file '" + path + "')");
  EXPECT_EQ(error_of("contacts-hid-recording 1\n0.1 01\n"),
            "no 'device' line: which parser replays it is unknown (file '" + path + "')");
  EXPECT_EQ(error_of("contacts-hid-recording 1\ndevice hid-ff 1 2 x\n"),
            "a hid-ff recording needs its 'descriptor' line (file '" + path + "')");
  std::remove(path.c_str());
  HidRecording missing;
  const Status none = read_hid_recording("/nonexistent/x.hid", missing);
  EXPECT_EQ(none.code, StatusCode::ReadError);
  EXPECT_EQ(none.file, "/nonexistent/x.hid");
}

TEST(HidRecording, RecorderStampsArrivalsFromItsOrigin) {
  HidRecorder recorder(100.0);
  const std::uint8_t report[] = {1, 2, 3};
  recorder.report(100.25, report, 3);
  recorder.unplugged(100.5);
  recorder.report(99.0, report, 3);  // before the origin: clamped to 0
  const HidRecording r = recorder.recording();
  ASSERT_EQ(r.reports.size(), 3u);
  EXPECT_DOUBLE_EQ(r.reports[0].time, 0.25);
  EXPECT_TRUE(r.reports[1].bytes.empty());
  EXPECT_DOUBLE_EQ(r.reports[2].time, 0.0);
}

// This machine has no /dev/hidraw: hardware requests fail with the HID
// devices seen (none here, and the message says so); the panel's fallback
// gives the simulated hand and says why.
TEST(DeviceFactory, NoHardwareIsDeviceUnavailableWithTheDevicesSeen) {
  const auto seen = enumerate_hid_devices();
  for (const char* kind : {"spacemouse", "hid-ff"}) {
    DeviceRequest q;
    q.kind = kind;
    q.first_scan_wait = 0.05;
    const DeviceResult r = open_device(q);
    if (r.status.ok()) continue;  // hardware present: nothing to check here
    EXPECT_TRUE(r.device_missing) << kind;
    EXPECT_EQ(r.status.code, StatusCode::InvalidInput) << kind;
    EXPECT_EQ(r.device, nullptr);
    EXPECT_EQ(r.seen.size(), seen.size());
    EXPECT_NE(r.status.message.find("HID devices seen: " + describe_devices_seen(seen)), std::string::npos)
        << r.status.message;
    if (seen.empty()) EXPECT_NE(r.status.message.find("no HID devices seen"), std::string::npos);

    q.fall_back_to_simulated = true;
    const DeviceResult fallback = open_device(q);
    ASSERT_TRUE(fallback.status.ok());
    EXPECT_TRUE(fallback.fell_back);
    EXPECT_TRUE(fallback.simulated);
    ASSERT_NE(fallback.hand, nullptr);
    EXPECT_EQ(fallback.device.get(), static_cast<Device*>(fallback.hand));
    EXPECT_NE(fallback.message.find("using the simulated hand"), std::string::npos);
  }
  EXPECT_EQ(describe_devices_seen({}), "no HID devices seen");
  HidDeviceSeen one;
  one.path = "/dev/hidraw3";
  one.vendor = 0x256f;
  one.product_id = 0xc635;
  one.manufacturer = "3Dconnexion";
  one.product = "SpaceMouse Compact";
  EXPECT_EQ(describe_devices_seen({one}), "256f:c635 3Dconnexion SpaceMouse Compact (/dev/hidraw3)");

  DeviceRequest bad;
  bad.kind = "joystick";
  EXPECT_EQ(open_device(bad).status.code, StatusCode::InvalidArgument);
  DeviceRequest sim;
  const DeviceResult hand = open_device(sim);
  ASSERT_TRUE(hand.status.ok());
  EXPECT_EQ(hand.device->capabilities().name, "simulated hand");
}

// A replay goes through the live device's parser: SpaceMouse reports as
// parse_report reads them, HID PID input through the descriptor's layout.
TEST(DeviceFactory, ReplayThroughTheLiveParsers) {
  DeviceRequest q;
  q.kind = "replay";
  q.replay.kind = "spacemouse";
  q.replay.vendor = 0x046d;
  q.replay.product = 0xc626;  // SpaceNavigator: two reports, y/z swapped and inverted
  q.replay.reports = {{0.010, {0x01, 0x5e, 0x01, 0x00, 0x00, 0xa2, 0xfe}}, {0.020, {0x02, 0, 0, 0, 0, 0xa2, 0xfe}}};
  DeviceResult r = open_device(q);
  ASSERT_TRUE(r.status.ok()) << r.status.describe();
  DeviceSample s = r.device->read(0.03);
  SpaceMouseState expected;
  parse_report(q.replay.reports[0].bytes.data(), 7, *find_model(0x046d, 0xc626), expected);
  parse_report(q.replay.reports[1].bytes.data(), 7, *find_model(0x046d, 0xc626), expected);
  for (int i = 0; i < 6; ++i) EXPECT_DOUBLE_EQ(s.axes[i], expected.axes[i]) << i;
  EXPECT_DOUBLE_EQ(s.axes[0], 1.0);
  EXPECT_DOUBLE_EQ(s.axes[1], 1.0);  // HID z = -350 -> y, inverted
  EXPECT_DOUBLE_EQ(s.time, 0.020);
  EXPECT_NE(r.message.find("2 recorded reports"), std::string::npos) << r.message;

  // HID PID input (the simulated device's descriptor), as a position device.
  DeviceRequest p;
  p.kind = "replay";
  p.replay.kind = "hid-ff";
  p.replay.descriptor = simulated_pid_descriptor();
  p.pid.control = ControlMode::Position;
  p.pid.workspace_mm = 20;
  // X = 32767 (+1), Y = -16384, Z = 0; then 0.1 s later X = 0.
  p.replay.reports = {{0.1, {1, 0xFF, 0x7F, 0x00, 0xC0, 0, 0}}, {0.2, {1, 0, 0, 0x00, 0xC0, 0, 0}}};
  r = open_device(p);
  ASSERT_TRUE(r.status.ok()) << r.status.describe();
  EXPECT_EQ(r.device->capabilities().control, ControlMode::Position);
  EXPECT_EQ(r.device->capabilities().input_dof, 3);
  s = r.device->read(0.15);
  EXPECT_DOUBLE_EQ(s.pose.translation().x(), 20.0);
  EXPECT_NEAR(s.pose.translation().y(), -20.0 * 16384 / 32767, 1e-12);
  s = r.device->read(0.25);
  EXPECT_DOUBLE_EQ(s.pose.translation().x(), 0.0);
  EXPECT_NEAR(s.velocity.x(), -200.0, 1e-9);  // -20 mm in 0.1 s

  DeviceRequest broken = p;
  broken.replay.descriptor = {0x05, 0x01, 0xC0};
  EXPECT_EQ(open_device(broken).status.code, StatusCode::InvalidInput);
}

// The simulated hand on a simulated HID PID device: the loop's force goes out
// as PID reports (spring, damper, constant force) that the simulated firmware
// decodes and pushes the hand with. The part is held: the hand, pulled to
// +2 mm by its own 1 N/mm spring, settles where the device pushes back as
// hard, 0.5 N/mm (the coupling, at the device's limit) x x = 1 N/mm x (2 - x):
// x = 4/3 mm, force 2/3 N.
TEST(SimulatedPid, TheLoopsForceReachesTheHandThroughReports) {
  PidLayout layout;
  std::string why;
  ASSERT_TRUE(find_pid_layout(simulated_pid_descriptor().data(), simulated_pid_descriptor().size(), layout, &why)) << why;
  EXPECT_TRUE(layout.has_conditions());
  EXPECT_EQ(layout.axis_count(), 3);

  HandKey start, end;
  end.t = 0.5;
  end.pose.translation() = Vec3(2, 0, 0);
  PidForceConfig pid;
  pid.full_scale_force = 3;
  pid.workspace_mm = 50;
  pid.max_stiffness = 0.5;
  SimulatedPidDevice device(HandScript({start, end}), HandParameters{}, Vec3::Zero(), Pose::Identity(), pid);
  EXPECT_EQ(device.capabilities().control, ControlMode::Position);
  EXPECT_TRUE(device.capabilities().force_output);
  ServoConfig config = lockstep();
  config.damping = 0.002;
  ServoLoop loop(device, config, Pose::Identity());
  loop.hold_to(fixed_joint());
  for (int i = 0; i < 4000; ++i) loop.step_lockstep();
  EXPECT_TRUE(device.pid().renders_conditions());
  EXPECT_TRUE(device.firmware().actuators_enabled());
  EXPECT_EQ(device.firmware().playing_effects(), 5);  // 3 constant forces, the spring, the damper
  EXPECT_NEAR(device.hand().reference_point().x(), 4.0 / 3.0, 2e-3);
  EXPECT_NEAR(device.felt().force.x(), -2.0 / 3.0, 2e-3);
  EXPECT_NEAR(loop.last().wrench.force.x(), -2.0 / 3.0, 2e-3);
  EXPECT_EQ(loop.last().watchdog, Watchdog::None);
  // Disable: the device stops every effect; the hand then reaches its target.
  loop.set_enabled(false);
  for (int i = 0; i < 3000; ++i) loop.step_lockstep();
  EXPECT_EQ(device.firmware().playing_effects(), 0);
  EXPECT_NEAR(device.felt().force.norm(), 0.0, 1e-12);
  EXPECT_NEAR(device.hand().reference_point().x(), 2.0, 1e-3);
}
