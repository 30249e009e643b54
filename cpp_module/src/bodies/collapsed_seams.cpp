#include "bodies/collapsed_seams.h"

#include <cmath>

#include <BRep_Tool.hxx>
#include <Geom2d_Curve.hxx>
#include <Precision.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>

namespace contactcore {

CollapsedSeam find_collapsed_seam(const TopoDS_Shape& shape) {
  TopTools_IndexedMapOfShape faces, edges;
  TopExp::MapShapes(shape, TopAbs_FACE, faces);
  TopExp::MapShapes(shape, TopAbs_EDGE, edges);
  for (int f = 1; f <= faces.Extent(); ++f) {
    const TopoDS_Face& face = TopoDS::Face(faces(f));
    for (TopExp_Explorer it(face, TopAbs_EDGE); it.More(); it.Next()) {
      const TopoDS_Edge& edge = TopoDS::Edge(it.Current());
      if (!BRep_Tool::IsClosed(edge, face)) continue;
      // The edge's two uses on the face: the forward one takes the first curve, the reversed one the second.
      Standard_Real first1 = 0, last1 = 0, first2 = 0, last2 = 0;
      const Handle(Geom2d_Curve) one =
          BRep_Tool::CurveOnSurface(TopoDS::Edge(edge.Oriented(TopAbs_FORWARD)), face, first1, last1);
      const Handle(Geom2d_Curve) other =
          BRep_Tool::CurveOnSurface(TopoDS::Edge(edge.Oriented(TopAbs_REVERSED)), face, first2, last2);
      if (one.IsNull() || other.IsNull() || !std::isfinite(first1) || !std::isfinite(last1)) continue;
      const double middle = 0.5 * (first1 + last1);
      if (one->Value(middle).Distance(other->Value(middle)) <= Precision::PConfusion())
        return {f, edges.FindIndex(edge)};
    }
  }
  return {};
}

}  // namespace contactcore
