// Joints and mobility on canonical cases built from OCCT primitives (DOF and
// axes derived by hand in the comments), on the bundled motor, and under a
// rigid motion of the whole assembly.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include <BRepAlgoAPI_Cut.hxx>
#include <BRepAlgoAPI_Fuse.hxx>
#include <BRepBuilderAPI_Transform.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCone.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <gp_Ax1.hxx>
#include <gp_Ax2.hxx>
#include <gp_Trsf.hxx>

#include "contactcore/contacts/clearances.h"
#include "contactcore/joints/joints.h"
#include "test_helpers.h"

using namespace contactcore;
using contactcore::testing::sample;

namespace {

struct Analysed {
  Assembly assembly;
  ContactsResult contacts;
  JointsResult joints;
};

Analysed analyse(std::vector<std::pair<std::string, TopoDS_Shape>> shapes) {
  Analysed out;
  for (auto& [name, shape] : shapes) out.assembly.bodies.push_back({name, name, shape});
  out.contacts = find_contacts(out.assembly, ContactOptions{});
  EXPECT_TRUE(out.contacts.status.ok()) << out.contacts.status.describe();
  out.joints = find_joints(out.assembly, out.contacts);
  EXPECT_TRUE(out.joints.status.ok()) << out.joints.status.describe();
  return out;
}

const PairJoint& joint(const Analysed& a, int i, int j) {
  for (const PairJoint& pj : a.joints.joints)
    if (pj.body_a == std::min(i, j) && pj.body_b == std::max(i, j)) return pj;
  ADD_FAILURE() << "no joint between " << i << " and " << j;
  static PairJoint none;
  return none;
}

TopoDS_Shape box(gp_Pnt from, gp_Pnt to) { return BRepPrimAPI_MakeBox(from, to).Shape(); }
TopoDS_Shape cylinder(double r, double h, gp_Pnt base, gp_Dir axis = gp::DZ()) {
  return BRepPrimAPI_MakeCylinder(gp_Ax2(base, axis), r, h).Shape();
}
TopoDS_Shape fuse(const TopoDS_Shape& a, const TopoDS_Shape& b) { return BRepAlgoAPI_Fuse(a, b).Shape(); }
TopoDS_Shape cut(const TopoDS_Shape& a, const TopoDS_Shape& b) { return BRepAlgoAPI_Cut(a, b).Shape(); }

double angle(const gp_Dir& a, const gp_Dir& b) { return a.Angle(b); }
bool parallel(const gp_Dir& a, const gp_Dir& b) { return a.IsParallel(b, 1e-6); }
double line_distance(const gp_Pnt& p, const gp_Pnt& on, const gp_Dir& d) {
  return gp_Vec(on, p).Crossed(gp_Vec(d)).Magnitude();
}

// A 40 x 40 x 20 block at the origin with a vertical bore (r) at (20, 20).
TopoDS_Shape bored_block(double r) {
  return cut(box(gp_Pnt(0, 0, 0), gp_Pnt(40, 40, 20)), cylinder(r, 40, gp_Pnt(20, 20, -10)));
}

}  // namespace

// Pin r 5 through a 20 mm block, its shoulder (r 8) resting on the top face.
// By hand: the bore leaves rotation about and translation along x = y = 20;
// the shoulder's plane removes the translation: revolute about that line, one
// one-sided stop (normal +z, out of the block), so the pin leaves along +z only.
TEST(Joints, PinWithShoulderIsRevoluteWithAxialStop) {
  const TopoDS_Shape pin = fuse(cylinder(5, 30, gp_Pnt(20, 20, -5)), cylinder(8, 5, gp_Pnt(20, 20, 20)));
  const Analysed a = analyse({{"Block", bored_block(5)}, {"Pin", pin}});
  ASSERT_EQ(a.joints.joints.size(), 1u);
  const PairJoint& j = joint(a, 0, 1);
  EXPECT_EQ(j.type, JointType::Revolute);
  EXPECT_EQ(j.dof, 1);
  EXPECT_EQ(j.contacts.size(), 2u);
  ASSERT_EQ(j.rotations.size(), 1u);
  EXPECT_TRUE(parallel(j.rotations[0].direction, gp::DZ()));
  EXPECT_LT(line_distance(gp_Pnt(20, 20, 0), j.rotations[0].point, j.rotations[0].direction), 1e-6);
  ASSERT_EQ(j.stops.size(), 1u);
  EXPECT_LT(angle(j.stops[0].normal, gp::DZ()), 1e-9);
  ASSERT_EQ(j.free_directions.size(), 1u);
  EXPECT_LT(angle(j.free_directions[0], gp::DZ()), 1e-9);
}

