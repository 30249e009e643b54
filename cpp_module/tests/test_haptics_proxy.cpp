// The constraint-based proxy (god-object) judged on recorded paths: every
// acceptance case of issue 20 runs a scripted trial in lockstep and the path
// is checked by OCCT Booleans (path_checker.h), never by the loop's figures.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include <BRepAlgoAPI_Cut.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <gp_Ax2.hxx>

#include "contactcore/haptics/proxy_solver.h"
#include "contactcore/haptics/trial.h"
#include "path_checker.h"

using namespace contactcore::haptics;
using contactcore::testing::check_path;
using contactcore::testing::check_pose;
using contactcore::testing::PathOverlap;

namespace {

struct Scene {
  contactcore::Assembly assembly;
  std::unique_ptr<TrialScene> scene;
};

Scene& motor_part(const std::string& part) {
  static Scene axis, screw;
  Scene& s = part == "Axis" ? axis : screw;
  if (!s.scene) {
    auto read = contactcore::read_step(std::string(CONTACTS_SAMPLES) + "/motor.step");
    s.assembly = read.assembly;
    contactcore::Status status;
    s.scene = TrialScene::build(s.assembly, part, SceneOptions{}, status);
  }
  return s;
}

// A pin (radius 5, 25 long) in a blind bore of radius 5.05 (0.05 mm radial
// clearance) 20 deep in a block; assembled, the pin rests on the bore's bottom.
Scene& pin_in_block() {
  static Scene s;
  if (!s.scene) {
    const TopoDS_Shape box = BRepPrimAPI_MakeBox(gp_Pnt(0, 0, 0), 40, 40, 30).Shape();
    const TopoDS_Shape bore = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(20, 20, 10), gp_Dir(0, 0, 1)), 5.05, 25).Shape();
    const TopoDS_Shape block = BRepAlgoAPI_Cut(box, bore).Shape();
    const TopoDS_Shape pin = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(20, 20, 10), gp_Dir(0, 0, 1)), 5.0, 25).Shape();
    contactcore::Body b;
    b.name = "Block";
    b.shape = block;
    contactcore::Body p;
    p.name = "Pin";
    p.shape = pin;
    s.assembly.bodies = {b, p};
    contactcore::Status status;
    s.scene = TrialScene::build(s.assembly, "Pin", SceneOptions{}, status);
  }
  return s;
}

ScriptKey key(double t, Vec3 translate, Vec3 rotate = Vec3::Zero()) { return ScriptKey{t, translate, rotate}; }

TrialResult run(Scene& s, const TrialScript& script, double stiffness = 1.0, int record_every = 10,
                double settle = 1.5) {
  TrialOptions options;
  options.servo.stiffness = stiffness;
  options.record_every = record_every;
  options.settle = settle;
  const TrialResult r = run_trial(*s.scene, script, options);
  std::printf("[ figures ] final %.9f %.9f %.9f mm, %.9f %.9f %.9f deg; start/final/max penetration %.6f %.6f %.6f\n",
              r.final_translate.x(), r.final_translate.y(), r.final_translate.z(), r.final_rotate_deg.x(),
              r.final_rotate_deg.y(), r.final_rotate_deg.z(), r.start_penetration_mm, r.final_penetration_mm,
              r.max_penetration_mm);
  return r;
}

std::string where(const PathOverlap& o) {
  std::printf("[ judge ] deepest %.6f mm, volume %.6f mm3 with %s at t = %.3f (%d samples)\n", o.max_depth,
              o.max_volume, o.worst_body.c_str(), o.worst_t, o.samples_checked);
  return "deepest " + std::to_string(o.max_depth) + " mm with " + o.worst_body + " at t = " + std::to_string(o.worst_t);
}

// The judge's verdict, printed (the figures a reader of the log can check)
// and asserted: no overlap deeper than `depth` mm anywhere it looked.
void expect_no_deeper(const PathOverlap& o, double depth) {
  const std::string judged = where(o);
  EXPECT_LE(o.max_depth, depth) << judged;
}

}  // namespace

// ---- the solver alone: hand-derived answers

TEST(ProxySolver, SlidesAlongAWallInsteadOfStopping) {
  // Free part, a wall with normal +x touching (gap 0): the hand asks (-1, 1, 0).
  Mat6 basis = Mat6::Identity();
  Mat6 metric = Mat6::Identity();
  Vec6 desired;
  desired << -1, 1, 0, 0, 0, 0;
  ProxyConstraint wall;
  wall.row = contact_row(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 0, 0));
  wall.bound = 0;
  const ProxyStep step = solve_proxy_step(desired, metric, basis, 6, &wall, 1);
  EXPECT_NEAR(step.twist(0), 0.0, 1e-12);
  EXPECT_NEAR(step.twist(1), 1.0, 1e-12);  // the tangential part is kept whole
  EXPECT_EQ(step.active, 1);
}

