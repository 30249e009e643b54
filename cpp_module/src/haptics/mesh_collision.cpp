#include "contactcore/haptics/mesh_collision.h"

#include <BRepMesh_IncrementalMesh.hxx>
#include <BRep_Tool.hxx>
#include <Poly_Triangulation.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Face.hxx>

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/collision_object.h>

namespace contactcore::haptics {

TriangleMesh tessellate(const TopoDS_Shape& shape, const BodyPartitions& partitions, double deflection,
                        double angle) {
  TriangleMesh mesh;
  std::vector<int> face_partition;
  for (const Partition& p : partitions.partitions)
    for (int f : p.faces) {
      if (f >= static_cast<int>(face_partition.size())) face_partition.resize(f + 1, -1);
      face_partition[f] = p.id;
    }
  BRepMesh_IncrementalMesh mesher(shape, deflection, Standard_False, angle, Standard_True);
  int face_index = 0;
  for (TopExp_Explorer e(shape, TopAbs_FACE); e.More(); e.Next()) {
    ++face_index;
    const TopoDS_Face& face = TopoDS::Face(e.Current());
    TopLoc_Location location;
    Handle(Poly_Triangulation) triangulation = BRep_Tool::Triangulation(face, location);
    if (triangulation.IsNull()) continue;
    const int base = static_cast<int>(mesh.vertices.size());
    const gp_Trsf trsf = location.Transformation();
    for (int i = 1; i <= triangulation->NbNodes(); ++i) {
      const gp_Pnt p = triangulation->Node(i).Transformed(trsf);
      mesh.vertices.emplace_back(p.X(), p.Y(), p.Z());
    }
    const int partition = face_index < static_cast<int>(face_partition.size()) ? face_partition[face_index] : -1;
    for (int i = 1; i <= triangulation->NbTriangles(); ++i) {
      int a, b, c;
      triangulation->Triangle(i).Get(a, b, c);
      mesh.triangles.push_back({base + a - 1, base + b - 1, base + c - 1});
      mesh.triangle_partition.push_back(partition);
    }
  }
  return mesh;
}

namespace {
using Model = fcl::BVHModel<fcl::OBBRSSd>;

std::shared_ptr<Model> build(const TriangleMesh& mesh, const std::vector<int>& skipped, int skip_group,
                             const std::vector<int>* partition_group) {
  std::vector<fcl::Vector3d> vertices(mesh.vertices.begin(), mesh.vertices.end());
  std::vector<fcl::Triangle> triangles;
  triangles.reserve(mesh.triangles.size());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const int p = mesh.triangle_partition[t];
    if (std::find(skipped.begin(), skipped.end(), p) != skipped.end()) continue;
    if (partition_group && skip_group >= 0 && p >= 0 && p < static_cast<int>(partition_group->size()) &&
        (*partition_group)[p] == skip_group)
      continue;
    const auto& tri = mesh.triangles[t];
    triangles.emplace_back(tri[0], tri[1], tri[2]);
  }
  if (triangles.empty()) return nullptr;
  auto model = std::make_shared<Model>();
  model->beginModel(static_cast<int>(triangles.size()), static_cast<int>(vertices.size()));
  model->addSubModel(vertices, triangles);
  model->endModel();
  return model;
}
}  // namespace

struct MeshCollision::Impl {
  int moving = 0;
  // [group + 1]: group -1 (nothing switched off) first.
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> moving_models;
  std::vector<std::vector<std::unique_ptr<fcl::CollisionObjectd>>> other_models;  // [body][group + 1]
  std::vector<Eigen::AlignedBox3d> boxes;
  Eigen::AlignedBox3d moving_box;
  fcl::CollisionRequestd request;
  fcl::CollisionResultd result;
};

MeshCollision::MeshCollision(const std::vector<TriangleMesh>& meshes, int moving, const CollisionGroups& groups)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.moving = moving;
  const int group_count = groups.count();
  auto object = [](std::shared_ptr<Model> model) -> std::unique_ptr<fcl::CollisionObjectd> {
    if (!model) return nullptr;
    return std::make_unique<fcl::CollisionObjectd>(model, fcl::Transform3d::Identity());
  };
  const std::vector<int> none;
  for (int g = -1; g < group_count; ++g)
    m.moving_models.push_back(object(build(meshes[moving], none, g, &groups.moving_group)));
  m.other_models.resize(meshes.size());
  m.boxes.resize(meshes.size());
  for (std::size_t b = 0; b < meshes.size(); ++b) {
    for (const Vec3& v : meshes[b].vertices) m.boxes[b].extend(v);
    triangles_ += meshes[b].triangles.size();
    if (static_cast<int>(b) == moving) continue;
    m.other_models[b].push_back(object(build(meshes[b], none, -1, nullptr)));
    for (int g = 0; g < group_count; ++g) {
      const auto& off = groups.switched_off[g][b];
      m.other_models[b].push_back(off.empty() ? object(build(meshes[b], none, -1, nullptr))
                                              : object(build(meshes[b], off, -1, nullptr)));
    }
  }
  moving_triangles_ = meshes[moving].triangles.size();
  m.moving_box = m.boxes[moving];
  m.request.num_max_contacts = 1;
  m.request.enable_contact = false;
  m.result.clear();
}

MeshCollision::~MeshCollision() = default;

bool MeshCollision::collides(const Pose& pose, int group) noexcept {
  Impl& m = *impl_;
  const int slot = group + 1;
  if (slot < 0 || slot >= static_cast<int>(m.moving_models.size())) return false;
  fcl::CollisionObjectd* part = m.moving_models[slot].get();
  if (!part) return false;
  part->setTransform(fcl::Transform3d(pose.matrix()));
  part->computeAABB();
  // Broad phase on the moving part only: its box at this pose against the bodies' boxes.
  Eigen::AlignedBox3d box;
  for (int i = 0; i < 8; ++i) box.extend(pose * m.moving_box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(i)));
  for (std::size_t b = 0; b < m.other_models.size(); ++b) {
    if (static_cast<int>(b) == m.moving || m.other_models[b].empty() || !box.intersects(m.boxes[b])) continue;
    fcl::CollisionObjectd* other = m.other_models[b][slot].get();
    if (!other) continue;
    m.result.clear();
    fcl::collide(part, other, m.request, m.result);
    if (m.result.isCollision()) return true;
  }
  return false;
}

}  // namespace contactcore::haptics