// A fork of two parallel pins (r 4 at x = 10 and x = 30, joined by a bar
// above the block) through two bores. By hand: each bore alone leaves a
// cylindrical joint; two parallel axes keep only the common translation: prismatic along z.
TEST(Joints, TwoParallelPinsArePrismatic) {
  TopoDS_Shape block = cut(box(gp_Pnt(0, 0, 0), gp_Pnt(40, 20, 20)), cylinder(4, 40, gp_Pnt(10, 10, -10)));
  block = cut(block, cylinder(4, 40, gp_Pnt(30, 10, -10)));
  TopoDS_Shape fork = fuse(cylinder(4, 35, gp_Pnt(10, 10, -5)), cylinder(4, 35, gp_Pnt(30, 10, -5)));
  fork = fuse(fork, box(gp_Pnt(5, 5, 30), gp_Pnt(35, 15, 34)));
  const Analysed a = analyse({{"Block", block}, {"Fork", fork}});
  const PairJoint& j = joint(a, 0, 1);
  EXPECT_EQ(j.type, JointType::Prismatic);
  EXPECT_EQ(j.dof, 1);
  EXPECT_TRUE(j.rotations.empty());
  ASSERT_EQ(j.translations.size(), 1u);
  EXPECT_TRUE(parallel(j.translations[0], gp::DZ()));
  // No one-sided contact: the fork slides both ways.
  EXPECT_TRUE(j.stops.empty());
  ASSERT_EQ(j.free_directions.size(), 2u);
  EXPECT_TRUE(parallel(j.free_directions[0], gp::DZ()));
  EXPECT_TRUE(parallel(j.free_directions[1], gp::DZ()));
}

// A 20 x 20 plate on a 40 x 40 plate. By hand: planar (rotation about z,
// translations in x and y), one-sided: the free directions are the whole
// plane (both signs of two in-plane directions) and +z, five generators.
TEST(Joints, PlateOnPlateIsPlanarOneSided) {
  const Analysed a = analyse({{"Base", box(gp_Pnt(0, 0, 0), gp_Pnt(40, 40, 10))},
                              {"Top", box(gp_Pnt(10, 10, 10), gp_Pnt(30, 30, 15))}});
  const PairJoint& j = joint(a, 0, 1);
  EXPECT_EQ(j.type, JointType::Planar);
  EXPECT_EQ(j.dof, 3);
  ASSERT_EQ(j.rotations.size(), 1u);
  EXPECT_TRUE(parallel(j.rotations[0].direction, gp::DZ()));
  ASSERT_EQ(j.translations.size(), 2u);
  for (const gp_Dir& t : j.translations) EXPECT_NEAR(t.Dot(gp::DZ()), 0.0, 1e-9);
  ASSERT_EQ(j.stops.size(), 1u);
  ASSERT_EQ(j.free_directions.size(), 5u);
  int up = 0, in_plane = 0;
  for (const gp_Dir& d : j.free_directions) {
    if (angle(d, gp::DZ()) < 1e-9) ++up;
    if (std::abs(d.Z()) < 1e-9) ++in_plane;
  }
  EXPECT_EQ(up, 1);
  EXPECT_EQ(in_plane, 4);
}

