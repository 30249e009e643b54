#include <gtest/gtest.h>

#include <map>

#include <BRepAlgoAPI_Cut.hxx>
#include <BRepBuilderAPI_Transform.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCone.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <gp_Ax2.hxx>

#include "contactcore/contacts/contacts.h"
#include "test_helpers.h"

using namespace contactcore;
using contactcore::testing::contacts_of;
using contactcore::testing::make_assembly;
using contactcore::testing::shared_step;

namespace {

std::map<std::string, int> count_types(const ContactsResult& result) {
  std::map<std::string, int> counts;
  for (const Contact& c : result.contacts) ++counts[to_string(c.type)];
  return counts;
}

TopoDS_Shape box(double x, double y, double z, gp_Pnt at = gp_Pnt(0, 0, 0)) {
  return BRepPrimAPI_MakeBox(at, x, y, z).Shape();
}

TopoDS_Shape cylinder(double r, double h, gp_Pnt base = gp_Pnt(0, 0, 0)) {
  return BRepPrimAPI_MakeCylinder(gp_Ax2(base, gp::DZ()), r, h).Shape();
}

// A block 40 x 40 x 20 with a vertical bore of radius r through its centre.
TopoDS_Shape bored_block(double r) {
  return BRepAlgoAPI_Cut(box(40, 40, 20, gp_Pnt(-20, -20, 0)), cylinder(r, 40, gp_Pnt(0, 0, -10))).Shape();
}

}  // namespace

// ----------------------------------------------------------- common area

TEST(CommonArea, OverlappingSquares) {
  const std::vector<Polygon2> a{{{0, 0}, {2, 0}, {2, 2}, {0, 2}}};
  const std::vector<Polygon2> b{{{1, 1}, {3, 1}, {3, 3}, {1, 3}}};
  EXPECT_NEAR(common_area(a, b, 1e-9), 1.0, 1e-12);
}

TEST(CommonArea, IdenticalSquaresShareTheirBoundary) {
  const std::vector<Polygon2> a{{{0, 0}, {2, 0}, {2, 2}, {0, 2}}};
  EXPECT_NEAR(common_area(a, a, 1e-9), 4.0, 1e-12);
}

TEST(CommonArea, HoleIsExcluded) {
  const std::vector<Polygon2> plate{{{0, 0}, {10, 0}, {10, 10}, {0, 10}}, {{4, 4}, {4, 6}, {6, 6}, {6, 4}}};
  const std::vector<Polygon2> square{{{3, 3}, {7, 3}, {7, 7}, {3, 7}}};
  EXPECT_NEAR(common_area(plate, square, 1e-9), 16.0 - 4.0, 1e-12);
}

TEST(CommonArea, EdgeTouchingSquaresHaveNoArea) {
  const std::vector<Polygon2> a{{{0, 0}, {1, 0}, {1, 1}, {0, 1}}};
  const std::vector<Polygon2> b{{{1, 0}, {2, 0}, {2, 1}, {1, 1}}};
  EXPECT_NEAR(common_area(a, b, 1e-9), 0.0, 1e-12);
}

TEST(CommonArea, NonConvexLShape) {
  const std::vector<Polygon2> l{{{0, 0}, {4, 0}, {4, 1}, {1, 1}, {1, 4}, {0, 4}}};
  const std::vector<Polygon2> square{{{0.5, 0.5}, {3, 0.5}, {3, 3}, {0.5, 3}}};
  // L covers [0.5,3]x[0.5,1] and [0.5,1]x[1,3].
  EXPECT_NEAR(common_area(l, square, 1e-9), 2.5 * 0.5 + 0.5 * 2.0, 1e-12);
}

// ----------------------------------------------------------- broad phase

TEST(BroadPhase, OnlyMeetingBoxes) {
  std::vector<Bnd_Box> boxes(3);
  boxes[0].Update(0, 0, 0, 1, 1, 1);
  boxes[1].Update(1, 0, 0, 2, 1, 1);      // touches 0
  boxes[2].Update(5, 5, 5, 6, 6, 6);      // alone
  const auto pairs = broad_phase(boxes, 1e-6).pairs;
  ASSERT_EQ(pairs.size(), 1u);
  EXPECT_EQ(pairs[0], std::make_pair(0, 1));
}

// ----------------------------------------------------------- contact types

