#include "contacts/boundary_crossing.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include <Bnd_Box.hxx>
#include <BRep_Tool.hxx>
#include <BRepAdaptor_Curve.hxx>
#include <BRepAdaptor_Surface.hxx>
#include <BRepBndLib.hxx>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeVertex.hxx>
#include <BRepClass3d_SolidClassifier.hxx>
#include <BRepExtrema_DistShapeShape.hxx>
#include <BRepTopAdaptor_FClass2d.hxx>
#include <Geom_Line.hxx>
#include <Geom_Surface.hxx>
#include <GeomAPI_ProjectPointOnSurf.hxx>
#include <GeomLProp_SLProps.hxx>
#include <IntCurvesFace_Intersector.hxx>
#include <IntTools_Context.hxx>
#include <IntTools_Curve.hxx>
#include <IntTools_FaceFace.hxx>
#include <Precision.hxx>
#include <TopExp.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <gp_Ax2.hxx>
#include <gp_Circ.hxx>
#include <gp_Lin.hxx>
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
// Pairs are dropped only where no crossing can be (may_cross, may_enter: a
// face or edge outside a surface's inside never crosses it). Parallel planes
// never cross, and faces that meet only where their normals are parallel
// touch (coincident faces, a shaft in its bore, a ball on a plane).
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
  SurfaceParams params;  // the partitions' typing (free-form faces recognised)
  Bnd_Box box;           // enlarged by the tolerance
  std::unique_ptr<IntCurvesFace_Intersector> intersector;  // built on first use
  // Locating points on the face, built on first use.
  std::unique_ptr<GeomAPI_ProjectPointOnSurf> projector;
  std::unique_ptr<BRepTopAdaptor_FClass2d> bounds;
  double uv_tolerance = 0;
};

struct EdgeEntry {
  TopoDS_Edge edge;
  Bnd_Box box;
};

