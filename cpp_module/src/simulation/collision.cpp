// Collision queries on FCL 0.7: one OBBRSS BVH per partition of a body (so a
// partition is switched off by a flag, never by a rebuild; built in
// collision_model.cpp), pruned per query by the partitions' world boxes,
// traversed by bvh_traversal.cpp; penetration from the mesh vertices of one
// body inside the other, found by flooding from the intersecting triangles.
#include "contactcore/simulation/collision.h"

#include <algorithm>
#include <string>
#include <cstddef>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <limits>
#include <optional>

#include "simulation/bvh_traversal.h"
#include "simulation/collision_model.h"

namespace contactcore {

Status check_rigid_transform(const RigidTransform& placement) {
  const auto fail = [](const std::string& message) { return Status::failure(StatusCode::InvalidArgument, message); };
  for (double v : placement.rotation)
    if (!std::isfinite(v)) return fail("a placement's rotation holds a number that is not finite");
  for (double v : placement.translation)
    if (!std::isfinite(v) || std::abs(v) > 1e100) return fail("a placement's translation is not a finite length");
  const auto& r = placement.rotation;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const double dot = r[3 * i] * r[3 * j] + r[3 * i + 1] * r[3 * j + 1] + r[3 * i + 2] * r[3 * j + 2];
      if (std::abs(dot - (i == j ? 1.0 : 0.0)) > 1e-6)
        return fail("a placement's rotation is not orthonormal (rows " + std::to_string(i) + " and " +
                    std::to_string(j) + " give " + std::to_string(dot) + "): scaled, sheared or all zero");
    }
  const double det = r[0] * (r[4] * r[8] - r[5] * r[7]) - r[1] * (r[3] * r[8] - r[5] * r[6]) +
                     r[2] * (r[3] * r[7] - r[4] * r[6]);
  if (det < 0) return fail("a placement's rotation is a mirror (determinant -1)");
  return Status::success();
}


namespace {
constexpr std::size_t kMaxContactsPerPair = 512;  // intersecting triangle pairs kept per partition pair
constexpr std::size_t kMaxFloodVertices = 4096;   // vertices tested for depth per side and query
constexpr double kTouching = 1e-12;               // mm: triangles this close intersect
constexpr std::size_t kMaxRing = 16;  // a triangle and those sharing a corner (13 on a regular mesh)
// Front tracking of Intersect: fronts kept for this many partition pairs at once (the least
// recently used gives its slot up), each at most this many node pairs (beyond: back to the roots).
// Reserved when the pair is made, so that queries never allocate.
constexpr std::size_t kFrontSlots = 4;
constexpr std::size_t kFrontCapacity = 4096;
// Ticks between pull-up passes of a front (with motion-bounded pruning, 1, 2, 4, 8, 16, 32 and 128
// measured on the bench's trajectory: 16 and 32 best).
constexpr unsigned kPullUpEvery = 16;
}  // namespace

// ------------------------------------------------------------------ pair state

