// Issue 22 (the mechanism the designer meant): prismatic joints keep their
// direction, overlapping pairs keep their contacts, one-sided spheres,
// point and line contacts, annotations. Every expected value is derived by
// hand in the comment above its test.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include <BRepAlgoAPI_Common.hxx>
#include <BRepAlgoAPI_Cut.hxx>
#include <BRepAlgoAPI_Fuse.hxx>
#include <BRepBuilderAPI_Transform.hxx>
#include <BRepGProp.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCone.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <BRepPrimAPI_MakeTorus.hxx>
#include <GProp_GProps.hxx>
#include <gp_Ax1.hxx>
#include <gp_Ax2.hxx>
#include <gp_Trsf.hxx>

#include "contactcore/joints/joints.h"
#include "test_helpers.h"

using namespace contactcore;

namespace {

struct Analysed {
  Assembly assembly;
  ContactsResult contacts;
  JointsResult joints;
};

Analysed analyse(std::vector<std::pair<std::string, TopoDS_Shape>> shapes, const gp_Trsf& motion = gp_Trsf()) {
  Analysed out;
  for (auto& [name, shape] : shapes)
    out.assembly.bodies.push_back({name, name, BRepBuilderAPI_Transform(shape, motion, true).Shape()});
  out.contacts = find_contacts(out.assembly, ContactOptions{});
  EXPECT_TRUE(out.contacts.status.ok()) << out.contacts.status.describe();
  out.joints = find_joints(out.assembly, out.contacts);
  EXPECT_TRUE(out.joints.status.ok()) << out.joints.status.describe();
  return out;
}

const PairJoint& only_joint(const Analysed& a) {
  EXPECT_EQ(a.joints.joints.size(), 1u);
  static PairJoint none;
  return a.joints.joints.empty() ? none : a.joints.joints[0];
}

// The assembly's mobility with its first body as the ground (-1 when it fails).
int dof_with_the_first_body_grounded(const Analysed& a) {
  MobilityOptions options;
  options.ground = 0;
  const MobilityResult m = assembly_mobility(a.assembly, a.contacts, a.joints, options);
  EXPECT_TRUE(m.status.ok()) << m.status.describe();
  return m.status.ok() ? m.dof : -1;
}

TopoDS_Shape box(gp_Pnt from, gp_Pnt to) { return BRepPrimAPI_MakeBox(from, to).Shape(); }
TopoDS_Shape cylinder(double r, double h, gp_Pnt base, gp_Dir axis = gp::DZ()) {
  return BRepPrimAPI_MakeCylinder(gp_Ax2(base, axis), r, h).Shape();
}
TopoDS_Shape fuse(const TopoDS_Shape& a, const TopoDS_Shape& b) { return BRepAlgoAPI_Fuse(a, b).Shape(); }
TopoDS_Shape cut(const TopoDS_Shape& a, const TopoDS_Shape& b) { return BRepAlgoAPI_Cut(a, b).Shape(); }
bool parallel(const gp_Dir& a, const gp_Dir& b) { return a.IsParallel(b, 1e-6); }
bool contains(const std::vector<gp_Dir>& dirs, const gp_Dir& d, double tol = 1e-6) {
  return std::any_of(dirs.begin(), dirs.end(), [&](const gp_Dir& x) { return x.Angle(d) < tol; });
}

}  // namespace

// ------------------------------------------------- prismatic joints (defect)

// An L-shaped corner (floor z <= 10 and wall x <= 10, one body) and a block
// on the floor against the wall. By hand: the floor's PLF (normal +z) and the
// wall's (normal +x) leave only the translation along y: prismatic along y.
// Both stops are one-sided, so the block leaves along +-y (the lineality),
// +x and +z: four generators.
TEST(Mechanism, BlockInAnLShapedCornerIsPrismaticAlongTheCorner) {
  const TopoDS_Shape corner = fuse(box(gp_Pnt(0, 0, 0), gp_Pnt(40, 40, 10)), box(gp_Pnt(0, 0, 10), gp_Pnt(10, 40, 40)));
  const Analysed a = analyse({{"Corner", corner}, {"Block", box(gp_Pnt(10, 10, 10), gp_Pnt(20, 30, 20))}});
  const PairJoint& j = only_joint(a);
  EXPECT_EQ(j.contacts.size(), 2u);
  EXPECT_EQ(j.type, JointType::Prismatic);
  EXPECT_EQ(j.dof, 1);
  EXPECT_TRUE(j.rotations.empty());
  ASSERT_EQ(j.translations.size(), 1u);
  EXPECT_TRUE(parallel(j.translations[0], gp::DY()));
  ASSERT_EQ(j.free_directions.size(), 4u);
  for (const gp_Dir& d : {gp_Dir(0, 1, 0), gp_Dir(0, -1, 0), gp_Dir(1, 0, 0), gp_Dir(0, 0, 1)})
    EXPECT_TRUE(contains(j.free_directions, d)) << d.X() << " " << d.Y() << " " << d.Z();
}