TEST(ProxySolver, ACornerHoldsBothAndTheMetricWeighsRotation) {
  // Two walls (x >= 0 at (0,0,0), y >= 0 at (0,0,0)) and a push into both: no motion.
  Mat6 basis = Mat6::Identity(), metric = Mat6::Identity();
  Vec6 desired;
  desired << -1, -1, 0, 0, 0, 0;
  ProxyConstraint walls[2];
  walls[0].row = contact_row(Vec3::Zero(), Vec3::UnitX(), Vec3::Zero());
  walls[1].row = contact_row(Vec3::Zero(), Vec3::UnitY(), Vec3::Zero());
  const ProxyStep step = solve_proxy_step(desired, metric, basis, 6, walls, 2);
  EXPECT_LT(step.twist.norm(), 1e-12);
  // A contact 10 mm off the centre along y, normal +x, the hand pushes -x by 1:
  // the metric (rotation weight w = 50 mm^2) splits it into a translation and a
  // turn about z that keep the contact point still along x: multiplier
  // 1 / (1 + 100 / w), centre -100 / (w + 100), turn -10 / (w + 100).
  ProxyConstraint lever;
  lever.row = contact_row(Vec3(0, 10, 0), Vec3::UnitX(), Vec3::Zero());
  desired << -1, 0, 0, 0, 0, 0;
  metric.bottomRightCorner<3, 3>() *= 50.0;
  const ProxyStep turn = solve_proxy_step(desired, metric, basis, 6, &lever, 1);
  EXPECT_NEAR(lever.row.dot(turn.twist), 0.0, 1e-12);
  EXPECT_NEAR(turn.twist(0), -100.0 / 150.0, 1e-12);
  EXPECT_NEAR(turn.twist(5), -10.0 / 150.0, 1e-12);
}

TEST(ProxySolver, JointFreeTwistsAndAStop) {
  // Cylindrical on z: only z and the turn about z are free; a stop z >= 0 (at 0).
  JointState joint;
  joint.kind = JointKind::Cylindrical;
  Mat6 basis;
  const int free = free_twists(joint, Vec3::Zero(), basis);
  ASSERT_EQ(free, 2);
  ProxyConstraint stop;
  stop.row << 0, 0, 1, 0, 0, 0;
  stop.bound = 0;
  Vec6 desired;
  desired << 3, 2, -1, 0.1, 0, 0.2;
  const ProxyStep step = solve_proxy_step(desired, Mat6::Identity(), basis, free, &stop, 1);
  Vec6 expected;
  expected << 0, 0, 0, 0, 0, 0.2;
  EXPECT_LT((step.twist - expected).norm(), 1e-12);
}

// ---- acceptance on the motor and built cases (OCCT on the recorded path)

TEST(ProxyAcceptance, MotorAxisFrom30mmTiltedSeats) {
  Scene& s = motor_part("Axis");
  TrialScript script;
  script.start = key(0, Vec3(0.25, -0.2, 30), Vec3(0.4, -0.3, 0));
  script.hand = {key(0.0, Vec3(0.25, -0.2, 30), Vec3(0.4, -0.3, 0)), key(2.5, Vec3(0.3, 0.2, 0), Vec3(-0.5, 0.4, 2)),
                 key(3.0, Vec3::Zero())};
  const TrialResult r = run(s, script);
  ASSERT_TRUE(r.status.ok()) << r.status.message;
  // Acceptance: 0.05 mm and 0.1 degrees; lockstep, it ends exactly seated.
  EXPECT_LT(r.final_translate.norm(), 1e-9) << r.final_translate.transpose();
  EXPECT_LT(r.final_rotate_deg.norm(), 1e-9) << r.final_rotate_deg.transpose();
  const PathOverlap o = check_path(s.assembly, "Axis", s.scene->centre(), r.path, 15);
  expect_no_deeper(o, 0.01);
  EXPECT_GE(o.samples_checked, 30);
}

TEST(ProxyAcceptance, SeatedScrewPulledAlongItsAxisComesOut) {
  Scene& s = motor_part("Screw-1");
  TrialScript script;
  script.start = key(0, Vec3::Zero());
  script.hand = {key(0.0, Vec3::Zero()), key(1.5, Vec3(0, 0, 70))};
  const TrialResult r = run(s, script);
  ASSERT_TRUE(r.status.ok()) << r.status.message;
  EXPECT_NEAR(r.final_translate.z(), 70.0, 1e-9) << r.final_translate.transpose();
  EXPECT_LT(r.final_translate.head<2>().norm(), 1e-9);
  EXPECT_LT(r.final_rotate_deg.norm(), 1e-9);
  // Engaged in its holes on the way out (held >= 50 ticks).
  EXPECT_FALSE(r.joints_engaged.empty());
  const PathOverlap o = check_path(s.assembly, "Screw-1", s.scene->centre(), r.path, 10);
  expect_no_deeper(o, 0.01);
}

