#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include <BRepAlgoAPI_Cut.hxx>
#include <BRepClass3d_SolidClassifier.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakePolygon.hxx>
#include <BRepPrimAPI_MakePrism.hxx>
#include <BRepBndLib.hxx>
#include <Bnd_Box.hxx>
#include <TopExp.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <gp_Ax2.hxx>

#include "contactcore/bodies/bodies.h"
#include "contactcore/simulation/simplify.h"
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
    // All four small holes go, also the two at x = +-14 whose walls are split in half faces
    // across two layers (unified before the defeaturing).
    if (std::abs(p.params.radius - 1.2) < 1e-6) {
      ++small_holes;
      EXPECT_EQ(present.count(p.id), 0u) << "small hole partition " << p.id;
    } else if (std::abs(p.params.radius - 1.5) < 1e-6) {
      ++screw_holes;
      EXPECT_EQ(present.count(p.id), 1u) << "screw hole partition " << p.id;
    }
  }
  EXPECT_EQ(small_holes, 4);
  EXPECT_EQ(screw_holes, 4);
  // The removed faces are exactly the small holes' walls (4 x 2 + 2 x 2 half faces... as stored: 12).
  std::vector<int> small_hole_faces;
  for (const Partition& p : partitions.partitions)
    if (p.params.kind == SurfaceKind::Cylinder && std::abs(p.params.radius - 1.2) < 1e-6)
      small_hole_faces.insert(small_hole_faces.end(), p.faces.begin(), p.faces.end());
  std::sort(small_hole_faces.begin(), small_hole_faces.end());
  EXPECT_EQ(model.removed_faces, small_hole_faces);
  EXPECT_EQ(small_hole_faces.size(), 12u);
  EXPECT_TRUE(model.quality.watertight);
  // The holes go through the 8 mm cover: the filled walls are at most 4 mm from its faces.
  EXPECT_NEAR(model.hausdorff, 4.0, 1e-6);
}

TEST(Simplify, ASmallChamferIsRemovedAndItsHausdorffIsItsDepth) {
  // A 20 x 20 x 10 box, its top edge along x at y = 20 chamfered by c = 1 mm (45 degrees).
  const double c = 1.0;
  // Cut by a triangular prism along x whose hypotenuse runs from (y, z) = (20 - c, 10) to (20, 10 - c).
  const TopoDS_Shape box = BRepPrimAPI_MakeBox(20, 20, 10).Shape();
  const TopoDS_Wire triangle =
      BRepBuilderAPI_MakePolygon(gp_Pnt(-1, 20 - c, 10), gp_Pnt(-1, 20, 10 - c), gp_Pnt(-1, 21, 11), true).Wire();
  const TopoDS_Shape prism = BRepPrimAPI_MakePrism(BRepBuilderAPI_MakeFace(triangle).Face(), gp_Vec(22, 0, 0)).Shape();
  const TopoDS_Shape part = BRepAlgoAPI_Cut(box, prism).Shape();
  const BodyPartitions partitions = partition_shape(part, Tolerances{});
  ASSERT_EQ(partitions.faces.size(), 7u);
  // Detected: the chamfer strip (width c sqrt 2) and nothing else.
  const std::vector<int> features = small_features(part, partitions, 2.0);
  ASSERT_EQ(features.size(), 1u);
  const FaceInfo& strip = partitions.faces[features[0] - 1];
  EXPECT_EQ(strip.params.kind, SurfaceKind::Plane);
  EXPECT_NEAR(strip.area, 20 * c * std::sqrt(2.0), 1e-9);
  // Not below its width.
  EXPECT_TRUE(small_features(part, partitions, 1.0).empty());
  SimplifyOptions options;
  options.feature_size = 2.0;
  options.envelope = 1.0;
  const SimplifiedModel model = simplify_body(part, partitions, options);
  ASSERT_TRUE(model.status.ok()) << model.status.describe();
  EXPECT_EQ(model.removed_faces, features);
  TopTools_IndexedMapOfShape left;
  TopExp::MapShapes(model.shape, TopAbs_FACE, left);
  EXPECT_EQ(left.Extent(), 6);  // the box again
  EXPECT_TRUE(model.quality.watertight);
  // Hand-derived: the restored sharp edge lies c / sqrt 2 from the chamfer plane (its foot mid-strip);
  // the chamfer's points are at most c / 2 from the box's faces. Hausdorff: c / sqrt 2.
  EXPECT_NEAR(model.hausdorff, c / std::sqrt(2.0), 1e-6);
  // Envelope below it: refused.
  options.envelope = 0.7;
  EXPECT_FALSE(simplify_body(part, partitions, options).status.ok());
}