// A block 20 wide in a U-channel 20 wide (floor z = 10, walls x = 10 and
// x = 30), the whole assembly turned and moved several ways. By hand:
// prismatic along the channel (y, moved with the assembly); the stops +z,
// +x, -x leave +-y and +z (three generators), all moved likewise.
TEST(Mechanism, BlockInAUChannelKeepsItsDirectionUnderRigidMotions) {
  const TopoDS_Shape channel = cut(box(gp_Pnt(0, 0, 0), gp_Pnt(40, 30, 20)), box(gp_Pnt(10, -1, 10), gp_Pnt(30, 31, 21)));
  const TopoDS_Shape block = box(gp_Pnt(10, 5, 10), gp_Pnt(30, 25, 18));
  const std::vector<std::pair<gp_Ax1, double>> turns = {
      {gp_Ax1(gp::Origin(), gp::DZ()), 0.0},
      {gp_Ax1(gp_Pnt(3, -7, 11), gp_Dir(1, 2, 3)), 0.7},
      {gp_Ax1(gp_Pnt(-50, 20, 5), gp_Dir(0, 1, 1)), M_PI / 4},
      {gp_Ax1(gp_Pnt(10, 10, 10), gp_Dir(1, 1, 1)), 2 * M_PI / 3},
      {gp_Ax1(gp_Pnt(1, 2, 3), gp_Dir(-3, 1, 2)), 2.1},
      {gp_Ax1(gp_Pnt(0, 0, 0), gp_Dir(1, 0, 0)), M_PI / 2},
  };
  for (size_t k = 0; k < turns.size(); ++k) {
    gp_Trsf motion;
    if (turns[k].second != 0) motion.SetRotation(turns[k].first, turns[k].second);
    gp_Trsf shift;
    shift.SetTranslation(gp_Vec(120.0 * k, -35.0 * k, 7.5 * k));
    motion = shift * motion;
    const Analysed a = analyse({{"Channel", channel}, {"Block", block}}, motion);
    const PairJoint& j = only_joint(a);
    EXPECT_EQ(j.contacts.size(), 3u) << "motion " << k;
    EXPECT_EQ(j.type, JointType::Prismatic) << "motion " << k;
    ASSERT_EQ(j.translations.size(), 1u) << "motion " << k;
    EXPECT_TRUE(parallel(j.translations[0], gp::DY().Transformed(motion))) << "motion " << k;
    ASSERT_EQ(j.free_directions.size(), 3u) << "motion " << k;
    for (const gp_Dir& d : {gp_Dir(0, 1, 0), gp_Dir(0, -1, 0), gp_Dir(0, 0, 1)})
      EXPECT_TRUE(contains(j.free_directions, d.Transformed(motion))) << "motion " << k;
  }
}

// The classification alone: a pure translation whose omega part is round-off
// (5e-30) is prismatic with its direction, not a rotation.
TEST(Mechanism, ClassifyTwistsIgnoresRoundOffRotations) {
  const Twist slide{5e-30, -3e-30, 1e-30, 0, 0.6, 0.8};
  const TwistSpace space = classify_twists({slide}, gp_Pnt(10, 20, 30), 7);
  EXPECT_EQ(space.type, JointType::Prismatic);
  ASSERT_EQ(space.translations.size(), 1u);
  EXPECT_TRUE(parallel(space.translations[0], gp_Dir(0, 0.6, 0.8)));
  EXPECT_TRUE(space.rotations.empty());
}

// -------------------------------------- overlapping pairs keep their contacts

namespace {
double volume_of(const TopoDS_Shape& shape) {
  GProp_GProps props;
  BRepGProp::VolumeProperties(shape, props);
  return props.Mass();
}
}  // namespace

// A plate (40 x 30 x 10, z 0..10) with a slot 11.96 wide (x 14.02..25.98),
// 20 long (y 5..25) and 2.5 deep (floor z = 7.5); the plate above (z 10..15)
// has a tongue 12 (x 14..26) x 8 (y 11..19) x 2.5 (z 7.5..10): 0.02 mm into
// each long wall of the slot, 6 mm short of its ends. By hand:
//  - overlap: two slivers 0.02 x 8 x 2.5 = 0.4 mm3 each: 0.8 mm3;
//  - large faces (z = 10): the slotted plate's top, 40 x 30 - 11.96 x 20 =
//    960.8, minus the tongue's root inside it (2 x 0.02 x 8 = 0.32):
//    960.48 mm2, normal +z;
//  - the tongue's end on the slot floor (z = 7.5): 11.96 x 8 = 95.68 mm2, +z.
// The tongue's sides are 0.02 from the walls: no contact there.
TEST(Mechanism, OverlappingTongueKeepsItsContacts) {
  const TopoDS_Shape lower = cut(box(gp_Pnt(0, 0, 0), gp_Pnt(40, 30, 10)), box(gp_Pnt(14.02, 5, 7.5), gp_Pnt(25.98, 25, 11)));
  const TopoDS_Shape upper = fuse(box(gp_Pnt(0, 0, 10), gp_Pnt(40, 30, 15)), box(gp_Pnt(14, 11, 7.5), gp_Pnt(26, 19, 10)));
  const Analysed a = analyse({{"Slotted", lower}, {"Tongued", upper}});
  ASSERT_EQ(a.contacts.interferences.size(), 1u);
  const double boolean = volume_of(BRepAlgoAPI_Common(lower, upper).Shape());
  EXPECT_NEAR(boolean, 0.8, 1e-6);
  EXPECT_NEAR(a.contacts.interferences[0].volume, boolean, 1e-6);
  ASSERT_EQ(a.contacts.contacts.size(), 2u);
  std::vector<double> areas;
  for (const Contact& c : a.contacts.contacts) {
    EXPECT_EQ(c.type, ContactType::PLF);
    EXPECT_TRUE(parallel(c.direction, gp::DZ()));
    EXPECT_GT(c.direction.Z(), 0);  // out of the slotted plate
    areas.push_back(c.area);
  }
  std::sort(areas.begin(), areas.end());
  EXPECT_NEAR(areas[0], 95.68, 1e-6);
  EXPECT_NEAR(areas[1], 960.48, 1e-6);
  // The two planes leave the upper plate free in x and y and up: planar.
  const PairJoint& j = only_joint(a);
  EXPECT_EQ(j.type, JointType::Planar);
}

// ----------------------------------------------------- one-sided spheres

