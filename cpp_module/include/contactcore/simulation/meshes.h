// Stage 5 (simulation), meshes: the mixed representation. Each body tessellated with the user's
// chordal deviation, angular deflection and maximum edge length, conforming
// across shared B-rep edges (watertight: every mesh edge in exactly two
// triangles), every triangle tagged with its face and its partition.
#pragma once

#include <array>
#include <string>
#include <vector>

#include <TopoDS_Shape.hxx>

#include "contactcore/common/errors.h"
#include "contactcore/partitions/partitions.h"

namespace contactcore {

struct MeshOptions {
  double deflection = 0.1;     // chordal deviation, mm
  double angle = 0.5;          // angular deflection, radians
  double max_edge_length = 0;  // mm; 0: no bound
};

// Triangles share vertices by topology (B-rep vertices and edge polygons), so
// the mesh is closed when the B-rep is, whatever the CAD tolerances.
struct TaggedMesh {
  std::vector<std::array<double, 3>> vertices;  // mm, global coordinates
  std::vector<std::array<int, 3>> triangles;    // counter-clockwise seen from outside
  std::vector<int> triangle_face;               // 1-based FaceN of each triangle
  std::vector<int> triangle_partition;          // partition id of each triangle
  int partition_count = 0;
};

// Minimum angle and aspect ratio distribution (longest edge over the shortest
// altitude, times sqrt(3)/2: 1 for an equilateral triangle, the paper's
// equilaterality).
struct MeshQuality {
  std::size_t triangles = 0;
  std::size_t boundary_edges = 0;     // edges in one triangle only
  std::size_t nonmanifold_edges = 0;  // edges in three or more triangles
  bool watertight = false;            // every edge in exactly two triangles
  double min_angle_deg = 0;
  double aspect_p50 = 0, aspect_p90 = 0, aspect_p99 = 0, aspect_max = 0;
  double max_edge_length = 0;
};

struct MeshResult {
  Status status;
  TaggedMesh mesh;
  MeshQuality quality;
};

// Tessellates `shape` (one body) and tags each triangle with the face index
// and the partition of `partitions` (from partition_shape on the same shape).
MeshResult mesh_body(const TopoDS_Shape& shape, const BodyPartitions& partitions,
                     const MeshOptions& options, Progress* progress = nullptr);

MeshQuality mesh_quality(const TaggedMesh& mesh);

// Binary-free ASCII PLY: vertex x y z; face vertex_indices, face, partition.
Status write_ply(const TaggedMesh& mesh, const std::string& path);

// Sub-mesh of the triangles whose partition is enabled (vertices kept).
TaggedMesh mesh_without_partitions(const TaggedMesh& mesh, const std::vector<bool>& enabled);

}  // namespace contactcore
