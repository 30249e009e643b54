// Tagged tessellation: BRepMesh per body, then one global vertex per B-rep
// vertex and per edge-polygon node (BRepMesh discretises each edge once for
// all its faces), so faces meet at shared vertices whatever the CAD
// tolerances; then conforming refinement to a maximum edge length.
#include "contactcore/simulation/meshes.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <fstream>
#include <unordered_map>
#include <unordered_set>

#include <BRepAdaptor_Surface.hxx>
#include <BRepBndLib.hxx>
#include <BRepBuilderAPI_Copy.hxx>
#include <BRepGProp.hxx>
#include <Bnd_Box.hxx>
#include <GProp_GProps.hxx>
#include <BRepMesh_IncrementalMesh.hxx>
#include <BRepTools.hxx>
#include <BRep_Tool.hxx>
#include <IMeshTools_Parameters.hxx>
#include <Poly_PolygonOnTriangulation.hxx>
#include <Poly_Triangulation.hxx>
#include <Standard_Failure.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopLoc_Location.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Vertex.hxx>

#include "contactcore/common/angles.h"
#include "simulation/point3.h"

namespace contactcore {

namespace {

using UV = std::array<double, 2>;

std::uint64_t edge_key(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
}

// Node `along` (1-based, in the edge's own direction) of B-rep edge `edge`.
std::uint64_t edge_node_key(int edge, int along) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(edge)) << 32) | static_cast<std::uint32_t>(along);
}

// A triangle while refining: global vertices and the face-local UV of each corner.
struct WorkTriangle {
  std::array<int, 3> v;
  std::array<UV, 3> uv;
  int face;  // 1-based
};

Status face_failure(int face, const std::string& message) {
  Status status = Status::failure(StatusCode::GeometryError, message);
  status.face = face;
  return status;
}

