// Python view of stage 2 (partitions): read-only result classes with readable
// reprs, `partition_brep` on FreeCAD's BRep text, and `default_tolerances`.
#include <cstdio>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <BRepBndLib.hxx>
#include <TopoDS_Shape.hxx>

#include "contactcore/common/angles.h"
#include "common.h"
#include "contactcore/bodies/bodies.h"
#include "contactcore/common/occt_guard.h"
#include "contactcore/partitions/partitions.h"

namespace contactcore::bindings {

namespace {

constexpr double kDegreesPerRadian = 180 / kPi;
static_assert(kDegreesPerRadian == 57.29577951308232);

std::string number(double value) {
  if (value == 0) value = 0;  // no "-0"
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", value);
  return text;
}

std::string triple(double x, double y, double z) {
  return "(" + number(x) + ", " + number(y) + ", " + number(z) + ")";
}

// "Cylinder r=5", "Plane n=(0, 0, 1)", "Cone half_angle=30deg", ...
std::string describe(const SurfaceParams& s) {
  std::string out = to_string(s.kind);
  switch (s.kind) {
    case SurfaceKind::Plane: out += " n=" + triple(s.axis.X(), s.axis.Y(), s.axis.Z()); break;
    case SurfaceKind::Cylinder:
    case SurfaceKind::Sphere: out += " r=" + number(s.radius); break;
    case SurfaceKind::Cone: out += " half_angle=" + number(s.half_angle * kDegreesPerRadian) + "deg"; break;
    case SurfaceKind::Torus: out += " R=" + number(s.radius) + " r=" + number(s.minor_radius); break;
    case SurfaceKind::Other: break;
  }
  return out;
}

std::string side_suffix(SurfaceKind kind, MaterialSide side) {
  return kind == SurfaceKind::Plane || kind == SurfaceKind::Other ? "" : std::string(" ") + to_string(side);
}

std::string face_name(int index) { return "Face" + std::to_string(index); }

py::object box_tuple(const Bnd_Box& box) {
  if (box.IsVoid()) return py::none();
  double x0, y0, z0, x1, y1, z1;
  box.Get(x0, y0, z0, x1, y1, z1);
  return py::make_tuple(x0, y0, z0, x1, y1, z1);
}

py::list angular_list(const Extent& e) {
  py::list out;
  for (const AngularInterval& interval : e.angular) out.append(py::make_tuple(interval.start, interval.span));
  return out;
}

py::list outline_list(const Extent& e) {
  py::list loops;
  for (const Polygon2& polygon : e.outline) {
    py::list loop;
    for (const Point2& p : polygon) loop.append(py::make_tuple(p.x, p.y));
    loops.append(loop);
  }
  return loops;
}

}  // namespace

void bind_partitions(py::module_& m) {
  py::enum_<SurfaceKind>(m, "SurfaceKind")
      .value("Plane", SurfaceKind::Plane)
      .value("Cylinder", SurfaceKind::Cylinder)
      .value("Cone", SurfaceKind::Cone)
      .value("Sphere", SurfaceKind::Sphere)
      .value("Torus", SurfaceKind::Torus)
      .value("Other", SurfaceKind::Other);

  py::enum_<MaterialSide>(m, "MaterialSide")
      .value("Outward", MaterialSide::Outward)
      .value("Convex", MaterialSide::Convex)
      .value("Concave", MaterialSide::Concave);

  py::class_<Tolerances>(m, "Tolerances", "Linear (mm) and angular (rad) tolerances of partition merging")
      .def(py::init([](double linear, double angular) { return Tolerances{linear, angular}; }),
           py::arg("linear") = Tolerances{}.linear, py::arg("angular") = Tolerances{}.angular)
      .def_readwrite("linear", &Tolerances::linear, "mm")
      .def_readwrite("angular", &Tolerances::angular, "radians")
      .def("__repr__", [](const Tolerances& t) {
        return "<Tolerances linear=" + number(t.linear) + " angular=" + number(t.angular) + ">";
      });

  py::class_<SurfaceParams>(m, "SurfaceParams", "Analytic surface parameters in global coordinates (mm, rad)")
      .def_property_readonly("kind", read_only(&SurfaceParams::kind), "SurfaceKind")
      .def_property_readonly("location", [](const SurfaceParams& s) { return to_tuple(s.location); },
          "(x, y, z) mm: plane: a point; cylinder: on the axis; cone: apex; sphere, torus: centre")
      .def_property_readonly("axis", [](const SurfaceParams& s) { return to_tuple(s.axis); },
          "unit (x, y, z): plane: outward normal; cone: from the apex into the opening; cylinder, torus: axis (compare as lines)")
      .def_property_readonly("radius", read_only(&SurfaceParams::radius), "mm: cylinder, sphere; torus: major radius")
      .def_property_readonly("minor_radius", read_only(&SurfaceParams::minor_radius), "mm: torus")
      .def_property_readonly("half_angle", read_only(&SurfaceParams::half_angle), "radians: cone, in (0, pi/2)")
      .def("__repr__", [](const SurfaceParams& s) {
        return "<SurfaceParams " + describe(s) + " location=" +
               triple(s.location.X(), s.location.Y(), s.location.Z()) + " axis=" +
               triple(s.axis.X(), s.axis.Y(), s.axis.Z()) + ">";
      });

  py::class_<Extent>(m, "Extent", "Where a face or partition lies on its surface")
      .def_property_readonly("ref_dir", [](const Extent& e) { return to_tuple(e.ref_dir); },
          "unit (x, y, z) perpendicular to the axis: where angles start; plane: the outline's x axis")
      .def_property_readonly("axial_min", read_only(&Extent::axial_min),
          "mm along the axis from the surface's location (revolution surfaces)")
      .def_property_readonly("axial_max", read_only(&Extent::axial_max),
          "mm along the axis from the surface's location (revolution surfaces)")
      .def_property_readonly("angular", &angular_list, "[(start, span)] in radians")
      .def_property_readonly("outline", &outline_list, "plane outline: [[(x, y)]], outer loops counter-clockwise")
      .def_property_readonly("angular_span", &Extent::angular_span,
          "radians: the sum of the angular intervals, <= 2 pi")
      .def("__repr__", [](const Extent& e) {
        if (!e.outline.empty()) {
          std::size_t points = 0;
          for (const Polygon2& loop : e.outline) points += loop.size();
          return "<Extent outline loops=" + std::to_string(e.outline.size()) + " points=" + std::to_string(points) +
                 ">";
        }
        if (e.angular.empty()) return std::string("<Extent empty>");
        return "<Extent axial=[" + number(e.axial_min) + ", " + number(e.axial_max) +
               "] span=" + number(e.angular_span() * kDegreesPerRadian) + "deg>";
      });

  py::class_<FaceInfo>(m, "FaceInfo", "One typed face; index and name follow FreeCAD's Shape.Faces")
      .def_property_readonly("index", read_only(&FaceInfo::index), "1-based, in FreeCAD's Shape.Faces order")
      .def_property_readonly("name", [](const FaceInfo& f) { return face_name(f.index); },
          "FreeCAD's sub-element name, 'FaceN'")
      .def_property_readonly("params", read_only(&FaceInfo::params), "SurfaceParams of the face's surface, global")
      .def_property_readonly("side", read_only(&FaceInfo::side), "MaterialSide: where the body's material lies")
      .def_property_readonly("recognised", read_only(&FaceInfo::recognised), "stored as a free-form surface, typed by fitting")
      .def_property_readonly("max_deviation", read_only(&FaceInfo::max_deviation),
          "mm: of the fitted surface on samples (recognised faces)")
      .def_property_readonly("area", read_only(&FaceInfo::area), "mm^2, exact (Green's theorem on the boundary)")
      .def_property_readonly("extent", read_only(&FaceInfo::extent), "Extent: where the face lies on its surface")
      .def_property_readonly("box", [](const FaceInfo& f) { return box_tuple(f.box); },
          "(xmin, ymin, zmin, xmax, ymax, zmax) mm, or None")
      .def("__repr__", [](const FaceInfo& f) {
        std::string out = "<FaceInfo " + face_name(f.index) + " " + describe(f.params) +
                          side_suffix(f.params.kind, f.side);
        if (f.recognised) out += " recognised dev=" + number(f.max_deviation);
        return out + " area=" + number(f.area) + ">";
      });

  py::class_<Partition>(m, "Partition", "A maximal set of adjacent faces on the same surface")
      .def_property_readonly("id", read_only(&Partition::id), "0-based within its body")
      .def_property_readonly("faces", read_only(&Partition::faces), "1-based face indices, ascending")
      .def_property_readonly("face_names", [](const Partition& p) { return face_names(p.faces); }, "['FaceN', ...]")
      .def_property_readonly("params", read_only(&Partition::params), "SurfaceParams shared by its faces, global")
      .def_property_readonly("side", read_only(&Partition::side), "MaterialSide")
      .def_property_readonly("area", read_only(&Partition::area), "mm^2, the sum of its faces'")
      .def_property_readonly("extent", read_only(&Partition::extent), "Extent: axial range and angular union; plane outlines of all faces")
      .def_property_readonly("box", [](const Partition& p) { return box_tuple(p.box); },
          "(xmin, ymin, zmin, xmax, ymax, zmax) mm, or None")
      .def("__repr__", [](const Partition& p) {
        std::string names;
        for (int index : p.faces) names += (names.empty() ? "" : ", ") + face_name(index);
        return "<Partition " + std::to_string(p.id) + " " + describe(p.params) + side_suffix(p.params.kind, p.side) +
               " faces=[" + names + "] area=" + number(p.area) + ">";
      });

  py::class_<BodyPartitions>(m, "BodyPartitions", "Typed faces and maximal partitions of one body")
      .def_property_readonly("faces", read_only(&BodyPartitions::faces), "[FaceInfo], one per face in FaceN order")
      .def_property_readonly("partitions", read_only(&BodyPartitions::partitions), "[Partition], by id")
      .def_property_readonly("tolerances", read_only(&BodyPartitions::tolerances), "the tolerances this body was partitioned with")
      .def_property_readonly("ok", [](const BodyPartitions& b) { return b.status.ok(); },
          "True when the body was partitioned without error")
      .def_property_readonly("status", [](const BodyPartitions& b) { return b.status.describe(); },
          "why not, naming the face ('' when ok)")
      .def_property_readonly("box", [](const BodyPartitions& b) { return box_tuple(b.box); },
          "(xmin, ymin, zmin, xmax, ymax, zmax) mm, or None")
      .def("__repr__", [](const BodyPartitions& b) {
        return "<BodyPartitions faces=" + std::to_string(b.faces.size()) +
               " partitions=" + std::to_string(b.partitions.size()) + (b.status.ok() ? " ok" : " failed") + ">";
      });

  m.def(
      "default_tolerances",
      [](double xmin, double ymin, double zmin, double xmax, double ymax, double zmax) {
        return call_guarded([&] {
          Bnd_Box box;
          box.Update(xmin, ymin, zmin, xmax, ymax, zmax);
          return default_tolerances(box);
        });
      },
      py::arg("xmin"), py::arg("ymin"), py::arg("zmin"), py::arg("xmax"), py::arg("ymax"), py::arg("zmax"),
      "Tolerances scaled to a model box: linear 1e-5 of its diagonal (no floor or ceiling), angular 1e-4 rad");

  m.def(
      "partition_brep",
      [](const std::string& brep, std::optional<double> linear, std::optional<double> angular) {
        BodyPartitions result;
        const Status status = guarded([&]() {
          const OcctGuard guard;  // a signal inside OCCT: an error, not a crash
          return with_occt_signals([&]() -> Status {
            TopoDS_Shape shape;
            const Status read = shape_from_brep(brep, shape);
            if (!read.ok()) return read;
            Bnd_Box box;
            BRepBndLib::Add(shape, box);
            const Tolerances tolerances = resolve_tolerances(box, linear, angular);
            const Status valid = check_tolerances(box, tolerances);
            if (!valid.ok()) return valid;
            result = partition_shape(shape, tolerances);
            return Status::success();
          });
        });
        raise_if_failed(status);
        return result;
      },
      py::arg("brep"), py::arg("linear") = py::none(), py::arg("angular") = py::none(),
      "Types and merges the faces of a shape given as BRep text (Part.Shape.exportBrepToString()).\n"
      "Tolerances default to default_tolerances() of the shape's box. Raises ContactsError on a bad string.");
}

}  // namespace contactcore::bindings
