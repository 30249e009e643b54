// Contacts: the whole stage on an assembly, with progress and cancellation.
#include "common.h"

#include <pybind11/numpy.h>

#include <algorithm>
#include <memory>
#include <optional>
#include <sstream>

#include "contactcore/common/angles.h"
#include "contactcore/contacts/contacts.h"
#include "contactcore/contacts/contacts_memo.h"

#include <BRepGProp.hxx>
#include <GProp_GProps.hxx>
#include <TopExp_Explorer.hxx>

namespace contactcore::bindings {

namespace {

double region_area(const TopoDS_Shape& region) {
  if (region.IsNull()) return 0.0;
  GProp_GProps properties;
  BRepGProp::SurfaceProperties(region, properties);
  return properties.Mass();
}

// find_contacts' `regions`: False, True (all), or body indices (an empty list: none).
void set_regions(ContactOptions& options, const py::object& regions) {
  if (py::isinstance<py::bool_>(regions)) {
    options.regions = regions.cast<bool>();
    return;
  }
  if (regions.is_none()) return;
  try {
    options.region_bodies = regions.cast<std::vector<int>>();
  } catch (const py::cast_error&) {
    raise_argument_error("regions must be True, False or a list of body indices");
  }
  options.regions = !options.region_bodies.empty();
}

}  // namespace

void bind_contacts(py::module_& m) {
  py::enum_<ContactType>(m, "ContactType")
      .value("PLF", ContactType::PLF)
      .value("CLJ", ContactType::CLJ)
      .value("CJU", ContactType::CJU)
      .value("SPF", ContactType::SPF)
      .value("LAF", ContactType::LAF)
      .value("SPT", ContactType::SPT)
      .value("TRF", ContactType::TRF);

  py::class_<Contact>(m, "Contact", "A functional contact between two bodies.")
      .def_property_readonly("type", read_only(&Contact::type), "ContactType")
      .def_property_readonly("type_name", [](const Contact& c) { return std::string(to_string(c.type)); },
          "'PLF', 'CLJ', 'CJU', 'SPF', 'LAF', 'SPT' or 'TRF'")
      .def_property_readonly("body_a", read_only(&Contact::body_a), "index into Assembly.bodies, body_a < body_b")
      .def_property_readonly("body_b", read_only(&Contact::body_b), "index into Assembly.bodies")
      .def_property_readonly("partition_a", read_only(&Contact::partition_a), "partition id within body_a")
      .def_property_readonly("partition_b", read_only(&Contact::partition_b), "partition id within body_b")
      .def_property_readonly("faces_a", read_only(&Contact::faces_a), "1-based FaceN indices of body_a's faces in contact")
      .def_property_readonly("faces_b", read_only(&Contact::faces_b), "1-based FaceN indices of body_b's faces in contact")
      .def_property_readonly("face_names_a", [](const Contact& c) { return face_names(c.faces_a); },
          "['FaceN', ...] of body_a")
      .def_property_readonly("face_names_b", [](const Contact& c) { return face_names(c.faces_b); },
          "['FaceN', ...] of body_b")
      .def_property_readonly("point", [](const Contact& c) { return to_tuple(c.point); },
          "(x, y, z) mm: PLF a point of the common area; revolution: on the axis; sphere: centre")
      .def_property_readonly("direction", [](const Contact& c) { return to_tuple(c.direction); },
          "unit (x, y, z): PLF outward normal of body_a; revolution: axis")
      .def_property_readonly("radius", read_only(&Contact::radius), "mm: CLJ, SPF, LAF, SPT (ball radius), TRF (minor radius); else 0")
      .def_property_readonly("half_angle", read_only(&Contact::half_angle), "radians: CJU; else 0")
      .def_property_readonly("area", read_only(&Contact::area), "mm^2, exact common area (LAF, SPT: 0, they touch along a circle)")
      .def_property_readonly("partial", read_only(&Contact::partial), "a revolution contact spanning less than pi radians")
      .def_property_readonly("span", read_only(&Contact::span), "radians: common angular span (revolution contacts)")
      .def_property_readonly("tolerances", read_only(&Contact::tolerances), "Tolerances used")
      .def_property_readonly("region_axis", [](const Contact& c) { return to_tuple(c.region_axis); },
                             "SPF, LAF, SPT: middle of the directions from the centre to the common region")
      .def_property_readonly("region_angle", read_only(&Contact::region_angle),
                    "SPF, LAF, SPT: the common region lies within this angle of region_axis (pi: all around)")
      .def_property_readonly("has_region", [](const Contact& c) { return !c.region.IsNull(); },
                             "whether the common region was computed (find_contacts(regions=...), "
                             "find_common_regions); never for LAF, SPT")
      .def_property_readonly("region_area", [](const Contact& c) {
            return call_guarded([&] { return region_area(c.region); });
          }, "mm^2, area of the common region's faces (0 when not computed)")
      .def_property_readonly("region_faces", [](const Contact& c) {
            int faces = 0;
            for (TopExp_Explorer e(c.region, TopAbs_FACE); e.More(); e.Next()) ++faces;
            return faces;
          }, "number of faces of the common region")
      .def_property_readonly("region_brep", [](const Contact& c) {
            return c.region.IsNull() ? std::string() : call_guarded([&] { return shape_to_brep(c.region); });
          }, "the common region as BRep text (a compound of faces oriented out of body_a; "
             "Part.Shape.importBrepFromString), '' when not computed")
      .def("region_mesh", [](const Contact& c, double deflection, double angular) {
            RegionMesh mesh;
            const Status status = guarded([&] { return mesh_region(c.region, deflection, angular, mesh); });
            raise_if_failed(status);
            const py::ssize_t points = static_cast<py::ssize_t>(mesh.points.size() / 3);
            const py::ssize_t triangles = static_cast<py::ssize_t>(mesh.triangles.size() / 3);
            py::array_t<double> xyz({points, py::ssize_t(3)});
            std::copy(mesh.points.begin(), mesh.points.end(), xyz.mutable_data());
            py::array_t<int> corners({triangles, py::ssize_t(3)});
            std::copy(mesh.triangles.begin(), mesh.triangles.end(), corners.mutable_data());
            return py::make_tuple(xyz, corners);
          }, py::arg("deflection"), py::arg("angular") = 0.5,
          "(points (n, 3) float array, triangles (m, 3) int array) of the common region, meshed "
          "with this deflection (mm) and angle (radians); triangles wound counter-clockwise seen "
          "from outside body_a; empty arrays when not computed")
      .def("__repr__", [](const Contact& c) {
        std::ostringstream out;
        out << "<Contact " << to_string(c.type) << " bodies " << c.body_a << "-" << c.body_b
            << " area=" << c.area;
        if (c.radius > 0) out << " r=" << c.radius;
        if (c.partial) out << " partial span=" << c.span * 180.0 / kPi << "deg";
        out << ">";
        return out.str();
      });

  py::class_<HigherPair>(m, "HigherPair", "A point or line contact (apart from the surface contacts).")
      .def_property_readonly("type", [](const HigherPair& h) { return std::string(to_string(h.type)); },
          "'sphere_on_plane', 'sphere_on_cylinder', 'cylinder_on_plane', 'cylinder_on_cylinder', 'cone_on_plane', "
          "'torus_on_plane', 'torus_on_cylinder' or 'cone_on_cylinder'")
      .def_property_readonly("kind", [](const HigherPair& h) { return std::string(to_string(h.kind)); },
          "'point', 'line' or 'circle'")
      .def_property_readonly("axis", [](const HigherPair& h) { return to_tuple(h.axis); },
          "a circle's axis (its normals turn about it)")
      .def_property_readonly("radius", read_only(&HigherPair::radius), "mm: a circle's radius (0: a point or a line)")
      .def_property_readonly("body_a", read_only(&HigherPair::body_a), "index into Assembly.bodies")
      .def_property_readonly("body_b", read_only(&HigherPair::body_b), "index into Assembly.bodies")
      .def_property_readonly("partition_a", read_only(&HigherPair::partition_a), "partition id within body_a")
      .def_property_readonly("partition_b", read_only(&HigherPair::partition_b), "partition id within body_b")
      .def_property_readonly("faces_a", read_only(&HigherPair::faces_a), "1-based FaceN indices of body_a's faces in contact")
      .def_property_readonly("faces_b", read_only(&HigherPair::faces_b), "1-based FaceN indices of body_b's faces in contact")
      .def_property_readonly("face_names_a", [](const HigherPair& h) { return face_names(h.faces_a); },
          "['FaceN', ...] of body_a")
      .def_property_readonly("face_names_b", [](const HigherPair& h) { return face_names(h.faces_b); },
          "['FaceN', ...] of body_b")
      .def_property_readonly("point", [](const HigherPair& h) { return to_tuple(h.point); },
          "(x, y, z) mm: the point contact, or the middle of the line")
      .def_property_readonly("normal", [](const HigherPair& h) { return to_tuple(h.normal); },
                             "unit (x, y, z) out of body a's material")
      .def_property_readonly("start", [](const HigherPair& h) { return to_tuple(h.start); },
          "(x, y, z) mm: a line contact's first end (a point contact: the point)")
      .def_property_readonly("end", [](const HigherPair& h) { return to_tuple(h.end); },
          "(x, y, z) mm: a line contact's other end (a point contact: the point)")
      .def_property_readonly("length", read_only(&HigherPair::length), "mm: a line contact's length (0: a point)")
      .def("__repr__", [](const HigherPair& h) {
        return std::string("<HigherPair ") + to_string(h.type) + " bodies " + std::to_string(h.body_a) + "-" +
               std::to_string(h.body_b) + ">";
      });

  py::class_<StageTimes>(m, "StageTimes", "Seconds spent in each stage.")
      .def_property_readonly("partitions", read_only(&StageTimes::partitions), "seconds partitioning the bodies")
      .def_property_readonly("broad_phase", read_only(&StageTimes::broad_phase), "seconds finding body pairs with meeting boxes")
      .def_property_readonly("candidates", read_only(&StageTimes::candidates), "seconds finding candidate partition pairs")
      .def_property_readonly("area", read_only(&StageTimes::area), "seconds testing candidates (common areas)")
      .def_property_readonly("validity", read_only(&StageTimes::validity), "seconds of the solid checks")
      .def_property_readonly("interferences", read_only(&StageTimes::interferences), "seconds of the interference pass")
      .def_property_readonly("regions", read_only(&StageTimes::regions), "seconds computing common regions (regions=...)")
      .def("__repr__", [](const StageTimes& t) {
        std::ostringstream out;
        out << "<StageTimes partitions=" << t.partitions << " broad_phase=" << t.broad_phase
            << " candidates=" << t.candidates << " area=" << t.area << ">";
        return out.str();
      });

  py::class_<SkippedPair>(m, "SkippedPair", "A candidate pair whose test failed: skipped, the rest kept.")
      .def_property_readonly("body_a", read_only(&SkippedPair::body_a), "index into Assembly.bodies")
      .def_property_readonly("body_b", read_only(&SkippedPair::body_b), "index into Assembly.bodies")
      .def_property_readonly("partition_a", read_only(&SkippedPair::partition_a), "partition id within body_a")
      .def_property_readonly("partition_b", read_only(&SkippedPair::partition_b), "partition id within body_b")
      .def_property_readonly("faces_a", read_only(&SkippedPair::faces_a), "1-based FaceN of partition_a")
      .def_property_readonly("faces_b", read_only(&SkippedPair::faces_b), "1-based FaceN of partition_b")
      .def_property_readonly("message", read_only(&SkippedPair::message), "why the test failed (OCCT's message)")
      .def("__repr__", [](const SkippedPair& s) {
        return "<SkippedPair bodies " + std::to_string(s.body_a) + "-" + std::to_string(s.body_b) + ": " +
               s.message + ">";
      });

  py::class_<Interference>(m, "Interference", "Two bodies whose material overlaps (never a contact).")
      .def_property_readonly("body_a", read_only(&Interference::body_a), "index into Assembly.bodies, body_a < body_b")
      .def_property_readonly("body_b", read_only(&Interference::body_b), "index into Assembly.bodies")
      .def_property_readonly("volume", read_only(&Interference::volume), "common volume, mm^3")
      .def_property_readonly("has_solid", [](const Interference& i) { return !i.solid.IsNull(); },
                             "whether the overlapping solid was computed (find_contacts(regions=...))")
      .def_property_readonly("solid_brep", [](const Interference& i) {
            return i.solid.IsNull() ? std::string() : call_guarded([&] { return shape_to_brep(i.solid); });
          }, "the overlapping solid as BRep text, '' when not computed")
      .def("__repr__", [](const Interference& i) {
        return "<Interference bodies " + std::to_string(i.body_a) + "-" + std::to_string(i.body_b) +
               " volume=" + std::to_string(i.volume) + ">";
      });

  py::class_<InvalidBody>(m, "InvalidBody", "A body whose solid is not valid (BRepCheck).")
      .def_property_readonly("body", read_only(&InvalidBody::body), "index into Assembly.bodies")
      .def_property_readonly("faces", read_only(&InvalidBody::faces), "1-based FaceN where the fault lies")
      .def_property_readonly("reason", read_only(&InvalidBody::reason), "what is wrong with the solid");

  py::class_<ContactsResult>(m, "ContactsResult", "Contacts of an assembly and what led to them.")
      .def_property_readonly("interferences", read_only(&ContactsResult::interferences), "[Interference]: bodies whose material overlaps")
      .def_property_readonly("invalid_bodies", read_only(&ContactsResult::invalid_bodies), "[InvalidBody]: solids that are not valid")
      .def_property_readonly("tolerances", read_only(&ContactsResult::tolerances), "Tolerances used")
      .def_property_readonly("partitions", read_only(&ContactsResult::partitions), "[BodyPartitions], one per body")
      .def_property_readonly("body_pairs", read_only(&ContactsResult::body_pairs), "[(i, j)] with meeting boxes, i < j (broad phase)")
      .def_property_readonly("candidates", read_only(&ContactsResult::candidates), "number of candidate partition pairs tested")
      .def_property_readonly("contacts", read_only(&ContactsResult::contacts), "[Contact]")
      .def_property_readonly("higher_pairs", read_only(&ContactsResult::higher_pairs), "[HigherPair]: point and line contacts, apart from the contacts")
      .def_property_readonly("skipped", read_only(&ContactsResult::skipped), "[SkippedPair]: candidate pairs whose test failed")
      .def_property_readonly("messages", read_only(&ContactsResult::messages), "warnings (OCCT's, bodies skipped)")
      .def_property_readonly("clearances", read_only(&ContactsResult::clearances), "[Clearance] (with clearance_gap > 0)")
      .def_property_readonly("times", read_only(&ContactsResult::times), "StageTimes")
      .def_property_readonly("regions_computed", read_only(&ContactsResult::regions_computed),
                    "common regions and overlapping solids computed by the last region pass")
      .def("__repr__", [](const ContactsResult& r) {
        return "<ContactsResult " + std::to_string(r.contacts.size()) + " contacts, " +
               std::to_string(r.body_pairs.size()) + " body pairs, " + std::to_string(r.candidates) +
               " candidates>";
      });

  py::class_<ContactsMemo>(m, "ContactsMemo",
                           "What find_contacts(memo=...) keeps of its run for the next one (a recompute): "
                           "each body's shape, tolerances and partitions, each tested body pair's contacts, "
                           "each body pair's point and line contacts. Opaque; its counts say what the last run reused.")
      .def(py::init<>())
      .def_property_readonly("bodies", [](const ContactsMemo& m) { return m.shapes.size(); },
                             "bodies of the run it holds (0: none held)")
      .def_property_readonly("reused_bodies", read_only(&ContactsMemo::reused_bodies),
                             "bodies whose partitions the last run reused")
      .def_property_readonly("reused_tested_pairs", read_only(&ContactsMemo::reused_tested_pairs),
                             "body pairs whose candidate tests the last run reused")
      .def_property_readonly("reused_higher_pairs", read_only(&ContactsMemo::reused_higher_pairs),
                             "body pairs whose point and line contacts the last run reused")
      .def_property_readonly("reused_solid_checks", read_only(&ContactsMemo::reused_solid_checks),
                             "bodies (instance sources) whose solid checks the last run reused");

  m.def(
      "find_contacts",
      [](const Assembly& assembly, std::optional<double> linear, std::optional<double> angular,
         py::object progress, int threads, std::optional<std::size_t> max_pairs, bool reuse_instances,
         double clearance_gap, const std::string& check_solids, py::object regions, ContactsMemo* memo) {
        ContactOptions options;
        set_regions(options, regions);
        if (check_solids != "quick" && check_solids != "full")
          raise_argument_error("check_solids must be 'quick' or 'full', not '" + check_solids + "'");
        options.solid_checks = check_solids == "full" ? SolidChecks::Full : SolidChecks::Quick;
        options.clearance_gap = clearance_gap;
        options.linear = linear;
        options.angular = angular;
        options.threads = threads;
        if (max_pairs) options.max_body_pairs = *max_pairs;
        options.reuse_instances = reuse_instances;
        std::unique_ptr<PythonProgress> reporter;
        if (!progress.is_none()) reporter = std::make_unique<PythonProgress>(progress);
        ContactsResult result;
        const Status status = guarded([&] {
          result = find_contacts(assembly, options, reporter.get(), memo);
          return result.status;
        });
        if (reporter) reporter->rethrow_if_raised();
        raise_if_failed(status);
        return result;
      },
      py::arg("assembly"), py::arg("linear") = py::none(), py::arg("angular") = py::none(),
      py::arg("progress") = py::none(), py::arg("threads") = 0, py::arg("max_pairs") = py::none(),
      py::arg("reuse_instances") = true, py::arg("clearance_gap") = 0.0, py::arg("check_solids") = "quick",
      py::arg("regions") = false, py::arg("memo") = nullptr,
      "Partitions every body, then finds contacts, on `threads` threads (0: all cores; the result "
      "is the same for any number). `progress(stage, fraction)` returning False cancels (raises "
      "contactcore.Cancelled); it is called from the calling thread. Tolerances default to the "
      "model's scale. More than `max_pairs` body pairs with meeting boxes (default 2,000,000) "
      "stops with ContactsError saying how many. `clearance_gap` > 0 also reports clearance fits. "
      "`check_solids`: 'quick' (default) or 'full' (also OCCT's BRepCheck_Analyzer and faces crossing "
      "each other: seconds on a large model). `regions`: True computes every contact's common region "
      "(Contact.region_brep, region_mesh) and every interference's overlapping solid (Interference.solid_brep); "
      "a list of body indices, only those touching these bodies (counted in regions_computed). `memo` "
      "(ContactsMemo): what the last run with it kept is reused for the bodies that did not change since "
      "(the same Body shapes at the same indices: contactcore.assembly_of_bodies), the result the same to "
      "the last bit; then it keeps this run.");

  m.def(
      "find_common_regions",
      [](const Assembly& assembly, ContactsResult& result, std::optional<std::vector<int>> bodies, int threads) {
        const Status status = guarded([&] {
          return find_common_regions(assembly, result, bodies.value_or(std::vector<int>{}), threads);
        });
        raise_if_failed(status);
        return result.regions_computed;
      },
      py::arg("assembly"), py::arg("result"), py::arg("bodies") = py::none(), py::arg("threads") = 0,
      "Computes the common regions of `result`'s contacts (and interferences' solids) touching `bodies` "
      "(None: all), in place; returns how many were computed.");

  m.def(
      "common_area",
      [](const std::vector<std::vector<std::pair<double, double>>>& a,
         const std::vector<std::vector<std::pair<double, double>>>& b, double tol) {
        const auto convert = [](const auto& loops) {
          std::vector<Polygon2> out;
          for (const auto& loop : loops) {
            Polygon2 poly;
            for (const auto& [x, y] : loop) poly.push_back({x, y});
            out.push_back(std::move(poly));
          }
          return out;
        };
        const std::vector<Polygon2> loops_a = convert(a), loops_b = convert(b);
        return call_guarded([&] { return common_area(loops_a, loops_b, tol); });
      },
      py::arg("a"), py::arg("b"), py::arg("tol") = 1e-9,
      "Area common to two sets of 2D loops (outer counter-clockwise, holes clockwise).");
}

}  // namespace contactcore::bindings
