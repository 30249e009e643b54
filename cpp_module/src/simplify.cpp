// Defeaturing of small features, partitions carried through OCCT's history,
// Hausdorff distance on mesh vertices.
#include "contactcore/simplify.h"

#include <algorithm>
#include <cmath>

#include <BRepAlgoAPI_Defeaturing.hxx>
#include <BRepBuilderAPI_MakeVertex.hxx>
#include <BRepExtrema_DistShapeShape.hxx>
#include <BRep_Builder.hxx>
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
// exact surface of `shape`.
double one_sided(const TaggedMesh& mesh, const TopoDS_Shape& shape) {
  const TopoDS_Shape surface = faces_of(shape);
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
  double worst = 0;
  for (const gp_Pnt& p : samples) {
    BRepExtrema_DistShapeShape distance(BRepBuilderAPI_MakeVertex(p).Shape(), surface);
    if (distance.IsDone()) worst = std::max(worst, distance.Value());
  }
  return worst;
}

}  // namespace

std::vector<int> small_features(const BodyPartitions& partitions, double size) {
  std::vector<int> faces;
  if (size <= 0) return faces;
  for (const FaceInfo& face : partitions.faces) {
    const SurfaceParams& s = face.params;
    const bool hole = s.kind == SurfaceKind::Cylinder && face.side == MaterialSide::Concave && 2 * s.radius < size;
    const double blend_radius = s.kind == SurfaceKind::Torus ? s.minor_radius : s.radius;
    const bool blend = (s.kind == SurfaceKind::Cylinder || s.kind == SurfaceKind::Torus) && blend_radius < size / 2 &&
                       !face.extent.angular.empty() && face.extent.angular_span() < M_PI - 1e-6;
    if (hole || blend) faces.push_back(face.index);
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
  TopTools_IndexedMapOfShape faces;
  TopExp::MapShapes(shape, TopAbs_FACE, faces);
  const std::vector<int> candidates = small_features(partitions, options.feature_size);
  try {
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
    TopoDS_Shape result = shape;
    std::vector<int> removed;
    {
      BRepAlgoAPI_Defeaturing all;
      TopoDS_Shape out;
      if (candidates.empty() || attempt(shape, candidates, out, all)) {
        if (!candidates.empty()) result = out;
        removed = candidates;
      }
    }
    if (removed.empty() && !candidates.empty()) {
      // One feature (all faces of one partition: a whole hole) at a time, following each
      // remaining face through OCCT's history of the runs before.
      std::vector<int> face_partition(faces.Extent() + 1, -1);
      for (const Partition& p : partitions.partitions)
        for (int f : p.faces) face_partition[f] = p.id;
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
    model.removed_faces = removed;

    // Partitions of the simplified faces: each original face's partition goes to the face it
    // became (same face, or OCCT's Modified history); faces grown over a removed feature keep
    // the partition of the face they extend.
    TopTools_IndexedMapOfShape new_faces;
    TopExp::MapShapes(result, TopAbs_FACE, new_faces);
    std::vector<int> new_partition(new_faces.Extent() + 1, -1);
    std::vector<int> face_partition(faces.Extent() + 1, -1);
    for (const Partition& p : partitions.partitions)
      for (int f : p.faces) face_partition[f] = p.id;
    for (int f = 1; f <= faces.Extent(); ++f) {
      const int same = new_faces.FindIndex(faces(f));
      if (same > 0) new_partition[same] = face_partition[f];
    }
    // Faces not found as such: match by surface to an original face on the same surface.
    for (int g = 1; g <= new_faces.Extent(); ++g) {
      if (new_partition[g] >= 0) continue;
      FaceInfo info;
      type_face(TopoDS::Face(new_faces(g)), Tolerances{}, info);
      for (const FaceInfo& original : partitions.faces)
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
    model.hausdorff = std::max(one_sided(model.mesh, shape), one_sided(original.mesh, result));
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

}  // namespace contactcore