// A ball r 10 (centre 20, 20, 20) in a hemispherical cup cut into the top
// of a 40 x 40 x 20 block. By hand: the cup holds the ball on its lower
// half, normals (out of the cup) towards the centre over the cap of 90
// degrees about -z: the ball lifts out along +z only; spherical (3
// rotations about the centre, the rows stay bilateral for the joint).
// Listed the other way round (the cup relative to the ball) it leaves along -z.
TEST(Mechanism, BallInAHemisphericalCupLiftsOutAlongPlusZ) {
  const gp_Pnt centre(20, 20, 20);
  const TopoDS_Shape cup = cut(box(gp_Pnt(0, 0, 0), gp_Pnt(40, 40, 20)), BRepPrimAPI_MakeSphere(centre, 10).Shape());
  const TopoDS_Shape ball = BRepPrimAPI_MakeSphere(centre, 10).Shape();
  const Analysed a = analyse({{"Cup", cup}, {"Ball", ball}});
  ASSERT_EQ(a.contacts.contacts.size(), 1u);
  const Contact& c = a.contacts.contacts[0];
  EXPECT_EQ(c.type, ContactType::SPF);
  EXPECT_NEAR(c.region_angle, M_PI / 2, 1e-9);
  EXPECT_LT(c.region_axis.Angle(-gp::DZ()), 1e-6);
  const PairJoint& j = only_joint(a);
  EXPECT_EQ(j.type, JointType::Spherical);
  ASSERT_EQ(j.free_directions.size(), 1u);
  EXPECT_LT(j.free_directions[0].Angle(gp::DZ()), 1e-6);
  const auto out = body_free_directions(a.contacts, a.joints, 1);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_LT(out[0].Angle(gp::DZ()), 1e-6);

  const Analysed reversed = analyse({{"Ball", ball}, {"Cup", cup}});
  const PairJoint& r = only_joint(reversed);
  ASSERT_EQ(r.free_directions.size(), 1u);
  EXPECT_LT(r.free_directions[0].Angle(-gp::DZ()), 1e-6);
}

// The same ball in a shallow cup: the block's top at z = 15, 5 below the
// centre, so the cup is the cap within acos(5/10) = 60 degrees of -z. By
// hand: the ball leaves within the circular cone of 90 - 60 = 30 degrees
// about +z; the 12 generators lie exactly on it (the polygon inscribed in
// the true cone: no blocked direction allowed).
TEST(Mechanism, BallInAShallowCupLeavesWithinItsExactCone) {
  const gp_Pnt centre(20, 20, 20);
  const TopoDS_Shape cup = cut(box(gp_Pnt(0, 0, 0), gp_Pnt(40, 40, 15)), BRepPrimAPI_MakeSphere(centre, 10).Shape());
  const Analysed a = analyse({{"Cup", cup}, {"Ball", BRepPrimAPI_MakeSphere(centre, 10).Shape()}});
  ASSERT_EQ(a.contacts.contacts.size(), 1u);
  EXPECT_NEAR(a.contacts.contacts[0].region_angle, M_PI / 3, 1e-9);
  const PairJoint& j = only_joint(a);
  ASSERT_EQ(j.free_directions.size(), 12u);
  gp_XYZ mean(0, 0, 0);
  for (const gp_Dir& d : j.free_directions) {
    EXPECT_NEAR(d.Angle(gp::DZ()), M_PI / 6, 1e-9);
    mean += d.XYZ();
  }
  EXPECT_LT(gp_Dir(mean).Angle(gp::DZ()), 1e-9);
}

// A ball r 3 in an open torus groove (major radius 10, minor 3, about the
// vertical line x = y = 20, tube centres at z = 20, the block's top): the
// ball (centre 30, 20, 20) sits in the lower half of the tube. By hand: SPT,
// the contact circle in the xz plane, held over the lower half-circle
// (region 90 degrees about -z); the groove's tangent there is y. The ball
// rolls along the groove (+-y) and lifts out (+z): three generators.
TEST(Mechanism, BallInAnOpenTorusGrooveLiftsOutAlongPlusZ) {
  const TopoDS_Shape groove = BRepPrimAPI_MakeTorus(gp_Ax2(gp_Pnt(20, 20, 20), gp::DZ()), 10, 3).Shape();
  const TopoDS_Shape block = cut(box(gp_Pnt(0, 0, 0), gp_Pnt(40, 40, 20)), groove);
  const Analysed a = analyse({{"Block", block}, {"Ball", BRepPrimAPI_MakeSphere(gp_Pnt(30, 20, 20), 3).Shape()}});
  ASSERT_EQ(a.contacts.contacts.size(), 1u);
  const Contact& c = a.contacts.contacts[0];
  EXPECT_EQ(c.type, ContactType::SPT);
  EXPECT_NEAR(c.region_angle, M_PI / 2, 1e-6);
  EXPECT_LT(c.region_axis.Angle(-gp::DZ()), 1e-6);
  const PairJoint& j = only_joint(a);
  EXPECT_EQ(j.type, JointType::SphereCylinder);
  ASSERT_EQ(j.free_directions.size(), 3u);
  for (const gp_Dir& d : {gp_Dir(0, 1, 0), gp_Dir(0, -1, 0), gp_Dir(0, 0, 1)})
    EXPECT_TRUE(contains(j.free_directions, d, 1e-5)) << d.X() << " " << d.Y() << " " << d.Z();
}

// ------------------------------------------ point and line contacts (higher pairs)

namespace {
const HigherPair& only_higher(const Analysed& a) {
  EXPECT_EQ(a.contacts.higher_pairs.size(), 1u);
  static HigherPair none;
  return a.contacts.higher_pairs.empty() ? none : a.contacts.higher_pairs[0];
}
}  // namespace

