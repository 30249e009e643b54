// Stage 3 (contacts), part of the interference pass (interferences.h): whether the
// boundaries of two solids cross, for the pairs where no sample point of one
// lies inside the other (a thin plate across a pin between its samples, two
// balls overlapping in a lens, crossing cylinders or bars).
#pragma once

#include <TopoDS_Shape.hxx>

#include "contactcore/partitions/partitions.h"

namespace contactcore {

// True when the boundaries of the solids `a` and `b` cross: a piece of an
// edge of one, between the points where it meets the other's faces, lies
// strictly inside the other, or two faces (not parallel planes) cross
// transversally at a point inside both. Touching (faces against faces, a
// shaft in a bore, a ball on a plane, an edge resting on or lying in a face)
// is no crossing. False proves that they share no volume when neither holds
// a vertex or edge middle of the other strictly inside (the argument is in
// boundary_crossing.cpp); true is then measured by the Boolean common.
// `typed_a`, `typed_b`: the bodies' partitions (their faces' surface types,
// free-form faces recognised). `tol.linear`: the distance below which points
// coincide; `tol.angular`: normals closer than this are parallel (a touch).
bool boundaries_cross(const TopoDS_Shape& a, const BodyPartitions& typed_a, const TopoDS_Shape& b,
                      const BodyPartitions& typed_b, const Tolerances& tol);

}  // namespace contactcore
