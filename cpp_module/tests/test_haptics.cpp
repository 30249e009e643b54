// Haptic trials without hardware: SpaceMouse reports as byte vectors, replay,
// the simulated hand, and the servo loop in lockstep.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>
#include <cstdlib>
#include <new>
#include <set>

#include <BRepBndLib.hxx>
#include <Bnd_Box.hxx>

#include "contactcore/haptics/servo_loop.h"
#include "contactcore/haptics/simulated.h"
#include "contactcore/haptics/spacemouse.h"

// Counts heap allocations, to check that servo ticks allocate nothing.
static std::atomic<long> g_allocations{0};
void* operator new(std::size_t size) {
  ++g_allocations;
  if (void* p = std::malloc(size ? size : 1)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
// The array and nothrow forms too: each allocation must be released by the
// same family (AddressSanitizer's own forms would otherwise meet our free).
void* operator new[](std::size_t size) { return operator new(size); }
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  ++g_allocations;
  return std::malloc(size ? size : 1);
}
void* operator new[](std::size_t size, const std::nothrow_t& tag) noexcept { return operator new(size, tag); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }

using namespace contactcore::haptics;

namespace {

std::vector<std::uint8_t> bytes(std::initializer_list<int> values) {
  std::vector<std::uint8_t> out;
  for (int v : values) out.push_back(static_cast<std::uint8_t>(v));
  return out;
}

bool parse(const std::vector<std::uint8_t>& report, const SpaceMouseModel& model, SpaceMouseState& s) {
  return parse_report(report.data(), report.size(), model, s);
}

}  // namespace

TEST(SpaceMouse, ModelsAndVendors) {
  const SpaceMouseModel* navigator = find_model(0x046d, 0xc626);
  ASSERT_NE(navigator, nullptr);
  EXPECT_STREQ(navigator->name, "SpaceNavigator");
  EXPECT_EQ(navigator->format, ReportFormat::TwoReports);
  const SpaceMouseModel* compact = find_model(0x256f, 0xc635);
  ASSERT_NE(compact, nullptr);
  EXPECT_EQ(compact->format, ReportFormat::SixAxes);
  EXPECT_TRUE(compact->swap_yz && compact->invert_yz);
  const SpaceMouseModel* plus_xt = find_model(0x046d, 0xc603);
  ASSERT_NE(plus_xt, nullptr);
  EXPECT_FALSE(plus_xt->swap_yz || plus_xt->invert_yz);
  EXPECT_EQ(find_model(0x256f, 0xc650), nullptr);  // CadMouse
  EXPECT_TRUE(is_excluded_product(0x256f, 0xc650));
  EXPECT_TRUE(is_excluded_product(0x256f, 0xc658));
  EXPECT_FALSE(is_excluded_product(0x256f, 0xc635));
  EXPECT_TRUE(is_spacemouse_vendor(0x046d));
  EXPECT_TRUE(is_spacemouse_vendor(0x256f));
  EXPECT_FALSE(is_spacemouse_vendor(0x045e));
  EXPECT_EQ(generic_model(0x256f, 0xc6ff).format, ReportFormat::SixAxes);
}

// SpaceNavigator: translation in report 1, rotation in report 2; HID y and z
// are swapped and inverted into spacenavd's frame.
TEST(SpaceMouse, OlderFormatTwoReports) {
  const SpaceMouseModel& model = *find_model(0x046d, 0xc626);
  SpaceMouseState s;
  // Tx = 10, Ty = -10, Tz = 350
  ASSERT_TRUE(parse(bytes({0x01, 0x0a, 0x00, 0xf6, 0xff, 0x5e, 0x01}), model, s));
  EXPECT_EQ(s.raw[0], 10);
  EXPECT_EQ(s.raw[1], -10);
  EXPECT_EQ(s.raw[2], 350);
  EXPECT_DOUBLE_EQ(s.axes[0], 10.0 / 350);
  EXPECT_DOUBLE_EQ(s.axes[1], -1.0);       // -Tz
  EXPECT_DOUBLE_EQ(s.axes[2], 10.0 / 350);  // -Ty
  EXPECT_DOUBLE_EQ(s.axes[3], 0.0);
  // Rx = -30, Ry = 0, Rz = 100 (the rotation report leaves translation alone)
  ASSERT_TRUE(parse(bytes({0x02, 0xe2, 0xff, 0x00, 0x00, 0x64, 0x00}), model, s));
  EXPECT_EQ(s.raw[3], -30);
  EXPECT_EQ(s.raw[5], 100);
  EXPECT_DOUBLE_EQ(s.axes[0], 10.0 / 350);
  EXPECT_DOUBLE_EQ(s.axes[3], -30.0 / 350);
  EXPECT_DOUBLE_EQ(s.axes[4], -100.0 / 350);  // -Rz
  EXPECT_DOUBLE_EQ(s.axes[5], 0.0);           // -Ry
  // Buttons: report 3, bitmap
  ASSERT_TRUE(parse(bytes({0x03, 0x02, 0x00}), model, s));
  EXPECT_EQ(s.buttons, 2u);
  ASSERT_TRUE(parse(bytes({0x03, 0x00, 0x00}), model, s));
  EXPECT_EQ(s.buttons, 0u);
  EXPECT_EQ(s.reports, 4);
}

TEST(SpaceMouse, NewerFormatSixAxesInReportOne) {
  const SpaceMouseModel& model = *find_model(0x256f, 0xc635);
  SpaceMouseState s;
  ASSERT_TRUE(parse(bytes({0x01, 0x0a, 0x00, 0xf6, 0xff, 0x5e, 0x01, 0xe2, 0xff, 0x00, 0x00, 0x64, 0x00}),
                    model, s));
  const std::int16_t expected_raw[6] = {10, -10, 350, -30, 0, 100};
  for (int i = 0; i < 6; ++i) EXPECT_EQ(s.raw[i], expected_raw[i]) << i;
  const double expected[6] = {10.0 / 350, -1.0, 10.0 / 350, -30.0 / 350, -100.0 / 350, 0.0};
  for (int i = 0; i < 6; ++i) EXPECT_DOUBLE_EQ(s.axes[i], expected[i]) << i;
  // Beyond full scale: clamped to 1; the raw value is kept.
  ASSERT_TRUE(parse(bytes({0x01, 0x20, 0x03, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0}), model, s));
  EXPECT_EQ(s.raw[0], 800);
  EXPECT_DOUBLE_EQ(s.axes[0], 1.0);
  // Enterprise-style 4-byte button bitmap
  ASSERT_TRUE(parse(bytes({0x03, 0x01, 0x00, 0x00, 0x80}), model, s));
  EXPECT_EQ(s.buttons, 0x80000001u);
}

TEST(SpaceMouse, RejectsWhatItDoesNotUnderstand) {
  const SpaceMouseModel& model = *find_model(0x256f, 0xc635);
  SpaceMouseState s;
  EXPECT_FALSE(parse(bytes({0x01, 0x00}), model, s));
  EXPECT_FALSE(parse(bytes({0x02, 0x01, 0x00}), model, s));
  EXPECT_FALSE(parse(bytes({0x17, 0x01, 0x00, 0x00, 0x00, 0x00, 0x00}), model, s));
  EXPECT_FALSE(parse_report(nullptr, 0, model, s));
  EXPECT_EQ(s.reports, 0);
  for (int i = 0; i < 6; ++i) EXPECT_EQ(s.raw[i], 0);
}

TEST(SpaceMouse, PidUsagePageInDescriptor) {
  // Usage Page (Generic Desktop), Usage (Multi-axis), Collection, Report ID 1, ...
  const auto plain = bytes({0x05, 0x01, 0x09, 0x08, 0xa1, 0x01, 0x85, 0x01, 0x16, 0x0c, 0xfe, 0xc0});
  EXPECT_FALSE(descriptor_has_pid_page(plain.data(), plain.size()));
  const auto pid = bytes({0x05, 0x01, 0x09, 0x04, 0xa1, 0x01, 0x05, 0x0f, 0x09, 0x21, 0xc0});
  EXPECT_TRUE(descriptor_has_pid_page(pid.data(), pid.size()));
  const auto pid_two_bytes = bytes({0x06, 0x0f, 0x00, 0x09, 0x21});
  EXPECT_TRUE(descriptor_has_pid_page(pid_two_bytes.data(), pid_two_bytes.size()));
  // 0x0F as the data of another item (Logical Maximum 15) is not a usage page.
  const auto not_page = bytes({0x25, 0x0f, 0x05, 0x01});
  EXPECT_FALSE(descriptor_has_pid_page(not_page.data(), not_page.size()));
  const auto cut = bytes({0x05, 0x01, 0x06, 0x0f});
  EXPECT_FALSE(descriptor_has_pid_page(cut.data(), cut.size()));
}

TEST(SpaceMouse, ReplayHoldsSamplesAndUnplugs) {
  ReplayDevice replay(*find_model(0x046d, 0xc626),
                      {{0.010, bytes({0x01, 0x5e, 0x01, 0x00, 0x00, 0x00, 0x00})},
                       {0.020, bytes({0x02, 0x00, 0x00, 0x00, 0x00, 0xa2, 0xfe})},
                       {0.050, {}},
                       {0.080, {}},
                       {0.090, bytes({0x01, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00})}});
  EXPECT_EQ(replay.capabilities().control, ControlMode::Rate);
  EXPECT_FALSE(replay.capabilities().force_output);
  DeviceSample s = replay.read(0.0);
  EXPECT_TRUE(s.connected);
  EXPECT_DOUBLE_EQ(s.axes[0], 0.0);
  s = replay.read(0.015);
  EXPECT_DOUBLE_EQ(s.axes[0], 1.0);
  s = replay.read(0.030);  // held between reports
  EXPECT_DOUBLE_EQ(s.axes[0], 1.0);
  EXPECT_DOUBLE_EQ(s.axes[4], 1.0);  // Rz = -350 -> -(-1)
  s = replay.read(0.060);
  EXPECT_FALSE(s.connected);
  EXPECT_DOUBLE_EQ(s.axes[0], 0.0);  // unplugged: nothing held
  s = replay.read(0.085);
  EXPECT_TRUE(s.connected);
  s = replay.read(0.095);
  EXPECT_DOUBLE_EQ(s.axes[0], 0.0);
}

TEST(SpaceMouse, NoHardwareIsNotAnError) {
  // This machine has no /dev/hidraw: the back-end says so and reads zeros.
  HidSpaceMouse mouse;
  const DeviceSample s = mouse.read(0.0);
  if (!s.connected) {
    EXPECT_FALSE(mouse.description().empty());
    EXPECT_EQ(s.axes.norm(), 0.0);
  }
  EXPECT_EQ(mouse.capabilities().control, ControlMode::Rate);
}

// ---- simulated hand

TEST(SimulatedHand, ScriptIsPiecewiseLinearAndHeld) {
  const Vec3 centre(1, 2, 3);
  HandScript script({{0.0, offset_pose(Vec3(0, 0, 30), Vec3::Zero(), centre)},
                     {2.0, offset_pose(Vec3(0, 0, 10), Vec3(0, 0, rad(20)), centre)}});
  HandKey k = script.at(1.0, centre);
  Vec3 t, r;
  offset_of(k.pose, centre, t, r);
  EXPECT_NEAR(t.z(), 20.0, 1e-12);
  EXPECT_NEAR(deg(r.z()), 10.0, 1e-9);
  offset_of(script.at(5.0, centre).pose, centre, t, r);
  EXPECT_NEAR(t.z(), 10.0, 1e-12);
  EXPECT_NEAR(deg(r.z()), 20.0, 1e-9);
}

TEST(SimulatedHand, ReachesItsTarget) {
  const Vec3 centre = Vec3::Zero();
  SimulatedHand hand(HandScript({{0.0, Pose::Identity()}, {0.5, offset_pose(Vec3(10, 0, 0), Vec3::Zero(), centre)}}),
                     HandParameters{}, centre, Pose::Identity());
  DeviceSample s;
  for (int i = 0; i <= 3000; ++i) s = hand.read(i * 1e-3);
  EXPECT_NEAR(s.pose.translation().x(), 10.0, 1e-3);
  EXPECT_TRUE(s.connected);
}

// ---- servo loop in lockstep

namespace {

JointState cylinder_on_z(double x = 0, double y = 0) {
  JointState j;
  j.kind = JointKind::Cylindrical;
  j.point = Vec3(x, y, 0);
  j.axis = Vec3::UnitZ();
  j.part_point = Vec3(x, y, 0);
  j.part_axis = Vec3::UnitZ();
  j.part_axial_min = -10;
  j.part_axial_max = 10;
  return j;
}

ServoConfig lockstep_config() {
  ServoConfig c;
  c.lockstep = true;
  c.centre = Vec3::Zero();
  return c;
}

// Collides when the reference point is beyond x = wall: one contact, the
// reference point, normal -x, gap x_wall - x.
class Wall : public CollisionQuery {
 public:
  explicit Wall(double x) : x_(x) {}
  bool collides(const Pose& pose, int) noexcept override {
    ++queries;
    return pose.translation().x() > x_;
  }
  int contacts(const Pose& pose, int, double reach, ContactPoint* out, int capacity) noexcept override {
    ++queries;
    const double gap = x_ - pose.translation().x();
    if (gap >= reach || capacity < 1) return 0;
    out[0].point = pose.translation();
    out[0].normal = -Vec3::UnitX();
    out[0].gap = gap;
    out[0].body = 1;
    return 1;
  }
  double radius_about(const Vec3&) const noexcept override { return 0; }
  int queries = 0;

 private:
  double x_;
};

}  // namespace

TEST(ServoLoop, FreeMotionFollowsTheHand) {
  const Pose goal = offset_pose(Vec3(10, -5, 3), Vec3(0, 0, rad(10)), Vec3::Zero());
  SimulatedHand hand(HandScript({{0.0, Pose::Identity()}, {0.5, goal}}), HandParameters{}, Vec3::Zero(),
                     Pose::Identity());
  ServoLoop loop(hand, lockstep_config(), Pose::Identity());
  for (int i = 0; i < 3000; ++i) loop.step_lockstep();
  EXPECT_LT((loop.proxy().translation() - goal.translation()).norm(), 1e-3);
  EXPECT_LT(rotation_vector(loop.proxy().linear() * goal.linear().transpose()).norm(), 1e-5);
  EXPECT_EQ(loop.ticks(), 3000u);
  EXPECT_FALSE(loop.last().engaged);
}

TEST(ServoLoop, MotionStaysInTheFreeDirections) {
  // The hand pulls sideways, tilts and twists: the part only slides and turns on z.
  const Pose goal = offset_pose(Vec3(3, 2, 20), Vec3(rad(5), rad(-4), rad(30)), Vec3::Zero());
  SimulatedHand hand(HandScript({{0.0, Pose::Identity()}, {1.0, goal}}), HandParameters{}, Vec3::Zero(),
                     Pose::Identity());
  ServoLoop loop(hand, lockstep_config(), Pose::Identity());
  loop.hold_to(cylinder_on_z());
  double worst_offset = 0, worst_tilt = 0;
  for (int i = 0; i < 4000; ++i) {
    loop.step_lockstep();
    const Pose& p = loop.proxy();
    worst_offset = std::max(worst_offset, p.translation().head<2>().norm());
    worst_tilt = std::max(worst_tilt, (p.linear() * Vec3::UnitZ() - Vec3::UnitZ()).norm());
  }
  EXPECT_LT(worst_offset, 1e-9);
  EXPECT_LT(worst_tilt, 1e-9);
  EXPECT_NEAR(loop.proxy().translation().z(), 20.0, 0.05);  // free along the axis: it follows
  Vec3 t, r;
  offset_of(loop.proxy(), Vec3::Zero(), t, r);
  EXPECT_GT(deg(r.z()), 20.0);  // and turns with the hand
  EXPECT_GT(loop.last().coupling.force.head<2>().norm(), 1.0);  // the joint resists the side pull
}

TEST(ServoLoop, StopHolds) {
  // A shoulder: z >= -5 (normal -z, limit 5); the hand pushes to z = -20.
  SimulatedHand hand(HandScript({{0.0, Pose::Identity()}, {1.0, offset_pose(Vec3(0, 0, -20), Vec3::Zero(), Vec3::Zero())}}),
                     HandParameters{}, Vec3::Zero(), Pose::Identity());
  ServoLoop loop(hand, lockstep_config(), Pose::Identity());
  JointState joint = cylinder_on_z();
  joint.add_stop(Vec3(0, 0, -1), 5.0);
  loop.hold_to(joint);
  double lowest = 0;
  for (int i = 0; i < 3000; ++i) {
    loop.step_lockstep();
    lowest = std::min(lowest, loop.proxy().translation().z());
  }
  EXPECT_GE(lowest, -5.0 - 1e-12);
  EXPECT_NEAR(loop.proxy().translation().z(), -5.0, 1e-12);
  EXPECT_TRUE(loop.last().blocked);
  EXPECT_GT(loop.last().wrench.force.z(), 0.5);  // the device feels the shoulder
  EXPECT_LE(loop.last().max_penetration, 1e-12);
}

TEST(ServoLoop, CollisionHolds) {
  SimulatedHand hand(HandScript({{0.0, Pose::Identity()}, {0.5, offset_pose(Vec3(10, 0, 0), Vec3::Zero(), Vec3::Zero())}}),
                     HandParameters{}, Vec3::Zero(), Pose::Identity());
  ServoConfig config = lockstep_config();
  ServoLoop loop(hand, config, Pose::Identity());
  Wall wall(4.0);
  loop.set_collision(&wall);
  double furthest = 0;
  for (int i = 0; i < 2000; ++i) {
    loop.step_lockstep();
    furthest = std::max(furthest, loop.proxy().translation().x());
  }
  EXPECT_LE(furthest, 4.0);
  // The proxy rests on the wall, the contact's skin away.
  EXPECT_NEAR(loop.proxy().translation().x(), 4.0 - config.contact_skin, 1e-9);
  EXPECT_GT(wall.queries, 2000);
  EXPECT_LT(loop.last().wrench.force.x(), -0.5);
}

// A part held still against a wall (the hand pushing it there) moves no point
// at all: the end pose's query could only repeat the start's, so a tick makes
// one contact query, not two. While it still moves towards the wall within
// reach, its steps (0.15 mm a tick) are checked at their end pose as before.
TEST(ServoLoop, PartHeldStillAgainstAWallMakesOneQueryPerTick) {
  SimulatedHand hand(HandScript({{0.0, Pose::Identity()}, {0.5, offset_pose(Vec3(10, 0, 0), Vec3::Zero(), Vec3::Zero())}}),
                     HandParameters{}, Vec3::Zero(), Pose::Identity());
  ServoConfig config = lockstep_config();
  ServoLoop loop(hand, config, Pose::Identity());
  Wall wall(4.0);
  loop.set_collision(&wall);
  int approach_queries = 0, approach_ticks = 0;
  for (int i = 0; i < 1500; ++i) {
    const double x = loop.proxy().translation().x();
    const int before = wall.queries;
    loop.step_lockstep();
    // The wall within the query's reach (0.044 mm: the step's 0.02 mm, the hand's speed, plus the
    // push-out and skin), the part still 0.01 mm or more from its rest: its step moves it more
    // than the 0.002 mm allowed (two such ticks, at x 3.960 and 3.980).
    if (x > 4.0 - 0.04 && x < 4.0 - 0.01) {
      approach_queries += wall.queries - before;
      ++approach_ticks;
    }
  }
  EXPECT_EQ(approach_ticks, 2);
  EXPECT_EQ(approach_queries, 2 * approach_ticks);  // start and end pose of each step
  EXPECT_NEAR(loop.proxy().translation().x(), 4.0 - config.contact_skin, 1e-9);
  const int queries = wall.queries;
  const std::uint64_t skipped = loop.end_checks_skipped();
  for (int i = 0; i < 500; ++i) loop.step_lockstep();
  EXPECT_EQ(wall.queries - queries, 500);
  EXPECT_EQ(loop.end_checks_skipped() - skipped, 500u);
  EXPECT_NEAR(loop.proxy().translation().x(), 4.0 - config.contact_skin, 1e-9);  // still resting there
  EXPECT_LT(loop.last().wrench.force.x(), -0.5);                                 // pushed into it
}

TEST(ServoLoop, ForceAndStiffnessClampedToTheDevice) {
  HandParameters stiff_hand;
  stiff_hand.stiffness = 10;  // a hand pushing hard
  stiff_hand.damping = 0.3;
  SimulatedHand hand(HandScript({{0.0, Pose::Identity()}, {0.5, offset_pose(Vec3(0, 0, -20), Vec3::Zero(), Vec3::Zero())}}),
                     stiff_hand, Vec3::Zero(), Pose::Identity());
  ServoConfig config = lockstep_config();
  config.stiffness = 10;  // beyond the device's 2 N/mm
  config.damping = 0;
  ServoLoop loop(hand, config, Pose::Identity());
  JointState joint = cylinder_on_z();
  joint.add_stop(Vec3(0, 0, -1), 5.0);
  loop.hold_to(joint);
  const double max_force = hand.capabilities().max_force;
  double strongest = 0;
  for (int i = 0; i < 3000; ++i) {
    loop.step_lockstep();
    strongest = std::max(strongest, loop.last().wrench.force.norm());
  }
  EXPECT_NEAR(strongest, max_force, 1e-9);
  EXPECT_NEAR(loop.last().wrench.force.norm(), max_force, 1e-9);
  // The coupling used the device's stiffness, 2 N/mm, not the 10 asked for.
  const double stretch = loop.proxy().translation().z() - hand.pose().translation().z();
  EXPECT_GT(stretch, 6.0);
  EXPECT_NEAR(loop.last().coupling.force.z(), 2.0 * stretch, 0.05);
  EXPECT_NEAR(hand.applied().force.norm(), max_force, 1e-9);
}

TEST(ServoLoop, ZeroForceOnDisableAndUnplug) {
  SimulatedHand hand(HandScript({{0.0, Pose::Identity()}, {0.5, offset_pose(Vec3(0, 0, -20), Vec3::Zero(), Vec3::Zero())}}),
                     HandParameters{}, Vec3::Zero(), Pose::Identity());
  ServoLoop loop(hand, lockstep_config(), Pose::Identity());
  JointState joint = cylinder_on_z();
  joint.add_stop(Vec3(0, 0, -1), 5.0);
  loop.hold_to(joint);
  for (int i = 0; i < 1000; ++i) loop.step_lockstep();
  ASSERT_GT(hand.applied().force.norm(), 1.0);

  loop.set_enabled(false);
  loop.step_lockstep();
  EXPECT_EQ(hand.applied().force.norm(), 0.0);
  EXPECT_EQ(hand.applied().torque.norm(), 0.0);
  EXPECT_EQ(loop.last().watchdog, Watchdog::Disabled);
  const Pose held = loop.proxy();
  for (int i = 0; i < 100; ++i) loop.step_lockstep();
  EXPECT_TRUE(loop.proxy().isApprox(held));  // nothing moves while disabled

  loop.set_enabled(true);
  for (int i = 0; i < 200; ++i) loop.step_lockstep();
  EXPECT_EQ(loop.last().watchdog, Watchdog::None);

  hand.set_connected(false);
  loop.step_lockstep();
  EXPECT_EQ(hand.applied().force.norm(), 0.0);
  EXPECT_EQ(loop.last().watchdog, Watchdog::Unplugged);
  EXPECT_EQ(loop.snapshot().watchdog, Watchdog::Unplugged);
}

namespace {
// A device that stops reporting after a while (a cable that still answers, a frozen driver).
class FreezingDevice : public Device {
 public:
  FreezingDevice() : caps_(simulated_capabilities()) {}
  const DeviceCapabilities& capabilities() const override { return caps_; }
  DeviceSample read(double now) noexcept override {
    DeviceSample s;
    s.connected = true;
    s.time = std::min(now, 0.1);
    s.pose = offset_pose(Vec3(0, 0, -200 * s.time), Vec3::Zero(), Vec3::Zero());
    return s;
  }
  void write(const Wrench& w) noexcept override { last = w; }
  Wrench last;

 private:
  DeviceCapabilities caps_;
};
}  // namespace

TEST(ServoLoop, ZeroForceOnStaleDevice) {
  FreezingDevice device;
  ServoLoop loop(device, lockstep_config(), offset_pose(Vec3(0, 0, 10), Vec3::Zero(), Vec3::Zero()));
  JointState joint = cylinder_on_z();
  joint.add_stop(Vec3(0, 0, -1), -5.0);  // z >= 5
  loop.hold_to(joint);
  for (int i = 0; i < 200; ++i) loop.step_lockstep();
  EXPECT_GT(device.last.force.norm(), 1.0);
  for (int i = 0; i < 300; ++i) loop.step_lockstep();  // t = 0.5 s: 0.4 s without a report
  EXPECT_EQ(loop.last().watchdog, Watchdog::Stale);
  EXPECT_EQ(device.last.force.norm(), 0.0);
}

TEST(ServoLoop, EnergyNeverGrowsWithAPassiveHand) {
  // No script: the hand only carries its momentum into a wall through the coupling.
  HandParameters loose;
  loose.damping = 0.005;
  loose.angular_damping = 10;
  SimulatedHand hand(HandScript{}, loose, Vec3::Zero(), Pose::Identity());
  Vec6 push;
  push << 150, 40, 0, 0, 0, 1.0;
  hand.set_velocity(push);
  ServoConfig config = lockstep_config();
  ServoLoop loop(hand, config, Pose::Identity());
  Wall wall(2.0);
  loop.set_collision(&wall);
  const double k = std::min(config.stiffness, hand.capabilities().max_stiffness);
  const double kr = std::min(config.angular_stiffness, hand.capabilities().max_angular_stiffness);
  auto energy = [&] {
    const Pose& p = loop.proxy();
    const Pose& d = hand.pose();
    return hand.kinetic_energy() + 0.5 * k * (p.translation() - d.translation()).squaredNorm() +
           0.5 * kr * rotation_vector(p.linear() * d.linear().transpose()).squaredNorm();
  };
  loop.step_lockstep();
  double previous = energy();
  const double initial = previous;
  ASSERT_GT(initial, 1.0);
  double reach = 0;
  for (int i = 0; i < 3000; ++i) {
    loop.step_lockstep();
    reach = std::max(reach, hand.pose().translation().x());
    const double e = energy();
    ASSERT_LE(e, previous + 1e-9 * initial) << "tick " << i;
    previous = e;
  }
  EXPECT_LT(previous, 0.05 * initial);
  EXPECT_GT(reach, 3.0);  // the hand went past the wall the part stopped at
  EXPECT_LE(loop.last().max_force, hand.capabilities().max_force);
}

TEST(ServoLoop, TicksAllocateNothing) {
  SimulatedHand hand(HandScript({{0.0, Pose::Identity()}, {0.5, offset_pose(Vec3(10, 2, 30), Vec3(0.1, 0, 0.5), Vec3::Zero())}}),
                     HandParameters{}, Vec3::Zero(), Pose::Identity());
  ServoLoop loop(hand, lockstep_config(), Pose::Identity());
  Wall wall(4.0);
  loop.set_collision(&wall);
  JointState joint = cylinder_on_z();
  joint.add_stop(Vec3(0, 0, 1), 12.0);
  loop.hold_to(joint);
  loop.step_lockstep();
  const long before = g_allocations.load();
  for (int i = 0; i < 1000; ++i) loop.step_lockstep();
  (void)loop.snapshot();
  EXPECT_EQ(g_allocations.load() - before, 0);
}

TEST(ServoLoop, ThreadTicksPublishesSnapshotsAndStops) {
  // Functional only (the rate and jitter figures are benchmarks): the thread
  // ticks, publishes snapshots and stops on request.
  SimulatedHand hand(HandScript{}, HandParameters{}, Vec3::Zero(), Pose::Identity());
  ServoConfig config;
  ServoLoop loop(hand, config, Pose::Identity());
  ASSERT_TRUE(loop.start());
  EXPECT_FALSE(loop.start());
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  const ServoSnapshot s = loop.snapshot();
  loop.stop();
  EXPECT_GT(s.ticks, 10u);
  EXPECT_GT(loop.ticks(), s.ticks - 1);
  EXPECT_FALSE(loop.running());
}

TEST(TripleBuffer, ReaderGetsTheLatest) {
  TripleBuffer<int> buffer;
  EXPECT_EQ(buffer.read(), 0);
  buffer.write(1);
  buffer.write(2);
  EXPECT_EQ(buffer.read(), 2);
  EXPECT_EQ(buffer.read(), 2);
  buffer.write(3);
  EXPECT_EQ(buffer.read(), 3);
}

// ---- the motor: real-time contacts, engagement and the scripted insertion

#include "contactcore/haptics/trial.h"

namespace {
struct MotorScene {
  contactcore::Assembly assembly;
  std::unique_ptr<TrialScene> scene;
};
MotorScene& motor_scene() {
  static MotorScene motor = [] {
    MotorScene m;
    auto read = contactcore::read_step(std::string(CONTACTS_SAMPLES) + "/motor.step");
    m.assembly = read.assembly;
    contactcore::Status status;
    m.scene = TrialScene::build(m.assembly, "Axis", SceneOptions{}, status);
    return m;
  }();
  return motor;
}
int body_index(const TrialScene& scene, const std::string& name) {
  for (std::size_t i = 0; i < scene.body_names().size(); ++i)
    if (scene.body_names()[i] == name) return static_cast<int>(i);
  return -1;
}
}  // namespace

TEST(TrialScene, UnknownPartIsAClearError) {
  MotorScene& motor = motor_scene();
  contactcore::Status status;
  auto scene = TrialScene::build(motor.assembly, "Crankshaft", SceneOptions{}, status);
  EXPECT_EQ(scene, nullptr);
  EXPECT_EQ(status.code, contactcore::StatusCode::InvalidInput);
  EXPECT_NE(status.message.find("Crankshaft"), std::string::npos);
  EXPECT_NE(status.message.find("Axis"), std::string::npos);
}

TEST(RealtimeContacts, MotorAxisAssembledHasTheFiveShaftJoints) {
  TrialScene& scene = *motor_scene().scene;
  std::vector<LiveContact> live(64);
  const int n = scene.contacts().update(Pose::Identity(), live.data(), 64);
  std::set<std::string> clj;
  int plf = 0;
  for (int i = 0; i < n; ++i) {
    if (live[i].type == contactcore::ContactType::CLJ) clj.insert(scene.body_names()[live[i].body]);
    if (live[i].type == contactcore::ContactType::PLF) ++plf;
  }
  // The expected contacts of the motor (motor.expected.json): five CLJ, no PLF.
  EXPECT_EQ(clj, (std::set<std::string>{"Rotor-front", "Rotor-back", "Bearing-front", "Bearing-back", "Seal"}));
  EXPECT_EQ(plf, 0);
  // 30 mm out along the axis it has left the back bearing only.
  const int n30 = scene.contacts().update(offset_pose(Vec3(0, 0, 30), Vec3::Zero(), scene.centre()), live.data(), 64);
  std::set<std::string> clj30;
  for (int i = 0; i < n30; ++i)
    if (live[i].type == contactcore::ContactType::CLJ) clj30.insert(scene.body_names()[live[i].body]);
  EXPECT_EQ(clj30, (std::set<std::string>{"Rotor-front", "Rotor-back", "Bearing-front", "Seal"}));
  // Off the axis by more than the capture distance: none.
  const int far = scene.contacts().update(offset_pose(Vec3(2, 0, 30), Vec3::Zero(), scene.centre()), live.data(), 64);
  int clj_far = 0;
  for (int i = 0; i < far; ++i) clj_far += live[i].type == contactcore::ContactType::CLJ;
  EXPECT_EQ(clj_far, 0);
}

TEST(RealtimeContacts, CaptureSnapsOntoTheBoreAxis) {
  TrialScene& scene = *motor_scene().scene;
  const Pose misaligned = offset_pose(Vec3(0.2, -0.15, 30), Vec3(rad(0.3), rad(-0.2), 0), scene.centre());
  JointState joint;
  ASSERT_TRUE(scene.finder().capture(misaligned, joint));
  EXPECT_EQ(joint.kind, JointKind::Cylindrical);
  EXPECT_NEAR(std::abs(joint.axis.z()), 1.0, 1e-9);
  EXPECT_NEAR(joint.point.head<2>().norm(), 0.0, 1e-6);
  EXPECT_EQ(joint.stop_count, 0);  // the motor's shaft has no shoulder (no PLF contact)
  EXPECT_GE(joint.group, 0);
  const Pose snapped = snap_to_joint(joint, misaligned);
  EXPECT_LT(joint_deviation(joint, snapped), 1e-9);
  EXPECT_GT(joint_deviation(joint, misaligned), 0.1);
  // Switched off, the shaft slides in its bores without collision; without, it collides.
  EXPECT_FALSE(scene.collision().collides(snapped, joint.group));
  EXPECT_TRUE(scene.collision().collides(snapped, -1));
  // Free (not engaged), 1 mm off the axis: clear above the motor, colliding
  // once its end reaches the seal (z 54..57; the shaft's end is at z 4 + offset).
  EXPECT_FALSE(scene.collision().collides(offset_pose(Vec3(1, 0, 70), Vec3::Zero(), scene.centre()), -1));
  EXPECT_TRUE(scene.collision().collides(offset_pose(Vec3(1, 0, 51), Vec3::Zero(), scene.centre()), -1));
  EXPECT_FALSE(scene.collision().collides(offset_pose(Vec3(1, 0, 54), Vec3::Zero(), scene.centre()), -1));
  EXPECT_GE(body_index(scene, "Seal"), 0);
}

TEST(Trial, MotorAxisInsertionEndsSeated) {
  TrialScene& scene = *motor_scene().scene;
  TrialScript script;
  script.start.translate = Vec3(0.25, -0.2, 30);
  script.start.rotate_deg = Vec3(0.4, -0.3, 0);
  script.hand = {{0.0, Vec3(0.25, -0.2, 30), Vec3(0.4, -0.3, 0)},
                 {2.5, Vec3(0.3, 0.2, 0), Vec3(-0.5, 0.4, 2)},
                 {3.0, Vec3(0, 0, 0), Vec3(0, 0, 0)}};
  TrialOptions options;
  const TrialResult r = run_trial(scene, script, options);
  ASSERT_TRUE(r.status.ok());
  EXPECT_EQ(r.ticks, 4500u);
  EXPECT_LT(r.final_translate.norm(), 0.05) << r.final_translate.transpose();
  EXPECT_LT(r.final_rotate_deg.norm(), 0.1) << r.final_rotate_deg.transpose();
  EXPECT_LE(r.max_penetration_mm, 0.05);
  std::set<std::string> with;
  for (const auto& j : r.joints_engaged) with.insert(j.with);
  EXPECT_EQ(with, (std::set<std::string>{"Rotor-front", "Rotor-back", "Bearing-front", "Bearing-back", "Seal"}));
}

TEST(Trial, MotorTicksAllocateNothing) {
  // The whole tick on the motor: finder (real-time contacts), the collision
  // stage's queries with the joint's partitions switched off, the hand.
  TrialScene& scene = *motor_scene().scene;
  const Vec3 c = scene.centre();
  const Pose start = offset_pose(Vec3(0.2, 0.1, 30), Vec3(rad(0.3), 0, 0), c);
  SimulatedHand hand(HandScript({{0.0, start}, {1.0, offset_pose(Vec3(0, 0, 0), Vec3::Zero(), c)}}),
                     HandParameters{}, c, start);
  ServoConfig config;
  config.lockstep = true;
  config.centre = c;
  ServoLoop loop(hand, config, start);
  loop.set_joint_finder(&scene.finder());
  loop.set_collision(&scene.collision());
  for (int i = 0; i < 50; ++i) loop.step_lockstep();
  ASSERT_TRUE(loop.last().engaged);
  const long before = g_allocations.load();
  for (int i = 0; i < 1500; ++i) loop.step_lockstep();
  EXPECT_EQ(g_allocations.load() - before, 0);
  EXPECT_LT((loop.proxy() * c - c).norm(), 0.05);
}

// ---- the joints stage through the adapter

#include "contactcore/haptics/joint_adapter.h"

TEST(JointAdapter, BearingHeldToItsAssembledJointStopsOnTheCover) {
  MotorScene& motor = motor_scene();
  const auto& a = motor.assembly;
  const contactcore::ContactsResult contacts = contactcore::find_contacts(a, contactcore::ContactOptions{});
  const contactcore::JointsResult joints = contactcore::find_joints(a, contacts);
  auto id = [&](const std::string& name) { return body_index(*motor.scene, name); };
  const int bearing = id("Bearing-back"), cover = id("Back-cover");
  const auto it = std::find_if(joints.joints.begin(), joints.joints.end(), [&](const contactcore::PairJoint& p) {
    return std::min(bearing, cover) == p.body_a && std::max(bearing, cover) == p.body_b;
  });
  ASSERT_NE(it, joints.joints.end());
  // Bore and seat (CLJ + PLF): revolute in the joints stage, the seat a one-sided stop.
  ASSERT_EQ(it->type, contactcore::JointType::Revolute);
  ASSERT_FALSE(it->stops.empty());
  const contactcore::MassProperties mp = contactcore::mass_properties(a.bodies[bearing].shape);
  const Vec3 c(mp.centre.X(), mp.centre.Y(), mp.centre.Z());
  Bnd_Box bb;
  BRepBndLib::Add(a.bodies[bearing].shape, bb, false);
  double x0, y0, z0, x1, y1, z1;
  bb.Get(x0, y0, z0, x1, y1, z1);
  JointState joint;
  ASSERT_TRUE(joint_state_from_pair(*it, bearing, c, Eigen::AlignedBox3d(Vec3(x0, y0, z0), Vec3(x1, y1, z1)), joint));
  EXPECT_EQ(joint.kind, JointKind::Cylindrical);
  EXPECT_NEAR(std::abs(joint.axis.z()), 1.0, 1e-9);
  ASSERT_EQ(joint.stop_count, 1);
  EXPECT_NEAR(joint.stops[0].normal.z(), -1.0, 1e-9);  // it cannot go down into the cover
  // Pushed down by the hand, it stays seated; pulled up, it follows.
  for (double dz : {-3.0, 4.0}) {
    SimulatedHand hand(HandScript({{0.0, Pose::Identity()}, {0.5, offset_pose(Vec3(0.2, 0, dz), Vec3::Zero(), c)}}),
                       HandParameters{}, c, Pose::Identity());
    ServoConfig config;
    config.lockstep = true;
    config.centre = c;
    ServoLoop loop(hand, config, Pose::Identity());
    loop.hold_to(joint);
    double lowest = 0;
    for (int i = 0; i < 1500; ++i) {
      loop.step_lockstep();
      lowest = std::min(lowest, loop.proxy().translation().z());
    }
    EXPECT_GE(lowest, -1e-12);
    EXPECT_NEAR(loop.proxy().translation().z(), dz < 0 ? 0.0 : dz, 0.02);
    EXPECT_LT(loop.proxy().translation().head<2>().norm(), 1e-9);
  }
}

// ---- engagement on cones and planes (generated shapes, hand-derived poses)

#include <BRepAlgoAPI_Cut.hxx>

#include "test_helpers.h"
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCone.hxx>
#include <gp_Ax2.hxx>

namespace {

// A 40 x 40 x 20 block with a conical through-hole of half-angle 30 degrees
// (radius 5 at its bottom z = 0, opening upwards), and a conical plug of the
// same angle 0.1 mm larger in radius, z -3 .. 12 (it hangs out of the hole's
// bottom, so its ends touch nothing). Seated, the plug stands 0.1 / tan 30
// = 0.1 sqrt 3 = 0.17320508 mm above its modelled placement.
struct ConeSeat {
  contactcore::Assembly assembly;
  std::unique_ptr<TrialScene> scene;
};
ConeSeat& cone_seat_scene() {
  static ConeSeat seat = [] {
    const double t = std::tan(kPi / 6);
    const TopoDS_Shape box = BRepPrimAPI_MakeBox(gp_Pnt(-20, -20, 0), 40, 40, 20).Shape();
    // The hole runs a little past both faces so the cut is clean: radius 5 + z tan 30.
    const TopoDS_Shape hole =
        BRepPrimAPI_MakeCone(gp_Ax2(gp_Pnt(0, 0, -1), gp_Dir(0, 0, 1)), 5 - t, 5 + 21 * t, 22).Shape();
    const TopoDS_Shape seat_shape = BRepAlgoAPI_Cut(box, hole).Shape();
    const TopoDS_Shape plug =
        BRepPrimAPI_MakeCone(gp_Ax2(gp_Pnt(0, 0, -3), gp_Dir(0, 0, 1)), 5.1 - 3 * t, 5.1 + 12 * t, 15).Shape();
    ConeSeat s;
    s.assembly = contactcore::testing::make_assembly({{"Seat", seat_shape}, {"Plug", plug}});
    contactcore::Status status;
    s.scene = TrialScene::build(s.assembly, "Plug", SceneOptions{}, status);
    EXPECT_TRUE(status.ok()) << status.describe();
    return s;
  }();
  return seat;
}

// A 10 mm cube resting on a 40 x 40 x 5 plate (the plate's top at z = 0).
struct Plate {
  contactcore::Assembly assembly;
  std::unique_ptr<TrialScene> scene;
};
Plate& plate_scene() {
  static Plate plate = [] {
    Plate p;
    p.assembly = contactcore::testing::make_assembly(
        {{"Plate", BRepPrimAPI_MakeBox(gp_Pnt(-20, -20, -5), 40, 40, 5).Shape()},
         {"Block", BRepPrimAPI_MakeBox(gp_Pnt(-5, -5, 0), 10, 10, 10).Shape()}});
    contactcore::Status status;
    p.scene = TrialScene::build(p.assembly, "Block", SceneOptions{}, status);
    EXPECT_TRUE(status.ok()) << status.describe();
    return p;
  }();
  return plate;
}

}  // namespace

TEST(Engagement, ConeSnapsToTheAxisAndSeats) {
  TrialScene& scene = *cone_seat_scene().scene;
  const Vec3 c = scene.centre();
  // 15 mm up, 0.2 mm off the axis and tilted 0.5 degrees: captured on the axis.
  const Pose start = offset_pose(Vec3(0.2, -0.1, 15), Vec3(rad(0.5), 0, 0), c);
  JointState joint;
  ASSERT_TRUE(scene.finder().capture(start, joint));
  EXPECT_EQ(joint.kind, JointKind::Cylindrical);
  EXPECT_EQ(joint.contact_type, static_cast<int>(contactcore::ContactType::CJU));
  EXPECT_NEAR(joint.axis.z(), 1.0, 1e-9);
  EXPECT_NEAR(joint.point.head<2>().norm(), 0.0, 1e-6);
  ASSERT_EQ(joint.stop_count, 1);  // the seat only: the cone is open upwards
  // The seat stop: the centre may not go below 0.1 sqrt 3 above its modelled height.
  EXPECT_NEAR(joint.stops[0].normal.z(), -1.0, 1e-9);
  EXPECT_NEAR(-joint.stops[0].limit - c.z(), 0.1 * std::sqrt(3.0), 1e-6);
  // Far off the axis: no seat.
  EXPECT_FALSE(scene.finder().capture(offset_pose(Vec3(2, 0, 15), Vec3::Zero(), c), joint));

  // The hand pushes 2 mm below the modelled placement, off the axis by 0.36 mm:
  // the plug slides down the axis and stops on the seat.
  TrialScript script;
  script.start.translate = Vec3(0.2, -0.1, 15);
  script.start.rotate_deg = Vec3(0.5, 0, 0);
  script.hand = {{0.0, Vec3(0.2, -0.1, 15), Vec3(0.5, 0, 0)}, {2.0, Vec3(0.3, 0.2, -2), Vec3::Zero()}};
  const TrialResult r = run_trial(scene, script, TrialOptions{});
  ASSERT_TRUE(r.status.ok());
  EXPECT_NEAR(r.final_translate.z(), 0.1 * std::sqrt(3.0), 1e-6) << r.final_translate.transpose();
  EXPECT_LT(r.final_translate.head<2>().norm(), 1e-6);
  EXPECT_LT(r.final_rotate_deg.head<2>().norm(), 1e-6);
  EXPECT_LE(r.max_penetration_mm, 1e-6);
  ASSERT_EQ(r.joints_engaged.size(), 1u);
  EXPECT_EQ(r.joints_engaged[0].with, "Seat");
  EXPECT_EQ(r.joints_engaged[0].type, "CJU");
}

TEST(Engagement, ConeBreaksAwayAbovePullThreshold) {
  TrialScene& scene = *cone_seat_scene().scene;
  const Vec3 c = scene.centre();
  const Pose start = offset_pose(Vec3(0, 0, 5), Vec3::Zero(), c);
  // The hand pulls 30 mm sideways: its own spring (1 N/mm) and the coupling
  // (1 N/mm) in series pull 15 N across the axis, above the 8 N threshold.
  SimulatedHand hand(HandScript({{0.0, start}, {0.3, offset_pose(Vec3(30, 0, 5), Vec3::Zero(), c)}}),
                     HandParameters{}, c, start);
  ServoConfig config;
  config.lockstep = true;
  config.centre = c;
  ServoLoop loop(hand, config, start);
  loop.set_joint_finder(&scene.finder());
  loop.set_collision(&scene.collision());
  loop.step_lockstep();
  ASSERT_TRUE(loop.last().engaged);
  bool released = false;
  for (int i = 0; i < 600 && !released; ++i) {
    loop.step_lockstep();
    released = !loop.last().engaged;
  }
  EXPECT_TRUE(released);
}

TEST(Engagement, FaceSnapsParallelAndSlidesOnThePlane) {
  TrialScene& scene = *plate_scene().scene;
  const Vec3 c = scene.centre();
  // 0.3 mm above the plate, tilted (1, -0.5) degrees: captured, turned parallel.
  const Pose start = offset_pose(Vec3(3, 2, 0.3), Vec3(rad(1), rad(-0.5), rad(10)), c);
  JointState joint;
  ASSERT_TRUE(scene.finder().capture(start, joint));
  EXPECT_EQ(joint.kind, JointKind::Planar);
  EXPECT_NEAR(joint.axis.z(), 1.0, 1e-9);
  ASSERT_EQ(joint.stop_count, 1);
  // The block's centre (z = 5) may not go below 5: its face on the plate.
  EXPECT_NEAR(joint.stops[0].normal.z(), -1.0, 1e-9);
  EXPECT_NEAR(-joint.stops[0].limit, 5.0, 1e-9);
  const Pose snapped = snap_to_joint(joint, start);
  EXPECT_NEAR((snapped.linear() * Vec3::UnitZ()).z(), 1.0, 1e-12);
  EXPECT_LT(joint_deviation(joint, snapped), 1e-9);
  // Tilted 5 degrees: past the capture angle, no plane joint.
  EXPECT_FALSE(scene.finder().capture(offset_pose(Vec3(3, 2, 0.3), Vec3(rad(5), 0, 0), c), joint));

  // The hand slides it to (8, -5), turns it 30 degrees about z and pushes 1 mm
  // into the plate: it ends on the plate at (8, -5, 0), turned 30 degrees.
  TrialScript script;
  script.start.translate = Vec3(3, 2, 0.3);
  script.start.rotate_deg = Vec3(1, -0.5, 10);
  script.hand = {{0.0, Vec3(3, 2, 0.3), Vec3(1, -0.5, 10)}, {2.0, Vec3(8, -5, -1), Vec3(0, 0, 30)}};
  TrialOptions options;
  options.settle = 2.0;
  const TrialResult r = run_trial(scene, script, options);
  ASSERT_TRUE(r.status.ok());
  EXPECT_NEAR(r.final_translate.z(), 0.0, 1e-9);
  EXPECT_NEAR(r.final_translate.x(), 8.0, 1e-6) << r.final_translate.transpose();
  EXPECT_NEAR(r.final_translate.y(), -5.0, 1e-6);
  EXPECT_NEAR(r.final_rotate_deg.z(), 30.0, 1e-6) << r.final_rotate_deg.transpose();
  EXPECT_LT(r.final_rotate_deg.head<2>().norm(), 1e-9);
  EXPECT_LE(r.max_penetration_mm, 1e-9);
  ASSERT_EQ(r.joints_engaged.size(), 1u);
  EXPECT_EQ(r.joints_engaged[0].type, "PLF");
  EXPECT_EQ(r.joints_engaged[0].joint, "Planar");
}

TEST(Engagement, FaceLiftsOffAndBreaksAwayWhenTilted) {
  TrialScene& scene = *plate_scene().scene;
  const Vec3 c = scene.centre();
  const Pose start = offset_pose(Vec3(0, 0, 0.2), Vec3::Zero(), c);
  for (const bool tilt : {false, true}) {
    // Lifted 5 mm (free: it leaves the plane) or tilted 10 degrees (hand and
    // coupling in series, 1500 N mm/rad: 260 N mm, above 8 N x 10 mm: it breaks away).
    const Pose goal = tilt ? offset_pose(Vec3(0, 0, 0.2), Vec3(rad(10), 0, 0), c)
                           : offset_pose(Vec3(0, 0, 5), Vec3::Zero(), c);
    SimulatedHand hand(HandScript({{0.0, start}, {0.5, goal}}), HandParameters{}, c, start);
    ServoConfig config;
    config.lockstep = true;
    config.centre = c;
    ServoLoop loop(hand, config, start);
    loop.set_joint_finder(&scene.finder());
    loop.set_collision(&scene.collision());
    loop.step_lockstep();
    ASSERT_TRUE(loop.last().engaged);
    for (int i = 0; i < 1500; ++i) loop.step_lockstep();
    EXPECT_FALSE(loop.last().engaged) << (tilt ? "tilted" : "lifted");
    if (!tilt) EXPECT_NEAR((loop.proxy() * c - c).z(), 5.0, 0.01);
  }
}

// A joint chosen in the GUI reaches the running loop through its mailbox.
TEST(ServoLoop, HoldRequestsFromAnotherThread) {
  SimulatedHand hand(HandScript({{0.0, Pose::Identity()}, {0.2, offset_pose(Vec3(3, 4, 5), Vec3::Zero(), Vec3::Zero())}}),
                     HandParameters{}, Vec3::Zero(), Pose::Identity());
  ServoConfig config;
  ServoLoop loop(hand, config, Pose::Identity());
  ASSERT_TRUE(loop.start());
  JointState slider;
  slider.kind = JointKind::Prismatic;
  slider.axis = Vec3::UnitX();
  slider.part_axis = Vec3::UnitX();
  loop.request_hold(slider);
  std::this_thread::sleep_for(std::chrono::milliseconds(400));
  const ServoSnapshot held = loop.snapshot();
  loop.request_release();
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  const ServoSnapshot released = loop.snapshot();
  loop.stop();
  EXPECT_TRUE(held.held && held.engaged);
  EXPECT_EQ(held.joint.kind, JointKind::Prismatic);
  // Held to the x slide: the part followed the hand along x only.
  EXPECT_NEAR(held.proxy.translation().x(), 3.0, 0.2);
  EXPECT_LT(held.proxy.translation().tail<2>().norm(), 1e-9);
  EXPECT_FALSE(released.held || released.engaged);
}
