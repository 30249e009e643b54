#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <set>

#include <BRepAlgoAPI_Cut.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCone.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <BRepPrimAPI_MakeTorus.hxx>
#include <TopExp.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <gp_Ax2.hxx>

#include "contactcore/bodies/bodies.h"
#include "contactcore/simulation/meshes.h"
#include "test_helpers.h"

using namespace contactcore;
using contactcore::testing::sample;
using contactcore::testing::shared_step;

namespace {

MeshResult mesh_of(const TopoDS_Shape& shape, const MeshOptions& options) {
  const BodyPartitions partitions = partition_shape(shape, Tolerances{});
  EXPECT_TRUE(partitions.status.ok()) << partitions.status.describe();
  return mesh_body(shape, partitions, options);
}

// Every body of an assembly: watertight, every triangle tagged with a face of
// the body and that face's partition, every face present.
void expect_tagged_and_watertight(const Assembly& assembly, const MeshOptions& options, const std::string& what) {
  for (const Body& body : assembly.bodies) {
    const BodyPartitions partitions = partition_shape(body.shape, Tolerances{});
    ASSERT_TRUE(partitions.status.ok()) << what << " " << body.name;
    const MeshResult result = mesh_body(body.shape, partitions, options);
    ASSERT_TRUE(result.status.ok()) << what << " " << body.name << ": " << result.status.describe();
    EXPECT_TRUE(result.quality.watertight) << what << " " << body.name << ": boundary "
                                           << result.quality.boundary_edges << ", non-manifold "
                                           << result.quality.nonmanifold_edges;
    std::vector<int> face_partition(partitions.faces.size() + 1, -1);
    for (const Partition& p : partitions.partitions)
      for (int f : p.faces) face_partition[f] = p.id;
    std::set<int> faces_seen;
    const TaggedMesh& mesh = result.mesh;
    ASSERT_EQ(mesh.triangle_face.size(), mesh.triangles.size());
    ASSERT_EQ(mesh.triangle_partition.size(), mesh.triangles.size());
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
      const int face = mesh.triangle_face[i];
      ASSERT_GE(face, 1);
      ASSERT_LE(face, static_cast<int>(partitions.faces.size()));
      ASSERT_EQ(mesh.triangle_partition[i], face_partition[face]) << what << " " << body.name;
      faces_seen.insert(face);
    }
    EXPECT_EQ(faces_seen.size(), partitions.faces.size()) << what << " " << body.name << ": faces without triangles";
    if (options.max_edge_length > 0)
      EXPECT_LE(result.quality.max_edge_length, options.max_edge_length * (1 + 1e-9)) << what << " " << body.name;
  }
}

// Signed volume of a closed mesh (divergence theorem): checks orientation too.
double mesh_volume(const TaggedMesh& mesh) {
  double volume = 0;
  for (const auto& t : mesh.triangles) {
    const auto &a = mesh.vertices[t[0]], &b = mesh.vertices[t[1]], &c = mesh.vertices[t[2]];
    volume += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
               a[2] * (b[0] * c[1] - b[1] * c[0])) / 6.0;
  }
  return volume;
}

}  // namespace

TEST(Meshes, BoxIsTwelveTrianglesTaggedBySide) {
  const TopoDS_Shape box = BRepPrimAPI_MakeBox(10, 20, 30).Shape();
  const MeshResult result = mesh_of(box, MeshOptions{});
  ASSERT_TRUE(result.status.ok()) << result.status.describe();
  EXPECT_EQ(result.mesh.triangles.size(), 12u);
  EXPECT_EQ(result.mesh.vertices.size(), 8u);  // corners shared by three faces each
  EXPECT_TRUE(result.quality.watertight);
  EXPECT_NEAR(mesh_volume(result.mesh), 6000.0, 1e-9);
  EXPECT_EQ(result.mesh.partition_count, 6);
}

TEST(Meshes, MaxEdgeLengthRefinesConformingly) {
  const TopoDS_Shape box = BRepPrimAPI_MakeBox(10, 20, 30).Shape();
  MeshOptions options;
  options.max_edge_length = 2.0;
  const MeshResult result = mesh_of(box, options);
  ASSERT_TRUE(result.status.ok());
  EXPECT_TRUE(result.quality.watertight);
  EXPECT_LE(result.quality.max_edge_length, 2.0);
  EXPECT_NEAR(mesh_volume(result.mesh), 6000.0, 1e-6);  // planes: refinement adds no volume
  // Surface area is kept too: every triangle still lies on its face.
  EXPECT_GT(result.quality.min_angle_deg, 10.0);
}

