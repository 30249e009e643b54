// Validity of solids: a self-intersecting solid is named with its faces, a
// valid one is not.
#include <gtest/gtest.h>

#include <BRepBndLib.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakePolygon.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakePrism.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <gp_Vec.hxx>

#include "contactcore/contacts.h"
#include "contactcore/validity.h"
#include "test_helpers.h"

using namespace contactcore;
using namespace contactcore::testing;

namespace {

// A bowtie (two triangles meeting at a crossing of its own edges) pushed up
// by 5 mm: a solid whose top and bottom faces are bounded by crossing wires.
TopoDS_Shape bowtie_prism(double x) {
  BRepBuilderAPI_MakePolygon polygon(gp_Pnt(x, 0, 0), gp_Pnt(x + 10, 10, 0), gp_Pnt(x + 10, 0, 0),
                                     gp_Pnt(x, 10, 0), Standard_True);
  const TopoDS_Face face = BRepBuilderAPI_MakeFace(polygon.Wire(), Standard_True).Face();
  return BRepPrimAPI_MakePrism(face, gp_Vec(0, 0, 5)).Shape();
}

// FaceN (1-based, explorer order) of the faces lying in the plane z = height.
std::vector<int> faces_at_height(const TopoDS_Shape& shape, double height) {
  std::vector<int> found;
  int index = 0;
  for (TopExp_Explorer f(shape, TopAbs_FACE); f.More(); f.Next()) {
    ++index;
    Bnd_Box box;
    BRepBndLib::Add(f.Current(), box);
    double x0, y0, z0, x1, y1, z1;
    box.Get(x0, y0, z0, x1, y1, z1);
    if (std::abs(z0 - height) < 1e-6 && std::abs(z1 - height) < 1e-6) found.push_back(index);
  }
  return found;
}

}  // namespace

TEST(Validity, SelfIntersectingSolidIsNamedWithItsFaces) {
  const TopoDS_Shape bowtie = bowtie_prism(0);
  const ContactsResult result =
      contacts_of(make_assembly({{"block", BRepPrimAPI_MakeBox(gp_Pnt(0, 20, 0), 10, 10, 5).Shape()}, {"bowtie", bowtie}}));
  ASSERT_EQ(result.invalid_bodies.size(), 1u);
  EXPECT_EQ(result.invalid_bodies[0].body, 1);
  std::vector<int> expected = faces_at_height(bowtie, 0);
  const std::vector<int> top = faces_at_height(bowtie, 5);
  expected.insert(expected.end(), top.begin(), top.end());
  std::sort(expected.begin(), expected.end());
  ASSERT_EQ(expected.size(), 2u);
  EXPECT_EQ(result.invalid_bodies[0].faces, expected);
  EXPECT_EQ(result.invalid_bodies[0].reason, "self-intersecting boundary");
  bool named = false;
  for (const std::string& m : result.messages)
    named |= m.find("'bowtie' is not a valid solid") != std::string::npos &&
             m.find("Face" + std::to_string(expected[0])) != std::string::npos;
  EXPECT_TRUE(named);
}

TEST(Validity, ValidSolidsAreNotNamed) {
  const ContactsResult result = contacts_of(make_assembly({{"a", BRepPrimAPI_MakeBox(10, 10, 10).Shape()},
                                                           {"b", BRepPrimAPI_MakeBox(gp_Pnt(0, 0, 10), 10, 10, 5).Shape()}}));
  EXPECT_TRUE(result.invalid_bodies.empty());
}

TEST(Validity, InstancesShareTheirSourcesVerdict) {
  // One bowtie shape placed twice: both bodies named, the shape checked once.
  const TopoDS_Shape bowtie = bowtie_prism(0);
  gp_Trsf shift;
  shift.SetTranslation(gp_Vec(40, 0, 0));
  const ContactsResult result = contacts_of(make_assembly({{"first", bowtie}, {"second", bowtie.Moved(TopLoc_Location(shift))}}));
  ASSERT_EQ(result.invalid_bodies.size(), 2u);
  EXPECT_EQ(result.invalid_bodies[0].body, 0);
  EXPECT_EQ(result.invalid_bodies[1].body, 1);
  EXPECT_EQ(result.invalid_bodies[0].faces, result.invalid_bodies[1].faces);
}

TEST(Validity, MotorSolidsAreValidSerialAndParallel) {
  const AssemblyResult read = read_step(sample("motor.step"));
  ASSERT_TRUE(read.status.ok()) << read.status.describe();
  for (int threads : {1, 2}) {
    ContactOptions options;
    options.threads = threads;
    const ContactsResult result = find_contacts(read.assembly, options);
    ASSERT_TRUE(result.status.ok());
    EXPECT_TRUE(result.invalid_bodies.empty());
  }
}