struct CollisionPair::State {
  CollisionModelPtr models[2];
  std::vector<char> enabled[2];
  std::vector<char> pair_enabled;  // a * partitions of B + b
  std::size_t pairs_off = 0;       // zeros in pair_enabled
  // Per query: world boxes of the partitions, candidate partition pairs.
  std::vector<Eigen::Vector3d> box_center[2], box_half[2];
  struct Candidate {
    double lower_bound;
    int a, b;
  };
  std::vector<Candidate> candidates;
  fcl::Transform3d transform[2];
  bvh::Relative relative;  // B in A's frame
  bvh::Traversal traversal;
  std::vector<bvh::TriangleHit> hits;
  // Warm start of Distance: the last closest pair (partitions, local triangles), -1 when none.
  struct Cached {
    int partition_a = -1, partition_b = -1, triangle_a = -1, triangle_b = -1;
  };
  Cached cached_closest;
  // Warm start of Intersect: per partition pair (a * partitions of B + b), the last touching pair of
  // local triangles, {-1, -1} when none; and the triangles around a cached one (scratch).
  std::vector<bvh::TriangleHit> cached_hit;
  std::vector<int> ring[2];
  bool warm_start = true;
  // Front tracking (see bvh::FrontEntry), of Intersect and of Distance apart: per slot the front of
  // the last traversal of one partition pair (owner: a * partitions of B + b, -1 when free);
  // slot_of maps a partition pair to its slot (-1: none, i.e. start from the roots).
  struct FrontSlot {
    std::vector<bvh::FrontEntry> entries;
    bvh::Relative made_at;  // the placement the entries' margins hold for (when entries is not empty)
    int owner = -1;
    unsigned long used = 0;
    unsigned ticks = 0;
  };
  struct Fronts {
    FrontSlot slots[kFrontSlots];
    std::vector<int> slot_of;
    unsigned long clock = 0;
    FrontSlot& of(int pair_index);
    void clear();
  };
  Fronts intersect_fronts, distance_fronts;
  std::vector<bvh::FrontEntry> front_next;
  bool front_tracking = true;
  // Point queries and Penetration's touching pairs on the bodies' one trees (set_body_tree); off by
  // default: measured no faster in contact and twice slower out of it (docs/haptics.md).
  bool body_tree = false;
  // Penetration on the bodies' trees: touching pairs found per partition pair (a * partitions of B +
  // b), and per partition bucket of A (p % 64) the buckets of B still wanted (bit q % 64).
  std::vector<std::uint32_t> pair_hit_count;
  std::uint64_t wanted_rows[64] = {};
  // Wanted partition pairs (for the rows): within touching by their boxes, enabled, not yet full.
  std::vector<char> pair_wanted;
  void rebuild_wanted_rows() {
    std::fill(std::begin(wanted_rows), std::end(wanted_rows), 0);
    const std::size_t nb = enabled[1].size();
    for (std::size_t k = 0; k < pair_wanted.size(); ++k)
      if (pair_wanted[k]) wanted_rows[(k / nb) % 64] |= std::uint64_t{1} << ((k % nb) % 64);
  }
  void clear_fronts() {
    intersect_fronts.clear();
    distance_fronts.clear();
  }
  double distance_limit = std::numeric_limits<double>::infinity();
  // Security margin (set_margin): < 0 off. Triangles closer than `touching` intersect.
  double margin = -1;
  double touching = kTouching;

  // Whether the cached touching pair of partitions (pa, pb), or a pair of triangles sharing a corner
  // with it, still touches at the current placements; the touching pair found goes into `hits`.
  bool touching_near_cache(int pa, int pb);
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
  s.pair_enabled.assign(static_cast<std::size_t>(s.models[0]->partition_count()) * s.models[1]->partition_count(), 1);
  s.candidates.reserve(static_cast<std::size_t>(s.models[0]->partition_count()) * s.models[1]->partition_count());
  s.stack.reserve(kMaxFloodVertices * 4);
  s.hits.reserve(kMaxContactsPerPair);
  s.pair_hit_count.assign(s.pair_enabled.size(), 0);
  s.pair_wanted.assign(s.pair_enabled.size(), 0);
  for (auto& ring : s.ring) ring.reserve(kMaxRing);
  s.cached_hit.assign(static_cast<std::size_t>(s.models[0]->partition_count()) * s.models[1]->partition_count(),
                      {-1, -1});
  for (State::Fronts* fronts : {&s.intersect_fronts, &s.distance_fronts}) {
    fronts->slot_of.assign(s.cached_hit.size(), -1);
    for (auto& slot : fronts->slots) slot.entries.reserve(kFrontCapacity);
  }
  s.front_next.reserve(kFrontCapacity);
}

CollisionPair::State::FrontSlot& CollisionPair::State::Fronts::of(int pair_index) {
  ++clock;
  if (slot_of[pair_index] >= 0) {
    FrontSlot& slot = slots[slot_of[pair_index]];
    slot.used = clock;
    return slot;
  }
  std::size_t chosen = 0;
  for (std::size_t k = 1; k < kFrontSlots; ++k)
    if (slots[k].used < slots[chosen].used) chosen = k;
  FrontSlot& slot = slots[chosen];
  if (slot.owner >= 0) slot_of[slot.owner] = -1;
  slot.owner = pair_index;
  slot.used = clock;
  slot.ticks = 0;
  slot.entries.clear();  // empty: from the roots
  slot_of[pair_index] = static_cast<int>(chosen);
  return slot;
}

