// Stage 1: a body's rigid-body inertia (for the mechanism export, docs/mechanism.md):
// volume, centre of mass and inertia tensor of its solids at unit density, from
// OCCT's GProp volume integration, in the assembly's global axes and mm.
#pragma once

#include <array>

#include "contactcore/bodies/bodies.h"
#include "contactcore/common/errors.h"

namespace contactcore {

struct BodyInertia {
  Status status;
  double volume = 0;                    // mm^3 (the mass at unit density)
  std::array<double, 3> centre{};       // centre of mass, mm, global
  // Inertia tensor about the centre of mass, global axes, at unit density (mm^5):
  // multiply by a density (kg/mm^3) for kg mm^2. Row-major, symmetric.
  std::array<std::array<double, 3>, 3> tensor{};
};

// Never throws: an OCCT failure or signal is a failed status naming the body.
BodyInertia body_inertia(const Body& body);

}  // namespace contactcore
