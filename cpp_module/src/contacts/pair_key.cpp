#include "contacts/pair_key.h"

#include <cmath>
#include <functional>

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

}  // namespace contactcore