// A ball r 5 (centre 20, 20, 15) on a plate's top (z = 10). By hand: a point
// contact at (20, 20, 10), normal +z out of the plate; no surface contact.
// The joint: one force along z through the point: sphere_plane, 5 DOF
// (rotations about the point, translations in the plane); the ball leaves
// along the plane both ways and up: five generators. With the plate
// grounded the assembly has those 5 DOF (it had 6: the ball floated).
TEST(Mechanism, BallOnAPlaneIsASpherePlanePointContact) {
  const Analysed a = analyse({{"Plate", box(gp_Pnt(0, 0, 0), gp_Pnt(40, 40, 10))},
                              {"Ball", BRepPrimAPI_MakeSphere(gp_Pnt(20, 20, 15), 5).Shape()}});
  EXPECT_TRUE(a.contacts.contacts.empty());
  const HigherPair& h = only_higher(a);
  EXPECT_EQ(h.type, HigherPairType::SphereOnPlane);
  EXPECT_STREQ(to_string(h.type), "sphere_on_plane");
  EXPECT_FALSE(h.is_line());
  EXPECT_LT(h.point.Distance(gp_Pnt(20, 20, 10)), 1e-9);
  EXPECT_LT(h.normal.Angle(gp::DZ()), 1e-9);
  const PairJoint& j = only_joint(a);
  EXPECT_EQ(j.higher_pairs, std::vector<int>{0});
  EXPECT_TRUE(j.contacts.empty());
  EXPECT_EQ(j.type, JointType::SpherePlane);
  EXPECT_STREQ(to_string(j.type), "sphere_plane");
  EXPECT_EQ(j.dof, 5);
  // Rotations about any point of the normal through the contact: the axes
  // are placed through the contact point (nearest the contacts' centre).
  for (const FreeRotation& r : j.rotations) EXPECT_LT(r.point.Distance(gp_Pnt(20, 20, 10)), 1e-6);
  ASSERT_EQ(j.free_directions.size(), 5u);
  EXPECT_TRUE(contains(j.free_directions, gp::DZ()));
  EXPECT_FALSE(contains(j.free_directions, -gp::DZ()));
  EXPECT_EQ(dof_with_the_first_body_grounded(a), 5);
}

// A ball r 3 against a vertical shaft r 5 (axis x = y = 20), centre 8 from
// the axis at (28, 20, 15): a point at (25, 20, 15), normal +x out of the
// shaft. A ball r 3 inside a vertical bore r 5 (axis x = y = 20), its centre
// 2 off the axis at (22, 20, 10): the point (25, 20, 10) on the bore's wall,
// normal -x out of the block. Both: sphere_plane, 5 DOF.
TEST(Mechanism, BallAgainstACylinderOfAnotherRadiusIsAPointContact) {
  const Analysed outside = analyse({{"Shaft", cylinder(5, 30, gp_Pnt(20, 20, 0))},
                                    {"Ball", BRepPrimAPI_MakeSphere(gp_Pnt(28, 20, 15), 3).Shape()}});
  const HigherPair& h = only_higher(outside);
  EXPECT_EQ(h.type, HigherPairType::SphereOnCylinder);
  EXPECT_LT(h.point.Distance(gp_Pnt(25, 20, 15)), 1e-9);
  EXPECT_LT(h.normal.Angle(gp::DX()), 1e-9);
  EXPECT_EQ(only_joint(outside).type, JointType::SpherePlane);

  const TopoDS_Shape block = cut(box(gp_Pnt(0, 0, 0), gp_Pnt(40, 40, 20)), cylinder(5, 40, gp_Pnt(20, 20, -10)));
  const Analysed inside = analyse({{"Block", block}, {"Ball", BRepPrimAPI_MakeSphere(gp_Pnt(22, 20, 10), 3).Shape()}});
  EXPECT_TRUE(inside.contacts.contacts.empty());
  const HigherPair& g = only_higher(inside);
  EXPECT_EQ(g.type, HigherPairType::SphereOnCylinder);
  EXPECT_LT(g.point.Distance(gp_Pnt(25, 20, 10)), 1e-9);
  EXPECT_LT(g.normal.Angle(-gp::DX()), 1e-9);
  const PairJoint& j = only_joint(inside);
  EXPECT_EQ(j.type, JointType::SpherePlane);
  EXPECT_EQ(j.dof, 5);
  EXPECT_TRUE(contains(j.free_directions, -gp::DX()));
}

// A roller r 5 along x (x 5..35, axis y = 20, z = 15) lying on a plate's
// top (z = 10). By hand: a line contact from (5, 20, 10) to (35, 20, 10),
// 30 mm, normal +z. The joint: forces along z at both ends: cylinder_plane,
// 4 DOF (rolling about the line, turning about z, sliding in x and y).
TEST(Mechanism, CylinderLyingOnAPlaneIsALineContact) {
  const Analysed a = analyse({{"Plate", box(gp_Pnt(0, 0, 0), gp_Pnt(40, 40, 10))},
                              {"Roller", cylinder(5, 30, gp_Pnt(5, 20, 15), gp::DX())}});
  EXPECT_TRUE(a.contacts.contacts.empty());
  const HigherPair& h = only_higher(a);
  EXPECT_EQ(h.type, HigherPairType::CylinderOnPlane);
  EXPECT_TRUE(h.is_line());
  EXPECT_NEAR(h.length, 30, 1e-6);
  EXPECT_LT(std::min(h.start.Distance(gp_Pnt(5, 20, 10)), h.end.Distance(gp_Pnt(5, 20, 10))), 1e-6);
  EXPECT_LT(std::min(h.start.Distance(gp_Pnt(35, 20, 10)), h.end.Distance(gp_Pnt(35, 20, 10))), 1e-6);
  EXPECT_LT(h.normal.Angle(gp::DZ()), 1e-9);
  const PairJoint& j = only_joint(a);
  EXPECT_EQ(j.type, JointType::CylinderPlane);
  EXPECT_STREQ(to_string(j.type), "cylinder_plane");
  EXPECT_EQ(j.dof, 4);
  ASSERT_EQ(j.translations.size(), 2u);
  for (const gp_Dir& t : j.translations) EXPECT_NEAR(t.Z(), 0, 1e-9);
  EXPECT_EQ(j.free_directions.size(), 5u);
  EXPECT_TRUE(contains(j.free_directions, gp::DZ()));
}