// A ball r 10 in a hemispherical cup of its radius (centre 20, 20, 20). By
// hand: three rotations about the centre: spherical.
TEST(Joints, BallInSocketIsSpherical) {
  const gp_Pnt centre(20, 20, 20);
  const TopoDS_Shape cup = cut(box(gp_Pnt(0, 0, 0), gp_Pnt(40, 40, 20)), BRepPrimAPI_MakeSphere(centre, 10).Shape());
  const Analysed a = analyse({{"Cup", cup}, {"Ball", BRepPrimAPI_MakeSphere(centre, 10).Shape()}});
  const PairJoint& j = joint(a, 0, 1);
  EXPECT_EQ(j.type, JointType::Spherical);
  EXPECT_EQ(j.dof, 3);
  ASSERT_EQ(j.rotations.size(), 3u);
  for (const FreeRotation& r : j.rotations) EXPECT_LT(r.point.Distance(centre), 1e-6);
  EXPECT_TRUE(j.translations.empty());
}

// A ball r 5 in a vertical bore r 5, centre (20, 20, 10). By hand: rotations
// about the centre and the translation along the bore: sphere_cylinder, 4 DOF.
TEST(Joints, BallInBoreIsSphereCylinder) {
  const gp_Pnt centre(20, 20, 10);
  const Analysed a = analyse({{"Block", bored_block(5)}, {"Ball", BRepPrimAPI_MakeSphere(centre, 5).Shape()}});
  const PairJoint& j = joint(a, 0, 1);
  EXPECT_EQ(j.type, JointType::SphereCylinder);
  EXPECT_EQ(j.dof, 4);
  ASSERT_EQ(j.rotations.size(), 3u);
  for (const FreeRotation& r : j.rotations) EXPECT_LT(r.point.Distance(centre), 1e-6);
  ASSERT_EQ(j.translations.size(), 1u);
  EXPECT_TRUE(parallel(j.translations[0], gp::DZ()));
}

// A taper pin (r 4 at z = 0 to r 5 at z = 20, half angle atan(1/20)) in a
// taper hole of the same cone, its head (r 8) on the top face. By hand: the
// cone leaves rotation about the axis and stops the pin one way along it, the
// head's plane likewise: revolute; the pin leaves only within the cone's half
// angle about +z (extraction along the axis).
TEST(Joints, TaperPinSeatedByItsHeadIsRevoluteExtractedAlongItsAxis) {
  const gp_Ax2 axis(gp_Pnt(20, 20, 0), gp::DZ());
  const TopoDS_Shape hole = BRepPrimAPI_MakeCone(axis, 4, 5, 20).Shape();
  const TopoDS_Shape block = cut(box(gp_Pnt(0, 0, 0), gp_Pnt(40, 40, 20)), hole);
  const TopoDS_Shape pin = fuse(BRepPrimAPI_MakeCone(axis, 4, 5, 20).Shape(), cylinder(8, 5, gp_Pnt(20, 20, 20)));
  const Analysed a = analyse({{"Block", block}, {"TaperPin", pin}});
  const PairJoint& j = joint(a, 0, 1);
  EXPECT_EQ(j.type, JointType::Revolute);
  ASSERT_EQ(j.rotations.size(), 1u);
  EXPECT_TRUE(parallel(j.rotations[0].direction, gp::DZ()));
  EXPECT_LT(line_distance(gp_Pnt(20, 20, 0), j.rotations[0].point, j.rotations[0].direction), 1e-6);
  // The free cone is the circular cone of the taper's half angle about +z,
  // given as the 12-sided cone inscribed in it (JointOptions::cone_samples):
  // its edges exactly on the true cone, at atan(1/20) from the axis, and no
  // direction it allows is blocked (issue 22: it used to be the polygon
  // around the true cone, edges at atan(tan(half angle) / cos 15 deg)).
  const double edge_angle = std::atan(1.0 / 20.0);
  ASSERT_EQ(j.free_directions.size(), 12u);
  for (const gp_Dir& d : j.free_directions) EXPECT_NEAR(angle(d, gp::DZ()), edge_angle, 1e-9);
  // The generators surround the axis: their mean is along +z.
  gp_XYZ mean(0, 0, 0);
  for (const gp_Dir& d : j.free_directions) mean += d.XYZ();
  EXPECT_LT(angle(gp_Dir(mean), gp::DZ()), 1e-6);
}

