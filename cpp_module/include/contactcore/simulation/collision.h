// Stage 5 (simulation), collision: collision queries between two bodies' tagged meshes (FCL 0.7,
// OBBRSS bounding volume hierarchies). A body's model is one sub-BVH per
// partition, so switching a partition off for a pair costs one flag and the
// queries skip its triangles without rebuilding anything (the paper's Fig.
// 4c: the bore and shaft of the joint being followed), and one BVH over the
// whole body with each leaf's partition (set_body_tree).
//
// Real-time use (the haptic servo loop): a CollisionModel is immutable after
// build and can be shared by any number of threads; a CollisionPair holds the
// per-pair state (partition masks, traversal stacks, the warm-start cache of
// its last closest pair) and serves one query at a time: the thread that
// queries it (the servo thread) owns it; give each thread its own pairs.
// After the first queries have grown the scratch buffers, queries do not
// allocate.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <vector>

#include "contactcore/common/errors.h"
#include "contactcore/simulation/meshes.h"

namespace contactcore {

// x' = R x + t, R row-major (rotation only: no scale, no shear).
struct RigidTransform {
  std::array<double, 9> rotation{1, 0, 0, 0, 1, 0, 0, 0, 1};
  std::array<double, 3> translation{0, 0, 0};
  static RigidTransform identity() { return {}; }
  static RigidTransform translated(double x, double y, double z) {
    RigidTransform t;
    t.translation = {x, y, z};
    return t;
  }
};

// InvalidArgument unless the placement is finite (translation within 1e100
// mm) and its rotation orthonormal with determinant +1 (within 1e-6): NaN,
// infinite, scaled, mirrored or all-zero rotations are refused (issue 25: a
// NaN placement answered "intersecting, distance 0"). Python checks every
// placement given; C++ callers with placements from outside should too.
Status check_rigid_transform(const RigidTransform& placement);

class CollisionModel;
using CollisionModelPtr = std::shared_ptr<const CollisionModel>;

struct CollisionModelResult {
  Status status;
  CollisionModelPtr model;
};

// Builds the per-partition BVHs of a tagged mesh (coordinates as in the mesh,
// i.e. the body where the assembly places it; queries add a placement).
CollisionModelResult build_collision_model(const TaggedMesh& mesh);

class CollisionModel {
 public:
  ~CollisionModel();
  CollisionModel(const CollisionModel&) = delete;
  CollisionModel& operator=(const CollisionModel&) = delete;

  int partition_count() const;
  std::size_t triangle_count() const;
  const TaggedMesh& mesh() const;

  struct Impl;
  const Impl& impl() const { return *impl_; }

 private:
  friend CollisionModelResult build_collision_model(const TaggedMesh& mesh);
  CollisionModel();
  std::unique_ptr<Impl> impl_;
};

enum class QueryKind {
  Intersect,    // do the enabled triangles of the two bodies intersect (early exit)
  Distance,     // minimum distance and closest points (0 when intersecting)
  Penetration,  // intersect, distance when apart, depth and direction when not
};

struct QueryResult {
  bool intersecting = false;
  double distance = 0;             // >= 0; 0 when the surfaces intersect; infinity when not measured
  // Closest points, world coordinates, and their triangles: of the closest pair when apart (ties
  // go to the lower partition, then triangle ids), of one touching pair when intersecting.
  std::array<double, 3> point_a{};
  std::array<double, 3> point_b{};
  int triangle_a = -1, triangle_b = -1;  // indices into each mesh's triangles
  int face_a = 0, face_b = 0;            // 1-based FaceN
  int partition_a = -1, partition_b = -1;
  // Penetration: the deepest mesh vertex of one body inside the other, its
  // depth (distance to the other's surface) and the unit direction in which
  // body A must move to reduce it. 0 and zeros when not penetrating.
  double depth = 0;
  std::array<double, 3> direction{};
  // Penetration: where the deepest point lies on A's surface (world): the
  // deepest vertex of A, or the point of A's surface closest to B's deepest
  // vertex inside A (a contact point for a constraint solver).
  std::array<double, 3> depth_point_a{};
  // Partitions of each body that take part in the intersection (ascending).
  std::vector<int> partitions_a, partitions_b;
};

class CollisionPair {
 public:
  CollisionPair(CollisionModelPtr a, CollisionModelPtr b);
  ~CollisionPair();
  CollisionPair(const CollisionPair&) = delete;
  CollisionPair& operator=(const CollisionPair&) = delete;

