// Part of the interference pass (step 4, interferences.h): whether the
// boundaries of two solids cross, for the pairs where no sample point of one
// lies inside the other (a thin plate across a pin between its samples, two
// balls overlapping in a lens, crossing cylinders or bars).
#pragma once

#include <TopoDS_Shape.hxx>

namespace contactcore {

// True when the boundaries of the solids `a` and `b` may cross: an edge of
// one meets a face of the other transversally away from the edge's ends, or
// two faces (not parallel planes) cross transversally at a point inside
// both. Touching (faces against faces, a shaft in a bore, a ball on a plane,
// an edge or vertex resting on a face) is no crossing. False proves that
// they share no volume when neither holds a vertex of the other strictly
// inside (see the comment in boundary_crossing.cpp); true is then settled by
// the Boolean common. `linear`: the distance below which points coincide;
// `angular`: normals closer than this are parallel (a touch).
bool boundaries_cross(const TopoDS_Shape& a, const TopoDS_Shape& b, double linear, double angular);

}  // namespace contactcore
