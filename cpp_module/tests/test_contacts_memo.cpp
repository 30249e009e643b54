// find_contacts with a memo (contacts_memo.h): a recompute after one body
// moved reuses the unchanged bodies' partitions, the candidate tests of the
// body pairs without the moved body and their point and line contacts, and
// finds what a search without the memo finds, to the last bit.
#include <gtest/gtest.h>

#include <tuple>
#include <vector>

#include <BRepAlgoAPI_Cut.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <gp_Ax2.hxx>
#include <gp_Trsf.hxx>

#include "contactcore/contacts/contacts.h"
#include "contactcore/contacts/contacts_memo.h"
#include "test_helpers.h"

using namespace contactcore;
using contactcore::testing::make_assembly;

namespace {

TopoDS_Shape moved(const TopoDS_Shape& shape, double dx, double dy, double dz) {
  gp_Trsf move;
  move.SetTranslation(gp_Vec(dx, dy, dz));
  return shape.Moved(TopLoc_Location(move));
}

// A block with a bore, its shaft (CLJ), a plate on the block (PLF), a ball on
// the plate (a point contact), and two instances of one pad (one TShape placed
// twice) under the block, each a PLF.
Assembly workshop() {
  const TopoDS_Shape block = BRepAlgoAPI_Cut(BRepPrimAPI_MakeBox(gp_Pnt(-20, -20, 0), 40, 40, 20).Shape(),
                                             BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, -10), gp::DZ()), 5, 40).Shape())
                                 .Shape();
  const TopoDS_Shape shaft = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, -5), gp::DZ()), 5, 30).Shape();
  const TopoDS_Shape plate = BRepPrimAPI_MakeBox(gp_Pnt(8, -15, 20), 10, 30, 3).Shape();
  const TopoDS_Shape ball = BRepPrimAPI_MakeSphere(gp_Pnt(12, 0, 25), 2).Shape();
  const TopoDS_Shape pad = BRepPrimAPI_MakeBox(gp_Pnt(0, 0, -4), 8, 8, 4).Shape();
  return make_assembly({{"block", block}, {"shaft", shaft}, {"plate", plate}, {"ball", ball},
                        {"pad1", moved(pad, -18, -18, 0)}, {"pad2", moved(pad, 8, 8, 0)}});
}

using ContactKey = std::tuple<int, int, int, int, int, std::vector<int>, std::vector<int>, double, double, double, bool,
                              double, double, double, double, double, double>;
std::vector<ContactKey> contacts_exactly(const ContactsResult& result) {
  std::vector<ContactKey> out;
  for (const Contact& c : result.contacts)
    out.emplace_back(static_cast<int>(c.type), c.body_a, c.body_b, c.partition_a, c.partition_b, c.faces_a, c.faces_b,
                     c.area, c.radius, c.span, c.partial, c.point.X(), c.point.Y(), c.point.Z(), c.direction.X(),
                     c.direction.Y(), c.direction.Z());
  return out;
}

using HigherKey = std::tuple<int, int, int, int, double, double, double, double>;
std::vector<HigherKey> higher_exactly(const ContactsResult& result) {
  std::vector<HigherKey> out;
  for (const HigherPair& h : result.higher_pairs)
    out.emplace_back(static_cast<int>(h.type), h.body_a, h.body_b, h.partition_a, h.point.X(), h.point.Y(),
                     h.point.Z(), h.length);
  return out;
}

void expect_same(const ContactsResult& found, const ContactsResult& expected) {
  ASSERT_TRUE(found.status.ok()) << found.status.describe();
  ASSERT_TRUE(expected.status.ok()) << expected.status.describe();
  EXPECT_EQ(contacts_exactly(found), contacts_exactly(expected));
  EXPECT_EQ(higher_exactly(found), higher_exactly(expected));
  EXPECT_EQ(found.body_pairs, expected.body_pairs);
  EXPECT_EQ(found.candidates, expected.candidates);
  EXPECT_EQ(found.instance_of, expected.instance_of);
  EXPECT_EQ(found.messages, expected.messages);
  EXPECT_EQ(found.interferences.size(), expected.interferences.size());
  ASSERT_EQ(found.partitions.size(), expected.partitions.size());
  for (std::size_t i = 0; i < found.partitions.size(); ++i)
    EXPECT_EQ(found.partitions[i].partitions.size(), expected.partitions[i].partitions.size());
}

}  // namespace