  // Every partition starts enabled. Ids out of range are ignored.
  void set_partition_enabled(int side, int partition, bool enabled);  // side 0: A, 1: B
  void enable_all();
  bool partition_enabled(int side, int partition) const;
  // Per partition pair (a of A, b of B): a pair switched off here is skipped by every query while
  // both partitions stay on for their other pairs (a pair answered in closed form elsewhere, see
  // analytic_distance.h). Every pair starts enabled; enable_all() restores them too. Ids out of
  // range are ignored. Allocation-free. Penetration's flood skips a vertex all of whose
  // partitions are switched off against the partition of the other body's surface nearest to it
  // (that overlap is the switched-off pair's), neither counting its depth nor flooding from it.
  // (Partitions switched off by set_partition_enabled still count there: the flood judges against
  // the whole surface.)
  void set_pair_enabled(int partition_a, int partition_b, bool enabled);
  bool pair_enabled(int partition_a, int partition_b) const;

  // One query with A placed by `place_a` and B by `place_b`. `out` is reused:
  // pass the same object every tick to stay allocation-free.
  void query(const RigidTransform& place_a, const RigidTransform& place_b, QueryKind kind,
             QueryResult& out);

  const CollisionModel& model(int side) const;

  // Temporal coherence (on by default): a Distance query (and Penetration when apart) starts from
  // the closest triangle pair of the pair's previous query, measured at the new placements, as its
  // bound, so consecutive queries of a moving body traverse little more than the contact region.
  // The traversal still visits every pair below that bound, so the answer is the cold one: the
  // same distance, and the same closest points and partitions whenever the closest pair is unique
  // (under an exact tie, e.g. parallel facets, either of the tied pairs). Switching partitions off
  // or on needs nothing: a cached pair in a switched-off partition is not used.
  void set_warm_start(bool enabled);

  // Front tracking of Intersect (on by default, with the warm start; Ehmann and Lin's generalised
  // front): the next Intersect starts from the node pairs where the last one stopped descending
  // (separated boxes, leaf pairs), descending where boxes now overlap and pulling separated sibling
  // pairs back up to their parent. The front always covers every triangle pair (a cut of the test
  // tree), so the answer is the cold one whatever the motion; its storage is reserved here.
  void set_front_tracking(bool enabled);

  // Penetration's touching triangle pairs in one traversal of the two bodies' one trees (leaves
  // filtered by their partitions, nodes by the partitions under them), and the point queries (the
  // penetration flood's closest points, depth_inside, the margin's inside test) on the body's tree,
  // instead of one tree per partition (the default: measured as fast in contact and faster out of
  // it, docs/haptics.md). The same answers either way (ties between triangles aside).
  void set_body_tree(bool enabled);

  // Distances above `limit` are not needed (a haptic loop's safety distance): Distance, and
  // Penetration when apart, then answer "farther": distance infinity, no points, at the cost of a
  // search pruned at the limit. Exact below and at the limit. Default infinity (always exact);
  // a negative limit restores it.
  void set_distance_limit(double limit);

  // Conservative queries on request (as FCL's security margin): Intersect and Penetration then
  // report "intersecting" when the enabled triangles of the two meshes come within `margin` mm of
  // each other, and also when one body lies wholly inside the other deeper than the margin
  // (boundaries that never meet: a pin sunk in a block), so the answer does not rest on any
  // sample point. A mesh lies within its chordal deflection of the exact surface, so with margin
  // >= the two meshes' deflections together, no overlap of the exact solids is missed (test:
  // random poses against OCCT Booleans); a pair reported intersecting is then at most margin
  // apart. Distance is exact as before. InvalidArgument unless finite and >= 0 (mm).
  // Default: no margin (triangles must touch; a body wholly inside another is not seen).
  Status set_margin(double margin);
  void clear_margin();
  std::optional<double> margin() const;  // nullopt: none set

  // Bounding-volume and triangle tests run by this pair's queries so far: the work of a query,
  // independent of the machine's load (benchmarks, profiling).
  struct Counts {
    std::size_t bv_tests = 0, triangle_tests = 0;
  };
  Counts counts() const;

  // How deep a world point is inside body `side` (0: A, 1: B) placed by `place`: its distance to
  // that body's whole surface (switched-off partitions included) when inside, else 0. Inside is
  // judged by the angle-weighted pseudo-normal at the closest point.
  double depth_inside(int side, const RigidTransform& place, const std::array<double, 3>& point);

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace contactcore
