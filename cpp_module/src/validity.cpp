#include "contactcore/validity.h"

#include <algorithm>
#include <cmath>

#include <BRepCheck_Status.hxx>
#include <BRep_Tool.hxx>
#include <Geom2d_BSplineCurve.hxx>
#include <Geom2d_Line.hxx>
#include <Geom2d_TrimmedCurve.hxx>
#include <BRepCheck_Wire.hxx>
#include <Standard_Failure.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>

#include "contactcore/parallel.h"

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

std::string face_list(const std::vector<int>& faces) {
  std::string text;
  for (int f : faces) text += (text.empty() ? "Face" : ", Face") + std::to_string(f);
  return text;
}

}  // namespace

Status check_solids(const Assembly& assembly, ContactsResult& result, Progress* progress, int threads) {
  const std::size_t n = result.partitions.size();
  const auto source_of = [&](std::size_t i) {
    return i < result.instance_of.size() ? static_cast<std::size_t>(result.instance_of[i]) : i;
  };
  std::vector<std::vector<int>> faces(n);
  std::vector<std::string> failures(n);
  if (!parallel_for(n, threads, progress, "checking solids", [&](std::size_t i) {
        if (source_of(i) != i) return;
        try {
          faces[i] = self_intersecting_faces(result.partitions[i]);
        } catch (const Standard_Failure& failure) {
          failures[i] = std::string("its check failed: ") + failure.GetMessageString();
        }
      }))
    return Status::failure(StatusCode::Cancelled, "cancelled");
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t source = source_of(i);
    const std::string& name = assembly.bodies[i].name;
    if (!failures[source].empty()) {
      result.messages.push_back("body '" + name + "': " + failures[source]);
      continue;
    }
    if (faces[source].empty()) continue;
    InvalidBody invalid{static_cast<int>(i), faces[source], "self-intersecting boundary"};
    result.messages.push_back("body '" + name + "' is not a valid solid: " + invalid.reason + " (" +
                              face_list(invalid.faces) + "); its contacts and areas may be wrong");
    result.invalid_bodies.push_back(std::move(invalid));
  }
  return Status::success();
}

}  // namespace contactcore