// A hinge: leaf 1 (knuckles x 0..10 and 20..30 about the x axis, r 5, bore
// r 2), leaf 2 (knuckle x 10..20), a pin r 2 with a head seated on leaf 1's
// end face. By hand: the pin turns in leaf 1 (a passive spin), so pin and
// leaf 1 are one rigid group; leaf 2 turns about the x axis relative to it:
// revolute, 1 DOF. The leaves' own pair (two knuckle faces) is planar.
TEST(Joints, HingeLeavesAreRevoluteThroughThePin) {
  const gp_Dir x = gp::DX();
  auto knuckle = [&](double from, double to) {
    return cut(cylinder(5, to - from, gp_Pnt(from, 0, 0), x), cylinder(2, to - from + 2, gp_Pnt(from - 1, 0, 0), x));
  };
  TopoDS_Shape leaf1 = fuse(knuckle(0, 10), knuckle(20, 30));
  leaf1 = fuse(leaf1, box(gp_Pnt(0, 7, -1), gp_Pnt(30, 20, 1)));
  leaf1 = fuse(leaf1, box(gp_Pnt(0, 3, -1), gp_Pnt(10, 8, 1)));
  leaf1 = fuse(leaf1, box(gp_Pnt(20, 3, -1), gp_Pnt(30, 8, 1)));
  const TopoDS_Shape leaf2 = fuse(knuckle(10, 20), box(gp_Pnt(10, -20, -1), gp_Pnt(20, -3, 1)));
  const TopoDS_Shape pin = fuse(cylinder(2, 32, gp_Pnt(0, 0, 0), x), cylinder(4, 3, gp_Pnt(-3, 0, 0), x));
  const Analysed a = analyse({{"Leaf1", leaf1}, {"Leaf2", leaf2}, {"Pin", pin}});
  EXPECT_EQ(joint(a, 0, 2).type, JointType::Revolute);     // pin seated in leaf 1
  EXPECT_EQ(joint(a, 1, 2).type, JointType::Cylindrical);  // pin through leaf 2
  EXPECT_EQ(joint(a, 0, 1).type, JointType::Planar);       // knuckle faces only

  MobilityOptions options;
  options.ground = 0;
  const MobilityResult m = assembly_mobility(a.assembly, a.contacts, a.joints, options);
  ASSERT_TRUE(m.status.ok()) << m.status.describe();
  ASSERT_EQ(m.groups.size(), 2u);
  EXPECT_EQ(m.groups[0], (std::vector<int>{0, 2}));
  EXPECT_EQ(m.groups[1], (std::vector<int>{1}));
  EXPECT_EQ(m.dof, 2);  // leaf 2 turning, the pin spinning
  EXPECT_EQ(m.passive, 1);
  ASSERT_EQ(m.passive_spins.size(), 1u);
  EXPECT_EQ(m.passive_spins[0].body, 2);
  const GroupMotion& leaf2_motion = m.group_motions[1];
  EXPECT_EQ(leaf2_motion.type, JointType::Revolute);
  ASSERT_EQ(leaf2_motion.rotations.size(), 1u);
  EXPECT_TRUE(parallel(leaf2_motion.rotations[0].direction, x));
  EXPECT_LT(line_distance(gp_Pnt(0, 0, 0), leaf2_motion.rotations[0].point, x), 1e-6);
  EXPECT_EQ(m.group_motions[0].type, JointType::Rigid);

  const std::string dot = liaison_graph_dot(a.assembly, a.joints, &m);
  EXPECT_NE(dot.find("\"Leaf1\" -- \"Pin\" [label=\"revolute (1)\""), std::string::npos) << dot;
  EXPECT_NE(dot.find("subgraph cluster_0"), std::string::npos);
}

