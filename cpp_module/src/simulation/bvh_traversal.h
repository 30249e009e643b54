// Stage 5 (simulation): traversals of FCL's OBBRSS hierarchies driven by the collision queries
// themselves (FCL's bounding-volume and triangle distance routines, our
// loops): fcl::distance cannot be seeded with a known upper bound (its
// preprocess starts from triangles 0 and 0), cannot stop at a threshold, and
// fcl::collide's triangle test reports some nearly parallel, merely nearby
// triangles as crossing, which cost a full distance query to refute.
#pragma once

#include <cstddef>
#include <vector>

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/math/bv/OBBRSS.h>

namespace contactcore::bvh {

using Bvh = fcl::BVHModel<fcl::OBBRSSd>;

// Node pairs (and partition pairs) are pruned only when their bound exceeds the best distance by
// this much (mm): a pair holding a tie (a closest point on a corner or edge belongs to every
// triangle around it; a sphere's pole touching a plane, to the whole fan) is then always reached,
// whatever the rounding of the bounds on the way to it, so that every search order (from the roots,
// from a warm start, from a front) breaks the tie the same way.
constexpr double kTieSlack = 1e-9;

// B's frame expressed in A's: a point x of B is at R x + T in A's frame.
// Touching thresholds above this (mm) are security margins: the traversals then open disjoint box
// pairs whose distance bound is within the threshold (below it, disjoint boxes are pruned).
constexpr double kWideTouching = 1e-9;

struct Relative {
  fcl::Matrix3d R = fcl::Matrix3d::Identity();
  fcl::Vector3d T = fcl::Vector3d::Zero();
};

// The best triangle pair so far: the bound a traversal must beat, then its answer.
struct Closest {
  double distance = 0;
  int triangle_a = -1, triangle_b = -1;  // local triangle ids of each hierarchy
  fcl::Vector3d point_a{0, 0, 0}, point_b{0, 0, 0};  // in A's frame
};

struct TriangleHit {
  int triangle_a, triangle_b;
};

// One node pair of a front (Ehmann and Lin's generalised front tracking): a set of node pairs whose
// products of leaves partition all triangle pairs of the two hierarchies (a cut of the bounding
// volume test tree). Whatever the placements, a search that tests every front pair and descends
// those whose boxes overlap visits every triangle pair a search from the roots could reach, so its
// answer is the cold one by construction: a stale front (after a jump, a partition switched off and
// on) costs tests, never correctness. `separated`: the boxes were disjoint when last tested, then
// `margin` is a lower bound of their distance at the placements the front was made for (0: none
// known).
struct FrontEntry {
  int a, b, separated;
  double margin = 0;
};

// Whether two oriented boxes are disjoint by the separating-axis test (FCL's obbDisjoint, the same
// axes, order and tolerance), and when they are, a lower bound of their distance: the largest
// separation along a face axis, else along the first separating edge-edge axis (normalised; 0
// when that axis is nearly degenerate). Box A is axis-aligned at the origin with half-extents a; B
// has rotation B, centre T and half-extents b in A's frame.
struct BoxSeparation {
  bool disjoint;
  double margin;
};
BoxSeparation box_separation(const fcl::Matrix3d& B, const fcl::Vector3d& T, const fcl::Vector3d& a,
                             const fcl::Vector3d& b);

// What a traversal of two whole-body trees (leaves tagged by partition) may visit: a node pair is
// opened only while open() says some partition pair still wanted lies under both nodes, a leaf pair
// measured only when live() says its partition pair is wanted; hit() receives each touching leaf pair
// (primitive ids) and returns false to stop the traversal.
class LeafFilter {
 public:
  virtual ~LeafFilter() = default;
  virtual bool open(int node_a, int node_b) = 0;
  virtual bool live(int triangle_a, int triangle_b) = 0;
  virtual bool hit(int triangle_a, int triangle_b) = 0;
};

class Traversal {
 public:
  // A depth-first stack holds about one entry per level of both trees: reserved for trees up to
  // 512 levels deep together, so that queries do not allocate (deeper trees grow it once).
  Traversal() {
    stack_.reserve(1024);
    single_stack_.reserve(1024);
  }

  // Exact distance of one triangle pair (the routine the traversals use: same inputs, same bits).
  static double triangle_distance(const Bvh& a, int triangle_a, const Bvh& b, int triangle_b, const Relative& rel,
                                  fcl::Vector3d& point_a, fcl::Vector3d& point_b);

