// Internal to the simulation stage: the vector operations on points and
// directions held as std::array<double, 3> (the meshes' vertices,
// disassembly's Direction), one copy for both.
#pragma once

#include <array>
#include <cmath>

namespace contactcore {

using Point3 = std::array<double, 3>;

inline Point3 sub(const Point3& a, const Point3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
inline double dot(const Point3& a, const Point3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline Point3 cross(const Point3& a, const Point3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline double norm(const Point3& a) { return std::sqrt(dot(a, a)); }

}  // namespace contactcore
