#include "contactcore/boundary_crossing.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include <BRepAdaptor_Curve.hxx>
#include <BRepAdaptor_Surface.hxx>
#include <BRepBndLib.hxx>
#include <BRepClass3d_SolidClassifier.hxx>
#include <BRepTopAdaptor_FClass2d.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <GeomAPI_ProjectPointOnSurf.hxx>
#include <GeomLProp_SLProps.hxx>
#include <Geom_Line.hxx>
#include <Geom_Surface.hxx>
#include <IntCurvesFace_Intersector.hxx>
#include <IntTools_Context.hxx>
#include <IntTools_Curve.hxx>
#include <IntTools_FaceFace.hxx>
#include <Precision.hxx>
#include <TopExp.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <gp_Vec.hxx>

// Why this test is complete. Let A and B be closed solids sharing volume,
// neither the same solid as the other (step 1) nor holding a vertex or an
// edge's middle of the other strictly inside (step 4's samples).
//  1. A point of A's boundary lies inside B, or of B's inside A: otherwise
//     B's interior, connected and meeting no point of A's boundary, lies all
//     inside A or all outside; sharing volume, inside; likewise A's inside B,
//     and A = B.
//  2. If an edge of either has a point inside the other: (a) cuts the edge
//     wherever it meets the other's faces, and the piece holding that point
//     lies inside, its middle too (an edge never cut is the sample already
//     classified).
//  3. Otherwise a face F of A (say) has a point inside B while its edges, and
//     B's edges, stay outside the other's interior. The part of F inside B
//     lies away from F's edges and is bounded by curves where F crosses faces
//     G of B, away from G's edges too, unless an edge of G lies exactly in F:
//     (b) samples the intersection curves of F and G for a point inside both
//     where their normals are not parallel. Such a curve is closed and inside
//     both faces (balls in a lens, a ball in a torus), a whole intersection
//     curve, so every one of its samples finds it.
// Parallel planes never cross, and faces meeting only where their normals are
// parallel touch (coincident faces, a shaft in its bore, a ball on a plane).
// Not covered: an edge of one lying exactly in a face of the other where the
// crossing runs along it with no edge of either entering the other, and
// surfaces crossing while tangent all along the crossing (z = 0 and z = x^3);
// both are borderline positions, and the intersectors' own tolerances apply.
// Each witness is sound: a point strictly inside the other, or two faces
// crossing transversally (a wedge of each inside the other next to them);
// the Boolean common then measures the volume.