TEST(Contacts, StackedBoxesArePlanarFit) {
  const auto result = contacts_of(make_assembly({{"lower", box(10, 10, 10)},
                                                 {"upper", box(4, 4, 4, gp_Pnt(2, 2, 10))}}));
  ASSERT_EQ(result.contacts.size(), 1u);
  const Contact& c = result.contacts[0];
  EXPECT_EQ(c.type, ContactType::PLF);
  EXPECT_NEAR(c.area, 16.0, 1e-6);
  EXPECT_NEAR(c.direction.Z(), 1.0, 1e-9);  // lower's outward normal
}

TEST(Contacts, SideBySideCoplanarTopsAreNotAContact) {
  // Same normal on the tops; the side faces touch along a full face though.
  const auto result = contacts_of(make_assembly({{"a", box(10, 10, 10)},
                                                 {"b", box(10, 10, 10, gp_Pnt(10, 0, 0))}}));
  ASSERT_EQ(result.contacts.size(), 1u);
  EXPECT_NEAR(result.contacts[0].direction.X(), 1.0, 1e-9);  // the shared side face, not the tops
  EXPECT_NEAR(result.contacts[0].area, 100.0, 1e-6);
}

TEST(Contacts, CornerTouchIsNotAContact) {
  const auto result = contacts_of(make_assembly({{"a", box(10, 10, 10)},
                                                 {"b", box(10, 10, 10, gp_Pnt(10, 10, 10))}}));
  EXPECT_TRUE(result.contacts.empty());
}

TEST(Contacts, ShaftInBoreIsCylindricalJoint) {
  const auto result = contacts_of(make_assembly({{"block", bored_block(5)},
                                                 {"shaft", cylinder(5, 60, gp_Pnt(0, 0, -20))}}));
  ASSERT_EQ(result.contacts.size(), 1u);
  const Contact& c = result.contacts[0];
  EXPECT_EQ(c.type, ContactType::CLJ);
  EXPECT_NEAR(c.radius, 5.0, 1e-9);
  EXPECT_NEAR(c.area, 2 * M_PI * 5 * 20, 1e-6);
  EXPECT_FALSE(c.partial);
}

TEST(Contacts, ClearanceFitIsNotAContact) {
  const auto result = contacts_of(make_assembly({{"block", bored_block(5)},
                                                 {"shaft", cylinder(4.95, 60, gp_Pnt(0, 0, -20))}}));
  EXPECT_TRUE(result.contacts.empty());
}

TEST(Contacts, InterferenceIsNotAContact) {
  const auto result = contacts_of(make_assembly({{"block", bored_block(5)},
                                                 {"shaft", cylinder(5.2, 60, gp_Pnt(0, 0, -20))}}));
  EXPECT_TRUE(result.contacts.empty());
}

TEST(Contacts, CylinderLyingOnPlaneIsALineNotAContact) {
  const TopoDS_Shape lying = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 5, 15), gp::DX()), 5, 20).Shape();
  const auto result = contacts_of(make_assembly({{"plate", box(30, 30, 10)}, {"roller", lying}}));
  EXPECT_TRUE(result.contacts.empty());
}

TEST(Contacts, ShaftInCradleIsPartial) {
  // A block whose top is a 120-degree circular cradle of radius 5 (axis along
  // X at height 9, so the cradle edges stand at 60 degrees either side).
  const TopoDS_Shape groove_cutter = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(-10, 0, 9.0), gp::DX()), 5, 40).Shape();
  const TopoDS_Shape cradle =
      BRepAlgoAPI_Cut(box(20, 20, 6.5, gp_Pnt(0, -10, 0)), groove_cutter).Shape();
  const TopoDS_Shape shaft = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(-5, 0, 9.0), gp::DX()), 5, 30).Shape();
  const auto result = contacts_of(make_assembly({{"cradle", cradle}, {"shaft", shaft}}));
  ASSERT_EQ(result.contacts.size(), 1u);
  const Contact& c = result.contacts[0];
  EXPECT_EQ(c.type, ContactType::CLJ);
  EXPECT_TRUE(c.partial);
  // cos(half span) = (9 - 6.5) / 5 -> half span 60 degrees.
  EXPECT_NEAR(c.span * 180 / M_PI, 120.0, 0.5);
}