void CollisionPair::State::Fronts::clear() {
  for (auto& slot : slots) {
    if (slot.owner >= 0) slot_of[slot.owner] = -1;
    slot.owner = -1;
    slot.used = 0;
    slot.entries.clear();
  }
}

CollisionPair::~CollisionPair() = default;

void CollisionPair::set_partition_enabled(int side, int partition, bool enabled) {
  if (side < 0 || side > 1) return;
  auto& flags = state_->enabled[side];
  if (partition >= 0 && partition < static_cast<int>(flags.size())) flags[partition] = enabled ? 1 : 0;
  // The fronts stay exact (each covers its own partition pair whole) but may be stale: restart them.
  state_->clear_fronts();
}

void CollisionPair::set_pair_enabled(int partition_a, int partition_b, bool enabled) {
  State& s = *state_;
  const int na = static_cast<int>(s.enabled[0].size()), nb = static_cast<int>(s.enabled[1].size());
  if (partition_a < 0 || partition_a >= na || partition_b < 0 || partition_b >= nb) return;
  char& flag = s.pair_enabled[static_cast<std::size_t>(partition_a) * nb + partition_b];
  if (flag && !enabled) ++s.pairs_off;
  if (!flag && enabled) --s.pairs_off;
  flag = enabled ? 1 : 0;
  // No front to restart: each front covers its own partition pair, which is skipped while off.
}

bool CollisionPair::pair_enabled(int partition_a, int partition_b) const {
  const State& s = *state_;
  const int na = static_cast<int>(s.enabled[0].size()), nb = static_cast<int>(s.enabled[1].size());
  if (partition_a < 0 || partition_a >= na || partition_b < 0 || partition_b >= nb) return false;
  return s.pair_enabled[static_cast<std::size_t>(partition_a) * nb + partition_b] != 0;
}

void CollisionPair::enable_all() {
  for (auto& flags : state_->enabled) std::fill(flags.begin(), flags.end(), 1);
  std::fill(state_->pair_enabled.begin(), state_->pair_enabled.end(), 1);
  state_->pairs_off = 0;
  state_->clear_fronts();
}

bool CollisionPair::partition_enabled(int side, int partition) const {
  if (side < 0 || side > 1) return false;
  const auto& flags = state_->enabled[side];
  return partition >= 0 && partition < static_cast<int>(flags.size()) && flags[partition];
}

void CollisionPair::set_warm_start(bool enabled) {
  state_->warm_start = enabled;
  state_->cached_closest = {};
  std::fill(state_->cached_hit.begin(), state_->cached_hit.end(), bvh::TriangleHit{-1, -1});
  state_->clear_fronts();
}

void CollisionPair::set_body_tree(bool enabled) { state_->body_tree = enabled; }

void CollisionPair::set_front_tracking(bool enabled) {
  state_->front_tracking = enabled;
  state_->clear_fronts();
}

void CollisionPair::set_distance_limit(double limit) {
  state_->distance_limit = limit >= 0 ? limit : std::numeric_limits<double>::infinity();
}

Status CollisionPair::set_margin(double margin) {
  if (!std::isfinite(margin) || margin < 0)
    return Status::failure(StatusCode::InvalidArgument,
                           "a collision margin is a finite length >= 0 (mm), not " + std::to_string(margin));
  state_->margin = margin;
  state_->touching = std::max(kTouching, margin);
  std::fill(state_->cached_hit.begin(), state_->cached_hit.end(), bvh::TriangleHit{-1, -1});
  state_->clear_fronts();
  return Status::success();
}

void CollisionPair::clear_margin() {
  state_->margin = -1;
  state_->touching = kTouching;
  std::fill(state_->cached_hit.begin(), state_->cached_hit.end(), bvh::TriangleHit{-1, -1});
  state_->clear_fronts();
}

std::optional<double> CollisionPair::margin() const {
  if (state_->margin < 0) return std::nullopt;
  return state_->margin;
}

CollisionPair::Counts CollisionPair::counts() const {
  return {state_->traversal.bv_tests, state_->traversal.triangle_tests};
}

