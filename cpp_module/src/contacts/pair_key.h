// Stage 3 (contacts): body pairs placed alike. Two bodies' shapes (their
// instance sources) and the placement of the second relative to the first,
// rounded far below the tolerance: pairs with equal keys are the same two
// shapes in the same relative placement (a bolt in each of 500 plates), so
// they make the same contacts, moved, and share material or not alike. The
// contacts and the interference pass test one pair of each key.
#pragma once

#include <array>
#include <cstddef>
#include <functional>
#include <vector>

#include "contactcore/bodies/bodies.h"

namespace contactcore {

struct PairKey {
  int source_a, source_b;
  std::array<long long, 12> placement;
  bool operator==(const PairKey& o) const {
    return source_a == o.source_a && source_b == o.source_b && placement == o.placement;
  }
};
struct PairKeyHash {
  std::size_t operator()(const PairKey& key) const;
};

// `linear`: the pair's linear tolerance (the translation is rounded to a
// thousandth of it, the rotation to 1e-10).
PairKey pair_key(int source_a, int source_b, const Body& a, const Body& b, double linear);

// For each of `count` pairs, the first pair with its key (`key_of(k)`): k
// itself when it is the first. The pairs tested are those that are their own.
std::vector<std::size_t> first_pairs_placed_alike(std::size_t count, const std::function<PairKey(std::size_t)>& key_of);

}  // namespace contactcore
