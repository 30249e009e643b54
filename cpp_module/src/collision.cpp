// Collision queries on FCL 0.7: one OBBRSS BVH per partition of a body (so a
// partition is switched off by a flag, never by a rebuild), pruned per query
// by the partitions' world boxes; penetration from the mesh vertices of one
// body inside the other, found by flooding from the intersecting triangles.
#include "contactcore/collision.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>

namespace contactcore {

namespace {
using Bvh = fcl::BVHModel<fcl::OBBRSSd>;
constexpr std::size_t kMaxContactsPerPair = 512;  // intersecting triangle pairs kept per partition pair
constexpr std::size_t kMaxFloodVertices = 4096;   // vertices tested for depth per side and query
constexpr double kTouching = 1e-12;               // mm: triangles this close intersect
}  // namespace

struct CollisionModel::Impl {
  struct Sub {
    std::shared_ptr<Bvh> bvh;          // null when the partition has no triangles
    std::vector<int> triangle;         // local triangle -> mesh triangle
    Eigen::Vector3d center{0, 0, 0};   // local axis-aligned box
    Eigen::Vector3d half{-1, -1, -1};
  };
  TaggedMesh mesh;
  std::vector<Sub> subs;                     // one per partition
  std::vector<Eigen::Vector3d> normals;      // unit normal of each triangle
  // Angle-weighted pseudo-normals (Baerentzen and Aanaes): the sign of
  // (p - closest) . normal tells inside from outside wherever the closest
  // point falls, face, edge or vertex.
  std::vector<Eigen::Vector3d> vertex_normals;
  std::vector<Eigen::Vector3d> edge_normals;  // 3 per triangle, edge (v[k], v[k+1])
  std::vector<int> adjacency_start, adjacency;  // vertex -> neighbouring vertices (CSR)
};

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
    sub.center = sub.bvh->aabb_local.center();
    sub.half = 0.5 * (sub.bvh->aabb_local.max_ - sub.bvh->aabb_local.min_);
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
  result.model = model;
  return result;
}

// ------------------------------------------------------------------ pair state

struct CollisionPair::State {
  CollisionModelPtr models[2];
  std::vector<char> enabled[2];
  // Per query: world boxes of the partitions, candidate partition pairs.
  std::vector<Eigen::Vector3d> box_center[2], box_half[2];
  struct Candidate {
    double lower_bound;
    int a, b;
  };
  std::vector<Candidate> candidates;
  fcl::Transform3d transform[2];
  fcl::CollisionRequestd collide_first, collide_all;
  fcl::CollisionResultd collide_result;
  fcl::DistanceRequestd distance_request;
  fcl::DistanceResultd distance_result;
  // A point, as a one-triangle mesh 1e-12 mm across: FCL fits an oriented box to a shape on every
  // mesh-shape query (an eigen-decomposition), not to a mesh it already holds.
  std::shared_ptr<Bvh> point = [] {
    auto model = std::make_shared<Bvh>();
    const std::vector<fcl::Vector3d> corners{{0, 0, 0}, {1e-12, 0, 0}, {0, 1e-12, 0}};
    const std::vector<fcl::Triangle> triangle{{0, 1, 2}};
    model->beginModel(1, 3);
    model->addSubModel(corners, triangle);
    model->endModel();
    return model;
  }();
  // Penetration flood: visit stamps per vertex, a stack, the seeds.
  std::vector<unsigned> stamp[2];
  unsigned query_stamp = 0;
  std::vector<int> stack;
  std::vector<char> partition_hit[2];

  const CollisionModel::Impl& impl(int side) const { return models[side]->impl(); }
};