namespace contactcore {

namespace {

struct FaceEntry {
  TopoDS_Face face;
  Bnd_Box box;  // enlarged by the tolerance
  bool plane = false;
  gp_Dir normal;  // planes
  std::unique_ptr<IntCurvesFace_Intersector> intersector;  // built on first use
};

struct EdgeEntry {
  TopoDS_Edge edge;
  Bnd_Box box;
};

std::vector<FaceEntry> faces_of(const TopoDS_Shape& shape, double linear) {
  TopTools_IndexedMapOfShape map;
  TopExp::MapShapes(shape, TopAbs_FACE, map);
  std::vector<FaceEntry> faces(map.Extent());
  for (int i = 1; i <= map.Extent(); ++i) {
    FaceEntry& entry = faces[i - 1];
    entry.face = TopoDS::Face(map(i));
    BRepBndLib::Add(entry.face, entry.box, Standard_False);
    entry.box.Enlarge(linear);
    const BRepAdaptor_Surface surface(entry.face, Standard_False);
    if (surface.GetType() == GeomAbs_Plane) {
      entry.plane = true;
      entry.normal = surface.Plane().Axis().Direction();
    }
  }
  return faces;
}

std::vector<EdgeEntry> edges_of(const TopoDS_Shape& shape, double linear) {
  TopTools_IndexedMapOfShape map;
  TopExp::MapShapes(shape, TopAbs_EDGE, map);
  std::vector<EdgeEntry> edges;
  for (int i = 1; i <= map.Extent(); ++i) {
    const TopoDS_Edge& edge = TopoDS::Edge(map(i));
    if (BRep_Tool::Degenerated(edge) || !BRep_Tool::IsGeometric(edge)) continue;
    EdgeEntry entry{edge, {}};
    BRepBndLib::Add(edge, entry.box, Standard_False);
    entry.box.Enlarge(linear);
    edges.push_back(std::move(entry));
  }
  return edges;
}

bool boxes_meet(const Bnd_Box& a, const Bnd_Box& b) { return !a.IsVoid() && !b.IsVoid() && !a.IsOut(b); }

Bnd_Box box_of(const std::vector<FaceEntry>& faces) {
  Bnd_Box box;
  for (const FaceEntry& f : faces) box.Add(f.box);
  return box;
}

// (a): an edge of `from` cut at every point where it meets a face of `into`
// (inside the face, on its edges, crossing or tangent): each piece lies
// wholly inside `into` or wholly outside, as its middle does. A middle
// strictly inside proves the overlap; so an edge resting on a face, or lying
// in it, proves nothing.
bool edge_enters(const EdgeEntry& e, std::vector<FaceEntry>& faces, const TopoDS_Shape& into,
                 std::unique_ptr<BRepClass3d_SolidClassifier>& classifier, double linear) {
  Handle(BRepAdaptor_Curve) curve = new BRepAdaptor_Curve(e.edge);
  const double first = curve->FirstParameter(), last = curve->LastParameter();
  std::vector<double> cuts = {first, last};
  for (FaceEntry& f : faces) {
    if (!boxes_meet(e.box, f.box)) continue;
    if (!f.intersector) f.intersector = std::make_unique<IntCurvesFace_Intersector>(f.face, linear);
    f.intersector->Perform(curve, first, last);
    if (!f.intersector->IsDone()) return true;  // undecided: the Boolean settles it
    for (int i = 1; i <= f.intersector->NbPnt(); ++i)
      cuts.push_back(std::clamp(f.intersector->WParameter(i), first, last));
  }
  // No cut: the whole edge is in or out, as its middle, one of step 4's samples.
  if (cuts.size() == 2) return false;
  std::sort(cuts.begin(), cuts.end());
  for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
    const gp_Pnt from = curve->Value(cuts[k]), to = curve->Value(cuts[k + 1]);
    const gp_Pnt middle = curve->Value(0.5 * (cuts[k] + cuts[k + 1]));
    if (middle.Distance(from) <= linear && middle.Distance(to) <= linear) continue;  // a piece within the tolerance
    if (!classifier) classifier = std::make_unique<BRepClass3d_SolidClassifier>(into);
    classifier->Perform(middle, linear);
    if (classifier->State() == TopAbs_IN) return true;
  }
  return false;
}

// Where a point on a face's surface lies: IN the face farther than `linear`
// from its edges, with the surface normal there.
bool strictly_inside(const TopoDS_Face& face, const gp_Pnt& p, double linear, gp_Dir& normal) {
  const Handle(Geom_Surface) surface = BRep_Tool::Surface(face);
  const BRepAdaptor_Surface adaptor(face);
  GeomAPI_ProjectPointOnSurf projection(p, surface, adaptor.FirstUParameter(), adaptor.LastUParameter(),
                                        adaptor.FirstVParameter(), adaptor.LastVParameter());
  if (!projection.IsDone() || projection.NbPoints() == 0 || projection.LowerDistance() > 10 * linear) return false;
  double u, v;
  projection.LowerDistanceParameters(u, v);
  const double uv_tolerance = std::max(Precision::PConfusion(),
                                       std::min(adaptor.UResolution(linear), adaptor.VResolution(linear)));
  BRepTopAdaptor_FClass2d classifier(face, uv_tolerance);
  if (classifier.Perform(gp_Pnt2d(u, v)) != TopAbs_IN) return false;
  GeomLProp_SLProps props(surface, u, v, 1, Precision::Confusion());
  if (!props.IsNormalDefined()) return false;  // a pole: no crossing decided there
  normal = props.Normal();
  return true;
}

// The parameter range of an unbounded line inside a box (the slab method);
// false when it misses the box.
bool clip_line(const gp_Lin& line, const Bnd_Box& box, double& t0, double& t1) {
  double lo[3], hi[3];
  box.Get(lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]);
  const double o[3] = {line.Location().X(), line.Location().Y(), line.Location().Z()};
  const double d[3] = {line.Direction().X(), line.Direction().Y(), line.Direction().Z()};
  t0 = -Precision::Infinite();
  t1 = Precision::Infinite();
  for (int k = 0; k < 3; ++k) {
    if (std::abs(d[k]) < 1e-12) {
      if (o[k] < lo[k] || o[k] > hi[k]) return false;
      continue;
    }
    double a = (lo[k] - o[k]) / d[k], b = (hi[k] - o[k]) / d[k];
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
  }
  return t0 < t1;
}

