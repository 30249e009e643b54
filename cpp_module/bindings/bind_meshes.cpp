// Stage 5a in Python: tagged meshes of every body of an assembly, their
// quality, PLY files.

#include "common.h"
#include "contactcore/bodies/bodies.h"
#include "contactcore/contacts/contacts.h"
#include "contactcore/simulation/meshes.h"
#include "contactcore/common/occt_guard.h"

namespace contactcore::bindings {

namespace {

// A list of 3-tuples made with CPython's own calls: the bindings compile at
// -O0 (cpp_module/CMakeLists.txt), where pybind11's make_tuple per item costs
// about three times as much (20,000 vertices: 9 to 13 ms against 3 to 4 ms).
template <typename Triple, typename Convert>
py::list tuple_list(const std::vector<Triple>& items, Convert convert) {
  py::list out(items.size());
  for (std::size_t i = 0; i < items.size(); ++i) {
    PyObject* tuple = PyTuple_New(3);
    if (!tuple) throw py::error_already_set();
    for (Py_ssize_t k = 0; k < 3; ++k) {
      PyObject* value = convert(items[i][k]);
      if (!value) {
        Py_DECREF(tuple);
        throw py::error_already_set();
      }
      PyTuple_SET_ITEM(tuple, k, value);
    }
    PyList_SET_ITEM(out.ptr(), static_cast<Py_ssize_t>(i), tuple);
  }
  return out;
}

py::list vertex_list(const TaggedMesh& mesh) {
  return tuple_list(mesh.vertices, [](double x) { return PyFloat_FromDouble(x); });
}

py::list triangle_list(const TaggedMesh& mesh) {
  return tuple_list(mesh.triangles, [](auto index) { return PyLong_FromLongLong(static_cast<long long>(index)); });
}

}  // namespace

void bind_meshes(py::module_& m) {
  py::class_<MeshOptions>(m, "MeshOptions", "Chordal deviation (mm), angular deflection (rad), maximum edge (mm, 0: none)")
      .def(py::init([](double deflection, double angle, double max_edge_length, double max_triangles) {
             const MeshOptions options{deflection, angle, max_edge_length, max_triangles};
             raise_if_failed(check_mesh_options(options));  // NaN, infinite, negative: ArgumentError
             return options;
           }),
           py::arg("deflection") = MeshOptions{}.deflection, py::arg("angle") = MeshOptions{}.angle,
           py::arg("max_edge_length") = 0.0, py::arg("max_triangles") = MeshOptions{}.max_triangles)
      .def_readwrite("deflection", &MeshOptions::deflection, "mm: chordal deviation")
      .def_readwrite("angle", &MeshOptions::angle, "radians: angular deflection")
      .def_readwrite("max_edge_length", &MeshOptions::max_edge_length, "mm; 0: no bound")
      .def_readwrite("max_triangles", &MeshOptions::max_triangles, "refused beyond this many triangles (estimated first)");

  m.def("estimated_triangles", [](const Body& body, const MeshOptions& options) {
          return call_guarded([&] { return estimated_triangles(body.shape, options); });
        }, py::arg("body"), py::arg("options") = MeshOptions{},
        "A lower bound of the triangles mesh_assembly makes of the body with these options (no meshing).");

  py::class_<TaggedMesh>(m, "TaggedMesh", "Triangles sharing vertices, each tagged with its FaceN and partition")
      .def_property_readonly("vertices", &vertex_list, "[(x, y, z)] in mm")
      .def_property_readonly("triangles", &triangle_list, "[(i, j, k)], counter-clockwise seen from outside")
      .def_property_readonly("triangle_face", read_only(&TaggedMesh::triangle_face), "1-based FaceN of each triangle")
      .def_property_readonly("triangle_partition", read_only(&TaggedMesh::triangle_partition), "partition id of each triangle")
      .def_property_readonly("partition_count", read_only(&TaggedMesh::partition_count), "number of partitions of the body")
      .def(
          "write_ply",
          [](const TaggedMesh& mesh, const std::string& path) { raise_if_failed(guarded([&] { return write_ply(mesh, path); })); },
          py::arg("path"), "ASCII PLY: vertex x y z; face vertex_indices, face, partition")
      .def("__repr__", [](const TaggedMesh& mesh) {
        return "<TaggedMesh " + std::to_string(mesh.triangles.size()) + " triangles, " +
               std::to_string(mesh.vertices.size()) + " vertices>";
      });

  py::class_<MeshQuality>(m, "MeshQuality", "Closure and shape of a mesh's triangles")
      .def_property_readonly("triangles", read_only(&MeshQuality::triangles), "number of triangles")
      .def_property_readonly("boundary_edges", read_only(&MeshQuality::boundary_edges), "edges in one triangle only")
      .def_property_readonly("nonmanifold_edges", read_only(&MeshQuality::nonmanifold_edges), "edges in three or more triangles")
      .def_property_readonly("watertight", read_only(&MeshQuality::watertight), "every edge in exactly two triangles")
      .def_property_readonly("min_angle_deg", read_only(&MeshQuality::min_angle_deg), "degrees: smallest angle of any triangle")
      .def_property_readonly("aspect_p50", read_only(&MeshQuality::aspect_p50), "median aspect ratio (1: equilateral)")
      .def_property_readonly("aspect_p90", read_only(&MeshQuality::aspect_p90), "90th percentile aspect ratio")
      .def_property_readonly("aspect_p99", read_only(&MeshQuality::aspect_p99), "99th percentile aspect ratio")
      .def_property_readonly("aspect_max", read_only(&MeshQuality::aspect_max), "largest aspect ratio")
      .def_property_readonly("max_edge_length", read_only(&MeshQuality::max_edge_length), "mm: longest edge");

  py::class_<MeshResult>(m, "MeshResult", "A body's tagged mesh and its quality")
      .def_property_readonly("mesh", read_only(&MeshResult::mesh), "TaggedMesh")
      .def_property_readonly("quality", read_only(&MeshResult::quality), "MeshQuality")
      .def_property_readonly("failed_faces", [](const MeshResult& r) {
        py::list out;
        for (const FaceFailure& f : r.failed_faces) out.append(py::make_tuple("Face" + std::to_string(f.face), f.message));
        return out;
      }, "[(\"FaceN\", message)]: faces OCCT could not tessellate, left out of the mesh")
      .def_property_readonly("invalid_reason", read_only(&MeshResult::invalid_reason), "why the body is not a valid solid ('': valid)")
      .def_property_readonly("invalid_faces", [](const MeshResult& r) { return face_names(r.invalid_faces); },
                             "the faces of the fault ([]: the whole solid)");

  m.def(
      "mesh_quality", [](const TaggedMesh& mesh) { return call_guarded([&] { return mesh_quality(mesh); }); },
      py::arg("mesh"), "Closure and triangle shape of a mesh.");

  m.def(
      "mesh_assembly",
      [](const Assembly& assembly, const MeshOptions& options, std::optional<double> linear,
         std::optional<double> angular) {
        std::vector<MeshResult> results(assembly.bodies.size());
        raise_if_failed(guarded([&] {
          const OcctGuard guard;  // a signal inside OCCT fails the body, named
          std::vector<TopoDS_Shape> shapes;
          std::vector<std::string> names;
          for (const Body& body : assembly.bodies) shapes.push_back(body.shape), names.push_back(body.name);
          if (const Status budget = check_triangle_budget(shapes, names, options); !budget.ok()) return budget;
          std::vector<BodyPartitions> kept(assembly.bodies.size());
          double made = 0;
          for (std::size_t i = 0; i < assembly.bodies.size(); ++i) {
            // Each body's own tolerances, as find_contacts gives it.
            Tolerances tolerances;
            Status own = body_tolerances(assembly.bodies[i].shape, linear, angular, tolerances);
            if (!own.ok()) {
              own.body = assembly.bodies[i].name;
              return own;
            }
            const Status status = partition_and_build(
                assembly.bodies[i], tolerances, results[i],
                [&](const TopoDS_Shape& shape, const BodyPartitions& partitions) {
                  kept[i] = partitions;
                  return mesh_body(shape, partitions, options);
                });
            if (!status.ok()) return status;
            // The estimate is not exact: the meshes made so far count too.
            made += static_cast<double>(results[i].quality.triangles);
            if (made > options.max_triangles) {
              Status over = Status::failure(StatusCode::InvalidInput,
                                            "the meshes made so far hold " + std::to_string(static_cast<long long>(made)) +
                                                " triangles: more than the limit of " +
                                                std::to_string(static_cast<long long>(options.max_triangles)) +
                                                " (CLI --max-triangles); ask for coarser sizes");
              over.body = assembly.bodies[i].name;
              return over;
            }
          }
          // Invalid solids are meshed all the same, and named (meshes.json).
          std::vector<InvalidBody> invalid;
          if (const Status checked = find_invalid_solids(assembly, kept, invalid); !checked.ok()) return checked;
          for (const InvalidBody& body : invalid) {
            results[body.body].invalid_reason = body.reason;
            results[body.body].invalid_faces = body.faces;
          }
          return Status::success();
        }));
        return results;
      },
      py::arg("assembly"), py::arg("options") = MeshOptions{}, py::arg("linear") = py::none(),
      py::arg("angular") = py::none(),
      "Partitions (tolerances as find_contacts) and tessellates every body: one MeshResult per body, in order.\n"
      "A face OCCT could not tessellate is left out and named in MeshResult.failed_faces. Raises InputError\n"
      "before meshing when the estimated triangles exceed options.max_triangles.");
}

}  // namespace contactcore::bindings