// Dropped from 160 mm above its hole (the hand 1 mm below the seat) the screw
// ends on the cover: engaged in its holes, its head on the Front-cover, never
// inside it. Its shaft's end reaches the Front-cover's hole coaxially: there
// the line-to-line shaft's and hole's tessellations' rims cross, so the shaft
// is captured at the mouth (the lead-in) and slides in. It stopped 53.1 mm up
// before. Judged by OCCT along the path and at the end, and on the cover: the
// end pose 0.02 mm lower overlaps it.
TEST(ProxyAcceptance, ScrewDroppedFrom160mmEndsOnTheCover) {
  Scene& s = motor_part("Screw-1");
  TrialScript script;
  script.start = key(0, Vec3(0, 0, 160));
  script.hand = {key(0.0, Vec3(0, 0, 160)), key(1.2, Vec3(0, 0, -1))};
  const TrialResult r = run(s, script);
  ASSERT_TRUE(r.status.ok()) << r.status.message;
  // Lockstep is deterministic: seated, a contact skin above its seat, on its axis.
  EXPECT_NEAR(r.final_translate.z(), ServoConfig{}.contact_skin, 1e-9) << r.final_translate.transpose();
  EXPECT_LT(r.final_translate.head<2>().norm(), 1e-9) << r.final_translate.transpose();
  EXPECT_LT(r.final_rotate_deg.head<2>().norm(), 1e-9) << r.final_rotate_deg.transpose();
  // Engaged in its three holes (held >= 50 ticks), the Front-cover's first.
  std::vector<std::string> engaged;
  for (const EngagedJoint& j : r.joints_engaged) engaged.push_back(j.with);
  EXPECT_EQ(engaged, (std::vector<std::string>{"Front-cover", "Body", "Back-cover"}));
  // No wait at the three mouths (Front-cover 53.10 mm, Body 45.10 mm, Back-cover 5.10 mm up): until
  // it is seated the screw moves down between any two samples (10 ticks) while the hand is below.
  int longest_stall = 0, stall = 0;
  for (std::size_t i = 1; i < r.path.size(); ++i) {
    const double z = r.path[i].translate.z();
    const bool still = std::abs(z - r.path[i - 1].translate.z()) < 1e-4;
    stall = still && z > 0.01 ? stall + 1 : 0;
    longest_stall = std::max(longest_stall, stall);
  }
  EXPECT_EQ(longest_stall, 0);
  const PathOverlap o = check_path(s.assembly, "Screw-1", s.scene->centre(), r.path, 10);
  expect_no_deeper(o, 0.01);
  EXPECT_EQ(o.samples_checked, 28);  // every 10th of the path's samples and the last
  const PathOverlap end = check_pose(s.assembly, "Screw-1", s.scene->centre(), r.final_translate, r.final_rotate_deg);
  expect_no_deeper(end, 0.01);
  // On the cover, not hovering: 0.02 mm lower its head is inside the Front-cover.
  const PathOverlap lower = check_pose(s.assembly, "Screw-1", s.scene->centre(),
                                       r.final_translate - Vec3(0, 0, 0.02), r.final_rotate_deg);
  // The head's underside sunk 0.02 - 0.001 mm into the cover: the planar contact's area (the
  // contacts stage's PLF of Screw-1 and Front-cover, 16.6897 mm^2) times that depth.
  EXPECT_EQ(lower.worst_body, "Front-cover");
  EXPECT_NEAR(lower.max_volume, 16.68971097 * (0.02 - ServoConfig{}.contact_skin), 1e-6);
  EXPECT_NEAR(lower.max_depth, 0.02 - ServoConfig{}.contact_skin, 1e-9);
}

