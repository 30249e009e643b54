// Stage 5c in Python: blocking graphs and the removal sequence.
#include "common.h"
#include "contactcore/simulation/disassembly.h"

namespace contactcore::bindings {

void bind_disassembly(py::module_& m) {
  py::class_<DisassemblyStep>(m, "DisassemblyStep", "Parts moved together along one direction")
      .def_readonly("parts", &DisassemblyStep::parts)
      .def_readonly("direction", &DisassemblyStep::direction);

  py::class_<DisassemblyResult>(m, "DisassemblyResult", "Removal order, blocking graphs, or why none exists")
      .def_readonly("steps", &DisassemblyResult::steps)
      .def_readonly("base", &DisassemblyResult::base)
      .def_readonly("complete", &DisassemblyResult::complete)
      .def_readonly("reason", &DisassemblyResult::reason)
      .def_readonly("messages", &DisassemblyResult::messages)
      .def_readonly("directions", &DisassemblyResult::directions)
      .def_readonly("blocking", &DisassemblyResult::blocking, "blocking[d][i]: parts blocking part i along directions[d]");

  m.def(
      "disassemble",
      [](const Assembly& assembly, const MeshOptions& mesh_options, double tolerance, std::optional<double> linear,
         std::optional<double> angular, const std::vector<std::vector<Direction>>& extra_directions) {
        ContactOptions contact_options;
        contact_options.linear = linear;
        contact_options.angular = angular;
        DisassemblyOptions options;
        options.tolerance = tolerance;
        DisassemblyResult result;
        raise_if_failed(guarded([&] {
          result = disassemble(assembly, contact_options, mesh_options, options, extra_directions);
          return result.status;
        }));
        return result;
      },
      py::arg("assembly"), py::arg("mesh_options") = MeshOptions{}, py::arg("tolerance") = DisassemblyOptions{}.tolerance,
      py::arg("linear") = py::none(), py::arg("angular") = py::none(),
      py::arg("extra_directions") = std::vector<std::vector<Direction>>{},
      "Contacts, joints, meshes, then blocking and the removal sequence (see disassembly.h).");
}

}  // namespace contactcore::bindings
