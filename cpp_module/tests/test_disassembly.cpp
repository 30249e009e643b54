#include <gtest/gtest.h>

#include <cmath>

#include <BRepAlgoAPI_Cut.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <gp_Ax2.hxx>

#include "contactcore/disassembly.h"
#include "test_helpers.h"

using namespace contactcore;
using contactcore::testing::contacts_of;
using contactcore::testing::make_assembly;
using contactcore::testing::sample;

namespace {

int direction_index(const DisassemblyResult& r, const Direction& d) {
  for (std::size_t i = 0; i < r.directions.size(); ++i)
    if (r.directions[i] == d) return static_cast<int>(i);
  return -1;
}

}  // namespace

// A base block, a plate on it with a hole, a peg through the hole standing on the base.
TEST(Disassembly, PegPlateBaseComeApartTopDown) {
  const TopoDS_Shape base = BRepPrimAPI_MakeBox(gp_Pnt(-20, -20, -10), 40, 40, 10).Shape();
  const TopoDS_Shape plate =
      BRepAlgoAPI_Cut(BRepPrimAPI_MakeBox(gp_Pnt(-15, -15, 0), 30, 30, 5).Shape(),
                      BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, -1), gp::DZ()), 3, 7).Shape())
          .Shape();
  const TopoDS_Shape peg = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, 0), gp::DZ()), 3, 12).Shape();
  const Assembly assembly = make_assembly({{"base", base}, {"plate", plate}, {"peg", peg}});
  const DisassemblyResult result = disassemble(assembly, ContactOptions{}, MeshOptions{}, DisassemblyOptions{});
  ASSERT_TRUE(result.status.ok()) << result.status.describe();
  ASSERT_TRUE(result.complete) << result.reason;
  ASSERT_EQ(result.steps.size(), 2u);
  EXPECT_EQ(result.steps[0].parts, std::vector<int>{2});  // the peg (smallest) up its axis
  EXPECT_EQ(result.steps[0].direction, (Direction{0, 0, 1}));
  EXPECT_EQ(result.steps[1].parts, std::vector<int>{1});  // then the plate: up, or sideways off the base
  EXPECT_EQ(result.base, 0);
  // Hand-derived blocking: along -z the base blocks both; sideways the plate holds the peg and the peg the plate.
  const int down = direction_index(result, {0, 0, -1}), up = direction_index(result, {0, 0, 1}),
            east = direction_index(result, {1, 0, 0});
  ASSERT_GE(down, 0);
  EXPECT_EQ(result.blocking[down][2], std::vector<int>({0}));
  EXPECT_EQ(result.blocking[down][1], std::vector<int>({0}));  // the plate slides down the peg onto the base
  EXPECT_EQ(result.blocking[up][2], std::vector<int>{});
  EXPECT_EQ(result.blocking[up][1], std::vector<int>{});  // and up off the peg's top
  EXPECT_EQ(result.blocking[up][0], std::vector<int>({1, 2}));
  EXPECT_EQ(result.blocking[east][2], std::vector<int>({1}));
  EXPECT_EQ(result.blocking[east][1], std::vector<int>({2}));
  EXPECT_EQ(result.blocking[east][0], std::vector<int>{});  // the base slides out from under both
}

TEST(Disassembly, ACubeShutInABoxHasNoSequence) {
  const TopoDS_Shape box = BRepAlgoAPI_Cut(BRepPrimAPI_MakeBox(gp_Pnt(-10, -10, -10), 20, 20, 20).Shape(),
                                           BRepPrimAPI_MakeBox(gp_Pnt(-5, -5, -5), 10, 10, 10).Shape())
                               .Shape();
  const TopoDS_Shape cube = BRepPrimAPI_MakeBox(gp_Pnt(-2, -2, -2), 4, 4, 4).Shape();
  const DisassemblyResult result = disassemble(make_assembly({{"box", box}, {"cube", cube}}), ContactOptions{},
                                               MeshOptions{}, DisassemblyOptions{});
  ASSERT_TRUE(result.status.ok());
  EXPECT_FALSE(result.complete);
  EXPECT_TRUE(result.steps.empty());
  EXPECT_NE(result.reason.find("box, cube"), std::string::npos) << result.reason;
  for (const auto& per_part : result.blocking) {
    EXPECT_EQ(per_part[0], std::vector<int>{1});
    EXPECT_EQ(per_part[1], std::vector<int>{0});
  }
}

TEST(Disassembly, MotorScrewsComeOutFirstEachAlongItsAxis) {
  const AssemblyResult motor = read_step(sample("motor.step"));
  ASSERT_TRUE(motor.status.ok());
  const ContactsResult contacts = find_contacts(motor.assembly, ContactOptions{});
  const DisassemblyResult result = disassemble(motor.assembly, ContactOptions{}, MeshOptions{}, DisassemblyOptions{});
  ASSERT_TRUE(result.status.ok()) << result.status.describe();
  ASSERT_GE(result.steps.size(), 4u);
  for (int k = 0; k < 4; ++k) {
    const DisassemblyStep& step = result.steps[k];
    ASSERT_EQ(step.parts.size(), 1u);
    const int screw = step.parts[0];
    EXPECT_EQ(motor.assembly.bodies[screw].name.rfind("Screw", 0), 0u) << motor.assembly.bodies[screw].name;
    // Along the axis of its cylindrical joints, head first.
    int joints = 0;
    for (const Contact& c : contacts.contacts) {
      if (c.type != ContactType::CLJ || (c.body_a != screw && c.body_b != screw)) continue;
      ++joints;
      EXPECT_NEAR(std::abs(c.direction.X() * step.direction[0] + c.direction.Y() * step.direction[1] +
                           c.direction.Z() * step.direction[2]),
                  1.0, 1e-9);
    }
    EXPECT_GT(joints, 0);
    // Its head's planar fit faces away: moving the other way is blocked by what it holds.
    const int opposite = direction_index(result, {-step.direction[0], -step.direction[1], -step.direction[2]});
    ASSERT_GE(opposite, 0);
    EXPECT_FALSE(result.blocking[opposite][screw].empty());
  }
  for (int k = 4; k < static_cast<int>(result.steps.size()); ++k)
    for (int part : result.steps[k].parts)
      EXPECT_NE(motor.assembly.bodies[part].name.rfind("Screw", 0), 0u);
}
