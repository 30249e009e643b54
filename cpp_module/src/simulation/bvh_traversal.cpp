#include "simulation/bvh_traversal.h"

#include <algorithm>
#include <cmath>

#include <fcl/narrowphase/detail/primitive_shape_algorithm/triangle_distance.h>

namespace contactcore::bvh {

namespace {

using fcl::Vector3d;
using TriangleDistance = fcl::detail::TriangleDistance<double>;

// Lower bound of the distance between a's node and b's node (FCL's RSS distance).
inline double bv_distance(const Bvh& a, int node_a, const Bvh& b, int node_b, const Relative& rel) {
  return fcl::distance(rel.R, rel.T, a.getBV(node_a).bv, b.getBV(node_b).bv);
}

// Whether a's node and b's node overlap (FCL's oriented boxes, with its small tolerance).
inline bool bv_overlap(const Bvh& a, int node_a, const Bvh& b, int node_b, const Relative& rel) {
  return fcl::overlap(rel.R, rel.T, a.getBV(node_a).bv, b.getBV(node_b).bv);
}

// Lower bound of the distance from p (a's frame) to a's node: to its rectangle, less its radius.
inline double point_bv_distance(const Bvh& a, int node, const Vector3d& p) {
  const fcl::RSSd& rss = a.getBV(node).bv.rss;
  const Vector3d local = rss.axis.transpose() * (p - rss.To);
  const Vector3d on(std::clamp(local.x(), 0.0, rss.l[0]), std::clamp(local.y(), 0.0, rss.l[1]), 0.0);
  return std::max(0.0, (local - on).norm() - rss.r);
}

// The separation of a's node and b's node (their oriented boxes), transformed as FCL's overlap() does.
inline BoxSeparation bv_separation(const Bvh& a, int node_a, const Bvh& b, int node_b, const Relative& rel) {
  const fcl::OBBd& box_a = a.getBV(node_a).bv.obb;
  const fcl::OBBd& box_b = b.getBV(node_b).bv.obb;
  return box_separation(box_a.axis.transpose() * rel.R * box_b.axis,
                        box_a.axis.transpose() * (rel.R * box_b.To + rel.T - box_a.To), box_a.extent, box_b.extent);
}

// Splits the larger of two nodes (a's when b is a leaf) and calls visit(child_a, child_b, disjoint) for
// its two children against the other node, by the oriented-box test (box_separation). The node kept is transformed
// once for both children (FCL's overlap() would redo it per pair): the boxes' relative rotation is
// axis_a^T R axis_b, their offset axis_a^T (R To_b + T - To_a).
template <typename Visit>
inline void split_by_obb(const Bvh& a, const fcl::BVNode<fcl::OBBRSSd>& na, int node_a, const Bvh& b,
                         const fcl::BVNode<fcl::OBBRSSd>& nb, int node_b, const Relative& rel, Visit&& visit) {
  const bool split_a = !na.isLeaf() && (nb.isLeaf() || na.bv.size() > nb.bv.size());
  if (split_a) {
    const fcl::OBBd& kept = nb.bv.obb;
    const fcl::Matrix3d rotated = rel.R * kept.axis;
    const Vector3d moved = rel.R * kept.To + rel.T;
    for (int child : {na.rightChild(), na.leftChild()}) {
      const fcl::OBBd& box = a.getBV(child).bv.obb;
      visit(child, node_b,
            box_separation(box.axis.transpose() * rotated, box.axis.transpose() * (moved - box.To), box.extent,
                           kept.extent));
    }
  } else {
    const fcl::OBBd& kept = na.bv.obb;
    const fcl::Matrix3d rotation = kept.axis.transpose() * rel.R;
    const Vector3d offset = kept.axis.transpose() * (rel.T - kept.To);
    for (int child : {nb.rightChild(), nb.leftChild()}) {
      const fcl::OBBd& box = b.getBV(child).bv.obb;
      visit(node_a, child,
            box_separation(rotation * box.axis, rotation * box.To + offset, kept.extent, box.extent));
    }
  }
}

// Splits the larger of a node pair (a's when b's is a leaf) into its two children pairs, each with
// the lower bound of its distance (FCL's RSS distance). The node kept is transformed once for both
// children (FCL's RSS distance would redo it per pair): the rectangles' relative rotation is
// axis_a^T R axis_b, their offset axis_a^T (R To_b + T - To_a).
template <typename Entry>
inline void split_by_rss(const Bvh& a, const fcl::BVNode<fcl::OBBRSSd>& na, const Entry& e, const Bvh& b,
                         const fcl::BVNode<fcl::OBBRSSd>& nb, const Relative& rel, Entry children[2]) {
  const bool split_a = !na.isLeaf() && (nb.isLeaf() || na.bv.size() > nb.bv.size());
  if (split_a) {
    const fcl::RSSd& kept = nb.bv.rss;
    const fcl::Matrix3d rotated = rel.R * kept.axis;
    const Vector3d moved = rel.R * kept.To + rel.T;
    const int ids[2] = {na.leftChild(), na.rightChild()};
    for (int k = 0; k < 2; ++k) {
      const fcl::RSSd& box = a.getBV(ids[k]).bv.rss;
      const double gap = fcl::rectDistance<double>(box.axis.transpose() * rotated, box.axis.transpose() * (moved - box.To),
                                                   box.l, kept.l) - (box.r + kept.r);
      children[k] = {ids[k], e.b, std::max(0.0, gap)};
    }
  } else {
    const fcl::RSSd& kept = na.bv.rss;
    const fcl::Matrix3d rotation = kept.axis.transpose() * rel.R;
    const Vector3d offset = kept.axis.transpose() * (rel.T - kept.To);
    const int ids[2] = {nb.leftChild(), nb.rightChild()};
    for (int k = 0; k < 2; ++k) {
      const fcl::RSSd& box = b.getBV(ids[k]).bv.rss;
      const double gap = fcl::rectDistance<double>(rotation * box.axis, rotation * box.To + offset, kept.l, box.l) -
                         (kept.r + box.r);
      children[k] = {e.a, ids[k], std::max(0.0, gap)};
    }
  }
}

// Appends e to a front; while e is pruned and the pair appended just before is its sibling (same
// node on the other side), pruned too, the two merge into their parent pair when parent_pruned(pa,
// pb, margin) says the parent is pruned as well (the leaves covered stay the same: the front stays
// a cut). Sets `overflow` instead of exceeding next's capacity.
template <typename ParentPruned>
void append_to_front(FrontEntry e, std::vector<FrontEntry>& next, bool& overflow, bool pull_up,
                     const std::vector<int>& parent_a, const std::vector<int>& parent_b, ParentPruned&& parent_pruned) {
  while (pull_up && e.separated && !next.empty() && next.back().separated) {
    const FrontEntry& last = next.back();
    int pa = e.a, pb = e.b;
    if (last.b == e.b && last.a != e.a && parent_a[e.a] >= 0 && parent_a[last.a] == parent_a[e.a])
      pa = parent_a[e.a];
    else if (last.a == e.a && last.b != e.b && parent_b[e.b] >= 0 && parent_b[last.b] == parent_b[e.b])
      pb = parent_b[e.b];
    else
      break;
    double margin = 0;
    if (!parent_pruned(pa, pb, margin)) break;
    next.pop_back();
    e = {pa, pb, 1, margin};
  }
  if (next.size() == next.capacity()) {
    overflow = true;
    return;
  }
  next.push_back(e);
}

}  // namespace

BoxSeparation box_separation(const fcl::Matrix3d& B, const Vector3d& T, const Vector3d& a, const Vector3d& b) {
  // FCL's obbDisjoint with the separations kept: |B| widened by its 1e-6, the same 15 axes.
  constexpr double kWiden = 1e-6;
  fcl::Matrix3d Bf = B.cwiseAbs();
  Bf.array() += kWiden;
  double margin = 0;
  bool disjoint = false;
  for (int i = 0; i < 3; ++i) {  // A's faces: unit axes
    const double gap = std::abs(T[i]) - (a[i] + Bf.row(i).dot(b));
    if (gap > 0) {
      disjoint = true;
      margin = std::max(margin, gap);
    }
  }
  for (int j = 0; j < 3; ++j) {  // B's faces
    const double gap = std::abs(B.col(j).dot(T)) - (b[j] + Bf.col(j).dot(a));
    if (gap > 0) {
      disjoint = true;
      margin = std::max(margin, gap);
    }
  }
  if (disjoint) return {true, margin};
  for (int i = 0; i < 3; ++i) {  // A's edge i across B's edge j: axis A_i x B_j, of length sin(angle)
    const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
    for (int j = 0; j < 3; ++j) {
      const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
      const double gap = std::abs(T[i2] * B(i1, j) - T[i1] * B(i2, j)) -
                         (a[i1] * Bf(i2, j) + a[i2] * Bf(i1, j) + b[j1] * Bf(i, j2) + b[j2] * Bf(i, j1));
      if (gap > 0) {
        const double length_squared = 1 - B(i, j) * B(i, j);
        return {true, length_squared > 1e-6 ? gap / std::sqrt(length_squared) : 0.0};
      }
    }
  }
  return {false, 0};
}

double Traversal::triangle_distance(const Bvh& a, int triangle_a, const Bvh& b, int triangle_b, const Relative& rel,
                                    Vector3d& point_a, Vector3d& point_b) {
  const fcl::Triangle& ta = a.tri_indices[triangle_a];
  const fcl::Triangle& tb = b.tri_indices[triangle_b];
  return TriangleDistance::triDistance(a.vertices[ta[0]], a.vertices[ta[1]], a.vertices[ta[2]], b.vertices[tb[0]],
                                       b.vertices[tb[1]], b.vertices[tb[2]], rel.R, rel.T, point_a, point_b);
}

double Traversal::point_triangle_distance(const Bvh& a, int triangle, const Vector3d& p, Vector3d& closest) {
  // The point as a triangle 1e-12 mm across (FCL has no point-triangle routine).
  const fcl::Triangle& t = a.tri_indices[triangle];
  const Vector3d q1 = p + Vector3d(1e-12, 0, 0), q2 = p + Vector3d(0, 1e-12, 0);
  Vector3d on_point;
  return TriangleDistance::triDistance(a.vertices[t[0]], a.vertices[t[1]], a.vertices[t[2]], p, q1, q2, closest,
                                       on_point);
}

template <typename Stopped>
bool Traversal::distance_search(const Bvh& a, const Bvh& b, const Relative& rel, int start_a, int start_b,
                                double lower, Closest& best, double stop_at, Held& held, bool& replaced,
                                Stopped&& stopped) {
  stack_.clear();
  stack_.push_back({start_a, start_b, lower});
  Vector3d pa, pb;
  while (!stack_.empty()) {
    const Entry e = stack_.back();
    stack_.pop_back();
    if (e.lower > best.distance + kTieSlack) {  // the bound fell since it was pushed (a tie may still win)
      stopped(e.a, e.b, e.lower, false);
      continue;
    }
    const auto& na = a.getBV(e.a);
    const auto& nb = b.getBV(e.b);
    if (na.isLeaf() && nb.isLeaf()) {
      ++triangle_tests;
      const int ta = na.primitiveId(), tb = nb.primitiveId();
      const double d = triangle_distance(a, ta, b, tb, rel, pa, pb);
      stopped(e.a, e.b, d, true);
      const bool tie_wins = held == Held::Later ||
                            (held == Held::Same && (ta < best.triangle_a || (ta == best.triangle_a && tb < best.triangle_b)));
      if (d < best.distance || (d == best.distance && tie_wins)) {
        held = Held::Same;
        replaced = true;
        best.distance = d;
        best.triangle_a = na.primitiveId();
        best.triangle_b = nb.primitiveId();
        best.point_a = pa;
        best.point_b = pb;
        if (d <= stop_at) {
          for (const Entry& rest : stack_) stopped(rest.a, rest.b, rest.lower, false);
          return true;
        }
      }
      continue;
    }
    Entry children[2];
    bv_tests += 2;
    split_by_rss(a, na, e, b, nb, rel, children);
    // The nearer pair pushed last: visited first, it lowers the bound for the other.
    if (children[0].lower < children[1].lower) std::swap(children[0], children[1]);
    for (const Entry& child : children) {
      if (child.lower <= best.distance + kTieSlack)
        stack_.push_back(child);
      else
        stopped(child.a, child.b, child.lower, false);
    }
  }
  return false;
}

bool Traversal::distance(const Bvh& a, const Bvh& b, const Relative& rel, Closest& best, double stop_at,
                         Held held) {
  if (best.distance <= stop_at) return false;
  bool replaced = false;
  ++bv_tests;
  distance_search(a, b, rel, 0, 0, bv_distance(a, 0, b, 0, rel), best, stop_at, held, replaced,
                  [](int, int, double, bool) {});
  return replaced;
}

bool Traversal::distance_from_front(const Bvh& a, const std::vector<int>& parent_a, const Bvh& b,
                                    const std::vector<int>& parent_b, const Relative& rel, Closest& best,
                                    double stop_at, Held held, const std::vector<FrontEntry>& front, double moved,
                                    bool pull_up, std::vector<FrontEntry>& next, bool& overflow) {
  next.clear();
  overflow = false;
  // Appends a pair to the next front (margin: its distance bound; separated: not a measured leaf
  // pair). Two pruned siblings merge into their parent pair while the parent's bound is above the
  // best too (pull-up, as in touching_pair_from_front).
  auto emit = [&](FrontEntry e) {
    append_to_front(e, next, overflow, pull_up, parent_a, parent_b, [&](int pa, int pb, double& margin) {
      ++bv_tests;
      margin = bv_distance(a, pa, b, pb, rel);
      return margin > best.distance + kTieSlack;
    });
  };
  const auto stopped = [&](int node_a, int node_b, double lower, bool leaf) {
    emit({node_a, node_b, leaf ? 0 : 1, lower});
  };
  const FrontEntry root{0, 0, 1, 0};
  const std::size_t size = front.empty() ? 1 : front.size();
  bool replaced = false, done = best.distance <= stop_at;
  for (std::size_t i = 0; i < size; ++i) {
    const FrontEntry& start = front.empty() ? root : front[i];
    // Every triangle pair under a front pair was at least its margin apart when the front was made,
    // and no point of b has moved more than `moved` since.
    const double lower_now = start.margin - moved;
    if (done || lower_now > best.distance + kTieSlack) {
      emit({start.a, start.b, start.separated, std::max(lower_now, 0.0)});
      continue;
    }
    ++bv_tests;
    done = distance_search(a, b, rel, start.a, start.b, bv_distance(a, start.a, b, start.b, rel), best, stop_at,
                           held, replaced, stopped);
  }
  return replaced;
}

template <class Filter>
bool Traversal::touching_walk(const Bvh& a, const Bvh& b, const Relative& rel, double touching, Filter& filter) {
  // Pruned by FCL's oriented-box overlap test (a few times cheaper than the RSS distance; its
  // tolerance only ever keeps more pairs), decided by the exact triangle distance.
  stack_.clear();
  ++bv_tests;
  // A wide threshold (a security margin): disjoint boxes closer than it are opened too.
  const bool wide = touching > kWideTouching;
  if (!filter.open(0, 0)) return false;
  if (wide) {
    const BoxSeparation root = bv_separation(a, 0, b, 0, rel);
    if (root.disjoint && root.margin > touching) return false;
  } else if (!bv_overlap(a, 0, b, 0, rel)) {
    return false;
  }
  stack_.push_back({0, 0, 0});
  Vector3d pa, pb;
  bool any = false;
  while (!stack_.empty()) {
    const Entry e = stack_.back();
    stack_.pop_back();
    const auto& na = a.getBV(e.a);
    const auto& nb = b.getBV(e.b);
    if (na.isLeaf() && nb.isLeaf()) {
      const int ta = na.primitiveId(), tb = nb.primitiveId();
      if (!filter.live(ta, tb)) continue;
      ++triangle_tests;
      if (triangle_distance(a, ta, b, tb, rel, pa, pb) <= touching) {
        any = true;
        if (!filter.hit(ta, tb)) break;
      }
      continue;
    }
    bv_tests += 2;
    split_by_obb(a, na, e.a, b, nb, e.b, rel, [&](int child_a, int child_b, BoxSeparation separation) {
      if ((!separation.disjoint || (wide && separation.margin <= touching)) && filter.open(child_a, child_b))
        stack_.push_back({child_a, child_b, 0});
    });
  }
  return any;
}

bool Traversal::touching_pairs(const Bvh& a, const Bvh& b, const Relative& rel, double touching, std::size_t limit,
                               std::vector<TriangleHit>& hits) {
  if (hits.size() >= limit) return false;
  // Every node and leaf pair wanted; hits collected up to the limit.
  struct Collect {
    std::vector<TriangleHit>& hits;
    std::size_t limit;
    bool open(int, int) const { return true; }
    bool live(int, int) const { return true; }
    bool hit(int ta, int tb) {
      hits.push_back({ta, tb});
      return hits.size() < limit;
    }
  } collect{hits, limit};
  return touching_walk(a, b, rel, touching, collect);
}

bool Traversal::touching_pairs_filtered(const Bvh& a, const Bvh& b, const Relative& rel, double touching,
                                        LeafFilter& filter) {
  // As touching_pairs, each node pair also pruned by the partitions under it.
  return touching_walk(a, b, rel, touching, filter);
}

bool Traversal::touching_pair_from_front(const Bvh& a, const std::vector<int>& parent_a, const Bvh& b,
                                         const std::vector<int>& parent_b, const Relative& rel, double touching,
                                         const std::vector<FrontEntry>& front, double moved, bool pull_up,
                                         std::vector<FrontEntry>& next, bool& overflow, TriangleHit& hit) {
  next.clear();
  overflow = false;
  // Appends a pair to the next front; a separated pair whose sibling (same node on the other side)
  // was appended just before and is separated too merges with it into their parent pair when the
  // parent's boxes are disjoint (the leaves covered stay the same: the front stays a cut).
  auto emit = [&](FrontEntry e) {
    append_to_front(e, next, overflow, pull_up, parent_a, parent_b, [&](int pa, int pb, double& margin) {
      ++bv_tests;
      const BoxSeparation parent = bv_separation(a, pa, b, pb, rel);
      margin = parent.margin;
      return parent.disjoint;
    });
  };
  const FrontEntry root{0, 0, 0};
  const std::size_t size = front.empty() ? 1 : front.size();
  // Entry::lower holds the margin of a separated pair (>= 0), -1 when the boxes overlap.
  constexpr double kOverlap = -1;
  // A wide threshold (a security margin): disjoint boxes closer than it are opened too.
  const bool wide = touching > kWideTouching;
  auto lower_of = [&](const BoxSeparation& separation) {
    return separation.disjoint && !(wide && separation.margin <= touching) ? separation.margin : kOverlap;
  };
  Vector3d pa, pb;
  for (std::size_t i = 0; i < size; ++i) {
    const FrontEntry& start = front.empty() ? root : front[i];
    if (start.separated && start.margin > moved + touching) {
      emit({start.a, start.b, 1, start.margin - moved});  // no point of b came near enough to meet a
      continue;
    }
    ++bv_tests;
    stack_.clear();
    // Children are pushed right first so that the next front keeps the left-to-right order in which
    // siblings end up adjacent.
    const BoxSeparation separation = bv_separation(a, start.a, b, start.b, rel);
    stack_.push_back({start.a, start.b, lower_of(separation)});
    while (!stack_.empty()) {
      const Entry e = stack_.back();
      stack_.pop_back();
      if (e.lower >= 0) {
        emit({e.a, e.b, 1, e.lower});
        continue;
      }
      const auto& na = a.getBV(e.a);
      const auto& nb = b.getBV(e.b);
      if (na.isLeaf() && nb.isLeaf()) {
        ++triangle_tests;
        emit({e.a, e.b, 0});
        if (triangle_distance(a, na.primitiveId(), b, nb.primitiveId(), rel, pa, pb) <= touching) {
          hit = {na.primitiveId(), nb.primitiveId()};
          // The pairs not reached yet complete the cut, those of the old front with their margins.
          while (!stack_.empty()) {
            const Entry rest = stack_.back();
            stack_.pop_back();
            emit({rest.a, rest.b, rest.lower >= 0 ? 1 : 0, std::max(rest.lower, 0.0)});
          }
          for (std::size_t j = i + 1; j < size; ++j)
            emit({front[j].a, front[j].b, front[j].separated, std::max(front[j].margin - moved, 0.0)});
          return true;
        }
        continue;
      }
      bv_tests += 2;
      split_by_obb(a, na, e.a, b, nb, e.b, rel, [&](int child_a, int child_b, BoxSeparation child) {
        stack_.push_back({child_a, child_b, lower_of(child)});
      });
    }
  }
  return false;
}

void Traversal::point_distance(const Bvh& a, const Vector3d& p, Closest& best) {
  single_stack_.clear();
  ++bv_tests;
  single_stack_.push_back({0, 0, point_bv_distance(a, 0, p)});
  Vector3d closest;
  while (!single_stack_.empty()) {
    const Entry e = single_stack_.back();
    single_stack_.pop_back();
    if (e.lower >= best.distance) continue;
    const auto& node = a.getBV(e.a);
    if (node.isLeaf()) {
      ++triangle_tests;
      const double d = point_triangle_distance(a, node.primitiveId(), p, closest);
      if (d < best.distance) {
        best.distance = d;
        best.triangle_a = node.primitiveId();
        best.point_a = closest;
      }
      continue;
    }
    Entry first{node.leftChild(), 0, 0}, second{node.rightChild(), 0, 0};
    bv_tests += 2;
    first.lower = point_bv_distance(a, first.a, p);
    second.lower = point_bv_distance(a, second.a, p);
    if (second.lower < first.lower) std::swap(first, second);
    if (second.lower < best.distance) single_stack_.push_back(second);
    if (first.lower < best.distance) single_stack_.push_back(first);
  }
}

}  // namespace contactcore::bvh