TEST(ContactsMemo, MovedBodyAloneSearchedAgainSameResultAsWithout) {
  Assembly assembly = workshop();
  ContactsMemo memo;
  const ContactsResult first = find_contacts(assembly, ContactOptions{}, nullptr, &memo);
  expect_same(first, find_contacts(assembly, ContactOptions{}));
  ASSERT_EQ(first.instance_of, (std::vector<int>{0, 1, 2, 3, 4, 4}));  // pad2 an instance of pad1
  EXPECT_EQ(memo.shapes.size(), 6u);
  EXPECT_EQ(memo.reused_bodies, 0u);
  // CLJ block-shaft, PLF block-plate, PLF block-pad1, PLF block-pad2
  EXPECT_EQ(first.contacts.size(), 4u);
  EXPECT_EQ(first.higher_pairs.size(), 1u);  // the ball on the plate

  // The plate slid 2 mm along y: it alone is searched again.
  assembly.bodies[2].shape = moved(assembly.bodies[2].shape, 0, 2, 0);
  const ContactsResult second = find_contacts(assembly, ContactOptions{}, nullptr, &memo);
  expect_same(second, find_contacts(assembly, ContactOptions{}));
  EXPECT_EQ(memo.reused_bodies, 5u);
  EXPECT_EQ(memo.reused_solid_checks, 4u);  // pad2 shares pad1's verdict
  std::size_t without_plate = 0;
  for (const auto& [a, b] : second.body_pairs) without_plate += a != 2 && b != 2 ? 1 : 0;
  // pad2's pair with the block is pad1's moved (placed alike? no: the block sees
  // them at different places), so every pair without the plate was tested itself
  EXPECT_EQ(memo.reused_tested_pairs, without_plate);
  EXPECT_EQ(memo.reused_higher_pairs, without_plate);
  EXPECT_EQ(without_plate, 3u);  // of the broad phase's body pairs, those without the plate

  // An instance moved (pad2): the instance's partitions moved from pad1's again, the rest reused.
  assembly.bodies[5].shape = moved(assembly.bodies[5].shape, 0, 0, -1);  // off the block
  const ContactsResult third = find_contacts(assembly, ContactOptions{}, nullptr, &memo);
  expect_same(third, find_contacts(assembly, ContactOptions{}));
  EXPECT_EQ(memo.reused_bodies, 5u);
  EXPECT_EQ(third.contacts.size(), 3u);

  // The source of an instance changed (pad1 replaced by another shape): pad2 is
  // now its own source, both searched again.
  assembly.bodies[4].shape = moved(BRepPrimAPI_MakeBox(gp_Pnt(0, 0, -4), 8, 8, 4).Shape(), -18, -18, 0);
  const ContactsResult fourth = find_contacts(assembly, ContactOptions{}, nullptr, &memo);
  expect_same(fourth, find_contacts(assembly, ContactOptions{}));
  EXPECT_EQ(memo.reused_bodies, 4u);

  // Other options: nothing reused.
  ContactOptions coarser;
  coarser.linear = 0.05;
  const ContactsResult fifth = find_contacts(assembly, coarser, nullptr, &memo);
  expect_same(fifth, find_contacts(assembly, coarser));
  EXPECT_EQ(memo.reused_bodies, 0u);
  EXPECT_EQ(memo.reused_tested_pairs, 0u);
  EXPECT_EQ(memo.reused_solid_checks, 0u);

  // The full solid checks: not the quick ones' verdicts.
  ContactOptions full;
  full.linear = 0.05;
  full.solid_checks = SolidChecks::Full;
  const ContactsResult sixth = find_contacts(assembly, full, nullptr, &memo);
  expect_same(sixth, find_contacts(assembly, full));
  EXPECT_EQ(memo.reused_bodies, 6u);
  EXPECT_EQ(memo.reused_solid_checks, 0u);
  const ContactsResult seventh = find_contacts(assembly, full, nullptr, &memo);
  expect_same(seventh, find_contacts(assembly, full));
  EXPECT_EQ(memo.reused_solid_checks, 6u);  // every source (pad2 its own since pad1 was replaced)
}

// A body the solid checks find faulty keeps its verdict and message when reused.
TEST(ContactsMemo, AnInvalidBodysVerdictIsReused) {
  Assembly assembly = workshop();
  // A box whose faces all point inward: inside out (validity.h), found by the quick checks.
  assembly.bodies.push_back({"inside_out", "inside_out", BRepPrimAPI_MakeBox(gp_Pnt(100, 0, 0), 5, 5, 5).Shape().Reversed()});
  ContactsMemo memo;
  const ContactsResult first = find_contacts(assembly, ContactOptions{}, nullptr, &memo);
  ASSERT_EQ(first.invalid_bodies.size(), 1u);
  EXPECT_EQ(first.invalid_bodies[0].body, 6);
  assembly.bodies[2].shape = moved(assembly.bodies[2].shape, 0, 2, 0);
  const ContactsResult second = find_contacts(assembly, ContactOptions{}, nullptr, &memo);
  expect_same(second, find_contacts(assembly, ContactOptions{}));
  EXPECT_EQ(memo.reused_solid_checks, 5u);
  ASSERT_EQ(second.invalid_bodies.size(), 1u);
  EXPECT_EQ(second.invalid_bodies[0].reason, first.invalid_bodies[0].reason);
}

TEST(ContactsMemo, AFailedRunLeavesItEmpty) {
  Assembly assembly = workshop();
  ContactsMemo memo;
  ASSERT_TRUE(find_contacts(assembly, ContactOptions{}, nullptr, &memo).status.ok());
  ContactOptions refused;
  refused.linear = -1.0;  // not a tolerance
  EXPECT_FALSE(find_contacts(assembly, refused, nullptr, &memo).status.ok());
  EXPECT_TRUE(memo.shapes.empty());
  const ContactsResult again = find_contacts(assembly, ContactOptions{}, nullptr, &memo);
  expect_same(again, find_contacts(assembly, ContactOptions{}));
  EXPECT_EQ(memo.reused_bodies, 0u);
}