// Longest-edge bisection (Rivara) in passes: every triangle with an edge
// longer than `max_edge` gets its longest edge split at a point of the surface
// (UV midpoint); a triangle with any split edge also splits its longest one,
// so each triangle is cut from the midpoint of its longest edge and angles stay
// bounded. A split edge is split in both its triangles (the midpoint is keyed
// by the edge's two global vertices), so the mesh stays conforming.
Status refine(std::vector<WorkTriangle>& triangles, std::vector<Point3>& vertices,
              const std::vector<BRepAdaptor_Surface>& surfaces, double max_edge, Progress* progress) {
  if (max_edge <= 0) return Status::success();
  constexpr std::size_t kMaxTriangles = 20'000'000;
  const double limit2 = max_edge * max_edge;
  auto length2 = [&](int a, int b) {
    const Point3 d = sub(vertices[a], vertices[b]);
    return dot(d, d);
  };
  // Index k of the longest edge (v[k], v[k+1]); ties broken by the edge key.
  auto longest_edge = [&](const WorkTriangle& t) {
    int best = 0;
    for (int k = 1; k < 3; ++k) {
      const double lk = length2(t.v[k], t.v[(k + 1) % 3]), lb = length2(t.v[best], t.v[(best + 1) % 3]);
      if (lk > lb || (lk == lb && edge_key(t.v[k], t.v[(k + 1) % 3]) > edge_key(t.v[best], t.v[(best + 1) % 3])))
        best = k;
    }
    return best;
  };
  for (int pass = 0; pass < 200; ++pass) {
    std::unordered_map<std::uint64_t, int> midpoint;
    for (const WorkTriangle& t : triangles) {
      const int k = longest_edge(t);
      if (length2(t.v[k], t.v[(k + 1) % 3]) > limit2) midpoint.emplace(edge_key(t.v[k], t.v[(k + 1) % 3]), -1);
    }
    if (midpoint.empty()) return Status::success();
    // Closure by a work list: a triangle with a split edge splits its longest one, which may in
    // turn reach the triangle across it.
    std::unordered_map<std::uint64_t, std::vector<int>> edge_triangles;
    edge_triangles.reserve(triangles.size() * 2);
    for (std::size_t i = 0; i < triangles.size(); ++i)
      for (int k = 0; k < 3; ++k)
        edge_triangles[edge_key(triangles[i].v[k], triangles[i].v[(k + 1) % 3])].push_back(static_cast<int>(i));
    std::vector<int> work;
    for (std::size_t i = 0; i < triangles.size(); ++i)
      for (int k = 0; k < 3; ++k)
        if (midpoint.count(edge_key(triangles[i].v[k], triangles[i].v[(k + 1) % 3]))) {
          work.push_back(static_cast<int>(i));
          break;
        }
    while (!work.empty()) {
      const WorkTriangle& t = triangles[work.back()];
      work.pop_back();
      const int k = longest_edge(t);
      const std::uint64_t longest = edge_key(t.v[k], t.v[(k + 1) % 3]);
      if (!midpoint.emplace(longest, -1).second) continue;
      for (int neighbour : edge_triangles[longest]) work.push_back(neighbour);
    }
    if (progress && !progress->report("refine", std::min(1.0, pass / 10.0)))
      return Status::failure(StatusCode::Cancelled, "cancelled while refining the mesh");
    if (triangles.size() + 3 * midpoint.size() > kMaxTriangles)
      return Status::failure(StatusCode::InvalidInput,
                             "maximum edge length " + std::to_string(max_edge) +
                                 " mm needs more than 20 million triangles: choose a larger one");

    std::vector<WorkTriangle> next;
    next.reserve(triangles.size() + 3 * midpoint.size());
    for (const WorkTriangle& t : triangles) {
      // Rotated so the longest edge is (v0, v1).
      const int r = longest_edge(t);
      const int v[3] = {t.v[r], t.v[(r + 1) % 3], t.v[(r + 2) % 3]};
      const UV uv[3] = {t.uv[r], t.uv[(r + 1) % 3], t.uv[(r + 2) % 3]};
      // Midpoint of edge (v[k], v[k+1]) and its UV in this face, or -1.
      int mid[3] = {-1, -1, -1};
      UV mid_uv[3]{};
      for (int k = 0; k < 3; ++k) {
        auto found = midpoint.find(edge_key(v[k], v[(k + 1) % 3]));
        if (found == midpoint.end()) continue;
        mid_uv[k] = {0.5 * (uv[k][0] + uv[(k + 1) % 3][0]), 0.5 * (uv[k][1] + uv[(k + 1) % 3][1])};
        if (found->second < 0) {
          const gp_Pnt p = surfaces[t.face - 1].Value(mid_uv[k][0], mid_uv[k][1]);
          found->second = static_cast<int>(vertices.size());
          vertices.push_back({p.X(), p.Y(), p.Z()});
        }
        mid[k] = found->second;
      }
      auto emit = [&](int a, const UV& ua, int b, const UV& ub, int c, const UV& uc) {
        next.push_back(WorkTriangle{{a, b, c}, {ua, ub, uc}, t.face});
      };
      if (mid[0] < 0) {
        next.push_back(t);
        continue;
      }
      // (v0, m0, v2) and (m0, v1, v2), each split again at its other marked edge.
      if (mid[2] >= 0) {
        emit(v[0], uv[0], mid[0], mid_uv[0], mid[2], mid_uv[2]);
        emit(mid[0], mid_uv[0], v[2], uv[2], mid[2], mid_uv[2]);
      } else {
        emit(v[0], uv[0], mid[0], mid_uv[0], v[2], uv[2]);
      }
      if (mid[1] >= 0) {
        emit(mid[0], mid_uv[0], v[1], uv[1], mid[1], mid_uv[1]);
        emit(mid[0], mid_uv[0], mid[1], mid_uv[1], v[2], uv[2]);
      } else {
        emit(mid[0], mid_uv[0], v[1], uv[1], v[2], uv[2]);
      }
    }
    triangles.swap(next);
  }
  return Status::failure(StatusCode::GeometryError, "mesh refinement did not converge");
}

}  // namespace

