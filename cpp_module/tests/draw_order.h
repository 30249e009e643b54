// Random numbers for a call's arguments, drawn in one fixed order.
#pragma once

#include <array>
#include <cstddef>

namespace contactcore::testing {

// N numbers drawn one after the other, the last argument's first: the order
// g++ evaluates a call's arguments in, which the tests' recorded values come
// from. C++ leaves that order unspecified and clang takes the first first, so
// `f(draw(), draw())` gives each compiler other inputs.
template <std::size_t N, class Draw>
std::array<double, N> drawn_last_first(Draw&& draw) {
  std::array<double, N> values{};
  for (std::size_t i = N; i-- > 0;) values[i] = draw();
  return values;
}

}  // namespace contactcore::testing
