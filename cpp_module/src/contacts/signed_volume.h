// Stage 3 (contacts), internal to the solid checks (validity.cpp): the signed volume of a solid from its typed
// faces, by the divergence theorem, far cheaper than BRepGProp.
#pragma once

#include <gp_Pnt.hxx>

#include "contactcore/partitions/partitions.h"

namespace contactcore::detail {

// Signed volume enclosed by `body`'s faces (their orientations honoured):
// negative for a solid turned inside out, zero for one whose faces enclose
// nothing (a bow-tie prism healed into faces crossing each other). `centre`:
// any point near the body (its box centre keeps the sums well conditioned).
double signed_volume(const BodyPartitions& body, const gp_Pnt& centre);

}  // namespace contactcore::detail