MeshResult mesh_body(const TopoDS_Shape& shape, const BodyPartitions& partitions, const MeshOptions& options,
                     Progress* progress) {
  MeshResult result;
  if (shape.IsNull()) {
    result.status = Status::failure(StatusCode::InvalidInput, "empty shape");
    return result;
  }
  if (const Status valid = check_mesh_options(options); !valid.ok()) {
    result.status = valid;
    return result;
  }
  TopTools_IndexedMapOfShape faces, edges, topo_vertices;
  TopExp::MapShapes(shape, TopAbs_FACE, faces);
  TopExp::MapShapes(shape, TopAbs_EDGE, edges);
  TopExp::MapShapes(shape, TopAbs_VERTEX, topo_vertices);

  std::vector<int> face_partition(faces.Extent() + 1, -1);
  for (const Partition& partition : partitions.partitions)
    for (int f : partition.faces)
      if (f >= 1 && f <= faces.Extent()) face_partition[f] = partition.id;
  for (int f = 1; f <= faces.Extent(); ++f)
    if (face_partition[f] < 0) {
      result.status = face_failure(f, "face has no partition (partitions of another shape?)");
      return result;
    }

  try {
    // A fresh tessellation with exactly these parameters, not one left on the shape.
    BRepTools::Clean(shape);
    IMeshTools_Parameters parameters;
    parameters.Deflection = options.deflection;
    parameters.Angle = options.angle;
    parameters.InParallel = false;
    BRepMesh_IncrementalMesh mesher(shape, parameters);
    if (progress && !progress->report("mesh", 0.3)) {
      result.status = Status::failure(StatusCode::Cancelled, "cancelled while meshing");
      return result;
    }

    std::vector<Point3> vertices;
    std::vector<WorkTriangle> work;
    std::vector<BRepAdaptor_Surface> surfaces;
    surfaces.reserve(faces.Extent());
    // Global vertex of each B-rep vertex, and of each interior node of each edge polygon.
    std::vector<int> vertex_global(topo_vertices.Extent() + 1, -1);
    std::unordered_map<std::uint64_t, int> edge_node_global;

    for (int f = 1; f <= faces.Extent(); ++f) {
      const TopoDS_Face face = TopoDS::Face(faces(f));
      surfaces.emplace_back(face);
      TopLoc_Location location;
      const Handle(Poly_Triangulation) triangulation = BRep_Tool::Triangulation(face, location);
      if (triangulation.IsNull() || triangulation->NbTriangles() == 0) {
        result.failed_faces.push_back({f, "OCCT could not tessellate the face"});
        continue;
      }
      const gp_Trsf transform = location.Transformation();
      std::vector<int> node_global(triangulation->NbNodes() + 1, -1);
      auto new_vertex = [&](int node) {
        const gp_Pnt p = triangulation->Node(node).Transformed(transform);
        vertices.push_back({p.X(), p.Y(), p.Z()});
        return static_cast<int>(vertices.size()) - 1;
      };
      // Poles and apexes (vertices of degenerated edges): BRepMesh may put
      // several nodes there, off the edge's polygon; they are one vertex.
      std::vector<std::pair<gp_Pnt, int>> poles;  // point, B-rep vertex index
      bool edges_discretised = true;
      for (TopExp_Explorer explorer(face, TopAbs_EDGE); explorer.More() && edges_discretised; explorer.Next())
        edges_discretised = !BRep_Tool::PolygonOnTriangulation(TopoDS::Edge(explorer.Current()), triangulation,
                                                               location).IsNull();
      if (!edges_discretised) {
        result.failed_faces.push_back({f, "an edge of the face has no discretisation"});
        continue;
      }
      if (!triangulation->HasUVNodes() && options.max_edge_length > 0) {
        result.failed_faces.push_back({f, "the face's tessellation has no UV nodes to refine"});
        continue;
      }
      for (TopExp_Explorer explorer(face, TopAbs_EDGE); explorer.More(); explorer.Next()) {
        const TopoDS_Edge edge = TopoDS::Edge(explorer.Current());
        const Handle(Poly_PolygonOnTriangulation) polygon =
            BRep_Tool::PolygonOnTriangulation(edge, triangulation, location);
        const int edge_index = edges.FindIndex(edge);
        const int count = polygon->NbNodes();
        TopoDS_Vertex first, last;
        TopExp::Vertices(TopoDS::Edge(edge.Oriented(TopAbs_FORWARD)), first, last);
        const bool reversed = polygon->HasParameters() && count > 1 &&
                              polygon->Parameter(1) > polygon->Parameter(count);
        const bool degenerated = BRep_Tool::Degenerated(edge);
        if (degenerated) poles.emplace_back(BRep_Tool::Pnt(first), topo_vertices.FindIndex(first));
        for (int i = 1; i <= count; ++i) {
          const int node = polygon->Node(i);
          const int along = reversed ? count + 1 - i : i;  // position in the edge's own direction
          int* slot = nullptr;
          if (degenerated || along == 1)
            slot = &vertex_global[topo_vertices.FindIndex(first)];
          else if (along == count)
            slot = &vertex_global[topo_vertices.FindIndex(last)];
          else
            slot = &edge_node_global.emplace(edge_node_key(edge_index, along), -1).first->second;
          if (*slot < 0) *slot = node_global[node] >= 0 ? node_global[node] : new_vertex(node);
          if (node_global[node] < 0) node_global[node] = *slot;
        }
      }
      const bool flip = face.Orientation() == TopAbs_REVERSED;
      const bool has_uv = triangulation->HasUVNodes();
      for (int t = 1; t <= triangulation->NbTriangles(); ++t) {
        int n[3];
        triangulation->Triangle(t).Get(n[0], n[1], n[2]);
        if (flip) std::swap(n[1], n[2]);
        WorkTriangle triangle;
        triangle.face = f;
        for (int k = 0; k < 3; ++k) {
          if (node_global[n[k]] < 0) {
            const gp_Pnt p = triangulation->Node(n[k]).Transformed(transform);
            for (const auto& [pole, vertex] : poles)
              if (p.Distance(pole) <= std::max(1e-7, BRep_Tool::Tolerance(TopoDS::Vertex(topo_vertices(vertex))))) {
                int& slot = vertex_global[vertex];
                if (slot < 0) slot = new_vertex(n[k]);
                node_global[n[k]] = slot;
              }
          }
          if (node_global[n[k]] < 0) node_global[n[k]] = new_vertex(n[k]);
          triangle.v[k] = node_global[n[k]];
          if (has_uv) {
            const gp_Pnt2d uv = triangulation->UVNode(n[k]);
            triangle.uv[k] = {uv.X(), uv.Y()};
          } else {
            triangle.uv[k] = {0, 0};
          }
        }
        // Nodes of a degenerated edge (a cone apex, a sphere pole) merge into one vertex.
        if (triangle.v[0] == triangle.v[1] || triangle.v[1] == triangle.v[2] || triangle.v[0] == triangle.v[2])
          continue;
        work.push_back(triangle);
      }
      if (progress && f % 16 == 0 && !progress->report("mesh", 0.3 + 0.4 * f / faces.Extent())) {
        result.status = Status::failure(StatusCode::Cancelled, "cancelled while meshing");
        return result;
      }
    }

    const Status refined = refine(work, vertices, surfaces, options.max_edge_length, progress);
    if (!refined.ok()) {
      result.status = refined;
      return result;
    }

    TaggedMesh& mesh = result.mesh;
    mesh.vertices = std::move(vertices);
    mesh.partition_count = static_cast<int>(partitions.partitions.size());
    mesh.triangles.reserve(work.size());
    mesh.triangle_face.reserve(work.size());
    mesh.triangle_partition.reserve(work.size());
    for (const WorkTriangle& t : work) {
      mesh.triangles.push_back(t.v);
      mesh.triangle_face.push_back(t.face);
      mesh.triangle_partition.push_back(face_partition[t.face]);
    }
    result.quality = mesh_quality(mesh);
  } catch (const Standard_Failure& failure) {
    result.status = Status::failure(StatusCode::GeometryError, std::string("OCCT: ") + failure.GetMessageString());
  }
  if (progress) progress->report("mesh", 1.0);
  return result;
}