  // How a pair at exactly the held distance compares with the held one (ties are common: a closest
  // point on an edge or corner belongs to every triangle around it): the held pair comes from an
  // earlier hierarchy pair (it stays), a later one (the tie takes over), or this one (lower ids win).
  enum class Held { Earlier, Same, Later };

  // Lowers `best` to the minimum distance between a's and b's triangles when that is below
  // best.distance, ties broken as above, so that the answer does not depend on the bound it
  // started from. Stops early once best.distance <= stop_at (then any pair that low). Returns
  // whether it replaced the held pair.
  bool distance(const Bvh& a, const Bvh& b, const Relative& rel, Closest& best, double stop_at, Held held);

  // distance() started from `front` (empty: the roots) instead of the roots, with the same answer
  // (the front is a cut): a front pair whose margin (its distance bound when the front was made)
  // less `moved` (as in touching_pair_from_front) exceeds the best distance is kept without a test.
  // The pairs where this search stopped (pruned, leaves measured) go into `next` with their bounds,
  // `overflow` set instead when its capacity would be exceeded.
  bool distance_from_front(const Bvh& a, const std::vector<int>& parent_a, const Bvh& b,
                           const std::vector<int>& parent_b, const Relative& rel, Closest& best, double stop_at,
                           Held held, const std::vector<FrontEntry>& front, double moved, bool pull_up,
                           std::vector<FrontEntry>& next, bool& overflow);

  // Triangle pairs at most `touching` apart, appended to `hits` until it holds `limit` pairs.
  // Returns whether any was found. Above kWideTouching (a security margin), box pairs that are
  // disjoint but may be closer than `touching` are opened too (their distance bound decides).
  bool touching_pairs(const Bvh& a, const Bvh& b, const Relative& rel, double touching, std::size_t limit,
                      std::vector<TriangleHit>& hits);

  // touching_pairs on two whole-body trees, filtered by partition (LeafFilter): one traversal for
  // every partition pair instead of one per pair. Returns whether any pair touched.
  bool touching_pairs_filtered(const Bvh& a, const Bvh& b, const Relative& rel, double touching, LeafFilter& filter);

  // touching_pairs with limit 1 started from `front` (empty: the roots) instead of the roots; the
  // front where this search stopped descending goes into `next` (its capacity is never exceeded:
  // `overflow` is set instead and `next` is then not a front). Sibling pairs both separated are
  // replaced by their parent pair when that is separated too (pull-up, when `pull_up`), so the front
  // follows a sliding contact without growing. parent_a/parent_b: each node's parent (-1: root).
  // `moved`: at most how far any point of b's hierarchy has moved relative to a's since `front` was
  // made (infinity: unknown); a separated pair whose margin exceeds it (and `touching`) is still
  // separated, and kept without a test, its margin less `moved` (motion-bounded pruning).
  bool touching_pair_from_front(const Bvh& a, const std::vector<int>& parent_a, const Bvh& b,
                                const std::vector<int>& parent_b, const Relative& rel, double touching,
                                const std::vector<FrontEntry>& front, double moved, bool pull_up,
                                std::vector<FrontEntry>& next, bool& overflow, TriangleHit& hit);

  // Lowers `best` (point_b unused) to the distance from point p (a's frame) to a's triangles.
  void point_distance(const Bvh& a, const fcl::Vector3d& p, Closest& best);
  static double point_triangle_distance(const Bvh& a, int triangle, const fcl::Vector3d& p, fcl::Vector3d& closest);

  // Bounding-volume and triangle tests since construction (profiling, tests).
  std::size_t bv_tests = 0, triangle_tests = 0;

 private:
  // The walk both touching_pairs and touching_pairs_filtered make: node pairs opened while
  // filter.open() allows, leaf pairs measured when filter.live(), each touching one handed to
  // filter.hit() (false: stop). A template so that the unfiltered walk calls no virtual function.
  template <class Filter>
  bool touching_walk(const Bvh& a, const Bvh& b, const Relative& rel, double touching, Filter& filter);

  struct Entry {
    int a, b;
    double lower;
  };
  // distance()'s depth-first search from one node pair (its bound `lower`): every pair where it
  // stops (pruned by the best distance, a leaf pair measured, left on the stack when it stopped
  // early) goes to stopped(a, b, bound, leaf). Returns whether it stopped early (best <= stop_at).
  template <typename Stopped>
  bool distance_search(const Bvh& a, const Bvh& b, const Relative& rel, int start_a, int start_b, double lower,
                       Closest& best, double stop_at, Held& held, bool& replaced, Stopped&& stopped);

  std::vector<Entry> stack_;
  std::vector<Entry> single_stack_;
};

}  // namespace contactcore::bvh