// Parallel cylinders of different radii. Outside: a roller r 5 along x
// (axis y = 20, z = 5, x 0..40) under a rod r 2 (axis z = 12, x 10..30):
// axes 7 = 5 + 2 apart, a line from (10, 20, 10) to (30, 20, 10), 20 mm,
// normal +z out of the roller. Inside: a pin r 3 lying against the wall of
// a bore r 5 (axes 2 = 5 - 3 apart, the pin's at x = 22): the line x = 25,
// y = 20 over the block's 20 mm, normal -x out of the block. Both
// cylinder_plane, 4 DOF.
TEST(Mechanism, ParallelCylindersOfDifferentRadiiMakeALineContact) {
  const Analysed outside = analyse({{"Roller", cylinder(5, 40, gp_Pnt(0, 20, 5), gp::DX())},
                                    {"Rod", cylinder(2, 20, gp_Pnt(10, 20, 12), gp::DX())}});
  const HigherPair& h = only_higher(outside);
  EXPECT_EQ(h.type, HigherPairType::CylinderOnCylinder);
  EXPECT_NEAR(h.length, 20, 1e-6);
  EXPECT_LT(h.point.Distance(gp_Pnt(20, 20, 10)), 1e-6);
  EXPECT_LT(h.normal.Angle(gp::DZ()), 1e-9);
  EXPECT_EQ(only_joint(outside).type, JointType::CylinderPlane);

  const TopoDS_Shape block = cut(box(gp_Pnt(0, 0, 0), gp_Pnt(40, 40, 20)), cylinder(5, 40, gp_Pnt(20, 20, -10)));
  const Analysed inside = analyse({{"Block", block}, {"Pin", cylinder(3, 30, gp_Pnt(22, 20, -5))}});
  EXPECT_TRUE(inside.contacts.contacts.empty());
  const HigherPair& g = only_higher(inside);
  EXPECT_EQ(g.type, HigherPairType::CylinderOnCylinder);
  EXPECT_NEAR(g.length, 20, 1e-6);
  EXPECT_LT(g.point.Distance(gp_Pnt(25, 20, 10)), 1e-6);
  EXPECT_LT(g.normal.Angle(-gp::DX()), 1e-9);
  const PairJoint& j = only_joint(inside);
  EXPECT_EQ(j.type, JointType::CylinderPlane);
  EXPECT_EQ(j.dof, 4);
}

// ------------------------------------ cone and torus higher pairs (item 3)

namespace {
TopoDS_Shape torus(gp_Pnt centre, gp_Dir axis, double major, double minor) {
  return BRepPrimAPI_MakeTorus(gp_Ax2(centre, axis), major, minor).Shape();
}
// Every direction of `dirs` at `angle` from `axis`.
void expect_all_at(const std::vector<gp_Dir>& dirs, const gp_Dir& axis, double angle) {
  for (const gp_Dir& d : dirs) EXPECT_NEAR(d.Angle(axis), angle, 1e-9) << d.X() << " " << d.Y() << " " << d.Z();
}
}  // namespace

// A frustum (radii 2 and 6 over 16: tan(half angle) = 1/4, so sin = 1/sqrt 17,
// cos = 4/sqrt 17; its apex 8 behind the small end) with its apex at the
// origin and its axis (4, 0, 1)/sqrt 17, lying on a plate's top (z = 0). By
// hand: its lowest generator cos(a) axis + sin(a) (1, 0, -4)/sqrt 17 is
// (1, 0, 0) at z = 0, from 8/cos a = 2 sqrt 17 to 24/cos a = 6 sqrt 17 from
// the apex: a line from (2 sqrt 17, 0, 0) to (6 sqrt 17, 0, 0), 4 sqrt 17 =
// 16.4924 mm long, normal +z out of the plate. The joint: forces along z at
// both ends, as a roller: cylinder_plane, 4 DOF, translations in the plane,
// five free directions with +z, never -z; with the plate grounded, 4 DOF.
TEST(Mechanism, ConeLyingOnAPlaneIsALineContactAlongAGenerator) {
  const double root17 = std::sqrt(17.0);
  const gp_Dir axis(4 / root17, 0, 1 / root17);
  const TopoDS_Shape cone =
      BRepPrimAPI_MakeCone(gp_Ax2(gp_Pnt(0, 0, 0).Translated(gp_Vec(axis) * 8), axis), 2, 6, 16).Shape();
  const Analysed a = analyse({{"Plate", box(gp_Pnt(-10, -20, -10), gp_Pnt(40, 20, 0))}, {"Cone", cone}});
  EXPECT_TRUE(a.contacts.contacts.empty());
  const HigherPair& h = only_higher(a);
  EXPECT_EQ(h.type, HigherPairType::ConeOnPlane);
  EXPECT_STREQ(to_string(h.type), "cone_on_plane");
  EXPECT_EQ(h.kind, HigherPairKind::Line);
  EXPECT_NEAR(h.length, 4 * root17, 1e-6);
  EXPECT_LT(h.start.Distance(gp_Pnt(2 * root17, 0, 0)), 1e-6);
  EXPECT_LT(h.end.Distance(gp_Pnt(6 * root17, 0, 0)), 1e-6);
  EXPECT_LT(h.point.Distance(gp_Pnt(4 * root17, 0, 0)), 1e-6);
  EXPECT_LT(h.normal.Angle(gp::DZ()), 1e-9);
  const PairJoint& j = only_joint(a);
  EXPECT_EQ(j.higher_pairs, std::vector<int>{0});
  EXPECT_EQ(j.type, JointType::CylinderPlane);
  EXPECT_EQ(j.dof, 4);
  ASSERT_EQ(j.translations.size(), 2u);
  for (const gp_Dir& t : j.translations) EXPECT_NEAR(t.Z(), 0, 1e-9);
  EXPECT_EQ(j.free_directions.size(), 5u);
  EXPECT_TRUE(contains(j.free_directions, gp::DZ()));
  EXPECT_FALSE(contains(j.free_directions, -gp::DZ()));
  EXPECT_EQ(dof_with_the_first_body_grounded(a), 4);
  // Tilted 1 deg more about its generator's normal: no longer on the plane.
  const TopoDS_Shape steeper = BRepPrimAPI_MakeCone(
      gp_Ax2(gp_Pnt(0, 0, 0).Translated(gp_Vec(axis.Rotated(gp_Ax1(gp::Origin(), -gp::DY()), 1 * M_PI / 180)) * 8),
             axis.Rotated(gp_Ax1(gp::Origin(), -gp::DY()), 1 * M_PI / 180)),
      2, 6, 16).Shape();
  const Analysed off = analyse({{"Plate", box(gp_Pnt(-10, -20, -10), gp_Pnt(40, 20, 0))}, {"Cone", steeper}});
  EXPECT_TRUE(off.contacts.higher_pairs.empty());
}