Status check_mesh_options(const MeshOptions& options) {
  const auto fail = [](const std::string& message) { return Status::failure(StatusCode::InvalidArgument, message); };
  if (!std::isfinite(options.deflection) || !(options.deflection > 0))
    return fail("the mesh deflection must be a positive, finite length in mm; got " + std::to_string(options.deflection));
  if (!std::isfinite(options.angle) || !(options.angle > 0) || options.angle > kPi)
    return fail("the mesh angle must be positive and at most pi radians; got " + std::to_string(options.angle));
  if (!std::isfinite(options.max_edge_length) || options.max_edge_length < 0)
    return fail("the maximum edge length must be a finite length in mm, 0 for none; got " +
                std::to_string(options.max_edge_length));
  if (!(options.max_triangles > 0))
    return fail("the maximum number of triangles must be positive");
  return Status::success();
}

double estimated_triangles(const TopoDS_Shape& shape, const MeshOptions& options) {
  constexpr double kEquilateral = 0.4330127018922193;  // sqrt(3) / 4: area of a unit equilateral triangle
  // The longest chord whose sagitta stays within the deflection and whose
  // normals turn by at most the angle, on a circle of radius r.
  const auto chord = [&](double r) {
    const double by_deflection = options.deflection >= r ? 2 * r : 2 * std::sqrt(2 * r * options.deflection);
    return std::min(by_deflection, 2 * r * std::sin(std::min(options.angle, kPi) / 2));
  };
  double total = 0;
  TopTools_IndexedMapOfShape faces;
  TopExp::MapShapes(shape, TopAbs_FACE, faces);
  for (int f = 1; f <= faces.Extent(); ++f) {
    const TopoDS_Face& face = TopoDS::Face(faces(f));
    GProp_GProps props;
    BRepGProp::SurfaceProperties(face, props);
    const double area = std::abs(props.Mass());
    if (!std::isfinite(area) || area <= 0) continue;
    double bound = options.max_edge_length > 0 ? area / (kEquilateral * options.max_edge_length * options.max_edge_length)
                                               : 0;
    Bnd_Box box;
    BRepBndLib::Add(face, box, false);
    const double diagonal = box.IsVoid() ? 0 : std::sqrt(box.SquareExtent());
    const BRepAdaptor_Surface surface(face, false);
    switch (surface.GetType()) {
      case GeomAbs_Sphere: {
        const double h = chord(surface.Sphere().Radius());
        if (h > 0) bound = std::max(bound, area / (kEquilateral * h * h));
        break;
      }
      case GeomAbs_Cylinder: {
        const double h = chord(surface.Cylinder().Radius());
        if (h > 0 && diagonal > 0) bound = std::max(bound, area / (h * diagonal));
        break;
      }
      case GeomAbs_Torus: {
        const double h = chord(surface.Torus().MinorRadius());
        if (h > 0 && diagonal > 0) bound = std::max(bound, area / (h * diagonal));
        break;
      }
      default: break;
    }
    total += bound;
  }
  return total;
}

