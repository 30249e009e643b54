// Joints, mobility, liaison graph and clearance fits.
#include "common.h"

#include <sstream>

#include "contactcore/contacts/clearances.h"
#include "contactcore/joints/joints.h"

namespace contactcore::bindings {

namespace {

py::list directions(const std::vector<gp_Dir>& dirs) {
  py::list out;
  for (const gp_Dir& d : dirs) out.append(to_tuple(d));
  return out;
}

py::list rotations(const std::vector<FreeRotation>& axes) {
  py::list out;
  for (const FreeRotation& r : axes) out.append(py::make_tuple(to_tuple(r.point), to_tuple(r.direction)));
  return out;
}

}  // namespace

void bind_joints(py::module_& m) {
  py::class_<Clearance>(m, "Clearance", "A fit with play (same surface, radii or planes a small gap apart).")
      .def_readonly("body_a", &Clearance::body_a, "index into Assembly.bodies, body_a < body_b")
      .def_readonly("body_b", &Clearance::body_b, "index into Assembly.bodies")
      .def_readonly("partition_a", &Clearance::partition_a, "partition id within body_a")
      .def_readonly("partition_b", &Clearance::partition_b, "partition id within body_b")
      .def_property_readonly("kind", [](const Clearance& c) { return std::string(to_string(c.kind)); },
          "surface kind name: 'Cylinder', 'Sphere', 'Plane', ...")
      .def_readonly("gap", &Clearance::gap, "mm, radial (cylinders, spheres) or normal (planes)")
      .def("__repr__", [](const Clearance& c) {
        std::ostringstream out;
        out << "<Clearance " << to_string(c.kind) << " bodies " << c.body_a << "-" << c.body_b << " gap=" << c.gap
            << ">";
        return out.str();
      });

  py::class_<OneSidedStop>(m, "OneSidedStop", "A unilateral contact: b may move with u . normal >= 0 at point.")
      .def_readonly("contact", &OneSidedStop::contact, "index into ContactsResult.contacts")
      .def_readonly("higher_pair", &OneSidedStop::higher_pair, "index into ContactsResult.higher_pairs (-1: a surface contact)")
      .def_property_readonly("point", [](const OneSidedStop& s) { return to_tuple(s.point); },
          "(x, y, z) mm where the unilateral force acts")
      .def_property_readonly("normal", [](const OneSidedStop& s) { return to_tuple(s.normal); },
          "unit (x, y, z) out of a's material");

  py::class_<PairJoint>(m, "PairJoint", "What two bodies in contact allow each other (b relative to a).")
      .def_readonly("body_a", &PairJoint::body_a, "index into Assembly.bodies, body_a < body_b")
      .def_readonly("body_b", &PairJoint::body_b, "index into Assembly.bodies")
      .def_readonly("contacts", &PairJoint::contacts, "indices into ContactsResult.contacts")
      .def_readonly("higher_pairs", &PairJoint::higher_pairs, "indices into ContactsResult.higher_pairs")
      .def_readonly("annotated_rigid", &PairJoint::annotated_rigid, "made rigid by the designer's annotations")
      .def_property_readonly("type", [](const PairJoint& j) { return std::string(to_string(j.type)); },
          "ISO 3952 name: 'rigid', 'revolute', 'cylindrical', ...")
      .def_readonly("dof", &PairJoint::dof, "degrees of freedom, = len(free_twists)")
      .def_readonly("free_twists", &PairJoint::free_twists,
                    "basis of free twists (wx, wy, wz, vx, vy, vz), v at the global origin")
      .def_property_readonly("rotations", [](const PairJoint& j) { return rotations(j.rotations); },
                             "[(point, direction)] per rotational DOF")
      .def_property_readonly("translations", [](const PairJoint& j) { return directions(j.translations); },
          "[unit (x, y, z)] per translational DOF")
      .def_readonly("pitch", &PairJoint::pitch, "mm per radian (helical joints only)")
      .def_readonly("stops", &PairJoint::stops, "[OneSidedStop]: unilateral contacts")
      .def_property_readonly("free_directions", [](const PairJoint& j) { return directions(j.free_directions); },
                             "generators of the cone of directions in which b can leave a")
      .def("__repr__", [](const PairJoint& j) {
        return "<PairJoint " + std::to_string(j.body_a) + "-" + std::to_string(j.body_b) + " " + to_string(j.type) +
               " dof=" + std::to_string(j.dof) + ">";
      });

  py::class_<JointsResult>(m, "JointsResult").def_readonly("joints", &JointsResult::joints,
      "[PairJoint], one per body pair in contact, sorted (a, b)");

  py::class_<PassiveSpin>(m, "PassiveSpin", "A rotation a body makes alone, every neighbour held still.")
      .def_readonly("body", &PassiveSpin::body, "index into Assembly.bodies")
      .def_property_readonly("point", [](const PassiveSpin& s) { return to_tuple(s.axis.point); },
          "(x, y, z) mm on the axis")
      .def_property_readonly("direction", [](const PassiveSpin& s) { return to_tuple(s.axis.direction); },
          "unit (x, y, z) of the axis");

  py::class_<GroupMotion>(m, "GroupMotion", "A rigid group's motion relative to the ground, passive spins aside.")
      .def_readonly("group", &GroupMotion::group, "index into MobilityResult.groups")
      .def_property_readonly("type", [](const GroupMotion& g) { return std::string(to_string(g.type)); },
          "ISO 3952 name of the motion")
      .def_readonly("dof", &GroupMotion::dof, "degrees of freedom")
      .def_property_readonly("rotations", [](const GroupMotion& g) { return rotations(g.rotations); },
          "[(point, direction)] per rotational DOF")
      .def_property_readonly("translations", [](const GroupMotion& g) { return directions(g.translations); },
          "[unit (x, y, z)] per translational DOF")
      .def_readonly("pitch", &GroupMotion::pitch, "mm per radian (helical only)")
      .def_readonly("passive_spins", &GroupMotion::passive_spins, "[PassiveSpin] of the group's bodies");

  py::class_<MobilityResult>(m, "MobilityResult", "Degrees of freedom, rigid groups and their motions.")
      .def_readonly("ground", &MobilityResult::ground, "index of the body held still")
      .def_readonly("dof", &MobilityResult::dof, "every free motion, passive spins included")
      .def_readonly("passive", &MobilityResult::passive, "number of passive spins")
      .def_readonly("groups", &MobilityResult::groups, "[[body index]]: rigid groups, groups[0] holds the ground")
      .def_readonly("group_of_body", &MobilityResult::group_of_body, "group index per body")
      .def_readonly("group_motions", &MobilityResult::group_motions, "[GroupMotion], one per group, same order")
      .def_readonly("passive_spins", &MobilityResult::passive_spins, "[PassiveSpin]")
      .def_readonly("components", &MobilityResult::components,
          "[[body index]]: connected components of the contact graph");

  m.def(
      "find_joints",
      [](const Assembly& assembly, const ContactsResult& contacts, double rank_tolerance,
         const std::vector<std::string>& contact_intents, const std::vector<std::string>& higher_pair_intents) {
        JointOptions options;
        options.rank_tolerance = rank_tolerance;
        // The designer's intents, one string per contact ("" unspecified).
        const auto parse = [](const std::vector<std::string>& texts, std::size_t count, const char* what,
                              std::vector<ContactIntent>& out) {
          if (texts.size() > count)
            raise_if_failed(Status::failure(StatusCode::InvalidArgument,
                                            std::string("more ") + what + " intents (" + std::to_string(texts.size()) +
                                                ") than " + what + "s (" + std::to_string(count) + ")"));
          for (std::size_t i = 0; i < texts.size(); ++i) {
            ContactIntent intent = ContactIntent::Unspecified;
            if (!texts[i].empty() && !parse_intent(texts[i], intent))
              raise_if_failed(Status::failure(StatusCode::InvalidArgument,
                                              std::string("unknown intent '") + texts[i] + "' for " + what + " " +
                                                  std::to_string(i) +
                                                  ": use clearance, transition, interference, bonded, ignored or threaded"));
            out.push_back(intent);
          }
        };
        parse(contact_intents, contacts.contacts.size(), "contact", options.contact_intents);
        parse(higher_pair_intents, contacts.higher_pairs.size(), "higher pair", options.higher_pair_intents);
        JointsResult result;
        raise_if_failed(guarded([&] {
          result = find_joints(assembly, contacts, options);
          return result.status;
        }));
        return result;
      },
      py::arg("assembly"), py::arg("contacts"), py::arg("rank_tolerance") = JointOptions{}.rank_tolerance,
      py::arg("contact_intents") = std::vector<std::string>{},
      py::arg("higher_pair_intents") = std::vector<std::string>{},
      "The joint of every body pair in contact (b relative to a). `contact_intents`: the designer's intent "
      "per contact (\"clearance\", \"transition\", \"interference\", \"bonded\", \"ignored\", \"threaded\" or \"\"): "
      "interference, transition, bonded and threaded make the pair rigid, ignored contacts are left out.");

  m.def(
      "body_free_directions",
      [](const ContactsResult& contacts, const JointsResult& joints, int body) {
        return directions(call_guarded([&] { return body_free_directions(contacts, joints, body); }));
      },
      py::arg("contacts"), py::arg("joints"), py::arg("body"),
      "Generators of the directions in which a body can translate out, its neighbours held still.");

  m.def(
      "assembly_mobility",
      [](const Assembly& assembly, const ContactsResult& contacts, const JointsResult& joints, int ground) {
        MobilityOptions options;
        options.ground = ground;
        MobilityResult result;
        raise_if_failed(guarded([&] {
          result = assembly_mobility(assembly, contacts, joints, options);
          return result.status;
        }));
        return result;
      },
      py::arg("assembly"), py::arg("contacts"), py::arg("joints"), py::arg("ground") = -1,
      "DOF, rigid groups and group motions with body `ground` held still (-1: the largest by volume).");

  m.def(
      "liaison_graph_dot",
      [](const Assembly& assembly, const JointsResult& joints, const MobilityResult* mobility) {
        return call_guarded([&] { return liaison_graph_dot(assembly, joints, mobility); });
      },
      py::arg("assembly"), py::arg("joints"), py::arg("mobility") = nullptr,
      "The liaison graph in Graphviz DOT (rigid groups as clusters when mobility is given).");

  m.def(
      "find_clearances",
      [](const ContactsResult& contacts, double gap) {
        std::vector<Clearance> result;
        raise_if_failed(guarded([&] {
          result = find_clearances(contacts.partitions, gap);
          return Status::success();
        }));
        return result;
      },
      py::arg("contacts"), py::arg("gap"), "Clearance fits with a gap below `gap` mm, from the contacts' partitions.");
}

}  // namespace contactcore::bindings