TEST(ProxyAcceptance, PinWithClearanceSlidesAlongTheWallAndSeats) {
  Scene& s = pin_in_block();
  ASSERT_TRUE(s.scene);
  TrialScript script;
  script.start = key(0, Vec3(0, 0, 15));  // 5 mm into its 20 mm bore
  // The hand 0.3 mm and 0.3 degrees off the axis, pushed 1 mm below the seat.
  script.hand = {key(0.0, Vec3(0, 0, 15)), key(0.3, Vec3(0.3, 0, 15), Vec3(0, 0.3, 0)),
                 key(2.0, Vec3(0.3, 0, -1), Vec3(0, 0.3, 0))};
  const TrialResult r = run(s, script);
  ASSERT_TRUE(r.status.ok()) << r.status.message;
  // Seated on the bore's bottom (a contact skin above it), on the bore's axis
  // (captured in the clearance fit), upright.
  EXPECT_NEAR(r.final_translate.z(), ServoConfig{}.contact_skin, 1e-9) << r.final_translate.transpose();
  EXPECT_LT(r.final_translate.head<2>().norm(), 1e-9) << r.final_translate.transpose();
  EXPECT_LT(r.final_rotate_deg.head<2>().norm(), 1e-9) << r.final_rotate_deg.transpose();
  const PathOverlap o = check_path(s.assembly, "Pin", s.scene->centre(), r.path, 25);
  expect_no_deeper(o, 0.01);
}

// The hand pushes the seated Axis 20 mm sideways (far past breakaway), holds, then goes straight up 90.
TrialScript axis_sideways_then_up() {
  TrialScript script;
  script.start = key(0, Vec3::Zero());
  script.hand = {key(0.0, Vec3::Zero()), key(0.5, Vec3(20, 0, 0)), key(1.0, Vec3(20, 0, 0)),
                 key(2.0, Vec3(20, 0, 90))};
  return script;
}

TEST(ProxyAcceptance, AxisPushedSidewaysThenPulledStraightUpComesOut) {
  Scene& s = motor_part("Axis");
  const TrialResult r = run(s, axis_sideways_then_up(), 1.0, 10, 1.0);
  ASSERT_TRUE(r.status.ok()) << r.status.message;
  // Out of every bore (the shaft is 66 long) and free: at the hand.
  EXPECT_LT((r.final_translate - Vec3(20, 0, 90)).norm(), 1e-9) << r.final_translate.transpose();
  EXPECT_LT(r.final_rotate_deg.norm(), 1e-9);
  const PathOverlap o = check_path(s.assembly, "Axis", s.scene->centre(), r.path, 15);
  expect_no_deeper(o, 0.01);
}

// The same motion on the loop's own thread (realtime: absolute deadlines, the
// thread's 1 ns timer slack, wall-clock ticks), judged the same way.
TEST(ProxyAcceptance, AxisPushedSidewaysThenPulledStraightUpComesOutInRealtime) {
  Scene& s = motor_part("Axis");
  TrialOptions options;
  options.settle = 1.0;
  options.record_every = 10;
  const TrialResult r = run_trial(*s.scene, axis_sideways_then_up(), options, true);
  ASSERT_TRUE(r.status.ok()) << r.status.message;
  EXPECT_TRUE(r.realtime);
  EXPECT_LT((r.final_translate - Vec3(20, 0, 90)).norm(), 0.01) << r.final_translate.transpose();
  const PathOverlap o = check_path(s.assembly, "Axis", s.scene->centre(), r.path, 15);
  // Every 15th recorded sample and the last one judged (the count follows the wall-clock ticks; an
  // empty path would expect 2 and fail here).
  const int n = static_cast<int>(r.path.size());
  EXPECT_EQ(o.samples_checked, (n - 1) / 15 + 1 + ((n - 1) % 15 != 0 ? 1 : 0));
  expect_no_deeper(o, 0.01);
}

TEST(ProxyAcceptance, StartOverlappingIsReportedAndNeverLeftInsideSilently) {
  Scene& s = motor_part("Screw-1");
  // 0.5 mm down: the head 0.5 mm inside the Front-cover; the hand holds still.
  TrialScript script;
  script.start = key(0, Vec3(0, 0, -0.5));
  script.hand = {key(0.0, Vec3(0, 0, -0.5))};
  const TrialResult r = run(s, script, 1.0, 10, 1.0);
  const PathOverlap start = check_pose(s.assembly, "Screw-1", s.scene->centre(), Vec3(0, 0, -0.5), Vec3::Zero());
  ASSERT_GT(start.max_depth, 0.4);  // the judge agrees it starts inside
  EXPECT_NEAR(r.start_penetration_mm, 0.5, 1e-6);  // reported, not hidden
  // Pushed out (0.02 mm a tick) along the screw's axis onto the cover, a
  // contact skin above its seat: a success the judge confirms.
  ASSERT_TRUE(r.status.ok()) << r.status.message;
  EXPECT_NEAR(r.final_translate.z(), ServoConfig{}.contact_skin, 1e-9) << r.final_translate.transpose();
  EXPECT_LT(r.final_translate.head<2>().norm(), 1e-9);
  EXPECT_EQ(r.final_penetration_mm, 0.0);
  const PathOverlap end = check_pose(s.assembly, "Screw-1", s.scene->centre(), r.final_translate, r.final_rotate_deg);
  expect_no_deeper(end, 0.01);
}