// A ring (torus R 10, r 2) lying flat on a plate's top (z = 10), centre
// (20, 20, 12). By hand: its tube's centres at z = 12 touch z = 10 along the
// circle of radius 10 about (20, 20, 10), normal +z all round. The joint:
// forces along z around a circle: planar, 3 DOF (slides in x, y, turns
// about z); free directions: the plane both ways and +z (five). Grounded
// plate: 3 DOF.
TEST(Mechanism, RingLyingFlatOnAPlaneIsACircleContactAndPlanar) {
  const Analysed a = analyse({{"Plate", box(gp_Pnt(0, 0, 0), gp_Pnt(40, 40, 10))},
                              {"Ring", torus(gp_Pnt(20, 20, 12), gp::DZ(), 10, 2)}});
  EXPECT_TRUE(a.contacts.contacts.empty());
  const HigherPair& h = only_higher(a);
  EXPECT_EQ(h.type, HigherPairType::TorusOnPlane);
  EXPECT_STREQ(to_string(h.type), "torus_on_plane");
  EXPECT_EQ(h.kind, HigherPairKind::Circle);
  EXPECT_STREQ(to_string(h.kind), "circle");
  EXPECT_LT(h.point.Distance(gp_Pnt(20, 20, 10)), 1e-9);
  EXPECT_NEAR(h.radius, 10, 1e-9);
  EXPECT_NEAR(h.length, 20 * M_PI, 1e-9);
  EXPECT_TRUE(h.axis.IsParallel(gp::DZ(), 1e-9));
  EXPECT_NEAR(h.start.Distance(gp_Pnt(20, 20, 10)), 10, 1e-9);
  EXPECT_NEAR(h.start.Z(), 10, 1e-9);
  EXPECT_LT(h.normal.Angle(gp::DZ()), 1e-9);
  const PairJoint& j = only_joint(a);
  EXPECT_EQ(j.type, JointType::Planar);
  EXPECT_EQ(j.dof, 3);
  EXPECT_EQ(j.free_directions.size(), 5u);
  EXPECT_TRUE(contains(j.free_directions, gp::DZ()));
  EXPECT_FALSE(contains(j.free_directions, -gp::DZ()));
  EXPECT_EQ(dof_with_the_first_body_grounded(a), 3);
}

// A rounded wheel (torus R 10, r 2) on a plate's top (z = 10). Standing (axis
// y, centre (20, 20, 22)): its lowest point (20, 20, 10), 22 - 10 - 2 above
// the plate's top is 0. Tilted 30 deg (axis (1/2, 0, sqrt 3/2), centre
// (20, 20, 17)): the normal's part across the axis has length sin 30 = 1/2,
// the lowest tube centre C + 10 (sqrt 3/2, 0, -1/2) at z = 12, the point
// (20 + 5 sqrt 3, 20, 10). Both: a point, normal +z; sphere_plane, 5 DOF.
TEST(Mechanism, WheelStandingOrTiltedOnAPlaneIsAPointContact) {
  const Analysed standing = analyse({{"Plate", box(gp_Pnt(0, 0, 0), gp_Pnt(40, 40, 10))},
                                     {"Wheel", torus(gp_Pnt(20, 20, 22), gp::DY(), 10, 2)}});
  const HigherPair& h = only_higher(standing);
  EXPECT_EQ(h.type, HigherPairType::TorusOnPlane);
  EXPECT_EQ(h.kind, HigherPairKind::Point);
  EXPECT_LT(h.point.Distance(gp_Pnt(20, 20, 10)), 1e-9);
  EXPECT_LT(h.normal.Angle(gp::DZ()), 1e-9);
  const PairJoint& j = only_joint(standing);
  EXPECT_EQ(j.type, JointType::SpherePlane);
  EXPECT_EQ(j.dof, 5);
  EXPECT_TRUE(contains(j.free_directions, gp::DZ()));

  const Analysed tilted = analyse({{"Plate", box(gp_Pnt(0, 0, 0), gp_Pnt(40, 40, 10))},
                                   {"Wheel", torus(gp_Pnt(20, 20, 17), gp_Dir(0.5, 0, std::sqrt(3.0) / 2), 10, 2)}});
  const HigherPair& g = only_higher(tilted);
  EXPECT_EQ(g.type, HigherPairType::TorusOnPlane);
  EXPECT_EQ(g.kind, HigherPairKind::Point);
  EXPECT_LT(g.point.Distance(gp_Pnt(20 + 5 * std::sqrt(3.0), 20, 10)), 1e-9);
  EXPECT_EQ(only_joint(tilted).type, JointType::SpherePlane);
  EXPECT_EQ(only_joint(tilted).dof, 5);
}

