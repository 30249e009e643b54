// Tests of the index-free gp_XYZ component helpers (common/xyz_components.h)
// and of the plane typing that OCCT's gp_XYZ::SetCoord broke under clang 14
// (undefined behaviour: docs/architecture.md "Compilers"). Run on a clang
// build, the last two failed before the fix: the motor's Axis Face18 and 72
// other planes were typed Other with "gp_Dir() - input vector has zero norm".
#include "common/xyz_components.h"
#include "contactcore/bodies/bodies.h"
#include "contactcore/partitions/partitions.h"
#include "partitions/outlines.h"
#include "test_helpers.h"

#include <gtest/gtest.h>

#include <string>

#include <BRepBndLib.hxx>
#include <BRepGProp.hxx>
#include <BRep_Tool.hxx>
#include <GProp_GProps.hxx>
#include <gp_Dir.hxx>

namespace contactcore {
namespace {

TEST(XyzComponents, UnitAndComponentByIndex) {
  // The index is a run-time value, as in the callers (a constant would let the
  // compiler fold the undefined indexing into the right member).
  for (volatile int index = 0; index < 3; index = index + 1) {
    const gp_XYZ unit = detail::xyz_unit(index);
    EXPECT_EQ(unit.X(), index == 0 ? 1.0 : 0.0) << index;
    EXPECT_EQ(unit.Y(), index == 1 ? 1.0 : 0.0) << index;
    EXPECT_EQ(unit.Z(), index == 2 ? 1.0 : 0.0) << index;
    EXPECT_EQ(detail::xyz_component(gp_XYZ(4, 5, 6), index), 4.0 + index);
  }
}

// The reference is the unit axis the normal is least along, made
// perpendicular: hand-derived for the axis normals (ties: the first axis).
TEST(XyzComponents, CanonicalPlaneRefOfAxisNormals) {
  struct Case {
    gp_Dir normal;
    gp_XYZ ref;
  };
  const Case cases[] = {
      {gp_Dir(1, 0, 0), gp_XYZ(0, 1, 0)},  {gp_Dir(-1, 0, 0), gp_XYZ(0, 1, 0)},
      {gp_Dir(0, 1, 0), gp_XYZ(1, 0, 0)},  {gp_Dir(0, -1, 0), gp_XYZ(1, 0, 0)},
      {gp_Dir(0, 0, 1), gp_XYZ(1, 0, 0)},  {gp_Dir(0, 0, -1), gp_XYZ(1, 0, 0)},
      // The motor's Rotor-back Face1: tiny X and Y, the least along Y.
      {gp_Dir(-7.783e-33, 3.632e-33, -1), gp_XYZ(0, 1, 0)},
  };
  for (const Case& c : cases) {
    const gp_Dir ref = detail::canonical_plane_ref(c.normal);
    EXPECT_NEAR(ref.X(), c.ref.X(), 1e-15) << c.normal.X() << " " << c.normal.Y() << " " << c.normal.Z();
    EXPECT_NEAR(ref.Y(), c.ref.Y(), 1e-15) << c.normal.X() << " " << c.normal.Y() << " " << c.normal.Z();
    EXPECT_NEAR(ref.Z(), c.ref.Z(), 1e-15) << c.normal.X() << " " << c.normal.Y() << " " << c.normal.Z();
  }
}

// Every face of the bundled motor is evaluated (375 faces in 18 bodies), and
// the Axis' Face18 is the plane x = 3.3 facing +X with OCCT's area.
TEST(XyzComponents, MotorFacesAllEvaluated) {
  const AssemblyResult read = read_step(testing::sample("motor.step"));
  ASSERT_TRUE(read.status.ok()) << read.status.describe();
  ASSERT_EQ(read.assembly.bodies.size(), 18u);
  int faces = 0, axis_checked = 0;
  for (const Body& body : read.assembly.bodies) {
    Bnd_Box box;
    BRepBndLib::Add(body.shape, box);
    const BodyPartitions parts = partition_shape(body.shape, default_tolerances(box));
    EXPECT_TRUE(parts.status.ok()) << body.name << ": " << parts.status.describe();
    EXPECT_EQ(parts.status.message, "") << body.name;  // "N face(s) could not be evaluated" otherwise
    faces += static_cast<int>(parts.faces.size());
    if (body.name != "Axis") continue;
    ASSERT_EQ(parts.faces.size(), 24u);
    const FaceInfo& face = parts.faces[17];
    ASSERT_EQ(face.index, 18);
    EXPECT_EQ(face.params.kind, SurfaceKind::Plane);
    EXPECT_NEAR(face.params.axis.X(), 1.0, 1e-12);
    EXPECT_NEAR(face.params.location.X(), 3.3, 1e-9);
    GProp_GProps props;
    BRepGProp::SurfaceProperties(face.face, props);
    EXPECT_NEAR(face.area, props.Mass(), 1e-6 * props.Mass());
    EXPECT_NEAR(face.area, 17.833805, 1e-5);
    EXPECT_FALSE(face.extent.outline.empty());
    ++axis_checked;
  }
  EXPECT_EQ(faces, 375);
  EXPECT_EQ(axis_checked, 1);
}

}  // namespace
}  // namespace contactcore