TEST(ProxyAcceptance, NoTeleportAtAnyStiffness) {
  Scene& s = motor_part("Axis");
  for (double k : {0.01, 0.1, 1.0, 10.0, 100.0}) {
    // Free above the motor, 3 mm off the bores' axis; the hand goes through the
    // motor to the seat: the part is blocked outside and never jumps.
    TrialScript script;
    script.start = key(0, Vec3(3, 0, 75));
    script.hand = {key(0.0, Vec3(3, 0, 75)), key(0.5, Vec3(3, 0, 0)), key(1.0, Vec3::Zero())};
    const TrialResult r = run(s, script, k, 1, 0.5);
    ASSERT_TRUE(r.status.ok()) << r.status.message;
    const ServoConfig defaults;
    // One tick moves the centre at most max_speed * dt, or once the capture snap.
    const double limit = defaults.max_speed * 1e-3 + 1e-9;
    int jumps = 0;
    for (std::size_t i = 1; i < r.path.size(); ++i) {
      const double step = (r.path[i].translate - r.path[i - 1].translate).norm();
      if (step > limit) {
        ++jumps;
        EXPECT_LE(step, SceneOptions{}.capture.distance + limit) << "k " << k << " t " << r.path[i].t;
      }
    }
    EXPECT_LE(jumps, 1) << "k " << k;
    const PathOverlap o = check_path(s.assembly, "Axis", s.scene->centre(), r.path, 100);
    EXPECT_LE(o.max_depth, 0.01) << "k " << k << ": " << where(o);
  }
}

TEST(ProxyAcceptance, StillHandLeavesThePartWhereItStarted) {
  Scene& s = motor_part("Axis");
  const Vec3 start(0, 0, 30);
  for (bool realtime : {false, true}) {
    TrialScript script;
    script.start = key(0, start);
    script.hand = {key(0.0, start)};
    TrialOptions options;
    options.settle = 0.5;
    const TrialResult r = run_trial(*s.scene, script, options, realtime);
    ASSERT_TRUE(r.status.ok()) << r.status.message;
    EXPECT_LT((r.final_translate - start).norm(), 1e-6) << (realtime ? "realtime " : "lockstep ")
                                                        << r.final_translate.transpose();
    EXPECT_LT(r.final_rotate_deg.norm(), 1e-6);
    EXPECT_EQ(r.realtime, realtime);
    if (!realtime) {
      EXPECT_EQ(r.rate_hz, 0.0);  // lockstep: no wall-time figures
      EXPECT_NEAR(r.sim_time_s, 0.5, 1e-9);
    } else {
      EXPECT_GT(r.rate_hz, 0.0);
    }
  }
}

// ---- a joint chosen in the panel (the joints stage through joint_adapter.h)

#include "contactcore/haptics/joint_adapter.h"
#include "contactcore/joints/joints.h"

namespace {
// The Axis' assembled joint with `other` from the joints stage, as the panel
// holds it (HapticSession::hold_to_pair): the adapter, then the collision group.
JointState motor_axis_joint_with(Scene& s, const std::string& other) {
  const auto& names = s.scene->body_names();
  const int axis = s.scene->moving();
  const int body = static_cast<int>(std::find(names.begin(), names.end(), other) - names.begin());
  const contactcore::ContactsResult contacts = contactcore::find_contacts(s.assembly, contactcore::ContactOptions{});
  const contactcore::JointsResult joints = contactcore::find_joints(s.assembly, contacts);
  JointState joint;
  for (const contactcore::PairJoint& p : joints.joints)
    if (std::min(axis, body) == p.body_a && std::max(axis, body) == p.body_b) {
      EXPECT_TRUE(joint_state_from_pair(p, axis, s.scene->centre(), s.scene->contacts().body_box(axis), joint));
      s.scene->attach_collision_group(joint);
    }
  return joint;
}
}  // namespace

