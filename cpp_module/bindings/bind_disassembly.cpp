// Stage 5c in Python: blocking graphs and the removal sequence.
#include "common.h"
#include "contactcore/simulation/disassembly.h"

namespace contactcore::bindings {

void bind_disassembly(py::module_& m) {
  py::class_<DisassemblyStep>(m, "DisassemblyStep", "Parts moved together along one direction")
      .def_readonly("parts", &DisassemblyStep::parts, "part indices moved together, ascending")
      .def_readonly("direction", &DisassemblyStep::direction, "unit (x, y, z)")
      .def_readonly("blocked_before", &DisassemblyStep::blocked_before,
                    "parts that blocked it along its direction at first, all removed before it")
      .def_readonly("released", &DisassemblyStep::released,
                    "indices of the threaded cylindrical contacts released (unscrewed) for this step");

  py::class_<DisassemblyResult>(m, "DisassemblyResult", "Removal order, blocking graphs, or why none exists")
      .def_readonly("steps", &DisassemblyResult::steps, "[DisassemblyStep] in removal order (the base is not a step)")
      .def_readonly("base", &DisassemblyResult::base, "the part left (the largest of the sub-assembly left), -1 "
                    "when the sequence stops early")
      .def_readonly("base_parts", &DisassemblyResult::base_parts, "every part left")
      .def_readonly("complete", &DisassemblyResult::complete, "every part but the base removed")
      .def_readonly("reason", &DisassemblyResult::reason, "why no sequence exists (when not complete)")
      .def_readonly("messages", &DisassemblyResult::messages, "warnings (faces left out, invalid solids)")
      .def_readonly("directions", &DisassemblyResult::directions, "[unit (x, y, z)]: every candidate direction used")
      .def_readonly("blocking", &DisassemblyResult::blocking,
          "blocking[d][i]: parts blocking part i along directions[d]");

  m.def(
      "disassemble",
      [](const Assembly& assembly, const MeshOptions& mesh_options, double tolerance, std::optional<double> linear,
         std::optional<double> angular, const std::vector<std::vector<Direction>>& extra_directions,
         const ContactsResult* contacts, const std::vector<std::string>& contact_intents, bool sample_free_cones) {
        ContactOptions contact_options;
        contact_options.linear = linear;
        contact_options.angular = angular;
        DisassemblyOptions options;
        options.tolerance = tolerance;
        options.sample_free_cones = sample_free_cones;
        if (!contact_intents.empty() && (contacts == nullptr || contact_intents.size() != contacts->contacts.size()))
          raise_if_failed(Status::failure(StatusCode::InvalidArgument,
                                          "contact_intents needs `contacts` and one intent per contact (" +
                                              std::to_string(contact_intents.size()) + " given)"));
        for (std::size_t i = 0; i < contact_intents.size(); ++i) {
          ContactIntent intent = ContactIntent::Unspecified;
          if (!contact_intents[i].empty() && !parse_intent(contact_intents[i], intent))
            raise_if_failed(Status::failure(StatusCode::InvalidArgument, "unknown intent '" + contact_intents[i] +
                                                                             "' for contact " + std::to_string(i)));
          options.contact_intents.push_back(intent);
        }
        DisassemblyResult result;
        raise_if_failed(guarded([&] {
          result = disassemble(assembly, contact_options, mesh_options, options, extra_directions, nullptr, contacts);
          return result.status;
        }));
        return result;
      },
      py::arg("assembly"), py::arg("mesh_options") = MeshOptions{}, py::arg("tolerance") = DisassemblyOptions{}.tolerance,
      py::arg("linear") = py::none(), py::arg("angular") = py::none(),
      py::arg("extra_directions") = std::vector<std::vector<Direction>>{}, py::arg("contacts") = nullptr,
      py::arg("contact_intents") = std::vector<std::string>{}, py::arg("sample_free_cones") = true,
      "Contacts (or `contacts`, found already with the same tolerances), joints, meshes, then blocking and the "
      "removal sequence (see disassembly.h). `contact_intents`: one per contact of `contacts` (\"\" none, "
      "clearance, transition, interference, bonded, ignored, threaded): fitted, bonded and threaded parts come out "
      "together; threads are undone (unscrewed) when nothing else can leave, bonds never.");
}

}  // namespace contactcore::bindings