// An O-ring (torus R 10, r 2, axis z, centre (20, 20, 10)) in a bore r 12
// through a block: its outer equator (radius 12) on the wall, a circle about
// (20, 20, 10), the block's normal towards the axis all round. The joint:
// radial forces in one plane have no moment about the centre: they hold
// x and y only: sphere_cylinder, 4 DOF (turns about the centre, slides along
// z), free along +-z only. The same ring on a shaft r 8 (its inner equator,
// 10 - 2): a circle r 8, the shaft's normal away from the axis; 4 DOF. A
// wheel (R 5, r 2, outer equator 7) in the bore r 12, 5 off its axis at
// (25, 20, 10): the point (32, 20, 10), normal -x out of the block;
// sphere_plane, 5 DOF.
TEST(Mechanism, RingInABoreOrOnAShaftIsACircleOrAPoint) {
  const TopoDS_Shape block = cut(box(gp_Pnt(0, 0, 0), gp_Pnt(40, 40, 20)), cylinder(12, 40, gp_Pnt(20, 20, -10)));
  const Analysed in_bore = analyse({{"Block", block}, {"ORing", torus(gp_Pnt(20, 20, 10), gp::DZ(), 10, 2)}});
  EXPECT_TRUE(in_bore.contacts.contacts.empty());
  const HigherPair& h = only_higher(in_bore);
  EXPECT_EQ(h.type, HigherPairType::TorusOnCylinder);
  EXPECT_STREQ(to_string(h.type), "torus_on_cylinder");
  EXPECT_EQ(h.kind, HigherPairKind::Circle);
  EXPECT_LT(h.point.Distance(gp_Pnt(20, 20, 10)), 1e-9);
  EXPECT_NEAR(h.radius, 12, 1e-9);
  EXPECT_NEAR(h.start.Distance(gp_Pnt(20, 20, 10)), 12, 1e-9);
  EXPECT_LT(h.normal.Angle(gp_Dir(gp_Vec(h.start, gp_Pnt(20, 20, 10)))), 1e-9);  // out of the block: inwards
  const PairJoint& j = only_joint(in_bore);
  EXPECT_EQ(j.type, JointType::SphereCylinder);
  EXPECT_EQ(j.dof, 4);
  ASSERT_EQ(j.free_directions.size(), 2u);
  EXPECT_TRUE(contains(j.free_directions, gp::DZ()));
  EXPECT_TRUE(contains(j.free_directions, -gp::DZ()));

  const Analysed on_shaft = analyse({{"Shaft", cylinder(8, 30, gp_Pnt(20, 20, -5))},
                                     {"ORing", torus(gp_Pnt(20, 20, 10), gp::DZ(), 10, 2)}});
  const HigherPair& g = only_higher(on_shaft);
  EXPECT_EQ(g.type, HigherPairType::TorusOnCylinder);
  EXPECT_EQ(g.kind, HigherPairKind::Circle);
  EXPECT_NEAR(g.radius, 8, 1e-9);
  EXPECT_LT(g.normal.Angle(gp_Dir(gp_Vec(gp_Pnt(20, 20, 10), g.start))), 1e-9);  // out of the shaft
  EXPECT_EQ(only_joint(on_shaft).dof, 4);

  const Analysed wheel = analyse({{"Block", block}, {"Wheel", torus(gp_Pnt(25, 20, 10), gp::DZ(), 5, 2)}});
  const HigherPair& w = only_higher(wheel);
  EXPECT_EQ(w.type, HigherPairType::TorusOnCylinder);
  EXPECT_EQ(w.kind, HigherPairKind::Point);
  EXPECT_LT(w.point.Distance(gp_Pnt(32, 20, 10)), 1e-9);
  EXPECT_LT(w.normal.Angle(-gp::DX()), 1e-9);
  EXPECT_EQ(only_joint(wheel).type, JointType::SpherePlane);
  EXPECT_EQ(only_joint(wheel).dof, 5);
}

// A pointed cone (half angle 45 deg, apex (20, 20, 15), axis +z, radius 10
// at z = 25) seated on the sharp rim of a bore r 5 through a block 20 high:
// its radius at the mouth (z = 20) is 5 tan 45 = 5. By hand: a circle r 5
// about (20, 20, 20), the block's normal (-radial + z)/sqrt 2. The joint:
// those forces around the circle hold x, y, z and the tilts: revolute about
// the bore's axis, 1 DOF; it lifts off within the circular cone of 45 deg
// about +z (the normals' cone, at 45 deg from +z, leaves 90 - 45): the 12
// generators exactly on it. Grounded block: 1 DOF.
TEST(Mechanism, ConeSeatedOnABoresRimIsACircleContactAndRevolute) {
  const TopoDS_Shape block = cut(box(gp_Pnt(0, 0, 0), gp_Pnt(40, 40, 20)), cylinder(5, 40, gp_Pnt(20, 20, -10)));
  const TopoDS_Shape cone = BRepPrimAPI_MakeCone(gp_Ax2(gp_Pnt(20, 20, 15), gp::DZ()), 0, 10, 10).Shape();
  const Analysed a = analyse({{"Block", block}, {"Cone", cone}});
  EXPECT_TRUE(a.contacts.contacts.empty());
  const HigherPair& h = only_higher(a);
  EXPECT_EQ(h.type, HigherPairType::ConeOnCylinder);
  EXPECT_STREQ(to_string(h.type), "cone_on_cylinder");
  EXPECT_EQ(h.kind, HigherPairKind::Circle);
  EXPECT_LT(h.point.Distance(gp_Pnt(20, 20, 20)), 1e-9);
  EXPECT_NEAR(h.radius, 5, 1e-9);
  EXPECT_NEAR(h.start.Z(), 20, 1e-9);
  const gp_Vec inwards(h.start, gp_Pnt(20, 20, 20));
  EXPECT_LT(h.normal.Angle(gp_Dir(inwards / 5 + gp_Vec(0, 0, 1))), 1e-9);
  const PairJoint& j = only_joint(a);
  EXPECT_EQ(j.type, JointType::Revolute);
  EXPECT_EQ(j.dof, 1);
  ASSERT_EQ(j.rotations.size(), 1u);
  EXPECT_TRUE(j.rotations[0].direction.IsParallel(gp::DZ(), 1e-9));
  EXPECT_NEAR(gp_Vec(j.rotations[0].point.X() - 20, j.rotations[0].point.Y() - 20, 0).Magnitude(), 0, 1e-6);
  EXPECT_EQ(j.free_directions.size(), 12u);
  expect_all_at(j.free_directions, gp::DZ(), M_PI / 4);
  EXPECT_EQ(dof_with_the_first_body_grounded(a), 1);
  // The cone free of the grounded block: the same exact cone.
  const std::vector<gp_Dir> out = body_free_directions(a.contacts, a.joints, 1);
  EXPECT_EQ(out.size(), 12u);
  expect_all_at(out, gp::DZ(), M_PI / 4);
}