// Held to the joint chosen in the panel (the Axis on Bearing-back's bore, not
// the one engagement finds on all five bores), the hand pulled 12 mm up and
// 0.2, 0.1 mm aside (tests/gui/test_haptic_panel.py does the same in the
// GUI): the axis slides out along the chosen axis only and never enters a
// body. It stopped 2.9 mm out: the chosen joint's collision group was the
// first coaxial surface's (not the cylinder in Bearing-back's bore) and its
// radius was unset, so the other bores' rims held it.
TEST(ProxyAcceptance, AxisHeldToAChosenJointSlidesOut) {
  Scene& s = motor_part("Axis");
  const JointState joint = motor_axis_joint_with(s, "Bearing-back");
  ASSERT_EQ(joint.kind, JointKind::Cylindrical);
  ASSERT_GE(joint.group, 0);
  EXPECT_NEAR(joint.radius, 4.0, 0.005);  // the journal in Bearing-back's bore
  TrialScript script;
  script.start = key(0, Vec3::Zero());
  script.hand = {key(0.0, Vec3::Zero()), key(0.5, Vec3(0.2, 0.1, 12))};
  TrialOptions options;
  options.hold = &joint;
  options.settle = 0.5;
  const TrialResult r = run_trial(*s.scene, script, options);
  ASSERT_TRUE(r.status.ok()) << r.status.message;
  // On the chosen axis (x, y: the centre of mass 0.018 mm off the axis turns
  // with the part), at the hand's height.
  EXPECT_NEAR(r.final_translate.z(), 12.0, 0.01) << r.final_translate.transpose();
  EXPECT_LT(r.final_translate.head<2>().norm(), 0.04) << r.final_translate.transpose();
  EXPECT_LT(r.final_rotate_deg.head<2>().norm(), 1e-9);
  EXPECT_TRUE(r.joints_engaged.empty());  // held, not found
  const PathOverlap o = check_path(s.assembly, "Axis", s.scene->centre(), r.path, 5);
  expect_no_deeper(o, 0.01);
  EXPECT_GE(o.samples_checked, 20);
}

// ---- held to a point contact's joint (issue 22 item 3: higher pairs in the trial)

namespace {
// A ball r 5 (centre (20, 20, 15)) resting on a plate's top (z = 10).
Scene& ball_on_plate() {
  static Scene s;
  if (!s.scene) {
    contactcore::Body plate;
    plate.name = "Plate";
    plate.shape = BRepPrimAPI_MakeBox(gp_Pnt(0, 0, 0), 40, 40, 10).Shape();
    contactcore::Body ball;
    ball.name = "Ball";
    ball.shape = BRepPrimAPI_MakeSphere(gp_Pnt(20, 20, 15), 5).Shape();
    s.assembly.bodies = {plate, ball};
    contactcore::Status status;
    s.scene = TrialScene::build(s.assembly, "Ball", SceneOptions{}, status);
  }
  return s;
}
}  // namespace

