// Stage 5c in Python: blocking graphs and the removal sequence.
#include "common.h"
#include "contactcore/simulation/disassembly.h"

namespace contactcore::bindings {

void bind_disassembly(py::module_& m) {
  py::class_<DisassemblyStep>(m, "DisassemblyStep", "Parts moved together along one direction")
      .def_readonly("parts", &DisassemblyStep::parts, "part indices moved together, ascending")
      .def_readonly("direction", &DisassemblyStep::direction, "unit (x, y, z)");

  py::class_<DisassemblyResult>(m, "DisassemblyResult", "Removal order, blocking graphs, or why none exists")
      .def_readonly("steps", &DisassemblyResult::steps, "[DisassemblyStep] in removal order (the base is not a step)")
      .def_readonly("base", &DisassemblyResult::base, "the part left, -1 when the sequence stops early")
      .def_readonly("complete", &DisassemblyResult::complete, "every part but the base removed")
      .def_readonly("reason", &DisassemblyResult::reason, "why no sequence exists (when not complete)")
      .def_readonly("messages", &DisassemblyResult::messages, "warnings (faces left out, invalid solids)")
      .def_readonly("directions", &DisassemblyResult::directions, "[unit (x, y, z)]: every candidate direction used")
      .def_readonly("blocking", &DisassemblyResult::blocking,
          "blocking[d][i]: parts blocking part i along directions[d]");

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
