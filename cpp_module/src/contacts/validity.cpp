#include "contacts/validity.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include <BOPAlgo_ArgumentAnalyzer.hxx>
#include <BOPAlgo_CheckResult.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepCheck_Edge.hxx>
#include <BRepCheck_ListOfStatus.hxx>
#include <BRepCheck_Result.hxx>
#include <BRepCheck_Status.hxx>
#include <BRep_Tool.hxx>
#include <Geom2d_BSplineCurve.hxx>
#include <Geom2d_Line.hxx>
#include <Geom2d_TrimmedCurve.hxx>
#include <BRepCheck_Wire.hxx>
#include <Standard_ErrorHandler.hxx>
#include <Standard_Failure.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS_Edge.hxx>
#include <gp_Pnt.hxx>

#include "contactcore/common/parallel.h"
#include "contactcore/common/occt_guard.h"
#include "contactcore/common/out_of_memory.h"
#include "common/occt_progress.h"
#include "partitions/outlines.h"
#include "contacts/signed_volume.h"

namespace contactcore {

namespace {

double orientation(const Point2& a, const Point2& b, const Point2& c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

// True when two chords of one loop cross (each strictly through the other).
bool loop_crosses_itself(const Polygon2& loop) {
  const std::size_t n = loop.size();
  if (n < 4) return false;
  struct Chord {
    double x0, x1, y0, y1;
    std::size_t i;
  };
  std::vector<Chord> chords(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Point2& a = loop[i];
    const Point2& b = loop[(i + 1) % n];
    chords[i] = {std::min(a.x, b.x), std::max(a.x, b.x), std::min(a.y, b.y), std::max(a.y, b.y), i};
  }
  std::sort(chords.begin(), chords.end(), [](const Chord& l, const Chord& r) { return l.x0 < r.x0; });
  std::vector<const Chord*> active;
  for (const Chord& c : chords) {
    active.erase(std::remove_if(active.begin(), active.end(), [&](const Chord* o) { return o->x1 < c.x0; }),
                 active.end());
    for (const Chord* o : active) {
      if (o->y1 < c.y0 || c.y1 < o->y0) continue;
      const std::size_t i = c.i, j = o->i;
      if ((i + 1) % n == j || (j + 1) % n == i) continue;  // neighbours share a point
      const Point2 &p1 = loop[i], &p2 = loop[(i + 1) % n], &q1 = loop[j], &q2 = loop[(j + 1) % n];
      const double o1 = orientation(p1, p2, q1), o2 = orientation(p1, p2, q2);
      const double o3 = orientation(q1, q2, p1), o4 = orientation(q1, q2, p2);
      if (((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0))) return true;
    }
    active.push_back(&c);
  }
  return false;
}

// One wire of at most four edges, each an iso-parametric line in the face's
// parameters (a cylinder or cone cut by two parallels, with its seam): a
// rectangle in (u, v), which cannot cross itself.
bool iso_rectangle(const TopoDS_Face& face) {
  int wires = 0, edges = 0;
  for (TopExp_Explorer w(face, TopAbs_WIRE); w.More(); w.Next()) ++wires;
  if (wires != 1) return false;
  for (TopExp_Explorer e(face, TopAbs_EDGE); e.More(); e.Next()) {
    if (++edges > 4) return false;
    double first, last;
    Handle(Geom2d_Curve) curve = BRep_Tool::CurveOnSurface(TopoDS::Edge(e.Current()), face, first, last);
    while (!curve.IsNull() && curve->IsKind(STANDARD_TYPE(Geom2d_TrimmedCurve)))
      curve = Handle(Geom2d_TrimmedCurve)::DownCast(curve)->BasisCurve();
    if (Handle(Geom2d_Line) line = Handle(Geom2d_Line)::DownCast(curve); !line.IsNull()) {
      const gp_Dir2d d = line->Direction();
      if (std::abs(d.X()) > 1e-12 && std::abs(d.Y()) > 1e-12) return false;
    } else if (Handle(Geom2d_BSplineCurve) spline = Handle(Geom2d_BSplineCurve)::DownCast(curve); !spline.IsNull()) {
      // Poles on one iso line hold the whole curve (convex hull).
      bool same_u = true, same_v = true;
      const gp_Pnt2d first_pole = spline->Pole(1);
      for (int i = 2; i <= spline->NbPoles(); ++i) {
        same_u &= std::abs(spline->Pole(i).X() - first_pole.X()) < 1e-12;
        same_v &= std::abs(spline->Pole(i).Y() - first_pole.Y()) < 1e-12;
      }
      if (!same_u && !same_v) return false;
    } else {
      return false;
    }
  }
  return true;
}

// FaceN of the faces whose wires cross themselves. A planar face whose
// outline loops (chords within the tolerance of its edges) do not cross
// is clear; the others are checked as BRepCheck does.
std::vector<int> self_intersecting_faces(const BodyPartitions& body) {
  std::vector<int> faces;
  for (const FaceInfo& info : body.faces) {
    if (info.params.kind == SurfaceKind::Plane && !info.extent.outline.empty() &&
        std::none_of(info.extent.outline.begin(), info.extent.outline.end(), loop_crosses_itself))
      continue;
    if (info.params.kind != SurfaceKind::Plane && iso_rectangle(info.face)) continue;
    for (TopExp_Explorer w(info.face, TopAbs_WIRE); w.More(); w.Next()) {
      Handle(BRepCheck_Wire) check = new BRepCheck_Wire(TopoDS::Wire(w.Current()));
      TopoDS_Edge first, second;
      if (check->SelfIntersect(info.face, first, second, Standard_False) != BRepCheck_NoError) {
        faces.push_back(info.index);
        break;
      }
    }
  }
  return faces;
}

// Faces (1-based FaceN) with an edge used by no other face, and faces turned
// against their neighbours: across every edge two faces must run it in
// opposite directions. Each connected set of faces is given orientations
// from its first face; the fewer faces of the two orientations are the
// ones turned (a box with one face reversed: that face).
struct ShellFaults {
  std::vector<int> open, misoriented;
};

ShellFaults shell_faults(const BodyPartitions& body) {
  struct Use {
    int face;  // position in body.faces
    bool reversed;
  };
  TopTools_IndexedMapOfShape edges;
  std::vector<std::vector<Use>> uses;
  for (std::size_t k = 0; k < body.faces.size(); ++k) {
    for (TopExp_Explorer e(body.faces[k].face, TopAbs_EDGE); e.More(); e.Next()) {
      const TopoDS_Edge& edge = TopoDS::Edge(e.Current());
      if (BRep_Tool::Degenerated(edge) || !detail::bounds_the_face(edge)) continue;
      const int index = edges.Add(edge);
      if (static_cast<std::size_t>(index) > uses.size()) uses.resize(index);
      uses[index - 1].push_back({static_cast<int>(k), edge.Orientation() == TopAbs_REVERSED});
    }
  }
  ShellFaults faults;
  struct Link {
    int face;
    bool flip;
  };
  std::vector<std::vector<Link>> links(body.faces.size());
  bool turned = false;
  for (const std::vector<Use>& u : uses) {
    if (u.size() == 1) faults.open.push_back(body.faces[u[0].face].index);
    if (u.size() != 2) continue;  // open, or shared by more faces (non-manifold): no orientation to compare
    const bool flip = u[0].reversed == u[1].reversed;
    if (u[0].face == u[1].face) {  // a seam: both ways in one face
      turned |= flip;
      continue;
    }
    turned |= flip;
    links[u[0].face].push_back({u[1].face, flip});
    links[u[1].face].push_back({u[0].face, flip});
  }
  if (turned) {
    std::vector<int> parity(body.faces.size(), -1);
    for (std::size_t seed = 0; seed < body.faces.size(); ++seed) {
      if (parity[seed] >= 0) continue;
      std::vector<int> component{static_cast<int>(seed)}, stack{static_cast<int>(seed)};
      parity[seed] = 0;
      std::vector<int> conflicts;  // a Moebius-like loop: no consistent orientation
      while (!stack.empty()) {
        const int f = stack.back();
        stack.pop_back();
        for (const Link& link : links[f]) {
          const int wanted = parity[f] ^ static_cast<int>(link.flip);
          if (parity[link.face] < 0) {
            parity[link.face] = wanted;
            component.push_back(link.face);
            stack.push_back(link.face);
          } else if (parity[link.face] != wanted) {
            conflicts.push_back(f);
            conflicts.push_back(link.face);
          }
        }
      }
      const std::size_t flipped = std::count_if(component.begin(), component.end(), [&](int f) { return parity[f]; });
      const int minority = 2 * flipped <= component.size() ? 1 : 0;
      for (int f : component)
        if (flipped > 0 && parity[f] == minority) faults.misoriented.push_back(body.faces[f].index);
      for (int f : conflicts) faults.misoriented.push_back(body.faces[f].index);
    }
  }
  for (std::vector<int>* list : {&faults.open, &faults.misoriented}) {
    std::sort(list->begin(), list->end());
    list->erase(std::unique(list->begin(), list->end()), list->end());
  }
  return faults;
}

bool has_fault(const BRepCheck_ListOfStatus& statuses) {
  for (BRepCheck_ListIteratorOfListOfStatus it(statuses); it.More(); it.Next())
    if (it.Value() != BRepCheck_NoError) return true;
  return false;
}

// Faces with an edge whose 3D curve and curve on the face's surface part by
// more than the edge's tolerance (or lack one), as BRepCheck_Edge finds.
// BRepCheck_Edge::InContext looks the edge up among all of its face's edges,
// quadratic in them (a plate of 25,281 holes: hours), so faces of more than
// kMostEdgesChecked edges are left to the full analyzer.
constexpr int kMostEdgesChecked = 1000;

std::vector<int> faces_with_edges_off_their_surface(const BodyPartitions& body) {
  std::vector<int> faces;
  for (const FaceInfo& info : body.faces) {
    int edges = 0;
    for (TopExp_Explorer e(info.face, TopAbs_EDGE); e.More() && edges <= kMostEdgesChecked; e.Next()) ++edges;
    if (edges > kMostEdgesChecked) continue;
    for (TopExp_Explorer e(info.face, TopAbs_EDGE); e.More(); e.Next()) {
      Handle(BRepCheck_Edge) check = new BRepCheck_Edge(TopoDS::Edge(e.Current()));
      // An edge without its 3D curve (faulted by the constructor's own
      // checks) would be dereferenced as null by InContext in OCCT 7.6.
      const bool bad_alone = has_fault(check->Status());
      if (!bad_alone) check->InContext(info.face);
      if (bad_alone || (check->IsStatusOnShape(info.face) && has_fault(check->StatusOnShape(info.face)))) {
        faces.push_back(info.index);
        break;
      }
    }
  }
  return faces;
}

// The faces BRepCheck_Analyzer finds fault with: the face, or one of its
// wires, edges or vertices, alone or in any context (a vertex off its edge
// is faulty in the edge's); empty when the fault is the shell's or solid's.
std::vector<int> faces_failing_the_analyzer(const BRepCheck_Analyzer& analyzer, const TopoDS_Shape& shape) {
  const auto faulty = [&](const TopoDS_Shape& sub) {
    Handle(BRepCheck_Result) result;
    try {
      result = analyzer.Result(sub);
    } CONTACTS_PASS_OUT_OF_MEMORY catch (const Standard_Failure&) {
      return false;  // not checked by the analyzer (not in its map)
    }
    if (result.IsNull()) return false;
    if (has_fault(result->Status())) return true;
    for (result->InitContextIterator(); result->MoreShapeInContext(); result->NextShapeInContext())
      if (has_fault(result->StatusOnShape())) return true;
    return false;
  };
  std::vector<int> faces;
  int index = 0;
  for (TopExp_Explorer f(shape, TopAbs_FACE); f.More(); f.Next()) {
    ++index;
    bool bad = faulty(f.Current());
    for (TopAbs_ShapeEnum kind : {TopAbs_WIRE, TopAbs_EDGE, TopAbs_VERTEX})
      for (TopExp_Explorer e(f.Current(), kind); e.More() && !bad; e.Next()) bad = faulty(e.Current());
    if (bad) faces.push_back(index);
  }
  return faces;
}

// The solid checks' stage, as reported; OCCT's self-interference check of
// one body of free-form faces takes seconds, so Cancel reaches inside it.
constexpr const char* kStage = "checking solids";

// FaceN of the faces that cross or overlap other faces of the same solid
// (BOPAlgo_ArgumentAnalyzer's self-interference, the intersection of every
// pair of its sub-shapes, face against face); nullopt when none does.
// Interferences of edges and vertices only (a boundary touching itself
// along coincident edges or at points, as R08's VERIN does at a shoulder)
// are not reported: they change no area or volume.
std::optional<std::vector<int>> faces_crossing_each_other(const TopoDS_Shape& shape, detail::CancelWatch& watch) {
  BOPAlgo_ArgumentAnalyzer analyzer;
  analyzer.SetShape1(shape);
  analyzer.ArgumentTypeMode() = Standard_False;
  analyzer.SelfInterMode() = Standard_True;
  analyzer.SmallEdgeMode() = Standard_False;
  analyzer.RebuildFaceMode() = Standard_False;
  analyzer.TangentMode() = Standard_False;
  analyzer.MergeVertexMode() = Standard_False;
  analyzer.MergeEdgeMode() = Standard_False;
  analyzer.ContinuityMode() = Standard_False;
  analyzer.CurveOnSurfaceMode() = Standard_False;
  analyzer.SetRunParallel(Standard_False);  // bodies are already checked in parallel
  Handle(detail::OcctBreak) indicator = new detail::OcctBreak(watch);
  analyzer.Perform(indicator->Start());
  if (watch.cancelled() || !analyzer.HasFaulty()) return std::nullopt;
  TopTools_IndexedMapOfShape faces;
  TopExp::MapShapes(shape, TopAbs_FACE, faces);
  std::vector<int> named;
  for (BOPAlgo_ListIteratorOfListOfCheckResult it(analyzer.GetCheckResult()); it.More(); it.Next()) {
    if (it.Value().GetCheckStatus() != BOPAlgo_SelfIntersect) continue;
    const TopTools_ListOfShape& pair = it.Value().GetFaultyShapes1();
    bool faces_only = !pair.IsEmpty();
    for (TopTools_ListIteratorOfListOfShape s(pair); s.More(); s.Next())
      faces_only &= s.Value().ShapeType() == TopAbs_FACE && faces.Contains(s.Value());
    if (!faces_only) continue;
    for (TopTools_ListIteratorOfListOfShape s(pair); s.More(); s.Next()) named.push_back(faces.FindIndex(s.Value()));
  }
  if (named.empty()) return std::nullopt;
  std::sort(named.begin(), named.end());
  named.erase(std::unique(named.begin(), named.end()), named.end());
  return named;
}

double total_area(const BodyPartitions& body) {
  double area = 0;
  for (const FaceInfo& info : body.faces) area += info.area;
  return area;
}

// The first fault found, in the order of the reasons in validity.h (empty
// reason: valid).
InvalidBody check_one(const Body& body, const BodyPartitions& partitions, const Tolerances& tol, SolidChecks checks,
                      detail::CancelWatch& watch) {
  InvalidBody verdict;
  const auto found = [&](std::vector<int> faces, const char* reason) {
    if (faces.empty()) return false;
    verdict.faces = std::move(faces);
    verdict.reason = reason;
    return true;
  };
  if (found(self_intersecting_faces(partitions), kSelfIntersecting)) return verdict;
  ShellFaults shells = shell_faults(partitions);
  if (found(std::move(shells.open), kOpenShell) || found(std::move(shells.misoriented), kMisorientedFaces))
    return verdict;
  if (found(faces_with_edges_off_their_surface(partitions), kEdgesOffSurface)) return verdict;
  // Thinner on average than the linear tolerance (volume / area is half a
  // slab's thickness): no material, or the faces enclose it the wrong way.
  double x0, y0, z0, x1, y1, z1;
  partitions.box.Get(x0, y0, z0, x1, y1, z1);
  const double volume = detail::signed_volume(partitions, gp_Pnt((x0 + x1) / 2, (y0 + y1) / 2, (z0 + z1) / 2));
  const double least = total_area(partitions) * tol.linear / 2;
  if (!(volume > least)) {  // NaN too
    verdict.reason = volume < -least ? kInsideOut : kZeroVolume;
    return verdict;
  }
  if (checks == SolidChecks::Full) {
    const BRepCheck_Analyzer analyzer(body.shape);
    if (!analyzer.IsValid()) {
      verdict.faces = faces_failing_the_analyzer(analyzer, body.shape);
      verdict.reason = kFailsAnalyzer;
      return verdict;
    }
    if (std::optional<std::vector<int>> crossing = faces_crossing_each_other(body.shape, watch)) {
      verdict.faces = std::move(*crossing);
      verdict.reason = kFacesCrossing;
    }
  }
  return verdict;
}

std::string face_list(const std::vector<int>& faces) {
  if (faces.empty()) return "whole solid";
  std::string text;
  for (int f : faces) text += (text.empty() ? "Face" : ", Face") + std::to_string(f);
  return text;
}

}  // namespace

Status check_solids(const Assembly& assembly, ContactsResult& result, Progress* progress, int threads,
                    SolidChecks checks, const std::vector<char>* reusable, const SolidVerdicts* known,
                    SolidVerdicts* kept) {
  const std::size_t n = result.partitions.size();
  const auto source_of = [&](std::size_t i) {
    return i < result.instance_of.size() ? static_cast<std::size_t>(result.instance_of[i]) : i;
  };
  std::vector<InvalidBody> verdicts(n);
  std::vector<std::string> failures(n);
  // BRepCheck_Edge dereferences null curves of some damaged shapes (make
  // fuzz, fuzz_brep): OCCT's signal handler makes that a failed check of the
  // body, not a crash.
  const OcctGuard guard;
  detail::CancelWatch watch(progress, kStage);
  if (!parallel_for(n, threads, &watch, kStage, [&](std::size_t i) {
        if (source_of(i) != i || watch.cancelled()) return;
        if (reusable && known && (*reusable)[i] && known->verdicts.size() == n && known->failures.size() == n) {
          verdicts[i] = known->verdicts[i];
          failures[i] = known->failures[i];
          return;
        }
        std::string failure;
        if (!run_guarded(
                [&] { verdicts[i] = check_one(assembly.bodies[i], result.partitions[i], result.partitions[i].tolerances, checks, watch); },
                failure))
          failures[i] = "its check failed: " + failure;
      }) ||
      watch.cancelled())
    return Status::failure(StatusCode::Cancelled, "cancelled");
  if (kept) *kept = SolidVerdicts{verdicts, failures};
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t source = source_of(i);
    const std::string& name = assembly.bodies[i].name;
    if (!failures[source].empty()) {
      result.messages.push_back("body '" + name + "': " + failures[source]);
      continue;
    }
    if (verdicts[source].reason.empty()) continue;
    InvalidBody invalid{static_cast<int>(i), verdicts[source].faces, verdicts[source].reason};
    result.messages.push_back("body '" + name + "' is not a valid solid: " + invalid.reason + " (" +
                              face_list(invalid.faces) + "); its contacts and areas may be wrong");
    result.invalid_bodies.push_back(std::move(invalid));
  }
  return Status::success();
}

Status find_invalid_solids(const Assembly& assembly, const std::vector<BodyPartitions>& partitions,
                           std::vector<InvalidBody>& invalid, SolidChecks checks) {
  if (partitions.size() != assembly.bodies.size())
    return Status::failure(StatusCode::InvalidArgument, "one BodyPartitions per body expected");
  ContactsResult result;
  result.partitions = partitions;
  result.instance_of.resize(partitions.size());
  for (std::size_t i = 0; i < partitions.size(); ++i) result.instance_of[i] = static_cast<int>(i);
  const Status status = check_solids(assembly, result, nullptr, 1, checks);
  invalid = std::move(result.invalid_bodies);
  return status;
}

}  // namespace contactcore