double extrapolated_triangles(const TopoDS_Shape& shape, const MeshOptions& options) {
  Bnd_Box box;
  BRepBndLib::Add(shape, box, false);
  if (box.IsVoid()) return 0;
  const double coarse = kCoarseRelativeDeflection * std::sqrt(box.SquareExtent());
  if (!(coarse > options.deflection) || !std::isfinite(coarse)) return 0;
  // A copy: the shape's own faces (shared by its instances) keep no triangulation.
  const TopoDS_Shape copy = BRepBuilderAPI_Copy(shape, true, false).Shape();
  IMeshTools_Parameters parameters;
  parameters.Deflection = coarse;
  parameters.Angle = options.angle;
  parameters.InParallel = false;
  BRepMesh_IncrementalMesh mesher(copy, parameters);
  double total = 0;
  for (TopExp_Explorer explorer(copy, TopAbs_FACE); explorer.More(); explorer.Next()) {
    const TopoDS_Face& face = TopoDS::Face(explorer.Current());
    TopLoc_Location location;
    const Handle(Poly_Triangulation) triangulation = BRep_Tool::Triangulation(face, location);
    if (triangulation.IsNull()) continue;
    const GeomAbs_SurfaceType type = BRepAdaptor_Surface(face, false).GetType();
    const bool singly_curved = type == GeomAbs_Plane || type == GeomAbs_Cylinder || type == GeomAbs_Cone ||
                               type == GeomAbs_SurfaceOfExtrusion;
    total += triangulation->NbTriangles() * std::pow(coarse / options.deflection, singly_curved ? 0.5 : 1.0);
  }
  return total;
}

Status check_triangle_budget(const std::vector<TopoDS_Shape>& shapes, const std::vector<std::string>& names,
                             const MeshOptions& options, Progress* progress) {
  if (const Status valid = check_mesh_options(options); !valid.ok()) return valid;
  double total = 0, largest = -1;
  const std::string* largest_name = nullptr;
  static const std::string unnamed;
  for (std::size_t i = 0; i < shapes.size(); ++i) {
    const double estimate =
        std::max(estimated_triangles(shapes[i], options), extrapolated_triangles(shapes[i], options));
    total += estimate;
    if (estimate > largest) largest = estimate, largest_name = i < names.size() ? &names[i] : &unnamed;
    if (progress && !progress->report("mesh estimate", double(i + 1) / shapes.size()))
      return Status::failure(StatusCode::Cancelled, "cancelled");
  }
  if (total <= options.max_triangles) return Status::success();
  char text[400];
  std::snprintf(text, sizeof text,
                "meshing with deflection %g mm, angle %g rad, maximum edge %g mm needs at least %.3g triangles "
                "(%.3g for body '%s'): more than the limit of %.0f (CLI --max-triangles); ask for coarser sizes",
                options.deflection, options.angle, options.max_edge_length, total, largest,
                largest_name ? largest_name->c_str() : "", options.max_triangles);
  Status status = Status::failure(StatusCode::InvalidInput, text);
  if (largest_name) status.body = *largest_name;
  return status;
}

