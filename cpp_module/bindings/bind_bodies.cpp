// Bodies: STEP files read in C++, FreeCAD shapes handed over as BRep text.
#include "common.h"

#include "contactcore/bodies.h"

namespace contactcore::bindings {

void bind_bodies(py::module_& m) {
  py::class_<Body>(m, "Body", "A solid of the assembly with its global placement (mm).")
      .def_readonly("name", &Body::name)
      .def_readonly("path", &Body::path)
      .def_property_readonly("brep", [](const Body& b) { return shape_to_brep(b.shape); },
                             "The located shape as BRep text (Part.Shape.importBrepFromString).")
      .def_property_readonly("volume", [](const Body& b) { return mass_properties(b.shape).volume; })
      .def_property_readonly("center", [](const Body& b) { return to_tuple(mass_properties(b.shape).centre); },
                             "Centre of mass (x, y, z), mm.")
      .def("__repr__", [](const Body& b) { return "<Body '" + b.name + "' path='" + b.path + "'>"; });

  py::class_<Assembly>(m, "Assembly", "Bodies of an assembly, in mm, with the source file's unit.")
      .def_readonly("bodies", &Assembly::bodies)
      .def_readonly("units", &Assembly::units)
      .def_readonly("source_unit_in_mm", &Assembly::source_unit_in_mm)
      .def_readonly("messages", &Assembly::messages)
      .def("to_brep", [](const Assembly& a) { return shape_to_brep(assembly_compound(a)); },
           "All bodies as one compound, BRep text.")
      .def("__len__", [](const Assembly& a) { return a.bodies.size(); })
      .def("__repr__", [](const Assembly& a) {
        return "<Assembly " + std::to_string(a.bodies.size()) + " bodies, units " + a.units + ">";
      });

  m.def(
      "read_step",
      [](const std::string& path) {
        AssemblyResult result;
        raise_if_failed(guarded([&] {
          result = read_step(path);
          return result.status;
        }));
        return result.assembly;
      },
      py::arg("path"),
      "Reads a STEP file through OCCT's XDE reader: product names, instances, units (shapes in mm).");

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
}

}  // namespace contactcore::bindings