bool CollisionPair::State::touching_near_cache(int pa, int pb) {
  const bvh::TriangleHit cached = cached_hit[static_cast<std::size_t>(pa) * enabled[1].size() + pb];
  if (cached.triangle_a < 0) return false;
  const bvh::Bvh& bvh_a = *impl(0).subs[pa].bvh;
  const bvh::Bvh& bvh_b = *impl(1).subs[pb].bvh;
  fcl::Vector3d point_a, point_b;
  auto touches = [&](int ta, int tb) {
    ++traversal.triangle_tests;
    if (bvh::Traversal::triangle_distance(bvh_a, ta, bvh_b, tb, relative, point_a, point_b) > touching) return false;
    hits.push_back({ta, tb});
    return true;
  };
  if (touches(cached.triangle_a, cached.triangle_b)) return true;
  // The crossing moves a little between ticks: look among the triangles around the cached ones.
  const int partition[2] = {pa, pb}, local[2] = {cached.triangle_a, cached.triangle_b};
  for (int side = 0; side < 2; ++side) {
    const CollisionModel::Impl& body = impl(side);
    ring[side].clear();
    ring[side].push_back(local[side]);
    const auto& corners = body.mesh.triangles[body.subs[partition[side]].triangle[local[side]]];
    for (int v : corners)
      for (int k = body.corner_start[v]; k < body.corner_start[v + 1] && ring[side].size() < kMaxRing; ++k) {
        const int t = body.corner_of[k];
        if (body.mesh.triangle_partition[t] != partition[side]) continue;
        const int id = body.local_triangle[t];
        if (std::find(ring[side].begin(), ring[side].end(), id) == ring[side].end()) ring[side].push_back(id);
      }
  }
  for (int ta : ring[0])
    for (int tb : ring[1])
      if ((ta != cached.triangle_a || tb != cached.triangle_b) && touches(ta, tb)) return true;
  return false;
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

// At most how far any point of B's partition `sub` (within its local box) has moved in A's frame
// from placement `from` to `to`: for x = c + d (c the box centre, |d| <= its half-diagonal),
// (R' - R) x + (T' - T) is at most |(R' - R) c + T' - T| + ||R' - R||_F |half|.
double motion_bound(const bvh::Relative& from, const bvh::Relative& to, const CollisionModel::Impl::Sub& sub) {
  const Eigen::Matrix3d turn = to.R - from.R;
  return (turn * sub.center + (to.T - from.T)).norm() + turn.norm() * sub.half.norm();
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

// Closest point of a body's whole surface (every partition) to world point p: its distance, the point
// (world and body frame) and the mesh triangle it lies on (-1 when the body has none). `hint`, a
// mesh triangle near p (-1: none), bounds the search from the start. One traversal of the body's
// tree (`body_tree`), or (the default) one per partition's tree nearer than the best so far; the
// same distance either way (ties between triangles may go to another of the tied ones).
double closest_point(const CollisionModel::Impl& impl, const fcl::Transform3d& transform, bvh::Traversal& traversal,
                     const Eigen::Vector3d& p, Eigen::Vector3d& closest, Eigen::Vector3d& local, int& triangle,
                     int hint = -1, bool body_tree = true) {
  const Eigen::Vector3d in_body = transform.inverse(Eigen::Isometry) * p;
  bvh::Closest best;
  best.distance = std::numeric_limits<double>::infinity();
  triangle = -1;
  if (body_tree) {
    if (!impl.body) return best.distance;
    if (hint >= 0) {
      ++traversal.triangle_tests;
      best.distance = bvh::Traversal::point_triangle_distance(*impl.body, hint, in_body, best.point_a);
      best.triangle_a = hint;
    }
    traversal.point_distance(*impl.body, in_body, best);
    triangle = best.triangle_a;  // primitive ids of the body's tree are mesh triangles
  } else {
    if (hint >= 0) {
      const int id = impl.local_triangle[hint];
      ++traversal.triangle_tests;
      best.distance = bvh::Traversal::point_triangle_distance(*impl.subs[impl.mesh.triangle_partition[hint]].bvh, id,
                                                              in_body, best.point_a);
      best.triangle_a = id;
      triangle = hint;
    }
    for (const auto& sub : impl.subs) {
      if (!sub.bvh) continue;
      if (box_gap(in_body, Eigen::Vector3d::Zero(), sub.center, sub.half) >= best.distance) continue;
      const double before = best.distance;
      traversal.point_distance(*sub.bvh, in_body, best);
      if (best.distance < before) triangle = sub.triangle[best.triangle_a];
    }
  }
  if (triangle < 0) return best.distance;
  local = best.point_a;
  closest = transform * local;
  return std::max(0.0, best.distance);
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
  out.depth_point_a = {0, 0, 0};
  out.partitions_a.clear();
  out.partitions_b.clear();
  s.transform[0] = to_fcl(place_a);
  s.transform[1] = to_fcl(place_b);
  // B in A's frame: the traversals work there.
  const fcl::Transform3d relative = s.transform[0].inverse(Eigen::Isometry) * s.transform[1];
  s.relative.R = relative.linear();
  s.relative.T = relative.translation();

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
      if (!s.enabled[1][pb] || !subs_b[pb].bvh || !s.pair_enabled[pa * subs_b.size() + pb]) continue;
      s.candidates.push_back({box_gap(s.box_center[0][pa], s.box_half[0][pa], s.box_center[1][pb], s.box_half[1][pb]),
                              static_cast<int>(pa), static_cast<int>(pb)});
    }
  }
  if (s.candidates.empty()) return;  // everything switched off: nothing to hit, infinitely far

  auto record_pair = [&](int pa, int pb, int local_a, int local_b) {
    out.partition_a = pa;
    out.partition_b = pb;
    out.triangle_a = subs_a[pa].triangle[local_a];
    out.triangle_b = subs_b[pb].triangle[local_b];
    out.face_a = s.impl(0).mesh.triangle_face[out.triangle_a];
    out.face_b = s.impl(1).mesh.triangle_face[out.triangle_b];
  };

  // Intersecting triangle pairs (up to kMaxContactsPerPair per partition pair for Penetration, the
  // first one otherwise).
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
    // Seeds of the flood: corners of an intersecting triangle pair (mesh triangles), tagged by side
    // (vertex * 2 + side).
    auto seed = [&](int mesh_triangle_a, int mesh_triangle_b) {
      const auto& ta = s.impl(0).mesh.triangles[mesh_triangle_a];
      const auto& tb = s.impl(1).mesh.triangles[mesh_triangle_b];
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
    };
    if (want_all && s.body_tree) {
      // One traversal of the two bodies' trees for every partition pair: a leaf pair counts when its
      // partition pair is a candidate within touching that has fewer than kMaxContactsPerPair
      // touching pairs so far; node pairs holding no such partition pair are not opened.
      std::fill(s.pair_wanted.begin(), s.pair_wanted.end(), 0);
      bool any_wanted = false;
      for (const State::Candidate& c : s.candidates) {
        const std::size_t index = static_cast<std::size_t>(c.a) * subs_b.size() + c.b;
        s.cached_hit[index] = {-1, -1};
        s.pair_hit_count[index] = 0;
        if (c.lower_bound > s.touching) continue;
        s.pair_wanted[index] = 1;
        any_wanted = true;
      }
      if (any_wanted) {
        s.rebuild_wanted_rows();
        struct Filter final : bvh::LeafFilter {
          State& s;
          const std::uint64_t* mask_a;
          const std::uint64_t* mask_b;
          const std::vector<int>& part_a;
          const std::vector<int>& part_b;
          std::size_t nb;
          decltype(seed)& seed_corners;
          Filter(State& state, decltype(seed)& seeding)
              : s(state),
                mask_a(state.impl(0).body_partitions.data()),
                mask_b(state.impl(1).body_partitions.data()),
                part_a(state.impl(0).mesh.triangle_partition),
                part_b(state.impl(1).mesh.triangle_partition),
                nb(state.enabled[1].size()),
                seed_corners(seeding) {}
          bool open(int node_a, int node_b) override {
            const std::uint64_t under_b = mask_b[node_b];
            for (std::uint64_t m = mask_a[node_a]; m; m &= m - 1)
              if (s.wanted_rows[__builtin_ctzll(m)] & under_b) return true;
            return false;
          }
          bool live(int ta, int tb) override {
            return s.pair_wanted[static_cast<std::size_t>(part_a[ta]) * nb + part_b[tb]] != 0;
          }
          bool hit(int ta, int tb) override {
            const int pa = part_a[ta], pb = part_b[tb];
            const std::size_t index = static_cast<std::size_t>(pa) * nb + pb;
            if (s.pair_hit_count[index]++ == 0)
              s.cached_hit[index] = {s.impl(0).local_triangle[ta], s.impl(1).local_triangle[tb]};
            s.partition_hit[0][pa] = s.partition_hit[1][pb] = 1;
            seed_corners(ta, tb);
            if (s.pair_hit_count[index] >= kMaxContactsPerPair) {  // this pair is full
              s.pair_wanted[index] = 0;
              s.rebuild_wanted_rows();
            }
            return true;
          }
        } filter(s, seed);
        any_hit = s.traversal.touching_pairs_filtered(*s.impl(0).body, *s.impl(1).body, s.relative, s.touching, filter);
        // The touching pair reported: the first found of the lowest partition pair that touches.
        for (const State::Candidate& c : s.candidates) {
          const bvh::TriangleHit hit = s.cached_hit[static_cast<std::size_t>(c.a) * subs_b.size() + c.b];
          if (hit.triangle_a < 0) continue;
          record_pair(c.a, c.b, hit.triangle_a, hit.triangle_b);
          break;
        }
      }
    }
    for (const State::Candidate& c : s.candidates) {
      if (want_all && s.body_tree) break;  // done above
      bvh::TriangleHit& cached_hit = s.cached_hit[static_cast<std::size_t>(c.a) * subs_b.size() + c.b];
      if (c.lower_bound > s.touching) {
        cached_hit = {-1, -1};
        continue;
      }
      s.hits.clear();
      // Intersect needs one touching pair per partition pair: the cached one's neighbourhood first.
      const bool near_cache = !want_all && s.warm_start && s.touching_near_cache(c.a, c.b);
      bool found = near_cache;
      if (!found && !want_all && s.warm_start && s.front_tracking) {
        // From the last traversal's front of this partition pair (exact whatever the front: a cut).
        const int pair_index = static_cast<int>(static_cast<std::size_t>(c.a) * subs_b.size() + c.b);
        State::FrontSlot& slot = s.intersect_fronts.of(pair_index);
        bool overflow = false;
        bvh::TriangleHit hit{-1, -1};
        const bool pull_up = ++slot.ticks % kPullUpEvery == 0;
        const double moved = slot.entries.empty() ? std::numeric_limits<double>::infinity()
                                                  : motion_bound(slot.made_at, s.relative, subs_b[c.b]);
        found = s.traversal.touching_pair_from_front(*subs_a[c.a].bvh, subs_a[c.a].parent, *subs_b[c.b].bvh,
                                                     subs_b[c.b].parent, s.relative, s.touching, slot.entries, moved,
                                                     pull_up, s.front_next, overflow, hit);
        if (overflow) {
          slot.entries.clear();
        } else {
          std::swap(slot.entries, s.front_next);
          slot.made_at = s.relative;
        }
        if (found) s.hits.push_back(hit);
      } else if (!found) {
        found = s.traversal.touching_pairs(*subs_a[c.a].bvh, *subs_b[c.b].bvh, s.relative, s.touching,
                                           want_all ? kMaxContactsPerPair : 1, s.hits);
      }
      if (!found) {
        cached_hit = {-1, -1};
        continue;
      }
      cached_hit = s.hits[0];
      any_hit = true;
      s.partition_hit[0][c.a] = s.partition_hit[1][c.b] = 1;
      if (out.partition_a < 0) record_pair(c.a, c.b, s.hits[0].triangle_a, s.hits[0].triangle_b);
      if (want_all)
        for (const bvh::TriangleHit& hit : s.hits)
          seed(subs_a[c.a].triangle[hit.triangle_a], subs_b[c.b].triangle[hit.triangle_b]);
    }
    if (!any_hit && s.margin >= 0) {
      // With a margin, overlaps whose boundaries do not meet count too: one body wholly inside the
      // other. No triangle pair is within the margin, so each connected piece of a body's surface
      // is wholly inside the other body or wholly outside; one vertex of each enabled partition
      // settles it (every piece holds a partition). Deeper than the margin: a vertex of a
      // switched-off partition's neighbour that only grazes the other body's matching,
      // switched-off partition (a shaft in its bore) is no overlap.
      for (int side = 0; side < 2 && !any_hit; ++side) {
        const int other = 1 - side;
        const auto& impl = s.impl(side);
        for (std::size_t p = 0; p < impl.subs.size(); ++p) {
          if (!s.enabled[side][p] || !impl.subs[p].bvh || impl.subs[p].triangle.empty()) continue;
          const int vertex = impl.mesh.triangles[impl.subs[p].triangle[0]][0];
          const auto& v = impl.mesh.vertices[vertex];
          const Eigen::Vector3d point = s.transform[side] * Eigen::Vector3d(v[0], v[1], v[2]);
          Eigen::Vector3d closest, local;
          int triangle = -1;
          const double gap = closest_point(s.impl(other), s.transform[other], s.traversal, point, closest, local,
                                           triangle, -1, s.body_tree);
          if (triangle < 0 || gap <= s.margin) continue;
          const Eigen::Vector3d normal = s.transform[other].linear() * pseudo_normal(s.impl(other), triangle, local);
          if ((point - closest).dot(normal) >= 0) continue;  // outside
          any_hit = true;
          s.partition_hit[side][p] = 1;
          if (want_all && s.stamp[side][vertex] != s.query_stamp) {  // the flood measures the depth from it
            s.stamp[side][vertex] = s.query_stamp;
            s.stack.push_back(vertex * 2 + side);
          }
          break;
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
    // Warm start: the last closest triangle pair, measured at the new placements, is a pair like any
    // other and bounds the search from the start; the traversal still finds every pair below it, so
    // the answer is the cold one (see collision.h).
    bvh::Closest best;
    best.distance = std::numeric_limits<double>::infinity();
    int best_pa = -1, best_pb = -1;
    const State::Cached& cached = s.cached_closest;
    if (s.warm_start && cached.partition_a >= 0 && s.enabled[0][cached.partition_a] &&
        s.enabled[1][cached.partition_b] &&
        s.pair_enabled[static_cast<std::size_t>(cached.partition_a) * subs_b.size() + cached.partition_b]) {
      best.triangle_a = cached.triangle_a;
      best.triangle_b = cached.triangle_b;
      ++s.traversal.triangle_tests;
      best.distance = bvh::Traversal::triangle_distance(*subs_a[cached.partition_a].bvh, cached.triangle_a,
                                                         *subs_b[cached.partition_b].bvh, cached.triangle_b,
                                                         s.relative, best.point_a, best.point_b);
      best_pa = cached.partition_a;
      best_pb = cached.partition_b;
    }
    if (best.distance > s.distance_limit) {  // beyond the limit nothing is measured: start from it
      best.distance = s.distance_limit;
      best_pa = best_pb = -1;
    }
    // The loop stops at the first pair whose boxes lie beyond the best distance, which only shrinks:
    // the pairs beyond it from the start are never measured, so only the others are sorted (a query
    // limited to a closed form's gap keeps a few of a few hundred).
    const double start_bound = best.distance + bvh::kTieSlack;
    const auto near_end = std::partition(s.candidates.begin(), s.candidates.end(),
                                         [start_bound](const State::Candidate& c) { return c.lower_bound <= start_bound; });
    std::sort(s.candidates.begin(), near_end,
              [](const State::Candidate& x, const State::Candidate& y) { return x.lower_bound < y.lower_bound; });
    for (auto it = s.candidates.begin(); it != near_end; ++it) {
      const State::Candidate& c = *it;
      if (c.lower_bound > best.distance + bvh::kTieSlack) break;
      // Ties between partition pairs go to the lower (partition A, partition B).
      using Held = bvh::Traversal::Held;
      const Held held = best_pa < 0 || std::make_pair(c.a, c.b) < std::make_pair(best_pa, best_pb) ? Held::Later
                        : std::make_pair(c.a, c.b) == std::make_pair(best_pa, best_pb)          ? Held::Same
                                                                                                 : Held::Earlier;
      bool replaced = false;
      if (s.warm_start && s.front_tracking) {
        // From the last traversal's front of this partition pair: the same answer (a cut), the pairs
        // pruned last time skipped while their bound, less B's motion since, stays above the best.
        const int pair_index = static_cast<int>(static_cast<std::size_t>(c.a) * subs_b.size() + c.b);
        State::FrontSlot& slot = s.distance_fronts.of(pair_index);
        bool overflow = false;
        const bool pull_up = ++slot.ticks % kPullUpEvery == 0;
        const double moved = slot.entries.empty() ? std::numeric_limits<double>::infinity()
                                                  : motion_bound(slot.made_at, s.relative, subs_b[c.b]);
        replaced = s.traversal.distance_from_front(*subs_a[c.a].bvh, subs_a[c.a].parent, *subs_b[c.b].bvh,
                                                   subs_b[c.b].parent, s.relative, best, 0.0, held, slot.entries,
                                                   moved, pull_up, s.front_next, overflow);
        if (overflow) {
          slot.entries.clear();
        } else {
          std::swap(slot.entries, s.front_next);
          slot.made_at = s.relative;
        }
      } else {
        replaced = s.traversal.distance(*subs_a[c.a].bvh, *subs_b[c.b].bvh, s.relative, best, 0.0, held);
      }
      if (replaced) {
        best_pa = c.a;
        best_pb = c.b;
      }
      if (best.distance <= 0) break;
    }
    if (best_pa < 0) return;
    s.cached_closest = {best_pa, best_pb, best.triangle_a, best.triangle_b};
    out.distance = std::max(0.0, best.distance);
    out.point_a = to_array(s.transform[0] * best.point_a);
    out.point_b = to_array(s.transform[0] * best.point_b);
    record_pair(best_pa, best_pb, best.triangle_a, best.triangle_b);
    if (out.distance <= 0) out.intersecting = true;
    return;
  }

  // Penetration: flood from the seeds through the vertices inside the other body.
  // Inside and depth are judged against the other body's whole surface, its
  // switched-off partitions included: without them it would not be closed.
  // Closest point of `side`'s surface to world point p (distance, point, triangle).
  // The flood moves from vertex to neighbouring vertex: the triangle closest to the last one tested
  // on a side bounds the next search on that side.
  int last_closest[2] = {-1, -1};
  auto closest_on = [&](int side, const Eigen::Vector3d& p, Eigen::Vector3d& closest, Eigen::Vector3d& local,
                        int& triangle) {
    const double gap =
        closest_point(s.impl(side), s.transform[side], s.traversal, p, closest, local, triangle, last_closest[side],
                      s.body_tree);
    if (triangle >= 0) last_closest[side] = triangle;
    return gap;
  };
  const std::size_t partitions_b = subs_b.size();
  auto masked_vertex = [&](int side, int vertex, int nearest_partition) {
    const CollisionModel::Impl& body = s.impl(side);
    for (int k = body.corner_start[vertex]; k < body.corner_start[vertex + 1]; ++k) {
      const int own = body.mesh.triangle_partition[body.corner_of[k]];
      const std::size_t index = side == 0 ? static_cast<std::size_t>(own) * partitions_b + nearest_partition
                                          : static_cast<std::size_t>(nearest_partition) * partitions_b + own;
      if (s.pair_enabled[index]) return false;
    }
    return true;
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
    // A vertex all of whose partitions are switched off against the partition of the other body's
    // surface nearest to it (set_pair_enabled: a pair answered elsewhere, in closed form) lies in
    // that pair's overlap, which is not this query's: it is neither counted nor flooded from.
    if (s.pairs_off > 0 && masked_vertex(side, vertex, s.impl(other).mesh.triangle_partition[triangle])) continue;
    if (gap > out.depth) {
      out.depth = gap;
      const Eigen::Vector3d move = side == 0 ? closest - p : p - closest;  // how A leaves
      out.direction = to_array(move.norm() > 0 ? move.normalized() : Eigen::Vector3d(-normal));
      out.depth_point_a = to_array(side == 0 ? p : closest);
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
  Eigen::Vector3d closest, local;
  int triangle = -1;
  const double best = closest_point(s.impl(side), transform, s.traversal, p, closest, local, triangle, -1, s.body_tree);
  if (triangle < 0) return 0;
  const Eigen::Vector3d normal = transform.linear() * pseudo_normal(s.impl(side), triangle, local);
  return (p - closest).dot(normal) < 0 ? best : 0;
}

}  // namespace contactcore

