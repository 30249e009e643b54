// Internal to the partitions stage: typing one face (face_typing.cpp; the
// public entry points type_face and revolution_extent_in are declared in
// partitions.h), and the angle helpers the stage shares.
#pragma once

#include <cmath>

#include "contactcore/common/angles.h"
#include "contactcore/partitions/partitions.h"

namespace contactcore::detail {

// unite() joins angular intervals separated by less than this: faces that
// meet on a seam or a split line must give one closed interval even when their
// boundaries carry round-off.
constexpr double kAngularJoinGap = 1e-6;

// An angle brought into [0, 2 pi).
inline double wrap_angle(double angle) {
  angle = std::fmod(angle, kTwoPi);
  if (angle < 0) angle += kTwoPi;
  if (angle >= kTwoPi) angle = 0;
  return angle;
}

inline bool is_revolution(SurfaceKind kind) {
  return kind == SurfaceKind::Cylinder || kind == SurfaceKind::Cone || kind == SurfaceKind::Sphere ||
         kind == SurfaceKind::Torus;
}

}  // namespace contactcore::detail
