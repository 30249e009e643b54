// Common to the stages: a gp_XYZ's components by index, without OCCT's
// gp_XYZ::Coord(i) / SetCoord(i, v). OCCT 7.6 implements those as (&x)[i - 1],
// pointer arithmetic past the scalar member x: undefined behaviour, which
// clang 14 at -O1 and above compiles into a SetCoord(2, v) on a local that
// never reaches y (the motor's planes then had a zero reference direction,
// docs/architecture.md "Compilers"). Named members only here.
#pragma once

#include <gp_XYZ.hxx>

namespace contactcore::detail {

// Component 0 (X), 1 (Y) or 2 (Z).
inline double xyz_component(const gp_XYZ& p, int index) {
  return index == 0 ? p.X() : index == 1 ? p.Y() : p.Z();
}

// The unit vector along axis 0 (X), 1 (Y) or 2 (Z).
inline gp_XYZ xyz_unit(int index) {
  return gp_XYZ(index == 0 ? 1.0 : 0.0, index == 1 ? 1.0 : 0.0, index == 2 ? 1.0 : 0.0);
}

}  // namespace contactcore::detail
