// Stage 1 (bodies): seam edges whose two curves on their face coincide,
// found before any Boolean meets them. A seam bounds a closed surface (a
// sphere's or a cylinder's u = 0 and u = 2 pi) by two parameter curves one
// period apart; a damaged BRep record can give both the same curve, which
// OCCT's reader accepts and whose face-face intersection then never returns
// (make fuzz: IntPatch_Intersection::CheckSingularPoints on such a sphere
// face), polling no progress.
#pragma once

#include <TopoDS_Shape.hxx>

namespace contactcore {

// A face with a collapsed seam: `face` 1-based in TopExp::MapShapes order
// (FreeCAD's FaceN), `edge` 1-based among the shape's edges (EdgeN). face 0:
// none.
struct CollapsedSeam {
  int face = 0;
  int edge = 0;
};

// The first such seam of `shape`: an edge closed on its face (two parameter
// curves) whose two curves give the same parameter point at the middle of
// the edge's range. May throw Standard_Failure from OCCT.
CollapsedSeam find_collapsed_seam(const TopoDS_Shape& shape);

}  // namespace contactcore