TEST(Contacts, ConeInConeIsUnidirectional) {
  const gp_Ax2 axis(gp_Pnt(0, 0, 0), gp::DZ());
  const TopoDS_Shape pin = BRepPrimAPI_MakeCone(axis, 3, 5, 20).Shape();
  const TopoDS_Shape hub = BRepAlgoAPI_Cut(box(30, 30, 10, gp_Pnt(-15, -15, 5)), pin).Shape();
  const auto result = contacts_of(make_assembly({{"hub", hub}, {"pin", pin}}));
  auto counts = count_types(result);
  EXPECT_EQ(counts["CJU"], 1);
  EXPECT_EQ(result.contacts.size(), 1u);
}

TEST(Contacts, BallInCupIsSphericalFit) {
  const TopoDS_Shape ball = BRepPrimAPI_MakeSphere(gp_Pnt(0, 0, 10), 4).Shape();
  const TopoDS_Shape cup = BRepAlgoAPI_Cut(box(20, 20, 10, gp_Pnt(-10, -10, 0)), ball).Shape();
  const auto result = contacts_of(make_assembly({{"cup", cup}, {"ball", ball}}));
  ASSERT_EQ(result.contacts.size(), 1u);
  EXPECT_EQ(result.contacts[0].type, ContactType::SPF);
  EXPECT_NEAR(result.contacts[0].area, 2 * M_PI * 16, 2 * M_PI * 16 * 0.1);  // half sphere, sampled
}

TEST(Contacts, BallInBoreIsLinearAnnular) {
  const TopoDS_Shape ball = BRepPrimAPI_MakeSphere(gp_Pnt(0, 0, 10), 5).Shape();
  const auto result = contacts_of(make_assembly({{"block", bored_block(5)}, {"ball", ball}}));
  ASSERT_EQ(result.contacts.size(), 1u);
  const Contact& c = result.contacts[0];
  EXPECT_EQ(c.type, ContactType::LAF);
  EXPECT_EQ(c.body_a, 0);  // the block, first in the assembly, even though the ball leads the test
  EXPECT_FALSE(c.partial);
  EXPECT_NEAR(c.span, 2 * M_PI, 0.1);
}

TEST(Contacts, BallAboveTheBoreIsNotAContact) {
  const TopoDS_Shape ball = BRepPrimAPI_MakeSphere(gp_Pnt(0, 0, 26), 5).Shape();
  const auto result = contacts_of(make_assembly({{"block", bored_block(5)}, {"ball", ball}}));
  EXPECT_TRUE(result.contacts.empty());
}

TEST(Contacts, InchScaledAssemblyGivesTheSameContacts) {
  gp_Trsf inch;
  inch.SetScale(gp_Pnt(0, 0, 0), 25.4);
  // A location cannot scale: transform the geometry itself.
  const auto scaled = [&inch](const TopoDS_Shape& s) { return BRepBuilderAPI_Transform(s, inch, true).Shape(); };
  const auto mm = contacts_of(make_assembly({{"block", bored_block(5)}, {"shaft", cylinder(5, 60, gp_Pnt(0, 0, -20))},
                                             {"cap", box(10, 10, 5, gp_Pnt(-5, -5, 20))}}));
  const auto in = contacts_of(make_assembly({{"block", scaled(bored_block(5))},
                                             {"shaft", scaled(cylinder(5, 60, gp_Pnt(0, 0, -20)))},
                                             {"cap", scaled(box(10, 10, 5, gp_Pnt(-5, -5, 20)))}}));
  EXPECT_EQ(count_types(mm), count_types(in));
  ASSERT_EQ(mm.contacts.size(), in.contacts.size());
  for (size_t i = 0; i < mm.contacts.size(); ++i)
    EXPECT_NEAR(in.contacts[i].area, mm.contacts[i].area * 25.4 * 25.4, 1e-6 * in.contacts[i].area);
}

TEST(Contacts, CancelledByProgress) {
  struct StopAtOnce : Progress {
    bool report(const char*, double) override { return false; }
  } stop;
  const auto result = find_contacts(make_assembly({{"a", box(1, 1, 1)}, {"b", box(1, 1, 1, gp_Pnt(1, 0, 0))}}),
                                    ContactOptions{}, &stop);
  EXPECT_EQ(result.status.code, StatusCode::Cancelled);
}

// ----------------------------------------------------------- shared files

namespace {
ContactsResult contacts_of_file(const std::string& path) {
  const AssemblyResult read = read_step(path);
  EXPECT_TRUE(read.status.ok()) << read.status.describe();
  return contacts_of(read.assembly);
}
}  // namespace

