// Stage 3 (contacts), for drawing: each contact's common region as faces and
// each interference's overlapping solid (find_common_regions, contacts.h).
// A face pair whose common region is one of the two faces (a screw head's
// ring on a cover, a bore inside a longer shaft) takes that face, found from
// the same outlines and extents the area test measures; any other pair takes
// OCCT's Boolean common of the two faces, as the area test does.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <string>

#include <BRepAlgoAPI_Common.hxx>
#include <BRepBuilderAPI_Copy.hxx>
#include <BRepGProp_Face.hxx>
#include <BRepMesh_IncrementalMesh.hxx>
#include <Poly_Triangulation.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_ListOfShape.hxx>
#include <TopLoc_Location.hxx>
#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Geom_Surface.hxx>
#include <Precision.hxx>
#include <ShapeAnalysis_Surface.hxx>
#include <TopoDS.hxx>
#include <gp_Vec.hxx>

#include "contactcore/common/occt_guard.h"
#include "contactcore/common/out_of_memory.h"
#include "contactcore/common/parallel.h"
#include "contactcore/contacts/contacts.h"
#include "contacts/common_area.h"

namespace contactcore {

namespace {

// The normal (out of the material, the face's orientation applied) at the
// point of `face` nearest to `p`.
gp_Vec normal_near(const TopoDS_Face& face, const gp_Pnt& p) {
  const Handle(Geom_Surface) surface = BRep_Tool::Surface(face);
  ShapeAnalysis_Surface analysis(surface);
  const gp_Pnt2d uv = analysis.ValueOfUV(p, Precision::Confusion());
  BRepGProp_Face properties(face);
  gp_Pnt on;
  gp_Vec normal;
  properties.Normal(uv.X(), uv.Y(), on, normal);
  return normal;
}

// A point inside a face (the middle of its parameter range, else a vertex's).
gp_Pnt point_of(const TopoDS_Face& face) {
  double u0 = 0, u1 = 0, v0 = 0, v1 = 0;
  BRepTools::UVBounds(face, u0, u1, v0, v1);
  return BRep_Tool::Surface(face)->Value((u0 + u1) / 2, (v0 + v1) / 2);
}

// `face` copied (its own TShape: meshing the region for drawing never writes
// into a body's face, which other threads may read) and turned, if need be,
// so that its normal points as side a's face does.
TopoDS_Face oriented_copy(const TopoDS_Face& face, const TopoDS_Face& side_a) {
  BRepBuilderAPI_Copy copy(face, Standard_True, Standard_False);
  TopoDS_Face out = TopoDS::Face(copy.Shape());
  const gp_Pnt p = point_of(out);
  if (normal_near(out, p).Dot(normal_near(side_a, p)) < 0) out.Reverse();
  return out;
}

enum class Piece { None, FaceA, FaceB, Boolean };

// Which region a face pair of a plane contact shares: the outlines in side
// a's plane frame, as planar_fit measures them.
Piece plane_piece(const FaceInfo& a, const FaceInfo& b, const Tolerances& tol) {
  const gp_Pnt origin = a.params.location;
  const gp_Dir x = a.extent.ref_dir;
  const gp_Dir y = a.params.axis.Crossed(x);
  const CommonRegion region = common_region(outline_in(a, origin, x, y), outline_in(b, origin, x, y), tol.linear);
  if (region.area <= tol.linear * region.perimeter) return Piece::None;  // along the edges only
  // Within a strip of tolerance width along its boundary, the whole face.
  const double slack = tol.linear * region.perimeter;
  if (std::abs(region.area - a.area) <= slack) return Piece::FaceA;
  if (std::abs(region.area - b.area) <= slack) return Piece::FaceB;
  return Piece::Boolean;
}

// The same for cylinders and cones: faces bounded by parallels and meridians
// lie one inside the other when their axial ranges and angular spans do.
Piece revolution_piece(const FaceInfo& a, const FaceInfo& b, const Tolerances& tol) {
  const gp_Pnt origin = a.params.location;
  const gp_Dir axis = a.params.axis;
  const gp_Dir ref = a.extent.ref_dir;
  const Extent ea = revolution_extent_in(a, origin, axis, ref, tol.linear);
  const Extent eb = revolution_extent_in(b, origin, axis, ref, tol.linear);
  const double z0 = std::max(ea.axial_min, eb.axial_min), z1 = std::min(ea.axial_max, eb.axial_max);
  if (z1 - z0 <= tol.linear) return Piece::None;
  const double angle = overlap(ea.angular, eb.angular);
  if (angle <= tol.angular) return Piece::None;
  if (!is_angle_axial_rectangle(a.face, origin, axis, tol.linear) ||
      !is_angle_axial_rectangle(b.face, origin, axis, tol.linear))
    return Piece::Boolean;
  const auto inside = [&](const Extent& inner, const Extent& outer) {
    return outer.axial_min <= inner.axial_min + tol.linear && inner.axial_max <= outer.axial_max + tol.linear &&
           angle >= inner.angular_span() - tol.angular;
  };
  if (inside(ea, eb)) return Piece::FaceA;
  if (inside(eb, ea)) return Piece::FaceB;
  return Piece::Boolean;
}

// The common region of one contact (see Contact::region).
Status contact_region(const Contact& contact, const std::vector<BodyPartitions>& parts, TopoDS_Compound& region) {
  region.Nullify();
  if (contact.type == ContactType::LAF || contact.type == ContactType::SPT) return Status::success();
  const Tolerances& tol = contact.tolerances;
  BRep_Builder builder;
  TopoDS_Compound out;
  builder.MakeCompound(out);
  std::vector<FaceInfo> pieces;
  for (int fa : contact.faces_a) {
    const FaceInfo& a = parts[contact.body_a].faces[fa - 1];
    for (int fb : contact.faces_b) {
      const FaceInfo& b = parts[contact.body_b].faces[fb - 1];
      if (!boxes_meet(a.box, b.box, tol.linear)) continue;
      Piece piece = Piece::Boolean;
      if (contact.type == ContactType::PLF) piece = plane_piece(a, b, tol);
      else if (contact.type == ContactType::CLJ || contact.type == ContactType::CJU) piece = revolution_piece(a, b, tol);
      if (piece == Piece::FaceA) builder.Add(out, oriented_copy(a.face, a.face));
      if (piece == Piece::FaceB) builder.Add(out, oriented_copy(b.face, a.face));
      if (piece != Piece::Boolean) continue;
      const Status common = boolean_common(a.face, b.face, tol, pieces);
      if (!common.ok()) return common;
      double area = 0;
      for (const FaceInfo& p : pieces) area += p.area;
      if (area <= tol.linear * tol.linear) continue;  // as the area test: no common area
      for (const FaceInfo& p : pieces) builder.Add(out, oriented_copy(p.face, a.face));
    }
  }
  region = out;
  return Status::success();
}

// The material two bodies share (OCCT's Boolean common of the two solids).
// Non-destructive: OCCT copies what it would otherwise change in the
// arguments (their sub-shapes' tolerances), so the bodies stay as they were
// read: other threads read them, and a recompute reuses them as they are.
Status common_solid(const TopoDS_Shape& a, const TopoDS_Shape& b, TopoDS_Shape& solid) {
  BRepAlgoAPI_Common common;
  TopTools_ListOfShape arguments, tools;
  arguments.Append(a);
  tools.Append(b);
  common.SetArguments(arguments);
  common.SetTools(tools);
  common.SetNonDestructive(Standard_True);
  common.Build();
  if (!common.IsDone()) return Status::failure(StatusCode::GeometryError, "OCCT: Boolean common of two solids failed");
  solid = common.Shape();
  return Status::success();
}

}  // namespace

Status find_common_regions(const Assembly& assembly, ContactsResult& result, const std::vector<int>& bodies,
                           int threads, Progress* progress) {
  const auto start = std::chrono::steady_clock::now();
  std::vector<bool> wanted(assembly.bodies.size(), bodies.empty());
  for (int body : bodies) {
    if (body < 0 || static_cast<std::size_t>(body) >= wanted.size())
      return Status::failure(StatusCode::InvalidArgument,
                             "no body " + std::to_string(body) + " among " + std::to_string(wanted.size()));
    wanted[body] = true;
  }
  // Work items: contacts (k >= 0) then interferences (-1 - k).
  std::vector<int> items;
  for (std::size_t k = 0; k < result.contacts.size(); ++k) {
    const Contact& c = result.contacts[k];
    if (wanted[c.body_a] || wanted[c.body_b]) items.push_back(static_cast<int>(k));
  }
  for (std::size_t k = 0; k < result.interferences.size(); ++k) {
    const Interference& i = result.interferences[k];
    if (wanted[i.body_a] || wanted[i.body_b]) items.push_back(-1 - static_cast<int>(k));
  }
  std::vector<std::string> failures(items.size());
  const bool finished = parallel_for(items.size(), threads, progress, "regions", [&](std::size_t t) {
    const int item = items[t];
    std::string failure;
    Status status;
    if (item >= 0) {
      Contact& contact = result.contacts[item];
      if (!run_guarded([&] { status = contact_region(contact, result.partitions, contact.region); }, failure, "OCCT: "))
        contact.region.Nullify();
    } else {
      Interference& overlap = result.interferences[-1 - item];
      if (!run_guarded([&] {
            status = common_solid(assembly.bodies[overlap.body_a].shape, assembly.bodies[overlap.body_b].shape,
                                  overlap.solid);
          }, failure, "OCCT: "))
        overlap.solid.Nullify();
    }
    if (failure.empty() && !status.ok()) failure = status.message;
    failures[t] = failure;
  });
  result.regions_computed = 0;
  for (std::size_t t = 0; t < items.size(); ++t) {
    if (failures[t].empty()) {
      ++result.regions_computed;
      continue;
    }
    const int item = items[t];
    const int a = item >= 0 ? result.contacts[item].body_a : result.interferences[-1 - item].body_a;
    const int b = item >= 0 ? result.contacts[item].body_b : result.interferences[-1 - item].body_b;
    result.messages.push_back(std::string(item >= 0 ? "common region" : "overlapping solid") + " of '" +
                              assembly.bodies[a].name + "' and '" + assembly.bodies[b].name +
                              "' not drawn: " + failures[t]);
  }
  result.times.regions = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!finished) return Status::failure(StatusCode::Cancelled, "cancelled");
  return Status::success();
}

