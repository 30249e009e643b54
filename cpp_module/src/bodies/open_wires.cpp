#include "bodies/open_wires.h"

#include <NCollection_DataMap.hxx>
#include <TopExp.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopTools_ShapeMapHasher.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Iterator.hxx>
#include <TopoDS_Vertex.hxx>

namespace contactcore {

namespace {

// Vertices ending an odd number of the wire's boundary edges, plus missing ends.
int loose_ends(const TopoDS_Shape& wire) {
  NCollection_DataMap<TopoDS_Shape, int, TopTools_ShapeMapHasher> ends;
  int missing = 0;
  for (TopoDS_Iterator it(wire); it.More(); it.Next()) {
    const TopoDS_Shape& edge = it.Value();
    if (edge.ShapeType() != TopAbs_EDGE) continue;
    const TopAbs_Orientation orientation = edge.Orientation();
    if (orientation != TopAbs_FORWARD && orientation != TopAbs_REVERSED) continue;
    TopoDS_Vertex first, last;
    TopExp::Vertices(TopoDS::Edge(edge), first, last);
    for (const TopoDS_Vertex& vertex : {first, last}) {
      if (vertex.IsNull()) {
        ++missing;
        continue;
      }
      if (int* count = ends.ChangeSeek(vertex)) ++*count;
      else ends.Bind(vertex, 1);
    }
  }
  int odd = missing;
  for (NCollection_DataMap<TopoDS_Shape, int, TopTools_ShapeMapHasher>::Iterator it(ends); it.More(); it.Next())
    odd += it.Value() % 2;
  return odd;
}

}  // namespace

OpenWire find_open_wire(const TopoDS_Shape& shape) {
  TopTools_IndexedMapOfShape faces;
  TopExp::MapShapes(shape, TopAbs_FACE, faces);
  for (int f = 1; f <= faces.Extent(); ++f) {
    int wire = 0;
    for (TopoDS_Iterator it(faces(f)); it.More(); it.Next()) {
      if (it.Value().ShapeType() != TopAbs_WIRE) continue;
      ++wire;
      if (const int loose = loose_ends(it.Value())) return {f, wire, loose};
    }
  }
  return {};
}

}  // namespace contactcore