// ------------------------------------------------------------ annotations

namespace {

struct Note {
  const char* a;
  const char* b;
  const char* type;  // nullptr: every contact of the pair
  ContactIntent intent;
};

// The designer's annotations of the motor (Resources/samples/motor.annotations.json).
const std::vector<Note> kMotorNotes = {
    {"Axis", "Rotor-front", "CLJ", ContactIntent::Interference},
    {"Axis", "Rotor-back", "CLJ", ContactIntent::Interference},
    {"Magnet-1", "Rotor-back", nullptr, ContactIntent::Bonded},
    {"Magnet-2", "Rotor-back", nullptr, ContactIntent::Bonded},
    {"Magnet-3", "Rotor-back", nullptr, ContactIntent::Bonded},
    {"Magnet-4", "Rotor-back", nullptr, ContactIntent::Bonded},
    {"Bearing-front", "Front-cover", "CLJ", ContactIntent::Interference},
    {"Bearing-back", "Back-cover", "CLJ", ContactIntent::Interference},
    {"Seal", "Front-cover", "CLJ", ContactIntent::Interference},
    {"Axis", "Bearing-front", "CLJ", ContactIntent::Clearance},
    {"Axis", "Bearing-back", "CLJ", ContactIntent::Clearance},
    {"Axis", "Seal", "CLJ", ContactIntent::Clearance},
    {"Stator", "Body", "CLJ", ContactIntent::Bonded},
    {"Screw-1", "Back-cover", "CLJ", ContactIntent::Threaded},
    {"Screw-2", "Back-cover", "CLJ", ContactIntent::Threaded},
    {"Screw-3", "Back-cover", "CLJ", ContactIntent::Threaded},
    {"Screw-4", "Back-cover", "CLJ", ContactIntent::Threaded},
};

}  // namespace

// The motor without annotations: 26 DOF with the Body grounded (docs/joints.md).
// With the designer's annotations (rotor halves pressed on the axis, magnets
// bonded to the rotor, bearings and seal pressed into their covers and
// turning freely on the axis, stator bonded, screws tightened): by hand,
// two rigid groups, everything else with the body, and the axis with the
// rotor halves and magnets; the rotor-front's plane on the front bearing
// (now part of the ground) and the rotor-back's on the rotor-front stop it
// along the axis, so it turns about the axis only: revolute, 1 DOF, and no
// passive spin is left (each spinning part is pressed or bonded).
TEST(Mechanism, MotorWithItsAnnotationsIsTwoGroupsAndOneDof) {
  Assembly motor = read_step(contactcore::testing::sample("motor.step")).assembly;
  ASSERT_EQ(motor.bodies.size(), 18u);
  const ContactsResult contacts = find_contacts(motor, ContactOptions{});
  ASSERT_TRUE(contacts.status.ok());
  std::map<std::string, int> id;
  for (size_t i = 0; i < motor.bodies.size(); ++i) id[motor.bodies[i].name] = static_cast<int>(i);
  MobilityOptions grounded;
  grounded.ground = id.at("Body");

  const JointsResult plain = find_joints(motor, contacts);
  const MobilityResult before = assembly_mobility(motor, contacts, plain, grounded);
  ASSERT_TRUE(before.status.ok());
  EXPECT_EQ(before.dof, 26);
  EXPECT_EQ(before.passive, 9);

  JointOptions options;
  options.contact_intents.assign(contacts.contacts.size(), ContactIntent::Unspecified);
  for (const Note& note : kMotorNotes) {
    int matched = 0;
    for (size_t k = 0; k < contacts.contacts.size(); ++k) {
      const Contact& c = contacts.contacts[k];
      if (std::set<int>{c.body_a, c.body_b} != std::set<int>{id.at(note.a), id.at(note.b)}) continue;
      if (note.type && std::string(to_string(c.type)) != note.type) continue;
      options.contact_intents[k] = note.intent;
      ++matched;
    }
    EXPECT_GT(matched, 0) << note.a << " - " << note.b;
  }
  const JointsResult annotated = find_joints(motor, contacts, options);
  ASSERT_TRUE(annotated.status.ok());
  int rigid_pairs = 0;
  for (const PairJoint& j : annotated.joints) rigid_pairs += j.annotated_rigid;
  EXPECT_EQ(rigid_pairs, 14);  // 2 rotor halves, 4 magnets, 2 bearings, the seal, the stator, 4 screws
  const MobilityResult after = assembly_mobility(motor, contacts, annotated, grounded);
  ASSERT_TRUE(after.status.ok()) << after.status.describe();
  ASSERT_EQ(after.groups.size(), 2u);
  std::set<std::string> rotor;
  for (int b : after.groups[1]) rotor.insert(motor.bodies[b].name);
  EXPECT_EQ(rotor, (std::set<std::string>{"Axis", "Rotor-front", "Rotor-back", "Magnet-1", "Magnet-2", "Magnet-3",
                                          "Magnet-4"}));
  EXPECT_EQ(after.groups[0].size(), 11u);
  EXPECT_EQ(after.dof, 1);
  EXPECT_EQ(after.passive, 0);
  const GroupMotion& spin = after.group_motions[1];
  EXPECT_EQ(spin.type, JointType::Revolute);
  ASSERT_EQ(spin.rotations.size(), 1u);
  EXPECT_TRUE(parallel(spin.rotations[0].direction, gp::DZ()));
  // An ignored contact is left out: ignoring the seal's two contacts leaves no joint for its pairs.
  JointOptions ignoring;
  ignoring.contact_intents.assign(contacts.contacts.size(), ContactIntent::Unspecified);
  for (size_t k = 0; k < contacts.contacts.size(); ++k)
    if (contacts.contacts[k].body_a == id.at("Seal") || contacts.contacts[k].body_b == id.at("Seal"))
      ignoring.contact_intents[k] = ContactIntent::Ignored;
  const JointsResult without_seal = find_joints(motor, contacts, ignoring);
  EXPECT_EQ(without_seal.joints.size() + 2, plain.joints.size());
}