CollisionPair::CollisionPair(CollisionModelPtr a, CollisionModelPtr b) : state_(std::make_unique<State>()) {
  State& s = *state_;
  s.models[0] = std::move(a);
  s.models[1] = std::move(b);
  for (int side = 0; side < 2; ++side) {
    const int partitions = s.models[side]->partition_count();
    s.enabled[side].assign(partitions, 1);
    s.box_center[side].resize(partitions);
    s.box_half[side].resize(partitions);
    s.stamp[side].assign(s.models[side]->mesh().vertices.size(), 0);
    s.partition_hit[side].assign(partitions, 0);
  }
  s.candidates.reserve(static_cast<std::size_t>(s.models[0]->partition_count()) * s.models[1]->partition_count());
  s.stack.reserve(kMaxFloodVertices * 4);
  s.collide_first.num_max_contacts = 1;
  s.collide_all.num_max_contacts = kMaxContactsPerPair;
  s.collide_result.clear();
  s.distance_request.enable_nearest_points = true;
  s.distance_request.rel_err = 0;
  s.distance_request.abs_err = 0;
}

CollisionPair::~CollisionPair() = default;

void CollisionPair::set_partition_enabled(int side, int partition, bool enabled) {
  if (side < 0 || side > 1) return;
  auto& flags = state_->enabled[side];
  if (partition >= 0 && partition < static_cast<int>(flags.size())) flags[partition] = enabled ? 1 : 0;
}

void CollisionPair::enable_all() {
  for (auto& flags : state_->enabled) std::fill(flags.begin(), flags.end(), 1);
}

bool CollisionPair::partition_enabled(int side, int partition) const {
  if (side < 0 || side > 1) return false;
  const auto& flags = state_->enabled[side];
  return partition >= 0 && partition < static_cast<int>(flags.size()) && flags[partition];
}

const CollisionModel& CollisionPair::model(int side) const { return *state_->models[side == 0 ? 0 : 1]; }