TEST(Meshes, CurvedSolidsAreClosedAndCloseToTheirVolume) {
  const TopoDS_Shape shapes[] = {
      BRepPrimAPI_MakeCylinder(5, 12).Shape(),
      BRepPrimAPI_MakeSphere(7).Shape(),
      BRepPrimAPI_MakeCone(4, 0, 9).Shape(),
      BRepPrimAPI_MakeTorus(10, 3).Shape(),
      BRepAlgoAPI_Cut(BRepPrimAPI_MakeBox(gp_Pnt(-20, -20, 0), 40, 40, 20).Shape(),
                      BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, -10), gp::DZ()), 5, 40).Shape())
          .Shape()};
  const double volumes[] = {M_PI * 25 * 12, 4.0 / 3 * M_PI * 343, M_PI * 16 * 9 / 3, 2 * M_PI * M_PI * 10 * 9,
                            40 * 40 * 20 - M_PI * 25 * 20};
  for (double max_edge : {0.0, 1.5}) {
    MeshOptions options;
    options.deflection = 0.01;
    options.max_edge_length = max_edge;
    for (int i = 0; i < 5; ++i) {
      const MeshResult result = mesh_of(shapes[i], options);
      ASSERT_TRUE(result.status.ok()) << i << ": " << result.status.describe();
      EXPECT_TRUE(result.quality.watertight) << "shape " << i << " max edge " << max_edge;
      EXPECT_NEAR(mesh_volume(result.mesh), volumes[i], volumes[i] * 0.01) << "shape " << i;
      if (max_edge > 0) EXPECT_LE(result.quality.max_edge_length, max_edge);
    }
  }
}

TEST(Meshes, AspectRatioOfAnEquilateralTriangleIsOne) {
  TaggedMesh mesh;
  mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {0.5, std::sqrt(3.0) / 2, 0}};
  mesh.triangles = {{0, 1, 2}};
  mesh.triangle_face = {1};
  mesh.triangle_partition = {0};
  const MeshQuality quality = mesh_quality(mesh);
  EXPECT_NEAR(quality.aspect_max, 1.0, 1e-12);
  EXPECT_NEAR(quality.min_angle_deg, 60.0, 1e-9);
  EXPECT_FALSE(quality.watertight);
  EXPECT_EQ(quality.boundary_edges, 3u);
}

TEST(Meshes, BadOptionsAndEmptyShapeAreErrors) {
  EXPECT_FALSE(mesh_body(TopoDS_Shape(), BodyPartitions{}, MeshOptions{}).status.ok());
  const TopoDS_Shape box = BRepPrimAPI_MakeBox(1, 1, 1).Shape();
  MeshOptions bad;
  bad.deflection = 0;
  EXPECT_FALSE(mesh_of(box, bad).status.ok());
  // Partitions of another shape: the face without partition is named.
  const BodyPartitions other = partition_shape(BRepPrimAPI_MakeSphere(1).Shape(), Tolerances{});
  const MeshResult result = mesh_body(box, other, MeshOptions{});
  EXPECT_FALSE(result.status.ok());
  EXPECT_EQ(result.status.face, 2);
}

TEST(Meshes, PlyFileHoldsSharedVerticesAndTags) {
  const MeshResult result = mesh_of(BRepPrimAPI_MakeBox(1, 2, 3).Shape(), MeshOptions{});
  const std::string path = contactcore::testing::temp_file("contacts_test_box.ply");
  ASSERT_TRUE(write_ply(result.mesh, path).ok());
  std::ifstream in(path);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("element vertex 8\n"), std::string::npos);
  EXPECT_NE(text.find("element face 12\n"), std::string::npos);
  EXPECT_NE(text.find("property int partition\nend_header\n"), std::string::npos);
  std::filesystem::remove(path);
  EXPECT_FALSE(write_ply(result.mesh, "/nonexistent-dir/x.ply").ok());
}

TEST(Meshes, MotorIsWatertightAndFullyTagged) {
  const AssemblyResult motor = read_step(sample("motor.step"));
  ASSERT_TRUE(motor.status.ok());
  MeshOptions options;
  expect_tagged_and_watertight(motor.assembly, options, "motor");
  options.deflection = 0.05;
  options.max_edge_length = 3;
  expect_tagged_and_watertight(motor.assembly, options, "motor refined");
}

TEST(Meshes, GeneratedCasesAreWatertightAndFullyTagged) {
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(sample("cases"))) {
    if (entry.path().extension() != ".step") continue;
    const AssemblyResult read = read_step(entry.path().string());
    ASSERT_TRUE(read.status.ok()) << entry.path();
    MeshOptions options;
    options.max_edge_length = 5;
    expect_tagged_and_watertight(read.assembly, options, entry.path().filename().string());
    ++files;
  }
  EXPECT_EQ(files, 14);  // every .step of Resources/samples/cases
}

TEST(Meshes, SharedStepFilesAreWatertightAndFullyTagged) {
  const std::string folder = std::string(CONTACTS_SHARED_DATA) + "/step";
  if (!std::filesystem::exists(folder)) GTEST_SKIP() << "data folder absent: " << folder;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    const AssemblyResult read = read_step(entry.path().string());
    ASSERT_TRUE(read.status.ok()) << entry.path();
    expect_tagged_and_watertight(read.assembly, MeshOptions{}, entry.path().filename().string());
  }
}
