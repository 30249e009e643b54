#include "contacts/pair_key.h"

#include <cmath>
#include <functional>
#include <unordered_map>

#include <gp_Trsf.hxx>

namespace contactcore {

std::size_t PairKeyHash::operator()(const PairKey& key) const {
  std::size_t h = std::hash<long long>()(key.source_a) * 1000003u ^ std::hash<long long>()(key.source_b);
  for (long long v : key.placement) h = h * 1000003u ^ std::hash<long long>()(v);
  return h;
}

PairKey pair_key(int source_a, int source_b, const Body& a, const Body& b, double linear) {
  const gp_Trsf relative =
      a.shape.Location().Transformation().Inverted().Multiplied(b.shape.Location().Transformation());
  PairKey key{source_a, source_b, {}};
  for (int row = 1; row <= 3; ++row) {
    for (int col = 1; col <= 4; ++col) {
      const double quantum = col == 4 ? linear * 1e-3 : 1e-10;
      key.placement[(row - 1) * 4 + col - 1] = std::llround(relative.Value(row, col) / quantum);
    }
  }
  return key;
}

std::vector<std::size_t> first_pairs_placed_alike(std::size_t count, const std::function<PairKey(std::size_t)>& key_of) {
  std::vector<std::size_t> first_of(count);
  std::unordered_map<PairKey, std::size_t, PairKeyHash> first;
  first.reserve(count);
  for (std::size_t k = 0; k < count; ++k) first_of[k] = first.try_emplace(key_of(k), k).first->second;
  return first_of;
}

}  // namespace contactcore
