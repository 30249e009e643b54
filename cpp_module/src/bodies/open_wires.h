// Stage 1 (bodies): faces whose boundary does not close, found before any
// Boolean meets them. OCCT's reader accepts such a face (a damaged wire
// record of a BRep that lost its edges), and its face-face intersection
// then never returns (make fuzz: IntPatch_Intersection::CheckSingularPoints
// on a sphere face bounded by its seam edge alone), polling no progress.
#pragma once

#include <TopoDS_Shape.hxx>

namespace contactcore {

// A face one of whose wires is open: `face` 1-based in TopExp::MapShapes
// order (FreeCAD's FaceN), `wire` 1-based among the face's wires,
// `loose_ends` the wire's vertices that end an odd number of its edges
// (an edge without a vertex counts one per missing end). face 0: none.
struct OpenWire {
  int face = 0;
  int wire = 0;
  int loose_ends = 0;
};

// The first such face of `shape`. A wire closes when every vertex ends an
// even number of its edges (a seam edge is in its wire twice, a closed or
// degenerate edge starts and ends on one vertex); INTERNAL and EXTERNAL
// edges are not part of the boundary and are left out.
OpenWire find_open_wire(const TopoDS_Shape& shape);

}  // namespace contactcore