// A twist basis naming itself: the classification alone, on hand-made spaces.
TEST(Joints, ClassifyTwistsNamesHandMadeSpaces) {
  const gp_Pnt c(5, 0, 0);
  // Rotation about the line x = 5, y = 0 along z: (0,0,1, p x d) with p = (5,0,0).
  const Twist spin{0, 0, 1, 0, -5, 0};
  const Twist slide_z{0, 0, 0, 0, 0, 1};
  EXPECT_EQ(classify_twists({spin}, c, 1).type, JointType::Revolute);
  EXPECT_EQ(classify_twists({spin, slide_z}, c, 1).type, JointType::Cylindrical);
  EXPECT_EQ(classify_twists({slide_z}, c, 1).type, JointType::Prismatic);
  EXPECT_EQ(classify_twists({{0, 0, 1, 0, 0, 2}}, c, 1).type, JointType::Helical);
  EXPECT_EQ(classify_twists({spin, {0, 0, 0, 1, 0, 0}, {0, 0, 0, 0, 1, 0}}, c, 1).type, JointType::Planar);
  EXPECT_EQ(classify_twists({}, c, 1).type, JointType::Rigid);
  const TwistSpace revolute = classify_twists({spin}, c, 1);
  EXPECT_LT(revolute.rotations[0].point.Distance(gp_Pnt(5, 0, 0)), 1e-9);
}

// ------------------------------------------------------------------ motor

namespace {

struct Motor {
  Analysed a;
  std::map<std::string, int> index;
  MobilityResult mobility;
};

Motor analyse_motor(const gp_Trsf& motion) {
  Motor m;
  AssemblyResult read = read_step(sample("motor.step"));
  EXPECT_TRUE(read.status.ok()) << read.status.describe();
  std::vector<std::pair<std::string, TopoDS_Shape>> shapes;
  for (const Body& b : read.assembly.bodies)
    shapes.push_back({b.name, BRepBuilderAPI_Transform(b.shape, motion, true).Shape()});
  m.a = analyse(shapes);
  for (size_t i = 0; i < m.a.assembly.bodies.size(); ++i) m.index[m.a.assembly.bodies[i].name] = static_cast<int>(i);
  MobilityOptions options;
  options.ground = m.index["Body"];
  m.mobility = assembly_mobility(m.a.assembly, m.a.contacts, m.a.joints, options);
  EXPECT_TRUE(m.mobility.status.ok()) << m.mobility.status.describe();
  return m;
}

std::set<std::string> names_of(const Motor& m, const std::vector<int>& bodies) {
  std::set<std::string> out;
  for (int b : bodies) out.insert(m.a.assembly.bodies[b].name);
  return out;
}

}  // namespace

