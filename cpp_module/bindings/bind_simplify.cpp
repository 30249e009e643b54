// Stage 5a' in Python: the view and collision models of bodies, the
// collision model simplified (small features removed) within an envelope.

#include "common.h"
#include "contactcore/bodies/bodies.h"
#include "contactcore/common/occt_guard.h"
#include "contactcore/simulation/simplify.h"

namespace contactcore::bindings {

void bind_simplify(py::module_& m) {
  py::class_<SimulationModels>(m, "SimulationModels",
                               "A body's view model (original B-rep) and collision model (simplified)")
      .def_property_readonly("view", read_only(&SimulationModels::view), "MeshResult of the original B-rep")
      .def_property_readonly("view_deviation", read_only(&SimulationModels::view_deviation),
                    "mm: farthest point of the view mesh from the original B-rep")
      .def_property_readonly("collision", read_only(&SimulationModels::collision), "MeshResult of the simplified (or original) shape")
      .def_property_readonly("simplified", read_only(&SimulationModels::simplified), "small features were removed")
      .def_property_readonly("collision_hausdorff", read_only(&SimulationModels::collision_hausdorff),
                    "mm: two-sided Hausdorff distance to the original when simplified, else the mesh's deviation")
      .def_property_readonly("removed_faces", read_only(&SimulationModels::removed_faces), "1-based FaceN of the original")
      .def_property_readonly("features_kept", read_only(&SimulationModels::features_kept), "small features OCCT could not remove")
      .def_property_readonly("message", read_only(&SimulationModels::message), "why the simplification was refused, if it was");

  m.def(
      "simulation_models",
      [](const Assembly& assembly, const MeshOptions& view, const MeshOptions& collision, double feature_size,
         double envelope, std::optional<double> linear, std::optional<double> angular,
         std::optional<std::vector<int>> bodies) {
        if (!std::isfinite(feature_size) || !std::isfinite(envelope) || feature_size < 0 || envelope < 0 ||
            (feature_size > 0 && envelope <= 0))
          raise_argument_error("a feature size needs a positive envelope (both in mm)");
        std::vector<int> chosen;
        if (bodies) {
          chosen = *bodies;
          for (int i : chosen)
            if (i < 0 || i >= static_cast<int>(assembly.bodies.size()))
              raise_argument_error("no body number " + std::to_string(i));
        } else {
          for (std::size_t i = 0; i < assembly.bodies.size(); ++i) chosen.push_back(static_cast<int>(i));
        }
        std::vector<SimulationModels> results(chosen.size());
        raise_if_failed(guarded([&] {
          const OcctGuard guard;  // a signal inside OCCT fails the body, named
          std::vector<TopoDS_Shape> shapes;
          std::vector<std::string> names;
          for (int i : chosen) shapes.push_back(assembly.bodies[i].shape), names.push_back(assembly.bodies[i].name);
          if (const Status budget = check_triangle_budget(shapes, names, view); !budget.ok()) return budget;
          SimulationModelOptions options;
          options.view = view;
          options.collision = collision;
          options.feature_size = feature_size;
          options.envelope = envelope;
          for (std::size_t k = 0; k < chosen.size(); ++k) {
            // Each body's own tolerances, as find_contacts gives it.
            Tolerances tolerances;
            Status own = body_tolerances(assembly.bodies[chosen[k]].shape, linear, angular, tolerances);
            if (!own.ok()) {
              own.body = assembly.bodies[chosen[k]].name;
              return own;
            }
            const Status status = partition_and_build(
                assembly.bodies[chosen[k]], tolerances, results[k],
                [&](const TopoDS_Shape& shape, const BodyPartitions& partitions) {
                  return simulation_models(shape, partitions, options);
                });
            if (!status.ok()) return status;
          }
          return Status::success();
        }));
        return results;
      },
      py::arg("assembly"), py::arg("view") = MeshOptions{}, py::arg("collision") = MeshOptions{},
      py::arg("feature_size") = 0.0, py::arg("envelope") = 0.0, py::arg("linear") = py::none(),
      py::arg("angular") = py::none(), py::arg("bodies") = py::none(),
      "View and collision models of the bodies (all, or the given numbers), in order: partitions with the\n"
      "tolerances of find_contacts, the collision model without the features below feature_size (mm) unless\n"
      "that leaves the envelope (mm). Raises ContactsError naming the body OCCT could not mesh.");
}

}  // namespace contactcore::bindings
