#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include <BRepAlgoAPI_Cut.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <gp_Ax2.hxx>

#include "contactcore/simulation/disassembly.h"
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
  ASSERT_TRUE(result.complete) << result.reason;
  // The whole sequence, as a mechanic would take it (issue 22): the four screws first (fasteners:
  // the smallest parts holding the most), each up its axis; the front cover right after them
  // (freed by the last screw); then, from the same side, what the cover freed: the stator (no
  // annotation says it is glued), the seal, the front bearing, the rotor-front, the magnets, the
  // rotor-back, the back bearing and the shaft (nothing says the rotor is pressed on it); the back
  // cover down; the body, the largest part, stays.
  const std::vector<std::pair<std::string, Direction>> expected{
      {"Screw-1", {0, 0, 1}},      {"Screw-3", {0, 0, 1}},      {"Screw-2", {0, 0, 1}},
      {"Screw-4", {0, 0, 1}},      {"Front-cover", {0, 0, 1}},  {"Stator", {0, 0, 1}},
      {"Seal", {0, 0, 1}},         {"Bearing-front", {0, 0, 1}}, {"Rotor-front", {0, 0, 1}},
      {"Magnet-1", {0, 0, 1}},     {"Magnet-2", {0, 0, 1}},     {"Magnet-3", {0, 0, 1}},
      {"Magnet-4", {0, 0, 1}},     {"Rotor-back", {0, 0, 1}},   {"Bearing-back", {0, 0, 1}},
      {"Axis", {0, 0, 1}},         {"Back-cover", {0, 0, -1}}};
  ASSERT_EQ(result.steps.size(), expected.size());
  for (std::size_t k = 0; k < expected.size(); ++k) {
    ASSERT_EQ(result.steps[k].parts.size(), 1u) << "step " << k + 1;
    EXPECT_EQ(motor.assembly.bodies[result.steps[k].parts[0]].name, expected[k].first) << "step " << k + 1;
    EXPECT_EQ(result.steps[k].direction, expected[k].second) << "step " << k + 1;
  }
  EXPECT_EQ(motor.assembly.bodies[result.base].name, "Body");
  for (int k = 0; k < 4; ++k) {
    const DisassemblyStep& step = result.steps[k];
    const int screw = step.parts[0];
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
  // Every step is free: nothing still in place blocks the moved part along its direction.
  std::vector<char> gone(motor.assembly.bodies.size(), 0);
  for (const DisassemblyStep& step : result.steps) {
    const int d = direction_index(result, step.direction);
    for (int part : step.parts)
      for (int blocker : result.blocking[d][part]) EXPECT_TRUE(gone[blocker]) << part << " blocked by " << blocker;
    for (int part : step.parts) gone[part] = 1;
  }
}

// A 10 x 10 x 10 grid of touching 10 mm cubes: hand-derived blocking (a cube moving along an axis
// meets exactly the cubes ahead of it on its line; the cubes beside it only slide along its faces),
// and every step removes a cube with none left ahead of it.
TEST(Disassembly, ThousandCubeGridComesApartCubeByCube) {
  const int side = 10;
  std::vector<std::pair<std::string, TopoDS_Shape>> shapes;
  auto index = [&](int x, int y, int z) { return (x * side + y) * side + z; };
  for (int x = 0; x < side; ++x)
    for (int y = 0; y < side; ++y)
      for (int z = 0; z < side; ++z)
        shapes.push_back({"Cube_" + std::to_string(x) + "_" + std::to_string(y) + "_" + std::to_string(z),
                          BRepPrimAPI_MakeBox(gp_Pnt(10 * x, 10 * y, 10 * z), 10, 10, 10).Shape()});
  const DisassemblyResult result = disassemble(make_assembly(shapes), ContactOptions{}, MeshOptions{}, DisassemblyOptions{});
  ASSERT_TRUE(result.status.ok()) << result.status.describe();
  ASSERT_TRUE(result.complete) << result.reason;
  ASSERT_EQ(result.directions.size(), 6u);  // the contacts' normals are the axes
  for (std::size_t d = 0; d < 6; ++d) {
    const Direction& dir = result.directions[d];
    const int axis = dir[0] != 0 ? 0 : dir[1] != 0 ? 1 : 2;
    const int sign = dir[axis] > 0 ? 1 : -1;
    for (int x = 0; x < side; ++x)
      for (int y = 0; y < side; ++y)
        for (int z = 0; z < side; ++z) {
          std::vector<int> ahead;
          int c[3] = {x, y, z};
          for (int t = 0; t < side; ++t) {
            if ((t - c[axis]) * sign <= 0) continue;
            int o[3] = {x, y, z};
            o[axis] = t;
            ahead.push_back(index(o[0], o[1], o[2]));
          }
          std::sort(ahead.begin(), ahead.end());
          ASSERT_EQ(result.blocking[d][index(x, y, z)], ahead) << "cube " << x << y << z << " direction " << d;
        }
  }
  ASSERT_EQ(result.steps.size(), 999u);
  std::vector<char> gone(1000, 0);
  for (const DisassemblyStep& step : result.steps) {
    ASSERT_EQ(step.parts.size(), 1u);
    const int d = direction_index(result, step.direction);
    for (int blocker : result.blocking[d][step.parts[0]]) ASSERT_TRUE(gone[blocker]);
    gone[step.parts[0]] = 1;
  }
  EXPECT_FALSE(gone[result.base]);
}