// The ball's sphere_plane joint from the joints stage, held as the panel
// holds a chosen joint: by hand, every twist free and one stop on the
// ball's centre, -z . c <= -15 (the centre never below z = 15, the plate's
// top plus the radius). The hand goes 3 mm into the plate while moving 12
// along x (0.6 s), 6 along y while turning 25 deg about x and 40 about z
// (to 1.2 s), stays there (to 1.6 s), then goes up 13 mm (to 2.2 s). By hand: the ball follows the hand
// along the plate at its own height (offset z 0, up to the contact skin),
// turns with the hand, and leaves the plate with the hand (z offset 10 at
// the end); the judge finds no overlap with the plate anywhere on the path.
TEST(ProxyAcceptance, BallHeldToItsSpherePlaneJointSlidesTurnsAndLiftsOff) {
  Scene& s = ball_on_plate();
  ASSERT_TRUE(s.scene);
  const int ball = s.scene->moving();
  const contactcore::ContactsResult contacts = contactcore::find_contacts(s.assembly, contactcore::ContactOptions{});
  const contactcore::JointsResult joints = contactcore::find_joints(s.assembly, contacts);
  ASSERT_EQ(joints.joints.size(), 1u);
  ASSERT_EQ(joints.joints[0].type, contactcore::JointType::SpherePlane);
  JointState joint;
  ASSERT_TRUE(joint_state_from_pair(joints.joints[0], ball, s.scene->centre(), s.scene->contacts().body_box(ball), joint));
  s.scene->attach_collision_group(joint);
  EXPECT_EQ(joint.kind, JointKind::HigherPair);
  EXPECT_STREQ(to_string(joint.kind), "Point/line contact");
  ASSERT_EQ(joint.stop_count, 1);
  EXPECT_TRUE(joint.stops[0].on_part_point);
  EXPECT_LT((joint.stops[0].part_point - Vec3(20, 20, 15)).norm(), 1e-9);
  EXPECT_LT((joint.stops[0].normal - Vec3(0, 0, -1)).norm(), 1e-12);
  EXPECT_NEAR(joint.stops[0].limit, -15, 1e-9);
  EXPECT_LT((joint.axis - Vec3(0, 0, 1)).norm(), 1e-12);
  Eigen::Matrix<double, 6, 6> basis;
  EXPECT_EQ(free_twists(joint, Vec3(20, 20, 15), basis), 6);

  TrialScript script;
  script.start = key(0, Vec3::Zero());
  script.hand = {key(0.0, Vec3::Zero()), key(0.6, Vec3(12, 0, -3)), key(1.2, Vec3(12, 6, -3), Vec3(25, 0, 40)),
                 key(1.6, Vec3(12, 6, -3), Vec3(25, 0, 40)), key(2.2, Vec3(12, 6, 10), Vec3(25, 0, 40))};
  TrialOptions options;
  options.hold = &joint;
  options.settle = 0.5;
  options.record_every = 10;
  const TrialResult r = run_trial(*s.scene, script, options);
  ASSERT_TRUE(r.status.ok()) << r.status.message;
  // On the plate, pushed into it: at its own height, where the hand is in x, y.
  const TrialSample* on_plate = nullptr;
  double lowest = 1e300;
  for (const TrialSample& sample : r.path) {
    if (sample.t <= 1.6) lowest = std::min(lowest, sample.translate.z());
    if (sample.t <= 1.6) on_plate = &sample;
  }
  ASSERT_NE(on_plate, nullptr);
  std::printf("[ figures ] at t = %.3f: %.6f %.6f %.6f mm, %.3f %.3f %.3f deg; lowest z offset %.9f\n", on_plate->t,
              on_plate->translate.x(), on_plate->translate.y(), on_plate->translate.z(), on_plate->rotate_deg.x(),
              on_plate->rotate_deg.y(), on_plate->rotate_deg.z(), lowest);
  // Never below its start on the plate: it rides at the contact skin the constraints keep (the
  // closed form's exact sphere touches the plate at gap 0 when assembled; the meshes alone, whose
  // chords lie inside the sphere, left it at 0).
  EXPECT_NEAR(lowest, ServoConfig{}.contact_skin, 1e-9);
  EXPECT_NEAR(on_plate->translate.z(), 0, 0.05);
  EXPECT_NEAR(on_plate->translate.x(), 12, 0.1);
  EXPECT_NEAR(on_plate->translate.y(), 6, 0.1);
  EXPECT_NEAR(on_plate->rotate_deg.x(), 25, 0.5);
  EXPECT_NEAR(on_plate->rotate_deg.z(), 40, 0.5);
  // Lifted with the hand: off the plate.
  EXPECT_NEAR(r.final_translate.z(), 10, 0.05) << r.final_translate.transpose();
  EXPECT_NEAR(r.final_translate.x(), 12, 0.05);
  EXPECT_NEAR(r.final_translate.y(), 6, 0.05);
  EXPECT_TRUE(r.joints_engaged.empty());  // held, not found
  // Pushed 3 mm into the plate: the judge finds no overlap anywhere.
  const PathOverlap o = check_path(s.assembly, "Ball", s.scene->centre(), r.path, 2);
  expect_no_deeper(o, 1e-3);
  EXPECT_EQ(o.samples_checked, 136);  // every 2nd of the 271 samples, the last included
}

// A roller r 5 along x (x 5..35, axis y = 20, z = 15) on a plate's top
// (z = 10): its cylinder_plane joint held as a point/line contact. By hand:
// two stops, one per end of the line (5, 20, 10) and (35, 20, 10), each moved
// up the normal by the radius onto the roller's axis, (5, 20, 15) and
// (35, 20, 15), each keeping -z . p <= -15: the axis never below z = 15
// whatever the roller does (rolls about its axis, turns about z, slides,
// lifts an end).
TEST(ProxyAcceptance, RollerHeldToItsCylinderPlaneJointHasStopsOnItsAxis) {
  Scene s;
  contactcore::Body plate;
  plate.name = "Plate";
  plate.shape = BRepPrimAPI_MakeBox(gp_Pnt(0, 0, 0), 40, 40, 10).Shape();
  contactcore::Body roller;
  roller.name = "Roller";
  roller.shape = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(5, 20, 15), gp_Dir(1, 0, 0)), 5, 30).Shape();
  s.assembly.bodies = {plate, roller};
  contactcore::Status status;
  s.scene = TrialScene::build(s.assembly, "Roller", SceneOptions{}, status);
  ASSERT_TRUE(s.scene) << status.message;
  const int moving = s.scene->moving();
  const contactcore::ContactsResult contacts = contactcore::find_contacts(s.assembly, contactcore::ContactOptions{});
  const contactcore::JointsResult joints = contactcore::find_joints(s.assembly, contacts);
  ASSERT_EQ(joints.joints.size(), 1u);
  ASSERT_EQ(joints.joints[0].type, contactcore::JointType::CylinderPlane);
  JointState joint;
  ASSERT_TRUE(joint_state_from_pair(joints.joints[0], moving, s.scene->centre(), s.scene->contacts().body_box(moving),
                                    joint));
  s.scene->attach_collision_group(joint);
  EXPECT_EQ(joint.kind, JointKind::HigherPair);
  ASSERT_EQ(joint.stop_count, 2);
  std::vector<double> xs;
  for (int k = 0; k < 2; ++k) {
    const Stop& stop = joint.stops[k];
    EXPECT_TRUE(stop.on_part_point);
    EXPECT_LT((stop.normal - Vec3(0, 0, -1)).norm(), 1e-12);
    EXPECT_NEAR(stop.part_point.y(), 20, 1e-6);
    EXPECT_NEAR(stop.part_point.z(), 15, 1e-6);
    EXPECT_NEAR(stop.limit, -15, 1e-6);
    xs.push_back(stop.part_point.x());
  }
  std::sort(xs.begin(), xs.end());
  EXPECT_NEAR(xs[0], 5, 1e-6);
  EXPECT_NEAR(xs[1], 35, 1e-6);
}

