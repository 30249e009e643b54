// Common to the stages: disjoint sets of 0..n-1 (partition merging groups
// faces, mobility groups bodies). Path halving; the caller says which root a
// union keeps, since the stages' output order follows the roots.
#pragma once

#include <algorithm>
#include <numeric>
#include <vector>

namespace contactcore::detail {

class UnionFind {
 public:
  explicit UnionFind(int n = 0) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0); }

  int find(int i) {
    while (parent_[i] != i) i = parent_[i] = parent_[parent_[i]];
    return i;
  }
  // Joins the sets of a and b; the smaller of their two roots stays the root.
  void unite(int a, int b) {
    a = find(a), b = find(b);
    if (a != b) parent_[std::max(a, b)] = std::min(a, b);
  }
  // Joins a's set into b's: b's root becomes the root of both.
  void attach(int a, int b) {
    a = find(a), b = find(b);
    if (a != b) parent_[a] = b;
  }

 private:
  std::vector<int> parent_;
};

}  // namespace contactcore::detail