// (b): two faces cross at a point inside both where their normals are not
// parallel, found on their intersection curves (9 points each, clipped to
// the boxes' common part).
bool faces_cross(const FaceEntry& fa, const FaceEntry& fb, double linear, double angular,
                 const Handle(IntTools_Context)& context) {
  if (fa.plane && fb.plane && fa.normal.IsParallel(fb.normal, angular)) return false;
  IntTools_FaceFace intersection;
  intersection.SetContext(context);
  intersection.SetParameters(Standard_True, Standard_False, Standard_False, 1e-7);
  intersection.Perform(fa.face, fb.face);
  if (!intersection.IsDone()) return true;  // undecided: the Boolean settles it
  if (intersection.TangentFaces()) return false;  // coincident surfaces touch
  Bnd_Box common;  // where both faces can be
  {
    double a[6], b[6];
    fa.box.Get(a[0], a[1], a[2], a[3], a[4], a[5]);
    fb.box.Get(b[0], b[1], b[2], b[3], b[4], b[5]);
    common.Update(std::max(a[0], b[0]), std::max(a[1], b[1]), std::max(a[2], b[2]), std::min(a[3], b[3]),
                  std::min(a[4], b[4]), std::min(a[5], b[5]));
  }
  const double min_sine = std::sin(angular);
  const IntTools_SequenceOfCurves& curves = intersection.Lines();
  for (int c = 1; c <= curves.Length(); ++c) {
    const Handle(Geom_Curve) curve = curves(c).Curve();
    if (curve.IsNull()) continue;
    double t0 = curve->FirstParameter(), t1 = curve->LastParameter();
    if (Precision::IsInfinite(t0) || Precision::IsInfinite(t1)) {
      const Handle(Geom_Line) line = Handle(Geom_Line)::DownCast(curve);
      if (line.IsNull()) return true;  // an unbounded curve other than a line: undecided
      if (!clip_line(line->Lin(), common, t0, t1)) continue;
    }
    constexpr int kSamples = 9;
    for (int k = 0; k < kSamples; ++k) {
      const gp_Pnt p = curve->Value(t0 + (k + 0.5) / kSamples * (t1 - t0));
      gp_Dir na, nb;
      if (!strictly_inside(fa.face, p, linear, na) || !strictly_inside(fb.face, p, linear, nb)) continue;
      if (gp_Vec(na).Crossed(gp_Vec(nb)).Magnitude() > min_sine) return true;
    }
  }
  return false;
}

// (a) for the edges of `from` against the faces of `into`.
bool edges_enter(const std::vector<EdgeEntry>& edges, std::vector<FaceEntry>& faces, const TopoDS_Shape& into,
                 const Bnd_Box& into_box, double linear) {
  std::unique_ptr<BRepClass3d_SolidClassifier> classifier;
  for (const EdgeEntry& e : edges)
    if (boxes_meet(e.box, into_box) && edge_enters(e, faces, into, classifier, linear)) return true;
  return false;
}

}  // namespace

bool boundaries_cross(const TopoDS_Shape& a, const TopoDS_Shape& b, double linear, double angular) {
  std::vector<FaceEntry> faces_a = faces_of(a, linear), faces_b = faces_of(b, linear);
  const Bnd_Box box_a = box_of(faces_a), box_b = box_of(faces_b);
  if (!boxes_meet(box_a, box_b)) return false;
  if (edges_enter(edges_of(a, linear), faces_b, b, box_b, linear)) return true;
  if (edges_enter(edges_of(b, linear), faces_a, a, box_a, linear)) return true;
  const Handle(IntTools_Context) context = new IntTools_Context();
  for (const FaceEntry& fa : faces_a) {
    if (!boxes_meet(fa.box, box_b)) continue;
    for (const FaceEntry& fb : faces_b)
      if (boxes_meet(fa.box, fb.box) && faces_cross(fa, fb, linear, angular, context)) return true;
  }
  return false;
}

}  // namespace contactcore
