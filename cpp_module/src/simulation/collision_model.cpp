// Building a collision model: the body's and the per-partition hierarchies (FCL), normals,
// angle-weighted pseudo-normals, vertex and corner adjacency.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

#include "simulation/collision_model.h"

namespace contactcore {

namespace {
using Bvh = fcl::BVHModel<fcl::OBBRSSd>;
}  // namespace

CollisionModel::CollisionModel() : impl_(std::make_unique<Impl>()) {}
CollisionModel::~CollisionModel() = default;
int CollisionModel::partition_count() const { return static_cast<int>(impl_->subs.size()); }
std::size_t CollisionModel::triangle_count() const { return impl_->mesh.triangles.size(); }
const TaggedMesh& CollisionModel::mesh() const { return impl_->mesh; }

CollisionModelResult build_collision_model(const TaggedMesh& mesh) {
  CollisionModelResult result;
  const std::size_t n = mesh.triangles.size();
  if (n == 0 || mesh.triangle_partition.size() != n || mesh.triangle_face.size() != n) {
    result.status = Status::failure(StatusCode::InvalidInput, "collision model of an empty or untagged mesh");
    return result;
  }
  int partitions = mesh.partition_count;
  for (int p : mesh.triangle_partition) {
    if (p < 0) {
      result.status = Status::failure(StatusCode::InvalidInput, "a triangle has no partition");
      return result;
    }
    partitions = std::max(partitions, p + 1);
  }
  for (const auto& t : mesh.triangles)
    for (int v : t)
      if (v < 0 || v >= static_cast<int>(mesh.vertices.size())) {
        result.status = Status::failure(StatusCode::InvalidInput, "a triangle refers to a missing vertex");
        return result;
      }

  std::shared_ptr<CollisionModel> model(new CollisionModel());
  CollisionModel::Impl& impl = *model->impl_;
  impl.mesh = mesh;
  impl.mesh.partition_count = partitions;
  impl.subs.resize(partitions);
  std::vector<std::vector<int>> members(partitions);
  for (std::size_t i = 0; i < n; ++i) members[mesh.triangle_partition[i]].push_back(static_cast<int>(i));

  for (int p = 0; p < partitions; ++p) {
    if (members[p].empty()) continue;
    CollisionModel::Impl::Sub& sub = impl.subs[p];
    sub.triangle = members[p];
    // Local vertex numbering of the partition's triangles.
    std::vector<int> local(mesh.vertices.size(), -1);
    std::vector<fcl::Vector3d> points;
    std::vector<fcl::Triangle> triangles;
    for (int t : members[p]) {
      int corner[3];
      for (int k = 0; k < 3; ++k) {
        const int v = mesh.triangles[t][k];
        if (local[v] < 0) {
          local[v] = static_cast<int>(points.size());
          points.emplace_back(mesh.vertices[v][0], mesh.vertices[v][1], mesh.vertices[v][2]);
        }
        corner[k] = local[v];
      }
      triangles.emplace_back(corner[0], corner[1], corner[2]);
    }
    sub.bvh = std::make_shared<Bvh>();
    sub.bvh->beginModel(static_cast<int>(triangles.size()), static_cast<int>(points.size()));
    sub.bvh->addSubModel(points, triangles);
    sub.bvh->endModel();
    sub.bvh->computeLocalAABB();
    sub.parent.assign(sub.bvh->getNumBVs(), -1);
    for (int node = 0; node < sub.bvh->getNumBVs(); ++node)
      if (!sub.bvh->getBV(node).isLeaf())
        sub.parent[sub.bvh->getBV(node).leftChild()] = sub.parent[sub.bvh->getBV(node).rightChild()] = node;
    sub.center = sub.bvh->aabb_local.center();
    sub.half = 0.5 * (sub.bvh->aabb_local.max_ - sub.bvh->aabb_local.min_);
  }

  {
    std::vector<fcl::Vector3d> points;
    points.reserve(mesh.vertices.size());
    for (const auto& v : mesh.vertices) points.emplace_back(v[0], v[1], v[2]);
    std::vector<fcl::Triangle> triangles;
    triangles.reserve(n);
    for (const auto& t : mesh.triangles) triangles.emplace_back(t[0], t[1], t[2]);
    impl.body = std::make_shared<Bvh>();
    impl.body->beginModel(static_cast<int>(triangles.size()), static_cast<int>(points.size()));
    impl.body->addSubModel(points, triangles);
    impl.body->endModel();
    // Children come after their parent in FCL's node array: leaves up, in reverse.
    impl.body_partitions.assign(impl.body->getNumBVs(), 0);
    for (int node = impl.body->getNumBVs() - 1; node >= 0; --node) {
      const auto& bv = impl.body->getBV(node);
      impl.body_partitions[node] =
          bv.isLeaf() ? std::uint64_t{1} << (mesh.triangle_partition[bv.primitiveId()] % 64)
                      : impl.body_partitions[bv.leftChild()] | impl.body_partitions[bv.rightChild()];
    }
  }

  impl.normals.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto& t = mesh.triangles[i];
    const Eigen::Vector3d a(mesh.vertices[t[0]].data()), b(mesh.vertices[t[1]].data()), c(mesh.vertices[t[2]].data());
    const Eigen::Vector3d normal = (b - a).cross(c - a);
    impl.normals[i] = normal.norm() > 0 ? normal.normalized() : Eigen::Vector3d::Zero();
  }
  impl.vertex_normals.assign(mesh.vertices.size(), Eigen::Vector3d::Zero());
  impl.edge_normals.assign(3 * n, Eigen::Vector3d::Zero());
  std::unordered_map<std::uint64_t, std::vector<int>> edge_uses;  // edge -> triangle * 3 + k
  for (std::size_t i = 0; i < n; ++i) {
    const auto& t = mesh.triangles[i];
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d p(mesh.vertices[t[k]].data()), q(mesh.vertices[t[(k + 1) % 3]].data()),
          r(mesh.vertices[t[(k + 2) % 3]].data());
      const Eigen::Vector3d e1 = q - p, e2 = r - p;
      if (e1.norm() > 0 && e2.norm() > 0)
        impl.vertex_normals[t[k]] += std::acos(std::clamp(e1.normalized().dot(e2.normalized()), -1.0, 1.0)) *
                                     impl.normals[i];
      const int a = std::min(t[k], t[(k + 1) % 3]), b = std::max(t[k], t[(k + 1) % 3]);
      edge_uses[(static_cast<std::uint64_t>(a) << 32) | static_cast<std::uint32_t>(b)].push_back(
          static_cast<int>(3 * i + k));
    }
  }
  for (auto& normal : impl.vertex_normals)
    if (normal.norm() > 0) normal.normalize();
  for (const auto& [edge, uses] : edge_uses) {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (int use : uses) sum += impl.normals[use / 3];
    if (sum.norm() > 0) sum.normalize();
    for (int use : uses) impl.edge_normals[use] = sum;
  }
  // Vertex adjacency through triangle edges (each neighbour listed once per edge use).
  std::vector<int> degree(mesh.vertices.size() + 1, 0);
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) degree[t[k] + 1] += 2;
  for (std::size_t v = 1; v < degree.size(); ++v) degree[v] += degree[v - 1];
  impl.adjacency_start = degree;
  impl.adjacency.resize(degree.back());
  std::vector<int> fill(degree.begin(), degree.end() - 1);
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) {
      impl.adjacency[fill[t[k]]++] = t[(k + 1) % 3];
      impl.adjacency[fill[t[k]]++] = t[(k + 2) % 3];
    }
  impl.local_triangle.assign(n, -1);
  for (const auto& sub : impl.subs)
    for (std::size_t k = 0; k < sub.triangle.size(); ++k) impl.local_triangle[sub.triangle[k]] = static_cast<int>(k);
  impl.corner_start.assign(mesh.vertices.size() + 1, 0);
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) ++impl.corner_start[t[k] + 1];
  for (std::size_t v = 1; v < impl.corner_start.size(); ++v) impl.corner_start[v] += impl.corner_start[v - 1];
  impl.corner_of.resize(impl.corner_start.back());
  std::vector<int> next(impl.corner_start.begin(), impl.corner_start.end() - 1);
  for (std::size_t i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) impl.corner_of[next[mesh.triangles[i][k]]++] = static_cast<int>(i);
  result.model = model;
  return result;
}

}  // namespace contactcore