TEST(Joints, MotorJointsMobilityAndGroups) {
  const Motor m = analyse_motor(gp_Trsf());
  ASSERT_EQ(m.a.assembly.bodies.size(), 18u);
  auto id = [&](const std::string& name) { return m.index.at(name); };

  // Each screw: revolute in the front cover about its own axis (parallel to z),
  // leaving along that axis on its head's side only.
  for (int k = 1; k <= 4; ++k) {
    const std::string screw = "Screw-" + std::to_string(k);
    const PairJoint& j = joint(m.a, id(screw), id("Front-cover"));
    EXPECT_EQ(j.type, JointType::Revolute) << screw;
    ASSERT_EQ(j.rotations.size(), 1u);
    EXPECT_TRUE(parallel(j.rotations[0].direction, gp::DZ()));
    ASSERT_EQ(j.free_directions.size(), 1u) << screw;
    EXPECT_TRUE(parallel(j.free_directions[0], gp::DZ()));
    // The screw (body b or a) moves away from the cover, towards its head.
    const bool screw_is_b = j.body_b == id(screw);
    const double towards_head = (screw_is_b ? 1 : -1) * j.free_directions[0].Z();
    const double head_side = j.stops[0].normal.Z() * (screw_is_b ? 1 : -1);
    EXPECT_GT(towards_head * head_side, 0) << screw;
    // Nothing holds a screw along its axis in the body and the back cover.
    EXPECT_EQ(joint(m.a, id(screw), id("Body")).type, JointType::Cylindrical);
    EXPECT_EQ(joint(m.a, id(screw), id("Back-cover")).type, JointType::Cylindrical);
  }
  for (int k = 1; k <= 4; ++k)
    EXPECT_EQ(joint(m.a, id("Magnet-" + std::to_string(k)), id("Rotor-back")).type, JointType::Planar);
  for (const char* part : {"Rotor-front", "Rotor-back", "Bearing-front", "Bearing-back", "Seal"})
    EXPECT_EQ(joint(m.a, id("Axis"), id(part)).type, JointType::Cylindrical) << part;

  // Body, covers and screws move as one group (the screws' spins passive);
  // the stator and the back bearing turn in their seats the same way.
  const MobilityResult& mob = m.mobility;
  EXPECT_EQ(mob.ground, id("Body"));
  EXPECT_EQ(names_of(m, mob.groups[0]),
            (std::set<std::string>{"Body", "Front-cover", "Back-cover", "Screw-1", "Screw-2", "Screw-3", "Screw-4",
                                   "Stator", "Bearing-back"}));
  std::set<std::string> spinning;
  for (const PassiveSpin& s : mob.passive_spins) spinning.insert(m.a.assembly.bodies[s.body].name);
  for (int k = 1; k <= 4; ++k) EXPECT_TRUE(spinning.count("Screw-" + std::to_string(k)));
  EXPECT_EQ(mob.group_motions[0].type, JointType::Rigid);

  // Each part's way out, its neighbours held still. A screw: up its axis
  // only (held across by three bores, stopped below by its head); the shaft:
  // both ways along its axis (bores only); the rotor-front: none (planes on
  // both sides along the axis, the shaft across); a magnet: its plane both
  // ways and away from the rotor-back (five generators).
  const auto out_of = [&](const std::string& name) { return body_free_directions(m.a.contacts, m.a.joints, id(name)); };
  const auto screw = out_of("Screw-1");
  ASSERT_EQ(screw.size(), 1u);
  EXPECT_LT(angle(screw[0], gp::DZ()), 1e-9);
  const auto shaft = out_of("Axis");
  ASSERT_EQ(shaft.size(), 2u);
  EXPECT_TRUE(parallel(shaft[0], gp::DZ()) && parallel(shaft[1], gp::DZ()));
  EXPECT_NEAR(shaft[0].Dot(shaft[1]), -1.0, 1e-12);
  EXPECT_TRUE(out_of("Rotor-front").empty());
  EXPECT_EQ(out_of("Magnet-1").size(), 5u);
}

// The same answers after a rigid motion of the whole assembly, axes moved with it.
TEST(Joints, MotorInvariantUnderRigidMotion) {
  gp_Trsf motion;
  motion.SetRotation(gp_Ax1(gp_Pnt(3, -7, 11), gp_Dir(1, 2, 3)), 0.7);
  gp_Trsf shift;
  shift.SetTranslation(gp_Vec(250, -120, 75));
  motion = shift * motion;
  const Motor still = analyse_motor(gp_Trsf());
  const Motor moved = analyse_motor(motion);
  ASSERT_EQ(still.a.joints.joints.size(), moved.a.joints.joints.size());
  for (size_t i = 0; i < still.a.joints.joints.size(); ++i) {
    const PairJoint& a = still.a.joints.joints[i];
    const PairJoint& b = moved.a.joints.joints[i];
    EXPECT_EQ(a.body_a, b.body_a);
    EXPECT_EQ(a.body_b, b.body_b);
    EXPECT_EQ(a.type, b.type);
    EXPECT_EQ(a.dof, b.dof);
    ASSERT_EQ(a.rotations.size(), b.rotations.size());
    for (size_t r = 0; r < a.rotations.size(); ++r) {
      EXPECT_LT(a.rotations[r].point.Transformed(motion).Distance(b.rotations[r].point), 1e-5);
      EXPECT_TRUE(parallel(a.rotations[r].direction.Transformed(motion), b.rotations[r].direction));
    }
    EXPECT_EQ(a.free_directions.size(), b.free_directions.size());
  }
  EXPECT_EQ(still.mobility.dof, moved.mobility.dof);
  EXPECT_EQ(still.mobility.passive, moved.mobility.passive);
  EXPECT_EQ(still.mobility.groups, moved.mobility.groups);
  for (size_t g = 0; g < still.mobility.group_motions.size(); ++g)
    EXPECT_EQ(still.mobility.group_motions[g].type, moved.mobility.group_motions[g].type);
}

