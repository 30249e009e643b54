// Defeaturing of small features, partitions carried through OCCT's history,
// Hausdorff distance on mesh vertices.
#include "contactcore/common/angles.h"
#include "contactcore/simulation/simplify.h"

#include <algorithm>
#include <cmath>

#include <functional>

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/narrowphase/distance.h>

#include <BRepAdaptor_Surface.hxx>
#include <BRepAlgoAPI_Defeaturing.hxx>
#include <BRepBndLib.hxx>
#include <BRepLProp_SLProps.hxx>
#include <BRepBuilderAPI_MakeVertex.hxx>
#include <BRepExtrema_DistShapeShape.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_OBB.hxx>
#include <Geom2d_Curve.hxx>
#include <GCPnts_AbscissaPoint.hxx>
#include <BRepAdaptor_Curve.hxx>
#include <ShapeUpgrade_UnifySameDomain.hxx>
#include <BRepTools_History.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <Standard_Failure.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopTools_ListOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>

namespace contactcore {

namespace {

TopoDS_Shape faces_of(const TopoDS_Shape& shape) {
  BRep_Builder builder;
  TopoDS_Compound faces;
  builder.MakeCompound(faces);
  for (TopExp_Explorer explorer(shape, TopAbs_FACE); explorer.More(); explorer.Next())
    builder.Add(faces, explorer.Current());
  return faces;
}

// Largest distance from the mesh (its vertices, edge midpoints and triangle
// centroids: a straight hole's wall has vertices on its rims only) to the
// exact surface of `shape`. Every sample is first measured against a fine
// tessellation of `shape` (FCL: point to triangle BVH; off by at most about
// its deflection), then the samples that can still be the farthest are
// measured exactly (BRepExtrema_DistShapeShape), farthest first, until none
// can beat the best exact one.
double one_sided(const TaggedMesh& mesh, const TopoDS_Shape& shape, double reference_deflection) {
  std::vector<gp_Pnt> samples;
  for (const auto& v : mesh.vertices) samples.emplace_back(v[0], v[1], v[2]);
  for (const auto& t : mesh.triangles) {
    gp_XYZ centroid(0, 0, 0);
    for (int k = 0; k < 3; ++k) {
      const auto &a = mesh.vertices[t[k]], &b = mesh.vertices[t[(k + 1) % 3]];
      centroid += gp_XYZ(a[0], a[1], a[2]) / 3.0;
      if (t[k] < t[(k + 1) % 3])  // each edge once from one of its triangles
        samples.emplace_back((a[0] + b[0]) / 2, (a[1] + b[1]) / 2, (a[2] + b[2]) / 2);
    }
    samples.emplace_back(centroid);
  }
  if (samples.empty()) return 0;
  const TopoDS_Shape surface = faces_of(shape);
  auto exact = [&](const gp_Pnt& p) {
    BRepExtrema_DistShapeShape distance(BRepBuilderAPI_MakeVertex(p).Shape(), surface);
    return distance.IsDone() ? distance.Value() : 0.0;
  };
  // The reference tessellation (its own partitions do not matter: one for all faces).
  BodyPartitions one;
  one.partitions.resize(1);
  TopTools_IndexedMapOfShape shape_faces;
  TopExp::MapShapes(shape, TopAbs_FACE, shape_faces);
  for (int f = 1; f <= shape_faces.Extent(); ++f) one.partitions[0].faces.push_back(f);
  MeshOptions fine;
  fine.deflection = reference_deflection;
  fine.angle = 0.2;
  const MeshResult reference = mesh_body(shape, one, fine);
  if (!reference.status.ok() || reference.mesh.triangles.empty()) {
    double worst = 0;
    for (const gp_Pnt& p : samples) worst = std::max(worst, exact(p));
    return worst;
  }
  auto bvh = std::make_shared<fcl::BVHModel<fcl::OBBRSSd>>();
  std::vector<fcl::Vector3d> points;
  std::vector<fcl::Triangle> triangles;
  for (const auto& v : reference.mesh.vertices) points.emplace_back(v[0], v[1], v[2]);
  for (const auto& t : reference.mesh.triangles) triangles.emplace_back(t[0], t[1], t[2]);
  bvh->beginModel();
  bvh->addSubModel(points, triangles);
  bvh->endModel();
  const fcl::Sphered point(0.0);
  const fcl::Transform3d identity = fcl::Transform3d::Identity();
  fcl::DistanceRequestd request;
  std::vector<std::pair<double, int>> approximate(samples.size());
  for (std::size_t i = 0; i < samples.size(); ++i) {
    fcl::Transform3d at = fcl::Transform3d::Identity();
    at.translation() = fcl::Vector3d(samples[i].X(), samples[i].Y(), samples[i].Z());
    fcl::DistanceResultd result;
    fcl::distance(&point, at, bvh.get(), identity, request, result);
    approximate[i] = {std::max(0.0, result.min_distance), static_cast<int>(i)};
  }
  std::sort(approximate.begin(), approximate.end(), std::greater<>());
  // |exact - approximate| <= the reference's distance to the surface: its deflection, with a margin.
  const double margin = 2 * reference_deflection + 1e-9;
  double best = 0;
  for (const auto& [distance, i] : approximate) {
    if (distance + margin < best) break;
    best = std::max(best, exact(samples[i]));
  }
  return best;
}

// Outward unit normal of `face` at the middle of its edge `edge`.
bool normal_at_edge(const TopoDS_Face& face, const TopoDS_Edge& edge, gp_Dir& normal) {
  double first = 0, last = 0;
  const Handle(Geom2d_Curve) pcurve = BRep_Tool::CurveOnSurface(edge, face, first, last);
  if (pcurve.IsNull()) return false;
  const gp_Pnt2d uv = pcurve->Value((first + last) / 2);
  BRepAdaptor_Surface surface(face);
  BRepLProp_SLProps props(surface, uv.X(), uv.Y(), 1, 1e-9);
  if (!props.IsNormalDefined()) return false;
  normal = props.Normal();
  if (face.Orientation() == TopAbs_REVERSED) normal.Reverse();
  return true;
}

// A chamfer: a plane strip narrower than `size` (its oriented box's middle side)
// and longer than wide, with two neighbours across its long edges that both lean
// towards its normal (the faces it bevels between; a thin wall's end face has its
// neighbours square to it).
bool is_chamfer(const TopoDS_Face& face, const TopTools_IndexedDataMapOfShapeListOfShape& edge_faces, double size) {
  Bnd_OBB box;
  BRepBndLib::AddOBB(face, box, true, true, false);
  double sides[3] = {2 * box.XHSize(), 2 * box.YHSize(), 2 * box.ZHSize()};
  std::sort(sides, sides + 3);
  const double width = sides[1], length = sides[2];
  if (!(width < size) || !(length > width)) return false;
  gp_Dir normal;
  int leaning = 0;
  for (TopExp_Explorer e(face, TopAbs_EDGE); e.More(); e.Next()) {
    const TopoDS_Edge& edge = TopoDS::Edge(e.Current());
    if (BRep_Tool::Degenerated(edge) || GCPnts_AbscissaPoint::Length(BRepAdaptor_Curve(edge)) <= width) continue;
    if (!normal_at_edge(face, edge, normal) || !edge_faces.Contains(edge)) continue;
    for (const TopoDS_Shape& other : edge_faces.FindFromKey(edge)) {
      if (other.IsSame(face)) continue;
      gp_Dir other_normal;
      if (normal_at_edge(TopoDS::Face(other), edge, other_normal) && normal.Dot(other_normal) > 0.1 &&
          normal.Dot(other_normal) < 1 - 1e-6)
        ++leaning;
    }
  }
  return leaning >= 2;
}

}  // namespace

double hausdorff_to_shape(const TaggedMesh& mesh, const TopoDS_Shape& shape, double reference_deflection) {
  return one_sided(mesh, shape, reference_deflection);
}

std::vector<int> small_features(const TopoDS_Shape& shape, const BodyPartitions& partitions, double size) {
  std::vector<int> faces;
  if (size <= 0) return faces;
  TopTools_IndexedDataMapOfShapeListOfShape edge_faces;
  TopExp::MapShapesAndAncestors(shape, TopAbs_EDGE, TopAbs_FACE, edge_faces);
  for (const FaceInfo& face : partitions.faces) {
    const SurfaceParams& s = face.params;
    const bool hole = s.kind == SurfaceKind::Cylinder && face.side == MaterialSide::Concave && 2 * s.radius < size;
    const double blend_radius = s.kind == SurfaceKind::Torus ? s.minor_radius : s.radius;
    const bool blend = (s.kind == SurfaceKind::Cylinder || s.kind == SurfaceKind::Torus) && blend_radius < size / 2 &&
                       !face.extent.angular.empty() && face.extent.angular_span() < kPi - 1e-6;
    const bool chamfer = s.kind == SurfaceKind::Plane && is_chamfer(face.face, edge_faces, size);
    if (hole || blend || chamfer) faces.push_back(face.index);
  }
  return faces;
}

SimplifiedModel simplify_body(const TopoDS_Shape& shape, const BodyPartitions& partitions,
                              const SimplifyOptions& options) {
  SimplifiedModel model;
  if (!(options.feature_size > 0) || !(options.envelope > 0)) {
    model.status = Status::failure(StatusCode::InvalidInput, "the feature size and the envelope must be positive");
    return model;
  }
  TopTools_IndexedMapOfShape original_faces;
  TopExp::MapShapes(shape, TopAbs_FACE, original_faces);
  std::vector<int> original_partition(original_faces.Extent() + 1, -1);
  for (const Partition& p : partitions.partitions)
    for (int f : p.faces)
      if (f >= 1 && f <= original_faces.Extent()) original_partition[f] = p.id;
  try {
    // Faces on one surface split by the modelling history (a hole's wall in halves, or in
    // layers) are one face first, so a feature is removed whole. `faces` and
    // `face_partition` below are those of the unified shape; its faces keep the partition
    // of the original faces they were made of (adjacent faces on one surface: one partition).
    ShapeUpgrade_UnifySameDomain unify(shape, true, true, false);
    unify.Build();
    const TopoDS_Shape base = unify.Shape();
    TopTools_IndexedMapOfShape faces;
    TopExp::MapShapes(base, TopAbs_FACE, faces);
    std::vector<int> face_partition(faces.Extent() + 1, -1);
    std::vector<std::vector<int>> originals_of(faces.Extent() + 1);  // unified face -> original FaceN
    for (int f = 1; f <= original_faces.Extent(); ++f) {
      int g = faces.FindIndex(original_faces(f));
      if (g == 0)
        for (const TopoDS_Shape& m : unify.History()->Modified(original_faces(f)))
          if ((g = faces.FindIndex(m)) > 0) break;
      if (g == 0) continue;
      originals_of[g].push_back(f);
      if (face_partition[g] < 0) face_partition[g] = original_partition[f];
    }
    const BodyPartitions base_partitions = partition_shape(base, Tolerances{});
    const std::vector<int> candidates = small_features(base, base_partitions, options.feature_size);
    // All at once; when OCCT refuses, one feature at a time, keeping what it can remove.
    auto attempt = [&](const TopoDS_Shape& from, const std::vector<int>& remove, TopoDS_Shape& out,
                       BRepAlgoAPI_Defeaturing& algo) {
      algo.SetShape(from);
      algo.SetRunParallel(false);
      for (int f : remove) algo.AddFaceToRemove(faces(f));
      algo.Build();
      if (!algo.IsDone() || algo.HasErrors()) return false;
      out = algo.Shape();
      // OCCT may finish without removing a feature it cannot fill: check.
      TopTools_IndexedMapOfShape left;
      TopExp::MapShapes(out, TopAbs_FACE, left);
      for (int f : remove)
        if (left.Contains(faces(f))) return false;
      return true;
    };
    TopoDS_Shape result = base;
    std::vector<int> removed;
    {
      BRepAlgoAPI_Defeaturing all;
      TopoDS_Shape out;
      if (candidates.empty() || attempt(base, candidates, out, all)) {
        if (!candidates.empty()) result = out;
        removed = candidates;
      }
    }
    if (removed.empty() && !candidates.empty()) {
      // One feature (all faces of one partition: a whole hole) at a time, following each
      // remaining face through OCCT's history of the runs before.
      std::vector<std::pair<int, std::vector<int>>> groups;  // partition, its candidate faces
      for (int f : candidates) {
        auto group = std::find_if(groups.begin(), groups.end(), [&](const auto& g) { return g.first == face_partition[f]; });
        if (group == groups.end()) groups.push_back({face_partition[f], {f}});
        else group->second.push_back(f);
      }
      std::vector<TopTools_ListOfShape> current(faces.Extent() + 1);
      for (int f : candidates) current[f].Append(faces(f));
      for (const auto& [partition, members] : groups) {
        BRepAlgoAPI_Defeaturing one;
        one.SetShape(result);
        one.SetRunParallel(false);
        int count = 0;
        for (int f : members)
          for (const TopoDS_Shape& piece : current[f]) {
            one.AddFaceToRemove(piece);
            ++count;
          }
        if (count == 0) continue;
        one.Build();
        bool still_there = false;
        if (one.IsDone() && !one.HasErrors()) {
          TopTools_IndexedMapOfShape left;
          TopExp::MapShapes(one.Shape(), TopAbs_FACE, left);
          for (int f : members)
            for (const TopoDS_Shape& piece : current[f]) still_there = still_there || left.Contains(piece);
        }
        if (!one.IsDone() || one.HasErrors() || still_there) {
          ++model.features_kept;
          continue;
        }
        for (int f : members) {
          removed.push_back(f);
          current[f].Clear();
        }
        for (int g : candidates) {
          TopTools_ListOfShape next;
          for (const TopoDS_Shape& piece : current[g]) {
            if (one.IsDeleted(piece)) continue;
            const TopTools_ListOfShape& modified = one.Modified(piece);
            if (modified.IsEmpty()) next.Append(piece);
            else
              for (const TopoDS_Shape& m : modified) next.Append(m);
          }
          current[g] = next;
        }
        result = one.Shape();
      }
      std::sort(removed.begin(), removed.end());
    }
    model.shape = result;
    for (int g : removed) model.removed_faces.insert(model.removed_faces.end(), originals_of[g].begin(), originals_of[g].end());
    std::sort(model.removed_faces.begin(), model.removed_faces.end());

    // Partitions of the simplified faces: each original face's partition goes to the face it
    // became (same face, or OCCT's Modified history); faces grown over a removed feature keep
    // the partition of the face they extend.
    TopTools_IndexedMapOfShape new_faces;
    TopExp::MapShapes(result, TopAbs_FACE, new_faces);
    std::vector<int> new_partition(new_faces.Extent() + 1, -1);
    for (int f = 1; f <= faces.Extent(); ++f) {
      const int same = new_faces.FindIndex(faces(f));
      if (same > 0) new_partition[same] = face_partition[f];
    }
    // Faces not found as such: match by surface to an original face on the same surface.
    for (int g = 1; g <= new_faces.Extent(); ++g) {
      if (new_partition[g] >= 0) continue;
      FaceInfo info;
      type_face(TopoDS::Face(new_faces(g)), Tolerances{}, info);
      for (const FaceInfo& original : base_partitions.faces)
        if (same_surface(info.params, original.params, Tolerances{}) && face_partition[original.index] >= 0) {
          new_partition[g] = face_partition[original.index];
          break;
        }
      if (new_partition[g] < 0) {
        model.status = Status::failure(StatusCode::GeometryError, "a face of the simplified model has no partition");
        model.status.face = g;
        return model;
      }
    }
    BodyPartitions carried;
    carried.partitions.resize(partitions.partitions.size());
    for (std::size_t p = 0; p < carried.partitions.size(); ++p) carried.partitions[p].id = static_cast<int>(p);
    for (int g = 1; g <= new_faces.Extent(); ++g) carried.partitions[new_partition[g]].faces.push_back(g);

    MeshResult meshed = mesh_body(result, carried, options.mesh);
    if (!meshed.status.ok()) {
      model.status = meshed.status;
      return model;
    }
    model.mesh = std::move(meshed.mesh);
    model.quality = meshed.quality;
    // Two-sided Hausdorff distance on the meshes' vertices against the exact other B-rep.
    const MeshResult original = mesh_body(shape, partitions, options.mesh);
    if (!original.status.ok()) {
      model.status = original.status;
      return model;
    }
    const double reference = std::min(options.mesh.deflection, options.envelope) / 10;
    model.hausdorff = std::max(one_sided(model.mesh, shape, reference), one_sided(original.mesh, result, reference));
    if (model.hausdorff > options.envelope) {
      model.status = Status::failure(StatusCode::InvalidInput,
                                     "simplified model leaves its envelope: Hausdorff distance " +
                                         std::to_string(model.hausdorff) + " mm > " + std::to_string(options.envelope) +
                                         " mm");
    }
  } catch (const Standard_Failure& failure) {
    model.status = Status::failure(StatusCode::GeometryError, std::string("OCCT: ") + failure.GetMessageString());
  }
  return model;
}

SimulationModels simulation_models(const TopoDS_Shape& shape, const BodyPartitions& partitions,
                                   const SimulationModelOptions& options) {
  SimulationModels models;
  models.view = mesh_body(shape, partitions, options.view);
  if (!models.view.status.ok()) {
    models.status = models.view.status;
    return models;
  }
  try {
    const double view_reference = options.view.deflection / 10;
    models.view_deviation = one_sided(models.view.mesh, shape, view_reference);
    if (options.feature_size > 0) {
      SimplifyOptions simplify;
      simplify.feature_size = options.feature_size;
      simplify.envelope = options.envelope;
      simplify.mesh = options.collision;
      SimplifiedModel model = simplify_body(shape, partitions, simplify);
      if (model.status.ok()) {
        models.simplified = true;
        models.collision.mesh = std::move(model.mesh);
        models.collision.quality = model.quality;
        models.collision_hausdorff = model.hausdorff;
        models.removed_faces = std::move(model.removed_faces);
        models.features_kept = model.features_kept;
        return models;
      }
      models.message = "simplification refused, the original kept: " + model.status.message;
    }
    models.collision = mesh_body(shape, partitions, options.collision);
    if (!models.collision.status.ok()) {
      models.status = models.collision.status;
      return models;
    }
    models.collision_hausdorff = one_sided(models.collision.mesh, shape, options.collision.deflection / 10);
  } catch (const Standard_Failure& failure) {
    models.status = Status::failure(StatusCode::GeometryError, std::string("OCCT: ") + failure.GetMessageString());
  }
  return models;
}

}  // namespace contactcore