TEST(SharedFiles, As1BsplineCylindersStillMakeJoints) {
  const std::string path = shared_step("R01_as1-oc-214.stp");
  CONTACTS_REQUIRE_FILE(path);
  auto counts = count_types(contacts_of_file(path));
  EXPECT_EQ(counts["PLF"], 16);
  EXPECT_EQ(counts["CLJ"], 22);
}

TEST(SharedFiles, DiskArmPinInSlotIsNotAContact) {
  const std::string path = shared_step("D03_asm4_tuto2_disk_arm.step");
  CONTACTS_REQUIRE_FILE(path);
  const auto result = contacts_of_file(path);
  auto counts = count_types(result);
  EXPECT_EQ(counts["PLF"], 3);
  EXPECT_EQ(counts["CLJ"], 1);
  EXPECT_EQ(result.contacts.size(), 4u);
}

TEST(SharedFiles, PressIsExactlyEightPlanarFitsAndSevenCylindricalJoints) {
  const std::string path = shared_step("R08_presse_asm.step");
  CONTACTS_REQUIRE_FILE(path);
  const auto result = contacts_of_file(path);
  auto counts = count_types(result);
  EXPECT_EQ(counts["PLF"], 8);
  EXPECT_EQ(counts["CLJ"], 7);
  EXPECT_EQ(result.contacts.size(), 15u);
}

// Every ball sits in both raceways: two SPT per ball, nothing else (R06's
// ring faces have their u range shifted by a turn: u in [pi, 3 pi]).
TEST(SharedFiles, EveryBearingBallTouchesBothRaceways) {
  for (const auto& [name, balls] : {std::pair<const char*, int>{"R05_SKF_6004.stp", 9},
                                    std::pair<const char*, int>{"R06_bearing_20x37x9_freecad.stp", 14}}) {
    const std::string path = shared_step(name);
    CONTACTS_REQUIRE_FILE(path);
    const auto result = contacts_of_file(path);
    std::map<int, int> per_ball;
    for (const Contact& c : result.contacts) {
      EXPECT_EQ(c.type, ContactType::SPT) << name;
      const int ball = result.partitions[c.body_a].partitions.size() == 1 ? c.body_a : c.body_b;
      ++per_ball[ball];
    }
    EXPECT_EQ(result.contacts.size(), static_cast<size_t>(2 * balls)) << name;
    EXPECT_EQ(per_ball.size(), static_cast<size_t>(balls)) << name;
    for (const auto& [ball, n] : per_ball) EXPECT_EQ(n, 2) << name << " ball body " << ball;
  }
}

TEST(SharedFiles, ChronoPinJoint) {
  const std::string path = shared_step("R09_chrono_assembly.stp");
  CONTACTS_REQUIRE_FILE(path);
  const auto result = contacts_of_file(path);
  auto counts = count_types(result);
  EXPECT_EQ(counts["CLJ"], 1);
  EXPECT_EQ(counts["PLF"], 1);
  EXPECT_EQ(result.contacts.size(), 2u);
}

TEST(SharedFiles, WrenchAndNutWithClearanceHaveNoContact) {
  const std::string path = shared_step("R10_wrenchnut.stp");
  CONTACTS_REQUIRE_FILE(path);
  EXPECT_TRUE(contacts_of_file(path).contacts.empty());
}

TEST(SharedFiles, BearingBallsNeverTouchEachOther) {
  for (const char* name : {"R05_SKF_6004.stp", "R06_bearing_20x37x9_freecad.stp"}) {
    const std::string path = shared_step(name);
    CONTACTS_REQUIRE_FILE(path);
    const AssemblyResult read = read_step(path);
    ASSERT_TRUE(read.status.ok());
    const auto result = contacts_of(read.assembly);
    // A ball: a body whose only partition is a convex sphere.
    const auto is_ball = [&result](int body) {
      const auto& parts = result.partitions[body].partitions;
      return parts.size() == 1 && parts[0].params.kind == SurfaceKind::Sphere;
    };
    int balls = 0;
    for (size_t i = 0; i < read.assembly.bodies.size(); ++i) balls += is_ball(static_cast<int>(i));
    EXPECT_GT(balls, 0) << name;
    for (const Contact& c : result.contacts) {
      EXPECT_FALSE(is_ball(c.body_a) && is_ball(c.body_b))
          << name << ": " << read.assembly.bodies[c.body_a].name << " - " << read.assembly.bodies[c.body_b].name;
    }
  }
}
