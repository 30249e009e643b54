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
  // Refused before meshing when the sizes asked need more triangles than this
  // (estimated_triangles summed over the bodies meshed together).
  double max_triangles = 10'000'000;
};

// InvalidArgument unless deflection and angle are finite and positive (angle
// at most pi), the maximum edge length finite and not negative and
// max_triangles positive (not NaN).
Status check_mesh_options(const MeshOptions& options);

// A lower bound of the triangles mesh_body makes of `shape` with `options`,
// from each face's area and surface, without meshing: every triangle's edges
// are at most the maximum edge length (area / (sqrt(3)/4 L^2)); on a sphere
// the chord of the deflection and the angle bounds them too, on a cylinder
// or a torus's tube the width across the curvature (area / (chord x the
// face's box diagonal)). Planes, cones and free forms: the edge bound only.
double estimated_triangles(const TopoDS_Shape& shape, const MeshOptions& options);

// For a deflection below kCoarseRelativeDeflection of the shape's box
// diagonal: the triangles of a mesh at that coarse deflection (cheap), each
// face's count scaled to the deflection asked as BRepMesh's counts grow:
// (coarse / deflection)^0.5 on planes, cylinders, cones and extrusions (their
// boundaries are refined, one direction), ^1 on doubly curved faces (spheres,
// tori, revolutions, free forms). An estimate, not a bound (within a factor
// of two of the motor's meshes at deflections 0.01 and 0.001; test). 0 when
// the deflection is coarser than that.
constexpr double kCoarseRelativeDeflection = 1e-3;
double extrapolated_triangles(const TopoDS_Shape& shape, const MeshOptions& options);

// InvalidInput when the bodies' estimates (the larger of estimated_triangles
// and extrapolated_triangles) together exceed options.max_triangles (naming the largest body, the estimate and the
// limit); checks the options first. Cancelled when `progress` says so.
// `names[i]` names `shapes[i]` in the message.
Status check_triangle_budget(const std::vector<TopoDS_Shape>& shapes, const std::vector<std::string>& names,
                             const MeshOptions& options, Progress* progress = nullptr);

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

// A face OCCT could not tessellate: left out of the mesh (which is then not
// watertight), the rest of the body meshed.
struct FaceFailure {
  int face = 0;  // 1-based FaceN
  std::string message;
};

struct MeshResult {
  Status status;
  TaggedMesh mesh;
  MeshQuality quality;
  std::vector<FaceFailure> failed_faces;
  // Set by the mesh tools (mesh_assembly) when the body is not a valid solid
  // (find_invalid_solids): reason empty when valid.
  std::string invalid_reason;
  std::vector<int> invalid_faces;
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
