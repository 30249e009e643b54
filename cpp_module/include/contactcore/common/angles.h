// Common to every stage: the one definition of pi (M_PI is POSIX, not C++17;
// std::numbers::pi is C++20). Angles are in radians everywhere in the core;
// names ending in _deg hold degrees.
#pragma once

namespace contactcore {

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kTwoPi = 2 * kPi;

}  // namespace contactcore
