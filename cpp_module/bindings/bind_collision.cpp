// Stage 5b in Python: collision models and pair queries (for tests, tools and
// scripting; the haptic loop calls the C++ API directly).
#include "common.h"
#include "contactcore/simulation/collision.h"

namespace contactcore::bindings {

namespace {

// None: identity; ((9 rotation values row-major), (tx, ty, tz)).
RigidTransform to_transform(const py::object& placement) {
  RigidTransform t;
  if (placement.is_none()) return t;
  const auto pair = placement.cast<std::pair<std::vector<double>, std::vector<double>>>();
  if (pair.first.size() != 9 || pair.second.size() != 3)
    raise_argument_error("a placement is ((9 rotation values, row-major), (tx, ty, tz))");
  std::copy(pair.first.begin(), pair.first.end(), t.rotation.begin());
  std::copy(pair.second.begin(), pair.second.end(), t.translation.begin());
  raise_if_failed(check_rigid_transform(t));  // ArgumentError: NaN, infinite, scaled or mirrored
  return t;
}

QueryKind to_kind(const std::string& kind) {
  if (kind == "intersect") return QueryKind::Intersect;
  if (kind == "distance") return QueryKind::Distance;
  if (kind == "penetration") return QueryKind::Penetration;
  raise_argument_error("query kind is 'intersect', 'distance' or 'penetration', not '" + kind + "'");
}

}  // namespace

void bind_collision(py::module_& m) {
  py::class_<CollisionModel, std::shared_ptr<CollisionModel>>(m, "CollisionModel",
                                                              "Per-partition BVHs of a tagged mesh (FCL)")
      .def_property_readonly("partition_count", &CollisionModel::partition_count, "number of partitions (one BVH each)")
      .def_property_readonly("triangle_count", &CollisionModel::triangle_count, "number of triangles");

  m.def(
      "build_collision_model",
      [](const TaggedMesh& mesh) {
        CollisionModelResult result;
        raise_if_failed(guarded([&] {
          result = build_collision_model(mesh);
          return result.status;
        }));
        return std::const_pointer_cast<CollisionModel>(result.model);
      },
      py::arg("mesh"));

  py::class_<QueryResult>(m, "QueryResult", "Intersection, distance, closest points, depth of a pair query")
      .def_property_readonly("intersecting", read_only(&QueryResult::intersecting), "the two meshes intersect")
      .def_property_readonly("distance", read_only(&QueryResult::distance), "mm >= 0; 0 when intersecting; infinity when not measured")
      .def_property_readonly("point_a", read_only(&QueryResult::point_a), "(x, y, z) mm, world: closest (or touching) point of A")
      .def_property_readonly("point_b", read_only(&QueryResult::point_b), "(x, y, z) mm, world: closest (or touching) point of B")
      .def_property_readonly("triangle_a", read_only(&QueryResult::triangle_a), "index into A's triangles, -1: none")
      .def_property_readonly("triangle_b", read_only(&QueryResult::triangle_b), "index into B's triangles, -1: none")
      .def_property_readonly("face_a", read_only(&QueryResult::face_a), "1-based FaceN of triangle_a")
      .def_property_readonly("face_b", read_only(&QueryResult::face_b), "1-based FaceN of triangle_b")
      .def_property_readonly("partition_a", read_only(&QueryResult::partition_a), "partition of triangle_a, -1: none")
      .def_property_readonly("partition_b", read_only(&QueryResult::partition_b), "partition of triangle_b, -1: none")
      .def_property_readonly("depth", read_only(&QueryResult::depth), "mm: penetration depth (kind 'penetration'), 0 when not penetrating")
      .def_property_readonly("direction", read_only(&QueryResult::direction),
          "unit (x, y, z) in which A must move to reduce the penetration")
      .def_property_readonly("partitions_a", read_only(&QueryResult::partitions_a), "A's partitions in the intersection, ascending")
      .def_property_readonly("partitions_b", read_only(&QueryResult::partitions_b), "B's partitions in the intersection, ascending")
      .def("__repr__", [](const QueryResult& r) {
        return std::string("<QueryResult ") + (r.intersecting ? "intersecting" : "apart") +
               " distance=" + std::to_string(r.distance) + " depth=" + std::to_string(r.depth) + ">";
      });

  py::class_<CollisionPair>(m, "CollisionPair", "Two models, their switched-off partitions, one query at a time")
      .def(py::init([](std::shared_ptr<CollisionModel> a, std::shared_ptr<CollisionModel> b, py::object margin) {
             auto pair = call_guarded([&] { return std::make_unique<CollisionPair>(a, b); });
             if (!margin.is_none()) raise_if_failed(pair->set_margin(margin.cast<double>()));
             return pair;
           }),
           py::arg("a"), py::arg("b"), py::arg("margin") = py::none(),
           "margin: None (triangles must touch) or a security margin in mm (see set_margin)")
      .def(
          "set_margin", [](CollisionPair& pair, double margin) { raise_if_failed(pair.set_margin(margin)); },
          py::arg("margin"),
          "Conservative intersect/penetration queries (FCL's security margin): intersecting when the meshes "
          "come within margin mm, or one body lies wholly inside the other; margin >= both meshes' deflections "
          "together misses no overlap of the exact solids. ArgumentError unless finite and >= 0.")
      .def("clear_margin", &CollisionPair::clear_margin, "Back to the default: triangles must touch")
      .def_property_readonly("margin", &CollisionPair::margin, "the security margin in mm, None when none is set")
      .def("set_partition_enabled",
           [](CollisionPair& pair, int side, int partition, bool enabled) {
             call_guarded([&] { pair.set_partition_enabled(side, partition, enabled); });
           }, py::arg("side"), py::arg("partition"),
           py::arg("enabled"), "side 0: A, 1: B")
      .def("enable_all", &CollisionPair::enable_all)
      .def("partition_enabled", &CollisionPair::partition_enabled, py::arg("side"), py::arg("partition"))
      .def("set_warm_start", &CollisionPair::set_warm_start, py::arg("enabled"),
           "Start each query from the previous one's closest or touching pair (default on; same answers)")
      .def("set_distance_limit", &CollisionPair::set_distance_limit, py::arg("limit"),
           "Distances above the limit answer infinity (farther); negative: always exact (the default)")
      .def("counts",
           [](const CollisionPair& pair) {
             const CollisionPair::Counts c = pair.counts();
             return py::make_tuple(c.bv_tests, c.triangle_tests);
           },
           "(bounding-volume tests, triangle tests) run by this pair's queries so far")
      .def(
          "query",
          [](CollisionPair& pair, py::object place_a, py::object place_b, const std::string& kind) {
            const RigidTransform a = to_transform(place_a), b = to_transform(place_b);
            const QueryKind k = to_kind(kind);
            return call_guarded([&] {
              QueryResult result;
              pair.query(a, b, k, result);
              return result;
            });
          },
          py::arg("place_a") = py::none(), py::arg("place_b") = py::none(), py::arg("kind") = "distance",
          "Placements: None or ((9 rotation values, row-major), (tx, ty, tz)); kind 'intersect', "
          "'distance' or 'penetration'.");
}

}  // namespace contactcore::bindings