MeshQuality mesh_quality(const TaggedMesh& mesh) {
  MeshQuality quality;
  quality.triangles = mesh.triangles.size();
  std::unordered_map<std::uint64_t, int> uses;
  uses.reserve(mesh.triangles.size() * 2);
  std::vector<double> aspects;
  aspects.reserve(mesh.triangles.size());
  double min_angle = kPi;
  for (const auto& t : mesh.triangles) {
    std::array<Point3, 3> p{mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]};
    double longest = 0;
    for (int k = 0; k < 3; ++k) {
      ++uses[edge_key(t[k], t[(k + 1) % 3])];
      const Point3 e1 = sub(p[(k + 1) % 3], p[k]), e2 = sub(p[(k + 2) % 3], p[k]);
      const double l1 = norm(e1), l2 = norm(e2);
      longest = std::max(longest, l1);
      if (l1 > 0 && l2 > 0) min_angle = std::min(min_angle, std::acos(std::clamp(dot(e1, e2) / (l1 * l2), -1.0, 1.0)));
      else min_angle = 0;
    }
    const double area2 = norm(cross(sub(p[1], p[0]), sub(p[2], p[0])));  // twice the area
    aspects.push_back(area2 > 0 ? longest * longest * std::sqrt(3.0) / (2 * area2)
                                : std::numeric_limits<double>::infinity());
    quality.max_edge_length = std::max(quality.max_edge_length, longest);
  }
  for (const auto& [key, count] : uses) {
    if (count == 1) ++quality.boundary_edges;
    if (count > 2) ++quality.nonmanifold_edges;
  }
  quality.watertight = !mesh.triangles.empty() && quality.boundary_edges == 0 && quality.nonmanifold_edges == 0;
  quality.min_angle_deg = mesh.triangles.empty() ? 0 : min_angle * 180 / kPi;
  if (!aspects.empty()) {
    std::sort(aspects.begin(), aspects.end());
    auto percentile = [&](double q) {
      return aspects[std::min(aspects.size() - 1, static_cast<std::size_t>(q * (aspects.size() - 1) + 0.5))];
    };
    quality.aspect_p50 = percentile(0.5);
    quality.aspect_p90 = percentile(0.9);
    quality.aspect_p99 = percentile(0.99);
    quality.aspect_max = aspects.back();
  }
  return quality;
}

Status write_ply(const TaggedMesh& mesh, const std::string& path) {
  std::ofstream out(path);
  if (!out) {
    Status status = Status::failure(StatusCode::ReadError, "cannot write the PLY file");
    status.file = path;
    return status;
  }
  out << "ply\nformat ascii 1.0\ncomment Contacts tagged mesh: face is FreeCAD's FaceN, partition its id\n"
      << "element vertex " << mesh.vertices.size() << "\nproperty double x\nproperty double y\nproperty double z\n"
      << "element face " << mesh.triangles.size()
      << "\nproperty list uchar int vertex_indices\nproperty int face\nproperty int partition\nend_header\n";
  out.precision(17);
  for (const auto& v : mesh.vertices) out << v[0] << ' ' << v[1] << ' ' << v[2] << '\n';
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    const auto& t = mesh.triangles[i];
    out << "3 " << t[0] << ' ' << t[1] << ' ' << t[2] << ' ' << mesh.triangle_face[i] << ' '
        << mesh.triangle_partition[i] << '\n';
  }
  if (!out) {
    Status status = Status::failure(StatusCode::ReadError, "writing the PLY file failed");
    status.file = path;
    return status;
  }
  return Status::success();
}

TaggedMesh mesh_without_partitions(const TaggedMesh& mesh, const std::vector<bool>& enabled) {
  TaggedMesh out;
  out.vertices = mesh.vertices;
  out.partition_count = mesh.partition_count;
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    const int partition = mesh.triangle_partition[i];
    if (partition >= 0 && partition < static_cast<int>(enabled.size()) && !enabled[partition]) continue;
    out.triangles.push_back(mesh.triangles[i]);
    out.triangle_face.push_back(mesh.triangle_face[i]);
    out.triangle_partition.push_back(partition);
  }
  return out;
}

}  // namespace contactcore