std::vector<FaceEntry> faces_of(const BodyPartitions& body, double linear) {
  std::vector<FaceEntry> faces(body.faces.size());
  for (std::size_t i = 0; i < faces.size(); ++i) {
    FaceEntry& entry = faces[i];
    entry.face = body.faces[i].face;
    entry.params = body.faces[i].params;
    BRepBndLib::Add(entry.face, entry.box, Standard_False);
    entry.box.Enlarge(linear);
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

// The distance from a point, line or circle to a face or edge (BRepExtrema).
double distance_to(const TopoDS_Shape& core, const TopoDS_Shape& face) {
  BRepExtrema_DistShapeShape distance(core, face);
  return distance.IsDone() && distance.NbSolution() > 0 ? distance.Value() : 0;
}

// Signed distances of a box's corners to a plane (or their positions along
// a line): their range.
void box_sides(const Bnd_Box& box, const gp_Pnt& origin, const gp_Dir& normal, double& low, double& high) {
  double x[2], y[2], z[2];
  box.Get(x[0], y[0], z[0], x[1], y[1], z[1]);
  low = Precision::Infinite();
  high = -Precision::Infinite();
  for (int i = 0; i < 8; ++i) {
    const double d = gp_Vec(origin, gp_Pnt(x[i & 1], y[(i >> 1) & 1], z[(i >> 2) & 1])).Dot(gp_Vec(normal));
    low = std::min(low, d);
    high = std::max(high, d);
  }
}

// The core of a face's surface, whose distance tells whether a shape enters
// the surface's open inside: a sphere's centre, a cylinder's axis (a segment
// over `span`'s projection), a torus's tube circle; null for other kinds.
TopoDS_Shape surface_core(const SurfaceParams& p, const Bnd_Box& span, double& inside_radius) {
  switch (p.kind) {
    case SurfaceKind::Sphere:
      inside_radius = p.radius;
      return BRepBuilderAPI_MakeVertex(p.location).Vertex();
    case SurfaceKind::Cylinder: {
      double t0, t1;
      box_sides(span, p.location, p.axis, t0, t1);
      inside_radius = p.radius;
      return BRepBuilderAPI_MakeEdge(gp_Lin(p.location, p.axis), t0, t1).Edge();
    }
    case SurfaceKind::Torus:
      inside_radius = p.minor_radius;
      return BRepBuilderAPI_MakeEdge(gp_Circ(gp_Ax2(p.location, p.axis), p.radius)).Edge();
    default:
      return TopoDS_Shape();
  }
}

// False when `shape` stays outside the open inside of f's sphere, cylinder or
// torus tube: it cannot cross f's surface (it may touch it).
bool may_enter(const FaceEntry& f, const TopoDS_Shape& shape, const Bnd_Box& shape_box, double linear) {
  double inside_radius = 0;
  const TopoDS_Shape core = surface_core(f.params, shape_box, inside_radius);
  return core.IsNull() || distance_to(core, shape) < inside_radius - linear;
}

// Where a point near a face's surface lies in the face (IN, ON its edges or
// OUT), with its surface parameters; OUT when farther than `max_distance`
// from the surface.
TopAbs_State locate(FaceEntry& f, const gp_Pnt& p, double max_distance, double linear, double& u, double& v) {
  if (f.box.IsOut(p)) return TopAbs_OUT;
  if (!f.projector) {
    const BRepAdaptor_Surface adaptor(f.face);
    f.projector = std::make_unique<GeomAPI_ProjectPointOnSurf>();
    f.projector->Init(BRep_Tool::Surface(f.face), adaptor.FirstUParameter(), adaptor.LastUParameter(),
                      adaptor.FirstVParameter(), adaptor.LastVParameter());
    f.uv_tolerance = std::max(Precision::PConfusion(),
                              std::min(adaptor.UResolution(linear), adaptor.VResolution(linear)));
    f.bounds = std::make_unique<BRepTopAdaptor_FClass2d>(f.face, f.uv_tolerance);
  }
  f.projector->Perform(p);
  if (!f.projector->IsDone() || f.projector->NbPoints() == 0 || f.projector->LowerDistance() > max_distance)
    return TopAbs_OUT;
  f.projector->LowerDistanceParameters(u, v);
  return f.bounds->Perform(gp_Pnt2d(u, v));
}

// (a): an edge of `from` cut at every point where it meets a face of `into`
// (inside the face, on its edges, crossing or tangent): each piece lies
// wholly inside `into` or wholly outside, as its middle does. A middle
// strictly inside proves the overlap; so an edge resting on a face, or lying
// in it, proves nothing (a piece lying on the face that cut it is skipped
// without classifying it: a ball's seam along its groove cuts into a hundred).
bool edge_enters(const EdgeEntry& e, std::vector<FaceEntry>& faces, const TopoDS_Shape& into,
                 std::unique_ptr<BRepClass3d_SolidClassifier>& classifier, double linear) {
  Handle(BRepAdaptor_Curve) curve = new BRepAdaptor_Curve(e.edge);
  const double first = curve->FirstParameter(), last = curve->LastParameter();
  std::vector<std::pair<double, int>> cuts = {{first, -1}, {last, -1}};  // parameter, face cutting there
  for (std::size_t i = 0; i < faces.size(); ++i) {
    FaceEntry& f = faces[i];
    // An edge staying outside a sphere's, cylinder's or torus tube's inside
    // only touches the face: the pieces on either side are in or out alike.
    if (!boxes_meet(e.box, f.box) || !may_enter(f, e.edge, e.box, linear)) continue;
    if (!f.intersector) f.intersector = std::make_unique<IntCurvesFace_Intersector>(f.face, linear);
    f.intersector->Perform(curve, first, last);
    if (!f.intersector->IsDone()) return true;  // undecided: the Boolean settles it
    for (int k = 1; k <= f.intersector->NbPnt(); ++k)
      cuts.push_back({std::clamp(f.intersector->WParameter(k), first, last), static_cast<int>(i)});
  }
  // No cut: the whole edge is in or out, as its middle, one of step 4's samples.
  if (cuts.size() == 2) return false;
  std::sort(cuts.begin(), cuts.end());
  for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
    const gp_Pnt from = curve->Value(cuts[k].first), to = curve->Value(cuts[k + 1].first);
    const gp_Pnt middle = curve->Value(0.5 * (cuts[k].first + cuts[k + 1].first));
    if (middle.Distance(from) <= linear && middle.Distance(to) <= linear) continue;  // a piece within the tolerance
    bool on_boundary = false;
    for (const int face : {cuts[k].second, cuts[k + 1].second}) {
      double u, v;
      if (face >= 0 && !on_boundary) on_boundary = locate(faces[face], middle, linear, linear, u, v) != TopAbs_OUT;
    }
    if (on_boundary) continue;
    if (!classifier) classifier = std::make_unique<BRepClass3d_SolidClassifier>(into);
    classifier->Perform(middle, linear);
    if (classifier->State() == TopAbs_IN) return true;
  }
  return false;
}

// A point on a face's surface strictly inside the face (ON within the
// tolerance of its edges is not), with the surface normal there.
bool strictly_inside(FaceEntry& f, const gp_Pnt& p, double linear, gp_Dir& normal) {
  double u, v;
  if (locate(f, p, 10 * linear, linear, u, v) != TopAbs_IN) return false;
  GeomLProp_SLProps props(BRep_Tool::Surface(f.face), u, v, 1, Precision::Confusion());
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

// False when face g cannot cross the surface of face f transversally inside
// both: crossing a surface needs points strictly on both of its sides, so g
// staying outside a sphere's, cylinder's or torus tube's open inside, or on
// one side of a plane, proves it (a ball in its groove, a shaft end on a
// face, parallel planes). Cheap cases first; true when undecided.
bool may_cross(const FaceEntry& f, const FaceEntry& g, double linear, double angular) {
  const SurfaceParams& p = f.params;
  const SurfaceParams& q = g.params;
  switch (p.kind) {
    case SurfaceKind::Plane: {
      if (q.kind == SurfaceKind::Plane && p.axis.IsParallel(q.axis, angular)) return false;
      const double centre = gp_Vec(p.location, q.location).Dot(gp_Vec(p.axis));
      if (q.kind == SurfaceKind::Sphere) return std::abs(centre) < q.radius - linear;
      if (q.kind == SurfaceKind::Cylinder && p.axis.IsNormal(q.axis, angular))
        return std::abs(centre) < q.radius - linear;
      if (q.kind == SurfaceKind::Torus && p.axis.IsParallel(q.axis, angular))
        return std::abs(centre) < q.minor_radius - linear;
      double low, high;
      // g's box, enlarged by the tolerance (at most 1.8 of it along any
      // direction): g on one side, up to twice the tolerance, never crosses.
      box_sides(g.box, p.location, p.axis, low, high);
      return low < -2 * linear && high > 2 * linear;
    }
    case SurfaceKind::Sphere:
    case SurfaceKind::Cylinder:
    case SurfaceKind::Torus:
      return may_enter(f, g.face, g.box, linear);
    default:
      return true;
  }
}

// (b): two faces cross at a point inside both where their normals are not
// parallel, found on their intersection curves (9 points each, clipped to
// the boxes' common part).
bool faces_cross(FaceEntry& fa, FaceEntry& fb, double linear, double angular,
                 const Handle(IntTools_Context)& context) {
  if (!may_cross(fa, fb, linear, angular) || !may_cross(fb, fa, linear, angular)) return false;
  // Free-form faces: apart faces never cross (cheaper than intersecting them).
  if ((fa.params.kind == SurfaceKind::Other || fb.params.kind == SurfaceKind::Other) &&
      distance_to(fa.face, fb.face) > linear)
    return false;
  Bnd_Box common;  // where both faces can be
  {
    double a[6], b[6];
    fa.box.Get(a[0], a[1], a[2], a[3], a[4], a[5]);
    fb.box.Get(b[0], b[1], b[2], b[3], b[4], b[5]);
    common.Update(std::max(a[0], b[0]), std::max(a[1], b[1]), std::max(a[2], b[2]), std::min(a[3], b[3]),
                  std::min(a[4], b[4]), std::min(a[5], b[5]));
  }
  const double min_sine = std::sin(angular);
  constexpr int kSamples = 9;
  // A crossing at one of kSamples points of a curve, over [t0, t1].
  const auto crossing_on = [&](const Handle(Geom_Curve)& curve, double t0, double t1) {
    for (int k = 0; k < kSamples; ++k) {
      const gp_Pnt p = curve->Value(t0 + (k + 0.5) / kSamples * (t1 - t0));
      gp_Dir na, nb;
      if (!strictly_inside(fa, p, linear, na) || !strictly_inside(fb, p, linear, nb)) continue;
      if (gp_Vec(na).Crossed(gp_Vec(nb)).Magnitude() > min_sine) return true;
    }
    return false;
  };
  if (fa.params.kind == SurfaceKind::Plane && fb.params.kind == SurfaceKind::Plane) {
    // Two planes (stored as free-form surfaces too) meet in a line: no
    // surface intersector needed. Its point closest to fa's origin.
    const gp_Vec n1(fa.params.axis), n2(fb.params.axis);
    const gp_Vec direction = n1.Crossed(n2);
    const double d1 = n1.Dot(gp_Vec(fa.params.location.XYZ())), d2 = n2.Dot(gp_Vec(fb.params.location.XYZ()));
    const gp_Vec through = (n2.Crossed(direction) * d1 + direction.Crossed(n1) * d2) / direction.SquareMagnitude();
    const gp_Lin line(gp_Pnt(through.XYZ()), gp_Dir(direction));
    double t0, t1;
    return clip_line(line, common, t0, t1) && crossing_on(new Geom_Line(line), t0, t1);
  }
  IntTools_FaceFace intersection;
  intersection.SetContext(context);
  intersection.SetParameters(Standard_True, Standard_False, Standard_False, 1e-7);
  intersection.Perform(fa.face, fb.face);
  if (!intersection.IsDone()) return true;  // undecided: the Boolean settles it
  if (intersection.TangentFaces()) return false;  // coincident surfaces touch
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
    if (crossing_on(curve, t0, t1)) return true;
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

bool boundaries_cross(const TopoDS_Shape& a, const BodyPartitions& typed_a, const TopoDS_Shape& b,
                      const BodyPartitions& typed_b, const Tolerances& tol) {
  const double linear = tol.linear, angular = tol.angular;
  std::vector<FaceEntry> faces_a = faces_of(typed_a, linear), faces_b = faces_of(typed_b, linear);
  const Bnd_Box box_a = box_of(faces_a), box_b = box_of(faces_b);
  if (!boxes_meet(box_a, box_b)) return false;
  if (edges_enter(edges_of(a, linear), faces_b, b, box_b, linear)) return true;
  if (edges_enter(edges_of(b, linear), faces_a, a, box_a, linear)) return true;
  const Handle(IntTools_Context) context = new IntTools_Context();
  for (FaceEntry& fa : faces_a) {
    if (!boxes_meet(fa.box, box_b)) continue;
    for (FaceEntry& fb : faces_b)
      if (boxes_meet(fa.box, fb.box) && faces_cross(fa, fb, linear, angular, context)) return true;
  }
  return false;
}

}  // namespace contactcore
