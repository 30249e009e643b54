#include <gtest/gtest.h>

#include <set>

#include <BRepAlgoAPI_Cut.hxx>
#include <BRepClass3d_SolidClassifier.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <gp_Ax2.hxx>

#include "contactcore/bodies.h"
#include "contactcore/simplify.h"
#include "test_helpers.h"

using namespace contactcore;
using contactcore::testing::sample;

TEST(Simplify, ASmallHoleIsFilledAndTheLargeOneStays) {
  // A 40 x 40 x 4 plate with a 2 mm hole at (-10, 0) and a 6 mm hole at (10, 0).
  TopoDS_Shape plate = BRepPrimAPI_MakeBox(gp_Pnt(-20, -20, 0), 40, 40, 4).Shape();
  plate = BRepAlgoAPI_Cut(plate, BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(-10, 0, -1), gp::DZ()), 1, 6).Shape()).Shape();
  plate = BRepAlgoAPI_Cut(plate, BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(10, 0, -1), gp::DZ()), 3, 6).Shape()).Shape();
  const BodyPartitions partitions = partition_shape(plate, Tolerances{});
  SimplifyOptions options;
  options.feature_size = 4;
  options.envelope = 3;
  const SimplifiedModel model = simplify_body(plate, partitions, options);
  ASSERT_TRUE(model.status.ok()) << model.status.describe();
  ASSERT_EQ(model.removed_faces.size(), 1u);
  EXPECT_EQ(partitions.faces[model.removed_faces[0] - 1].params.radius, 1.0);
  EXPECT_TRUE(model.quality.watertight);
  // The small hole's axis is inside the material now; the large one's is not.
  BRepClass3d_SolidClassifier small(model.shape, gp_Pnt(-10, 0, 2), 1e-7), large(model.shape, gp_Pnt(10, 0, 2), 1e-7);
  EXPECT_EQ(small.State(), TopAbs_IN);
  EXPECT_EQ(large.State(), TopAbs_OUT);
  // Hausdorff: the filled hole's wall lies inside the material now; its farthest point from the plate's
  // surface is at mid-depth, 2 mm from the top and bottom faces (the wall's vertical edges have their
  // midpoints there).
  EXPECT_NEAR(model.hausdorff, 2.0, 1e-6);
  // Partitions carried: the large hole's partition is still there, the small one's gone.
  std::set<int> present(model.mesh.triangle_partition.begin(), model.mesh.triangle_partition.end());
  int small_partition = -1, large_partition = -1;
  for (const Partition& p : partitions.partitions)
    if (p.params.kind == SurfaceKind::Cylinder) (p.params.radius < 2 ? small_partition : large_partition) = p.id;
  EXPECT_EQ(present.count(small_partition), 0u);
  EXPECT_EQ(present.count(large_partition), 1u);
  // A tighter envelope refuses the model.
  options.envelope = 0.5;
  EXPECT_FALSE(simplify_body(plate, partitions, options).status.ok());
}

TEST(Simplify, MotorFrontCoverLosesItsSmallThroughHolesAndKeepsTheScrewHoles) {
  const AssemblyResult motor = read_step(sample("motor.step"));
  ASSERT_TRUE(motor.status.ok());
  const Body* cover = nullptr;
  for (const Body& body : motor.assembly.bodies)
    if (body.name == "Front-cover") cover = &body;
  ASSERT_NE(cover, nullptr);
  const BodyPartitions partitions = partition_shape(cover->shape, Tolerances{});
  SimplifyOptions options;
  options.feature_size = 2.5;  // between the small holes (2.4 mm) and the screw holes (3 mm)
  options.envelope = 5;
  const SimplifiedModel model = simplify_body(cover->shape, partitions, options);
  ASSERT_TRUE(model.status.ok()) << model.status.describe();
  EXPECT_EQ(model.features_kept, 0);
  std::set<int> present(model.mesh.triangle_partition.begin(), model.mesh.triangle_partition.end());
  int small_holes = 0, screw_holes = 0;
  for (const Partition& p : partitions.partitions) {
    if (p.params.kind != SurfaceKind::Cylinder || p.side != MaterialSide::Concave) continue;
    // The two small holes on x = +-14 are split in half faces across two walls; OCCT's defeaturing
    // refills them on the same cylinder (a known gap, see docs/meshes.md): only the whole-face ones
    // are checked here.
    if (std::abs(p.params.radius - 1.2) < 1e-6 && p.faces.size() == 2) {
      ++small_holes;
      EXPECT_EQ(present.count(p.id), 0u) << "small hole partition " << p.id;
    } else if (std::abs(p.params.radius - 1.5) < 1e-6) {
      ++screw_holes;
      EXPECT_EQ(present.count(p.id), 1u) << "screw hole partition " << p.id;
    }
  }
  EXPECT_EQ(small_holes, 2);
  EXPECT_EQ(screw_holes, 4);
  EXPECT_TRUE(model.quality.watertight);
  // The holes go through the 8 mm cover: the filled walls are at most 4 mm from its faces.
  EXPECT_NEAR(model.hausdorff, 4.0, 1e-6);
}