// ------------------------------------------------------------- clearances

// A pin r 4.8 in a bore r 5: a 0.2 mm clearance, no contact. Found with a
// 0.5 mm gap, not with 0.1 mm.
TEST(Clearances, PinInLargerBore) {
  Assembly assembly;
  assembly.bodies.push_back({"Block", "Block", bored_block(5)});
  assembly.bodies.push_back({"Pin", "Pin", cylinder(4.8, 30, gp_Pnt(20, 20, -5))});
  ContactOptions options;
  options.clearance_gap = 0.5;
  const ContactsResult r = find_contacts(assembly, options);
  ASSERT_TRUE(r.status.ok());
  EXPECT_TRUE(r.contacts.empty());
  ASSERT_EQ(r.clearances.size(), 1u);
  EXPECT_EQ(r.clearances[0].kind, SurfaceKind::Cylinder);
  EXPECT_NEAR(r.clearances[0].gap, 0.2, 1e-9);
  EXPECT_TRUE(find_clearances(r.partitions, 0.1).empty());
}

// A pin r 5.02 in a bore r 5 (drawn oversize, a press fit): a coaxial overlap
// of 0.02 mm, reported as a negative gap with a 0.1 mm gap asked, not with
// 0.01 mm; no contact (the radii differ), the interference reported.
TEST(Clearances, OversizePinIsACoaxialOverlap) {
  Assembly assembly;
  assembly.bodies.push_back({"Block", "Block", bored_block(5)});
  assembly.bodies.push_back({"Pin", "Pin", cylinder(5.02, 30, gp_Pnt(20, 20, -5))});
  ContactOptions options;
  options.clearance_gap = 0.1;
  const ContactsResult r = find_contacts(assembly, options);
  ASSERT_TRUE(r.status.ok());
  EXPECT_TRUE(r.contacts.empty());
  ASSERT_EQ(r.clearances.size(), 1u);
  EXPECT_EQ(r.clearances[0].kind, SurfaceKind::Cylinder);
  EXPECT_NEAR(r.clearances[0].gap, -0.02, 1e-9);
  EXPECT_EQ(r.interferences.size(), 1u);
  EXPECT_TRUE(find_clearances(r.partitions, 0.01).empty());
}

// Results of another assembly, or a ground out of range: a clear error, no crash.
TEST(Joints, MismatchedInputIsAnError) {
  const Analysed a = analyse({{"Base", box(gp_Pnt(0, 0, 0), gp_Pnt(40, 40, 10))},
                              {"Top", box(gp_Pnt(10, 10, 10), gp_Pnt(30, 30, 15))}});
  Assembly one;
  one.bodies.push_back(a.assembly.bodies[0]);
  const JointsResult wrong = find_joints(one, a.contacts);
  EXPECT_EQ(wrong.status.code, StatusCode::InvalidInput);
  EXPECT_NE(wrong.status.message.find("another assembly"), std::string::npos);
  const MobilityResult m = assembly_mobility(one, a.contacts, a.joints);
  EXPECT_EQ(m.status.code, StatusCode::InvalidInput);
  MobilityOptions far;
  far.ground = 5;
  EXPECT_EQ(assembly_mobility(a.assembly, a.contacts, a.joints, far).status.code, StatusCode::InvalidInput);
}
