// Bodies: STEP files read in C++, FreeCAD shapes handed over as BRep text.
#include "common.h"

#include "contactcore/bodies/bodies.h"
#include "contactcore/bodies/assembly_of_bodies.h"
#include "contactcore/bodies/inertia.h"
#include "contactcore/common/occt_guard.h"

namespace contactcore::bindings {

namespace {
// The body's cached mass properties; an OCCT failure raises ContactsError naming the body.
MassProperties mass_of(const Body& body) {
  MassProperties mass;
  Status status = guarded([&] {
    const OcctGuard guard;  // a signal inside OCCT: an error naming the body
    mass = body.mass();
    return Status::success();
  });
  status.body = status.ok() ? "" : body.name;
  raise_if_failed(status);
  return mass;
}
}  // namespace

void bind_bodies(py::module_& m) {
  py::class_<Body>(m, "Body", "A solid of the assembly with its global placement (mm).")
      .def_property_readonly("name", read_only(&Body::name), "unique within the assembly")
      .def_property_readonly("path", read_only(&Body::path), "assembly tree path, 'Root/Sub/Part' (STEP) or the caller's")
      .def_property_readonly("brep", [](const Body& b) { return call_guarded([&] { return shape_to_brep(b.shape); }); },
                             "The located shape as BRep text (Part.Shape.importBrepFromString).")
      .def_property_readonly("volume", [](const Body& b) { return mass_of(b).volume; },
                             "Volume, mm^3 (computed on first use, then kept).")
      .def_property_readonly("center", [](const Body& b) { return to_tuple(mass_of(b).centre); },
                             "Centre of mass (x, y, z), mm (computed on first use, then kept).")
      .def(
          "inertia",
          [](const Body& b) {
            BodyInertia inertia;
            {
              py::gil_scoped_release release;
              inertia = body_inertia(b);
            }
            raise_if_failed(inertia.status);
            return py::make_tuple(inertia.volume, to_tuple(gp_Pnt(inertia.centre[0], inertia.centre[1],
                                                                   inertia.centre[2])),
                                  inertia.tensor);
          },
          "(volume mm^3, centre of mass (x, y, z) mm, inertia tensor about the centre, global axes, at unit "
          "density, mm^5, as 3 rows): OCCT GProp's volume integration, computed on each call.")
      .def("__repr__", [](const Body& b) { return "<Body '" + b.name + "' path='" + b.path + "'>"; });

  py::class_<Assembly>(m, "Assembly", "Bodies of an assembly, in mm, with the source file's unit.")
      .def_property_readonly("bodies", read_only(&Assembly::bodies), "[Body], in the file's order")
      .def_property_readonly("units", read_only(&Assembly::units), "unit of the source file ('mm', 'inch', ...); shapes are always in mm")
      .def_property_readonly("source_unit_in_mm", read_only(&Assembly::source_unit_in_mm),
          "mm per unit of the source file (25.4 for an inch file)")
      .def_property_readonly("messages", read_only(&Assembly::messages), "what was skipped and why (open shells, ...)")
      .def_property_readonly("reader", read_only(&Assembly::reader), "STEP: 'products' (the fast read) or 'xde' (its fallback); else ''")
      .def("to_brep", [](const Assembly& a) { return call_guarded([&] { return shape_to_brep(assembly_compound(a)); }); },
           "All bodies as one compound, BRep text.")
      .def(
          "compute_mass_properties",
          [](const Assembly& a, int threads) {
            raise_if_failed(guarded([&] { return compute_mass_properties(a, threads); }));
          },
          py::arg("threads") = 0,
          "Volumes and centres of every body at once, on all cores (each shared shape once); "
          "Body.volume and Body.center then read them.")
      .def("__len__", [](const Assembly& a) { return a.bodies.size(); })
      .def("__repr__", [](const Assembly& a) {
        return "<Assembly " + std::to_string(a.bodies.size()) + " bodies, units " + a.units + ">";
      });

  m.def(
      "read_step",
      [](const std::string& path, py::object progress, const std::string& reader, std::size_t max_bodies) {
        if (reader != "products" && reader != "xde")
          raise_argument_error("reader must be 'products' or 'xde', not '" + reader + "'");
        std::unique_ptr<PythonProgress> reporter;
        if (!progress.is_none()) reporter = std::make_unique<PythonProgress>(progress);
        AssemblyResult result;
        const Status status = guarded([&] {
          result = read_step(path, reporter.get(), reader == "xde" ? StepReadMode::Xde : StepReadMode::Products,
                             max_bodies);
          return result.status;
        });
        if (reporter) reporter->rethrow_if_raised();
        raise_if_failed(status);
        return result.assembly;
      },
      py::arg("path"), py::arg("progress") = py::none(), py::arg("reader") = "products",
      py::arg("max_bodies") = std::size_t{1'000'000},
      "Reads a STEP file: product names, instances, units (shapes in mm). reader='products' (the default) "
      "transfers each product once and places its instances, falling back to OCCT's XDE reader (said in "
      "Assembly.messages and by a progress stage 'read (XDE fallback)') on a product structure it does not "
      "know; reader='xde' uses the XDE reader alone. Assembly.reader says which read the file. "
      "`progress(\"read\", fraction)` returning False cancels (raises contactcore.Cancelled), also "
      "inside OCCT's transfer. An assembly expanding to more than `max_bodies` instances is refused "
      "(InputError) before the transfer.");

  m.def(
      "unique_names",
      [](const std::vector<std::string>& names) { return call_guarded([&] { return unique_names(names); }); },
      py::arg("names"),
        "Names made unique by appending '.2', '.3', ... to repeats, in order (linear time).");

  m.def(
      "bodies_from_brep",
      [](const std::string& brep, const std::vector<std::string>& names) {
        AssemblyResult result;
        raise_if_failed(guarded([&] {
          result = bodies_from_brep(brep, names);
          return result.status;
        }));
        return result.assembly;
      },
      py::arg("brep"), py::arg("names"),
      "Bodies from one BRep compound (one child per body, named in order).");

  m.def(
      "assembly_of_bodies",
      [](const std::vector<Body>& bodies, const std::vector<std::string>& names) {
        AssemblyResult result;
        raise_if_failed(guarded([&] {
          result = assembly_of_bodies(bodies, names);
          return result.status;
        }));
        return result.assembly;
      },
      py::arg("bodies"), py::arg("names"),
      "An Assembly of Body objects read before (from other Assemblies: their shapes and computed volumes "
      "shared, not copied), named in order and made unique as bodies_from_brep does: what bodies_from_brep "
      "gives for the compound of their shapes, without the BRep text.");
}

}  // namespace contactcore::bindings
