// Merging adjacent faces on the same surface into maximal partitions (the
// paper's list of merged partitions): union-find over the faces sharing an
// edge, then each partition's extent from its faces'.
#include "partitions/partition_merging.h"

#include "common/union_find.h"
#include "partitions/face_typing.h"

#include <algorithm>
#include <numeric>
#include <utility>
#include <vector>

#include <TopExp.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopTools_ListOfShape.hxx>

namespace contactcore::detail {

namespace {

bool mergeable(const FaceInfo& a, const FaceInfo& b, const Tolerances& tol) {
  return a.params.kind == b.params.kind && a.params.kind != SurfaceKind::Other && a.side == b.side &&
         same_surface(a.params, b.params, tol);
}

}  // namespace

std::vector<Partition> merge_faces(const TopoDS_Shape& shape, const TopTools_IndexedMapOfShape& face_map,
                                   const std::vector<FaceInfo>& faces, const Tolerances& tol) {
  const int count = static_cast<int>(faces.size());
  std::vector<Partition> partitions;
  UnionFind groups(count);
  TopTools_IndexedDataMapOfShapeListOfShape edge_faces;
  TopExp::MapShapesAndUniqueAncestors(shape, TopAbs_EDGE, TopAbs_FACE, edge_faces);
  std::vector<int> neighbours;
  for (int e = 1; e <= edge_faces.Extent(); ++e) {
    neighbours.clear();
    for (TopTools_ListOfShape::Iterator it(edge_faces(e)); it.More(); it.Next())
      neighbours.push_back(face_map.FindIndex(it.Value()) - 1);
    for (std::size_t i = 0; i < neighbours.size(); ++i) {
      for (std::size_t j = i + 1; j < neighbours.size(); ++j) {
        const int a = neighbours[i], b = neighbours[j];
        if (a < 0 || b < 0 || a == b) continue;
        if (groups.find(a) != groups.find(b) && mergeable(faces[a], faces[b], tol))
          groups.unite(a, b);
      }
    }
  }

  // Partitions in the order of their first face; faces ascending.
  std::vector<int> partition_of_root(count, -1);
  for (int i = 0; i < count; ++i) {
    const int root = groups.find(i);
    if (partition_of_root[root] < 0) {
      partition_of_root[root] = static_cast<int>(partitions.size());
      Partition partition;
      partition.id = partition_of_root[root];
      partition.params = faces[i].params;
      partition.side = faces[i].side;
      partitions.push_back(std::move(partition));
    }
    Partition& partition = partitions[partition_of_root[root]];
    partition.faces.push_back(i + 1);
    partition.area += faces[i].area;
    partition.box.Add(faces[i].box);
  }

  for (Partition& partition : partitions) {
    const FaceInfo& first = faces[partition.faces.front() - 1];
    if (partition.faces.size() == 1) {
      partition.extent = first.extent;  // the outline shared, not copied
      continue;
    }
    const SurfaceParams& s = partition.params;
    Extent& extent = partition.extent;
    extent.ref_dir = first.extent.ref_dir;
    if (s.kind == SurfaceKind::Plane) {
      const gp_Dir y_dir = s.axis.Crossed(extent.ref_dir);
      std::vector<Polygon2> outline;
      for (int index : partition.faces) {
        const FaceInfo& face = faces[index - 1];
        std::vector<Polygon2> loops = index == partition.faces.front()
                                          ? face.extent.outline.loops()
                                          : outline_in(face, s.location, extent.ref_dir, y_dir);
        for (Polygon2& loop : loops) outline.push_back(std::move(loop));
      }
      extent.outline = std::move(outline);
    } else if (is_revolution(s.kind)) {
      extent.axial_min = 1e300;
      extent.axial_max = -1e300;
      std::vector<AngularInterval> angular;
      for (int index : partition.faces) {
        const FaceInfo& face = faces[index - 1];
        const Extent seen = index == partition.faces.front()
                                ? face.extent
                                : revolution_extent_in(face, s.location, s.axis, extent.ref_dir, tol.linear);
        extent.axial_min = std::min(extent.axial_min, seen.axial_min);
        extent.axial_max = std::max(extent.axial_max, seen.axial_max);
        angular.insert(angular.end(), seen.angular.begin(), seen.angular.end());
      }
      extent.angular = unite(std::move(angular));
    }
  }
  return partitions;
}

}  // namespace contactcore::detail
