#include "contacts/signed_volume.h"

#include <vector>

#include <BRepAdaptor_Curve.hxx>
#include <BRepGProp_Domain.hxx>
#include <BRepGProp_Face.hxx>
#include <BRepGProp_Vinert.hxx>
#include <BRep_Tool.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Iterator.hxx>

#include "partitions/outlines.h"
#include "common/quadrature.h"

namespace contactcore::detail {

namespace {

// Vector area of a face, the integral of its outward normal over it, by
// Stokes: half the boundary integral of p x dp (edges in the face's
// orientation; seams cancel, degenerated edges add nothing). Exact to
// round-off on the project's Gauss pieces (quadrature.h).
gp_XYZ vector_area(const TopoDS_Face& face, const gp_XYZ& centre) {
  std::vector<double> breaks;
  gp_XYZ total(0, 0, 0);
  for (TopExp_Explorer edges(face, TopAbs_EDGE); edges.More(); edges.Next()) {
    const TopoDS_Edge& edge = TopoDS::Edge(edges.Current());
    if (BRep_Tool::Degenerated(edge) || !bounds_the_face(edge)) continue;
    const BRepAdaptor_Curve curve(edge);
    integration_pieces(curve, curve.FirstParameter(), curve.LastParameter(), breaks);
    gp_XYZ sum(0, 0, 0);
    for (std::size_t i = 0; i + 1 < breaks.size(); ++i) {
      // Gauss on each component, the curve evaluated once per node
      gauss_nodes(breaks[i], breaks[i + 1], [&](double t, double weight) {
        gp_Pnt p;
        gp_Vec d;
        curve.D1(t, p, d);
        sum += ((p.XYZ() - centre) ^ d.XYZ()) * weight;
      });
    }
    total += edge.Orientation() == TopAbs_REVERSED ? sum.Reversed() : sum;
  }
  return total / 2;
}

// Three times the volume of the cone from `centre` over a face, the flux of
// (p - centre) through it, by OCCT's Gauss integration over the face.
double flux_by_integration(const TopoDS_Face& face, const gp_Pnt& centre) {
  BRepGProp_Face surface(face);
  BRepGProp_Vinert integral;
  integral.SetLocation(centre);
  if (TopoDS_Iterator(face).More()) {
    BRepGProp_Domain domain(face);
    integral.Perform(surface, domain, centre);
  } else {
    integral.Perform(surface, centre);
  }
  return 3 * integral.Mass();
}

}  // namespace

double signed_volume(const BodyPartitions& body, const gp_Pnt& centre) {
  // V = 1/3 of the flux of (p - c) through the boundary. On each face, with
  // o a point of its surface's axis, plane or apex:
  //   flux = integral of (p - o).n + (o - c).(vector area),
  // and (p - o).n is 0 on a plane through o and on a cone from its apex o,
  // +-r on a cylinder about o's axis and a sphere about o (+ when the
  // material is inside, convex): only the face's area is needed, which the
  // partitions hold exactly. Other faces (tori, free forms, fitted ones) are
  // integrated by OCCT.
  double flux = 0;
  for (const FaceInfo& info : body.faces) {
    const SurfaceParams& s = info.params;
    const bool analytic = !info.recognised && (s.kind == SurfaceKind::Plane || s.kind == SurfaceKind::Cylinder ||
                                               s.kind == SurfaceKind::Cone || s.kind == SurfaceKind::Sphere);
    if (!analytic) {
      flux += flux_by_integration(info.face, centre);
      continue;
    }
    flux += (s.location.XYZ() - centre.XYZ()) * vector_area(info.face, centre.XYZ());
    if (s.kind == SurfaceKind::Cylinder || s.kind == SurfaceKind::Sphere)
      flux += (info.side == MaterialSide::Concave ? -1 : 1) * s.radius * info.area;
  }
  return flux / 3;
}

}  // namespace contactcore::detail