namespace {

fcl::Transform3d to_fcl(const RigidTransform& t) {
  fcl::Transform3d out = fcl::Transform3d::Identity();
  fcl::Matrix3d rotation;
  rotation << t.rotation[0], t.rotation[1], t.rotation[2], t.rotation[3], t.rotation[4], t.rotation[5],
      t.rotation[6], t.rotation[7], t.rotation[8];
  out.linear() = rotation;
  out.translation() = fcl::Vector3d(t.translation[0], t.translation[1], t.translation[2]);
  return out;
}

double box_gap(const Eigen::Vector3d& ca, const Eigen::Vector3d& ha, const Eigen::Vector3d& cb,
               const Eigen::Vector3d& hb) {
  const Eigen::Vector3d gap = ((ca - cb).cwiseAbs() - ha - hb).cwiseMax(0.0);
  return gap.norm();
}

std::array<double, 3> to_array(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

// The pseudo-normal at `point` (mesh frame) of triangle `t`: its face normal
// inside, the edge normal on an edge, the vertex normal at a corner.
Eigen::Vector3d pseudo_normal(const CollisionModel::Impl& impl, int t, const Eigen::Vector3d& point) {
  const auto& tri = impl.mesh.triangles[t];
  const Eigen::Vector3d a(impl.mesh.vertices[tri[0]].data()), b(impl.mesh.vertices[tri[1]].data()),
      c(impl.mesh.vertices[tri[2]].data());
  const Eigen::Vector3d n = (b - a).cross(c - a);
  const double area2 = n.squaredNorm();
  if (area2 <= 0) return impl.normals[t];
  // Barycentric weight of each corner; near zero means on the opposite edge.
  const double w[3] = {(c - b).cross(point - b).dot(n) / area2, (a - c).cross(point - c).dot(n) / area2,
                       (b - a).cross(point - a).dot(n) / area2};
  constexpr double kOnBoundary = 1e-9;
  int zeros = 0, corner = -1, edge = -1;
  for (int k = 0; k < 3; ++k)
    if (w[k] <= kOnBoundary) ++zeros;
  if (zeros >= 2) {
    for (int k = 0; k < 3; ++k)
      if (w[k] > kOnBoundary) corner = k;
    if (corner < 0) corner = 0;
    return impl.vertex_normals[tri[corner]];
  }
  if (zeros == 1) {
    for (int k = 0; k < 3; ++k)
      if (w[k] <= kOnBoundary) edge = (k + 1) % 3;  // the edge opposite corner k is (v[k+1], v[k+2])
    return impl.edge_normals[3 * t + edge];
  }
  return impl.normals[t];
}

}  // namespace

void CollisionPair::query(const RigidTransform& place_a, const RigidTransform& place_b, QueryKind kind,
                          QueryResult& out) {
  State& s = *state_;
  out.intersecting = false;
  out.distance = std::numeric_limits<double>::infinity();
  out.point_a = out.point_b = {0, 0, 0};
  out.triangle_a = out.triangle_b = -1;
  out.face_a = out.face_b = 0;
  out.partition_a = out.partition_b = -1;
  out.depth = 0;
  out.direction = {0, 0, 0};
  out.partitions_a.clear();
  out.partitions_b.clear();
  s.transform[0] = to_fcl(place_a);
  s.transform[1] = to_fcl(place_b);

  // World boxes of the enabled, non-empty partitions.
  for (int side = 0; side < 2; ++side) {
    const auto& subs = s.impl(side).subs;
    const Eigen::Matrix3d rotation = s.transform[side].linear();
    const Eigen::Matrix3d abs_rotation = rotation.cwiseAbs();
    for (std::size_t p = 0; p < subs.size(); ++p) {
      if (!subs[p].bvh) continue;  // every partition: the inside tests below use the whole surface
      s.box_center[side][p] = rotation * subs[p].center + s.transform[side].translation();
      s.box_half[side][p] = abs_rotation * subs[p].half;
    }
  }
  s.candidates.clear();
  const auto& subs_a = s.impl(0).subs;
  const auto& subs_b = s.impl(1).subs;
  for (std::size_t pa = 0; pa < subs_a.size(); ++pa) {
    if (!s.enabled[0][pa] || !subs_a[pa].bvh) continue;
    for (std::size_t pb = 0; pb < subs_b.size(); ++pb) {
      if (!s.enabled[1][pb] || !subs_b[pb].bvh) continue;
      s.candidates.push_back({box_gap(s.box_center[0][pa], s.box_half[0][pa], s.box_center[1][pb], s.box_half[1][pb]),
                              static_cast<int>(pa), static_cast<int>(pb)});
    }
  }
  if (s.candidates.empty()) return;  // everything switched off: nothing to hit, infinitely far

  auto record_closest = [&](int pa, int pb, const fcl::DistanceResultd& r) {
    out.distance = std::max(0.0, r.min_distance);
    out.point_a = to_array(r.nearest_points[0]);
    out.point_b = to_array(r.nearest_points[1]);
    out.triangle_a = subs_a[pa].triangle[r.b1];
    out.triangle_b = subs_b[pb].triangle[r.b2];
    out.face_a = s.impl(0).mesh.triangle_face[out.triangle_a];
    out.face_b = s.impl(1).mesh.triangle_face[out.triangle_b];
    out.partition_a = pa;
    out.partition_b = pb;
  };

  // Intersecting triangle pairs (all of them for Penetration, one per partition pair otherwise).
  const bool want_all = kind == QueryKind::Penetration;
  bool any_hit = false;
  if (kind != QueryKind::Distance) {
    for (int side = 0; side < 2; ++side) std::fill(s.partition_hit[side].begin(), s.partition_hit[side].end(), 0);
    if (want_all) {
      ++s.query_stamp;
      if (s.query_stamp == 0) {  // wrapped: reset the stamps once
        for (auto& stamps : s.stamp) std::fill(stamps.begin(), stamps.end(), 0);
        s.query_stamp = 1;
      }
      s.stack.clear();
    }
    for (const State::Candidate& c : s.candidates) {
      if (c.lower_bound > 0) continue;
      s.collide_result.clear();
      fcl::collide(subs_a[c.a].bvh.get(), s.transform[0], subs_b[c.b].bvh.get(), s.transform[1],
                   want_all ? s.collide_all : s.collide_first, s.collide_result);
      if (!s.collide_result.isCollision()) continue;
      // FCL's triangle-triangle test reports some nearly parallel, merely nearby triangles as
      // intersecting; its exact triangle distance decides.
      s.distance_result.clear();
      fcl::distance(subs_a[c.a].bvh.get(), s.transform[0], subs_b[c.b].bvh.get(), s.transform[1],
                    s.distance_request, s.distance_result);
      if (s.distance_result.min_distance > kTouching) continue;
      any_hit = true;
      s.partition_hit[0][c.a] = s.partition_hit[1][c.b] = 1;
      if (out.partition_a < 0) {
        const fcl::Contactd& contact = s.collide_result.getContact(0);
        out.partition_a = c.a;
        out.partition_b = c.b;
        out.triangle_a = subs_a[c.a].triangle[contact.b1];
        out.triangle_b = subs_b[c.b].triangle[contact.b2];
        out.face_a = s.impl(0).mesh.triangle_face[out.triangle_a];
        out.face_b = s.impl(1).mesh.triangle_face[out.triangle_b];
      }
      if (want_all) {
        // Seeds of the flood: corners of the intersecting triangles, tagged by side (vertex * 2 + side).
        for (std::size_t i = 0; i < s.collide_result.numContacts(); ++i) {
          const fcl::Contactd& contact = s.collide_result.getContact(i);
          const auto& ta = s.impl(0).mesh.triangles[subs_a[c.a].triangle[contact.b1]];
          const auto& tb = s.impl(1).mesh.triangles[subs_b[c.b].triangle[contact.b2]];
          for (int k = 0; k < 3; ++k) {
            if (s.stamp[0][ta[k]] != s.query_stamp) {
              s.stamp[0][ta[k]] = s.query_stamp;
              s.stack.push_back(ta[k] * 2);
            }
            if (s.stamp[1][tb[k]] != s.query_stamp) {
              s.stamp[1][tb[k]] = s.query_stamp;
              s.stack.push_back(tb[k] * 2 + 1);
            }
          }
        }
      }
    }
    for (std::size_t p = 0; p < s.partition_hit[0].size(); ++p)
      if (s.partition_hit[0][p]) out.partitions_a.push_back(static_cast<int>(p));
    for (std::size_t p = 0; p < s.partition_hit[1].size(); ++p)
      if (s.partition_hit[1][p]) out.partitions_b.push_back(static_cast<int>(p));
    if (any_hit) {
      out.intersecting = true;
      out.distance = 0;
    }
    if (kind == QueryKind::Intersect) return;
  }

  if (!any_hit) {
    // Closest pair of enabled partitions, nearest boxes first, pruned by the best distance so far.
    std::sort(s.candidates.begin(), s.candidates.end(),
              [](const State::Candidate& x, const State::Candidate& y) { return x.lower_bound < y.lower_bound; });
    for (const State::Candidate& c : s.candidates) {
      if (c.lower_bound >= out.distance) break;
      s.distance_result.clear();
      fcl::distance(subs_a[c.a].bvh.get(), s.transform[0], subs_b[c.b].bvh.get(), s.transform[1],
                    s.distance_request, s.distance_result);
      if (s.distance_result.min_distance < out.distance) record_closest(c.a, c.b, s.distance_result);
      if (out.distance <= 0) break;
    }
    if (out.distance <= 0) out.intersecting = true;
    return;
  }

  // Penetration: flood from the seeds through the vertices inside the other body.
  // Inside and depth are judged against the other body's whole surface, its
  // switched-off partitions included: without them it would not be closed.
  // Closest point of `side`'s surface to world point p (distance, point, triangle).
  auto closest_on = [&](int side, const Eigen::Vector3d& p, Eigen::Vector3d& closest, Eigen::Vector3d& local,
                        int& triangle) {
    const auto& subs = s.impl(side).subs;
    double best = std::numeric_limits<double>::infinity();
    triangle = -1;
    fcl::Transform3d at = fcl::Transform3d::Identity();
    at.translation() = p;
    for (std::size_t q = 0; q < subs.size(); ++q) {
      if (!subs[q].bvh) continue;
      const double bound = box_gap(p, Eigen::Vector3d::Zero(), s.box_center[side][q], s.box_half[side][q]);
      if (bound >= best) continue;
      s.distance_result.clear();
      // Mesh-mesh: FCL 0.7 gives the nearest points in world coordinates.
      fcl::distance(subs[q].bvh.get(), s.transform[side], s.point.get(), at, s.distance_request, s.distance_result);
      if (s.distance_result.min_distance < best) {
        best = std::max(0.0, s.distance_result.min_distance);
        closest = s.distance_result.nearest_points[0];
        local = s.transform[side].inverse() * closest;
        triangle = subs[q].triangle[s.distance_result.b1];
      }
    }
    return best;
  };
  std::size_t tested[2] = {0, 0};
  while (!s.stack.empty()) {
    const int tagged = s.stack.back();
    s.stack.pop_back();
    const int side = tagged & 1, vertex = tagged >> 1, other = 1 - side;
    if (tested[side] >= kMaxFloodVertices) continue;
    ++tested[side];
    const auto& v = s.impl(side).mesh.vertices[vertex];
    const Eigen::Vector3d p = s.transform[side] * Eigen::Vector3d(v[0], v[1], v[2]);
    Eigen::Vector3d closest, local;
    int triangle = -1;
    const double gap = closest_on(other, p, closest, local, triangle);
    if (triangle < 0) continue;
    const Eigen::Vector3d normal = s.transform[other].linear() * pseudo_normal(s.impl(other), triangle, local);
    if ((p - closest).dot(normal) >= 0) continue;  // outside the other body
    if (gap > out.depth) {
      out.depth = gap;
      const Eigen::Vector3d move = side == 0 ? closest - p : p - closest;  // how A leaves
      out.direction = to_array(move.norm() > 0 ? move.normalized() : Eigen::Vector3d(-normal));
    }
    const auto& impl = s.impl(side);
    for (int k = impl.adjacency_start[vertex]; k < impl.adjacency_start[vertex + 1]; ++k) {
      const int next = impl.adjacency[k];
      if (s.stamp[side][next] == s.query_stamp) continue;
      s.stamp[side][next] = s.query_stamp;
      s.stack.push_back(next * 2 + side);
    }
  }
}

double CollisionPair::depth_inside(int side, const RigidTransform& place, const std::array<double, 3>& point) {
  State& s = *state_;
  side = side == 0 ? 0 : 1;
  const fcl::Transform3d transform = to_fcl(place);
  const Eigen::Vector3d p(point[0], point[1], point[2]);
  const auto& impl = s.impl(side);
  const Eigen::Matrix3d rotation = transform.linear(), abs_rotation = rotation.cwiseAbs();
  double best = std::numeric_limits<double>::infinity();
  int triangle = -1;
  Eigen::Vector3d closest, local;
  fcl::Transform3d at = fcl::Transform3d::Identity();
  at.translation() = p;
  for (const auto& sub : impl.subs) {
    if (!sub.bvh) continue;
    if (box_gap(p, Eigen::Vector3d::Zero(), rotation * sub.center + transform.translation(), abs_rotation * sub.half) >=
        best)
      continue;
    s.distance_result.clear();
    fcl::distance(sub.bvh.get(), transform, s.point.get(), at, s.distance_request, s.distance_result);
    if (s.distance_result.min_distance < best) {
      best = std::max(0.0, s.distance_result.min_distance);
      closest = s.distance_result.nearest_points[0];
      local = transform.inverse() * closest;
      triangle = sub.triangle[s.distance_result.b1];
    }
  }
  if (triangle < 0) return 0;
  const Eigen::Vector3d normal = rotation * pseudo_normal(impl, triangle, local);
  return (p - closest).dot(normal) < 0 ? best : 0;
}

}  // namespace contactcore