// ---- Coulomb friction at the proxy's contacts

namespace {
// A position device at the part's pose on the first tick (the loop anchors a
// position device there), then held still at `pose` (no spring of its own):
// the coupling's force is exactly K times the hand's offset from the part.
class StillHand : public Device {
 public:
  explicit StillHand(const Pose& pose) : pose_(pose) {
    caps_.name = "still hand";
    caps_.force_output = true;
    caps_.max_force = 100;
    caps_.max_stiffness = 10;
    caps_.max_damping = 1;
  }
  const DeviceCapabilities& capabilities() const override { return caps_; }
  DeviceSample read(double now) noexcept override {
    DeviceSample s;
    s.connected = true;
    s.time = now;
    s.pose = now > 0 ? pose_ : Pose::Identity();
    return s;
  }
  void write(const Wrench&) noexcept override {}

 private:
  DeviceCapabilities caps_;
  Pose pose_;
};

// A 10 x 10 x 5 block resting on a 60 x 60 x 5 plate (assembled: touching).
Scene& block_on_plate() {
  static Scene s;
  if (!s.scene) {
    contactcore::Body plate, block;
    plate.name = "Plate";
    plate.shape = BRepPrimAPI_MakeBox(gp_Pnt(-30, -30, -5), 60, 60, 5).Shape();
    block.name = "Block";
    block.shape = BRepPrimAPI_MakeBox(gp_Pnt(-5, -5, 0), 10, 10, 5).Shape();
    s.assembly.bodies = {plate, block};
    contactcore::Status status;
    s.scene = TrialScene::build(s.assembly, "Block", SceneOptions{}, status);
  }
  return s;
}

// The block's offset after 1.5 s with the hand held 1 mm into the plate and
// `along` mm along x, friction mu.
Vec3 block_moved(double mu, double along) {
  Scene& s = block_on_plate();
  const Vec3 c = s.scene->centre();
  StillHand hand(offset_pose(Vec3(along, 0, -1), Vec3::Zero(), c));
  ServoConfig config;
  config.lockstep = true;
  config.centre = c;
  config.inertia_per_mass = s.scene->inertia_per_mass();
  config.friction = mu;
  config.damping = 0;
  ServoLoop loop(hand, config, Pose::Identity());
  loop.set_joint_finder(&s.scene->finder());
  loop.set_collision(&s.scene->collision());
  for (int i = 0; i < 1500; ++i) loop.step_lockstep();
  return loop.proxy().translation();
}
}  // namespace

TEST(ProxyFriction, ABlockSticksBelowMuTimesTheNormalForceAndSlidesAbove) {
  ASSERT_TRUE(block_on_plate().scene);
  // The hand 1 mm into the plate: a normal force K x 1 mm; along x 0.4 mm
  // (0.4 K < 0.5 K): it sticks, not a micrometre of slip.
  const Vec3 stuck = block_moved(0.5, 0.4);
  EXPECT_LT(std::abs(stuck.x()), 1e-9) << stuck.transpose();
  EXPECT_NEAR(stuck.z(), 0.0, 0.002);
  // 0.6 mm along (0.6 K > 0.5 K): it slides until the hand's pull is on the
  // cone's edge, 0.5 x 1 mm behind the hand: 0.1 mm (the contact skin of
  // 1 um changes the normal offset by 0.1 %).
  const Vec3 slid = block_moved(0.5, 0.6);
  EXPECT_NEAR(slid.x(), 0.1, 0.002) << slid.transpose();
  EXPECT_NEAR(slid.y(), 0.0, 1e-9);
  EXPECT_NEAR(slid.z(), 0.0, 0.002);
  // Without friction (the default) it goes all the way to the hand.
  const Vec3 free = block_moved(0.0, 0.4);
  EXPECT_NEAR(free.x(), 0.4, 1e-6) << free.transpose();
}