Status mesh_region(const TopoDS_Shape& region, double deflection, double angular, RegionMesh& mesh) {
  mesh = RegionMesh{};
  if (region.IsNull()) return Status::success();
  if (!(deflection > 0) || !std::isfinite(deflection) || !(angular > 0))
    return Status::failure(StatusCode::InvalidArgument, "mesh_region: deflection and angle must be positive");
  BRepMesh_IncrementalMesh mesher(region, deflection, Standard_False, angular, Standard_False);
  for (TopExp_Explorer faces(region, TopAbs_FACE); faces.More(); faces.Next()) {
    const TopoDS_Face& face = TopoDS::Face(faces.Current());
    TopLoc_Location location;
    const Handle(Poly_Triangulation) triangulation = BRep_Tool::Triangulation(face, location);
    if (triangulation.IsNull()) continue;
    const gp_Trsf placement = location.Transformation();
    const int base = static_cast<int>(mesh.points.size() / 3);
    for (int i = 1; i <= triangulation->NbNodes(); ++i) {
      const gp_Pnt p = triangulation->Node(i).Transformed(placement);
      mesh.points.insert(mesh.points.end(), {p.X(), p.Y(), p.Z()});
    }
    const bool reversed = face.Orientation() == TopAbs_REVERSED;
    for (int t = 1; t <= triangulation->NbTriangles(); ++t) {
      int n1 = 0, n2 = 0, n3 = 0;
      triangulation->Triangle(t).Get(n1, n2, n3);
      if (reversed) std::swap(n2, n3);
      mesh.triangles.insert(mesh.triangles.end(), {base + n1 - 1, base + n2 - 1, base + n3 - 1});
    }
  }
  return Status::success();
}

}  // namespace contactcore
