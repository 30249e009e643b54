#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include <BRepAlgoAPI_Cut.hxx>
#include <BRepBuilderAPI_MakeVertex.hxx>
#include <BRepBuilderAPI_Transform.hxx>
#include <BRepClass3d_SolidClassifier.hxx>
#include <BRepExtrema_DistShapeShape.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <BRep_Builder.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS_Compound.hxx>
#include <gp_Ax2.hxx>
#include <gp_Quaternion.hxx>
#include <gp_Trsf.hxx>
#include <gp_Vec.hxx>

#include <fcl/geometry/shape/box.h>
#include <fcl/math/bv/OBB.h>
#include <fcl/narrowphase/distance.h>
#include <fcl/narrowphase/detail/primitive_shape_algorithm/triangle_distance.h>

#include "contactcore/simulation/collision.h"
#include "simulation/bvh_traversal.h"
#include "contactcore/simulation/meshes.h"
#include "placement_helpers.h"
#include "draw_order.h"

using namespace contactcore;
using contactcore::testing::drawn_last_first;
using contactcore::testing::placed;
using contactcore::testing::random_placement;
using contactcore::testing::to_gp;

namespace {

struct Body {
  TopoDS_Shape shape;
  BodyPartitions partitions;
  TaggedMesh mesh;
  CollisionModelPtr model;
};

Body make_body(const TopoDS_Shape& shape, double deflection = 0.01) {
  Body body;
  body.shape = shape;
  body.partitions = partition_shape(shape, Tolerances{});
  MeshOptions options;
  options.deflection = deflection;
  const MeshResult meshed = mesh_body(shape, body.partitions, options);
  EXPECT_TRUE(meshed.status.ok()) << meshed.status.describe();
  body.mesh = meshed.mesh;
  const CollisionModelResult built = build_collision_model(body.mesh);
  EXPECT_TRUE(built.status.ok()) << built.status.describe();
  body.model = built.model;
  return body;
}

double exact_distance(const TopoDS_Shape& a, const TopoDS_Shape& b) {
  BRepExtrema_DistShapeShape dist(a, b);
  EXPECT_TRUE(dist.IsDone());
  return dist.Value();
}

TopoDS_Shape faces_of(const TopoDS_Shape& solid) {
  BRep_Builder builder;
  TopoDS_Compound faces;
  builder.MakeCompound(faces);
  for (TopExp_Explorer explorer(solid, TopAbs_FACE); explorer.More(); explorer.Next())
    builder.Add(faces, explorer.Current());
  return faces;
}

// Independent depth: the deepest mesh vertex of one body inside the other's
// exact solid, measured to its exact boundary.
double reference_depth(const Body& a, const RigidTransform& ta, const Body& b, const RigidTransform& tb) {
  const TopoDS_Shape sa = placed(a.shape, ta), sb = placed(b.shape, tb);
  double depth = 0;
  auto scan = [&](const Body& from, const RigidTransform& t, const TopoDS_Shape& into) {
    const gp_Trsf trsf = to_gp(t);
    BRepClass3d_SolidClassifier classifier(into);
    // Distance to the boundary: measured to the solid itself, a point inside is at 0.
    const TopoDS_Shape boundary = faces_of(into);
    for (const auto& v : from.mesh.vertices) {
      const gp_Pnt p = gp_Pnt(v[0], v[1], v[2]).Transformed(trsf);
      classifier.Perform(p, 1e-7);
      if (classifier.State() != TopAbs_IN) continue;
      depth = std::max(depth, exact_distance(BRepBuilderAPI_MakeVertex(p).Shape(), boundary));
    }
  };
  scan(a, ta, sb);
  scan(b, tb, sa);
  return depth;
}

double length(const std::array<double, 3>& v) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

// The id of a body's (only) cylindrical partition: a bore or a shaft's side.
int cylinder_partition(const Body& body) {
  for (const Partition& p : body.partitions.partitions)
    if (p.params.kind == SurfaceKind::Cylinder) return p.id;
  return -1;
}

}  // namespace

TEST(Collision, BoxesApartGiveTheGapAndClosestPoints) {
  const Body a = make_body(BRepPrimAPI_MakeBox(10, 10, 10).Shape());
  const Body b = make_body(BRepPrimAPI_MakeBox(4, 4, 4).Shape());
  CollisionPair pair(a.model, b.model);
  QueryResult result;
  pair.query(RigidTransform::identity(), RigidTransform::translated(12.5, 3, 3), QueryKind::Distance, result);
  EXPECT_FALSE(result.intersecting);
  EXPECT_NEAR(result.distance, 2.5, 1e-9);
  EXPECT_NEAR(result.point_a[0], 10, 1e-9);
  EXPECT_NEAR(result.point_b[0], 12.5, 1e-9);
  EXPECT_NEAR(result.point_b[1], result.point_a[1], 1e-9);
  // The closest faces: A's x = 10 side and B's x = 0 side.
  EXPECT_EQ(a.partitions.faces[result.face_a - 1].params.axis.X(), 1.0);
  EXPECT_EQ(b.partitions.faces[result.face_b - 1].params.axis.X(), -1.0);
  EXPECT_EQ(result.partition_a, a.mesh.triangle_partition[result.triangle_a]);
}

TEST(Collision, OverlappingBoxesGiveDepthAndDirection) {
  const Body a = make_body(BRepPrimAPI_MakeBox(10, 10, 10).Shape());
  const Body b = make_body(BRepPrimAPI_MakeBox(4, 4, 4).Shape());
  CollisionPair pair(a.model, b.model);
  QueryResult result;
  // B spans x in [8.5, 12.5]: its four corners at x = 8.5 are 1.5 deep in A.
  pair.query(RigidTransform::identity(), RigidTransform::translated(8.5, 3, 3), QueryKind::Penetration, result);
  EXPECT_TRUE(result.intersecting);
  EXPECT_EQ(result.distance, 0);
  EXPECT_NEAR(result.depth, 1.5, 1e-9);
  EXPECT_NEAR(result.direction[0], -1, 1e-9);  // A leaves towards -x
  // A's x = 10 side meets B's four sides around x.
  ASSERT_EQ(result.partitions_a.size(), 1u);
  EXPECT_EQ(result.partitions_b.size(), 4u);
  pair.query(RigidTransform::identity(), RigidTransform::translated(8.5, 3, 3), QueryKind::Intersect, result);
  EXPECT_TRUE(result.intersecting);
  // B wholly beside A: no intersection.
  pair.query(RigidTransform::identity(), RigidTransform::translated(10.001, 3, 3), QueryKind::Intersect, result);
  EXPECT_FALSE(result.intersecting);
}

TEST(Collision, DepthOfAPointInsideABody) {
  const Body a = make_body(BRepPrimAPI_MakeBox(10, 10, 10).Shape());
  const Body b = make_body(BRepPrimAPI_MakeBox(4, 4, 4).Shape());
  CollisionPair pair(a.model, b.model);
  // Hand-derived: the distance to the nearest face inside, 0 outside or on the surface.
  EXPECT_NEAR(pair.depth_inside(0, RigidTransform::identity(), {5, 5, 5}), 5.0, 1e-9);
  EXPECT_NEAR(pair.depth_inside(0, RigidTransform::identity(), {1, 6, 7}), 1.0, 1e-9);
  EXPECT_EQ(pair.depth_inside(0, RigidTransform::identity(), {11, 5, 5}), 0.0);
  EXPECT_EQ(pair.depth_inside(0, RigidTransform::identity(), {10, 5, 5}), 0.0);
  // B placed at (20, 0, 0): its centre 2 deep.
  EXPECT_NEAR(pair.depth_inside(1, RigidTransform::translated(20, 0, 0), {22, 2, 2}), 2.0, 1e-9);
  EXPECT_EQ(pair.depth_inside(1, RigidTransform::identity(), {22, 2, 2}), 0.0);
}

TEST(Collision, DistancesMatchTheExactBRepDistanceOnSampledPlacements) {
  const Body cylinder = make_body(BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, -5), gp::DZ()), 3, 10).Shape());
  const Body holed = make_body(BRepAlgoAPI_Cut(BRepPrimAPI_MakeBox(gp_Pnt(-6, -6, -4), 12, 12, 8).Shape(),
                                               BRepPrimAPI_MakeSphere(4.5).Shape())
                                   .Shape());
  CollisionPair pair(cylinder.model, holed.model);
  std::mt19937 rng(7);
  QueryResult result;
  int apart = 0, near = 0, intersecting = 0, contained = 0, deep = 0;
  for (int sample = 0; sample < 40; ++sample) {
    const RigidTransform ta = random_placement(rng, 6), tb = random_placement(rng, 6);
    pair.query(ta, tb, QueryKind::Penetration, result);
    const TopoDS_Shape sa = placed(cylinder.shape, ta), sb = placed(holed.shape, tb);
    const double exact = exact_distance(sa, sb);
    // Meshes are within the deflection (0.01) of the exact surfaces: each side may err by it.
    if (exact > 0.05) {
      ++apart;
      EXPECT_FALSE(result.intersecting) << sample;
      EXPECT_NEAR(result.distance, exact, 0.021) << sample;
      EXPECT_NEAR(length({result.point_a[0] - result.point_b[0], result.point_a[1] - result.point_b[1],
                          result.point_a[2] - result.point_b[2]}),
                  result.distance, 1e-9);
    } else if (exact > 0) {
      // Within twice the deflection: the meshes may cross, else their gap is the exact one.
      ++near;
      if (!result.intersecting) EXPECT_NEAR(result.distance, exact, 0.021) << sample;
    } else if (result.intersecting) {
      ++intersecting;
      EXPECT_NEAR(result.depth, reference_depth(cylinder, ta, holed, tb), 0.021) << sample;
      if (result.depth > 0) {
        ++deep;
        EXPECT_NEAR(length(result.direction), 1.0, 1e-9);
      }
    } else {
      // Surfaces apart, material overlapping: one body wholly inside the other (not an intersection of
      // the meshes); the B-rep says which.
      ++contained;
      BRepClass3d_SolidClassifier in_b(sb, gp_Pnt(ta.translation[0], ta.translation[1], ta.translation[2]), 1e-7);
      EXPECT_EQ(in_b.State(), TopAbs_IN) << sample;
    }
  }
  // Counts fixed by the seed and the exact B-rep distance.
  EXPECT_EQ(apart, 5);
  EXPECT_EQ(near, 1);
  EXPECT_EQ(apart + near + intersecting + contained, 40);
  // Of the 34 intersecting placements, one merely touches (depth 0); none is wholly inside.
  EXPECT_EQ(intersecting, 34);
  EXPECT_EQ(contained, 0);
  EXPECT_EQ(deep, 33);
}

TEST(Collision, SwitchedOffPartitionsAreIgnored) {
  // A shaft in a bore of its radius: the cylinders coincide (the paper's Fig. 4c).
  const Body block = make_body(BRepAlgoAPI_Cut(BRepPrimAPI_MakeBox(gp_Pnt(-10, -10, 0), 20, 20, 10).Shape(),
                                               BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, -1), gp::DZ()), 3, 12).Shape())
                                   .Shape());
  const Body shaft = make_body(BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, -5), gp::DZ()), 3, 20).Shape());
  CollisionPair pair(block.model, shaft.model);
  QueryResult result;
  // Turned by a few degrees about its own axis, the shaft's facets cut the bore's.
  const double angle = 0.05;
  RigidTransform turned;
  turned.rotation = {std::cos(angle), -std::sin(angle), 0, std::sin(angle), std::cos(angle), 0, 0, 0, 1};
  pair.query(RigidTransform::identity(), turned, QueryKind::Intersect, result);
  EXPECT_TRUE(result.intersecting);
  // The bore, and the block's top and bottom along the bore's rims.
  EXPECT_EQ(result.partitions_a.size(), 3u);
  EXPECT_EQ(std::count(result.partitions_a.begin(), result.partitions_a.end(), cylinder_partition(block)), 1);
  ASSERT_EQ(result.partitions_b.size(), 1u);
  EXPECT_EQ(result.partitions_b[0], cylinder_partition(shaft));
  pair.set_partition_enabled(0, cylinder_partition(block), false);
  pair.set_partition_enabled(1, cylinder_partition(shaft), false);
  EXPECT_FALSE(pair.partition_enabled(0, cylinder_partition(block)));
  pair.query(RigidTransform::identity(), turned, QueryKind::Penetration, result);
  EXPECT_FALSE(result.intersecting);
  // What is left: the shaft's end discs (z = -5, 15) against the block's faces (z = 0, 10): 5 apart.
  EXPECT_NEAR(result.distance, 5.0, 1e-9);
  // Moved sideways the shaft end discs still clear the block, but its side would hit the block's top: the
  // bore is off, the block's top is not.
  pair.enable_all();
  pair.query(RigidTransform::identity(), RigidTransform::translated(2, 0, 0), QueryKind::Intersect, result);
  EXPECT_TRUE(result.intersecting);
}

// The per-pair mask: only the bore-shaft pair switched off; the bore still meets
// the shaft's other partitions and the shaft the block's others.
TEST(Collision, SwitchedOffPairIsIgnoredAndOnlyIt) {
  const Body block = make_body(BRepAlgoAPI_Cut(BRepPrimAPI_MakeBox(gp_Pnt(-10, -10, 0), 20, 20, 10).Shape(),
                                               BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, -1), gp::DZ()), 3, 12).Shape())
                                   .Shape());
  const Body shaft = make_body(BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, -5), gp::DZ()), 3, 20).Shape());
  const int bore = cylinder_partition(block), side = cylinder_partition(shaft);
  CollisionPair pair(block.model, shaft.model);
  QueryResult result;
  const double angle = 0.05;
  RigidTransform turned;
  turned.rotation = {std::cos(angle), -std::sin(angle), 0, std::sin(angle), std::cos(angle), 0, 0, 0, 1};
  pair.set_pair_enabled(bore, side, false);
  EXPECT_FALSE(pair.pair_enabled(bore, side));
  EXPECT_TRUE(pair.partition_enabled(0, bore));
  pair.query(RigidTransform::identity(), turned, QueryKind::Intersect, result);
  // The shaft's side still crosses the block's top and bottom along the bore's rims, not the bore.
  EXPECT_TRUE(result.intersecting);
  EXPECT_EQ(std::count(result.partitions_a.begin(), result.partitions_a.end(), bore), 0);
  ASSERT_EQ(result.partitions_a.size(), 2u);
  // The rims off too (every pair of the shaft's side with the block): the end discs 5 from the block.
  for (const Partition& p : block.partitions.partitions) pair.set_pair_enabled(p.id, side, false);
  pair.query(RigidTransform::identity(), turned, QueryKind::Penetration, result);
  EXPECT_FALSE(result.intersecting);
  EXPECT_NEAR(result.distance, 5.0, 1e-9);
  pair.enable_all();
  EXPECT_TRUE(pair.pair_enabled(bore, side));
  pair.query(RigidTransform::identity(), turned, QueryKind::Intersect, result);
  EXPECT_EQ(result.partitions_a.size(), 3u);
}

TEST(Collision, EverythingSwitchedOffIsInfinitelyFar) {
  const Body a = make_body(BRepPrimAPI_MakeBox(1, 1, 1).Shape());
  CollisionPair pair(a.model, a.model);
  for (int p = 0; p < 6; ++p) pair.set_partition_enabled(0, p, false);
  QueryResult result;
  pair.query(RigidTransform::identity(), RigidTransform::identity(), QueryKind::Penetration, result);
  EXPECT_FALSE(result.intersecting);
  EXPECT_TRUE(std::isinf(result.distance));
}

TEST(Collision, BadMeshIsAnError) {
  EXPECT_FALSE(build_collision_model(TaggedMesh{}).status.ok());
  TaggedMesh mesh;
  mesh.vertices = {{0, 0, 0}, {1, 0, 0}};
  mesh.triangles = {{0, 1, 2}};
  mesh.triangle_face = {1};
  mesh.triangle_partition = {0};
  EXPECT_FALSE(build_collision_model(mesh).status.ok());
}

namespace {

// A moving body's placements: small steps (a 1 kHz path), a jump, small steps again.
std::vector<RigidTransform> path_with_jump(std::mt19937& rng, const RigidTransform& start, const RigidTransform& jump,
                                           int steps) {
  std::vector<RigidTransform> path;
  std::normal_distribution<double> normal(0, 0.02);
  for (const RigidTransform& origin : {start, jump}) {
    RigidTransform place = origin;
    for (int i = 0; i < steps; ++i) {
      const double angle = normal(rng);  // a small turn about z composed with the origin's rotation
      const double c = std::cos(angle), s = std::sin(angle);
      std::array<double, 9> turned{};
      for (int col = 0; col < 3; ++col) {
        turned[0 + col] = c * place.rotation[0 + col] - s * place.rotation[3 + col];
        turned[3 + col] = s * place.rotation[0 + col] + c * place.rotation[3 + col];
        turned[6 + col] = place.rotation[6 + col];
      }
      place.rotation = turned;
      for (double& x : place.translation) x += normal(rng);
      path.push_back(place);
    }
  }
  return path;
}

void expect_same(const QueryResult& warm, const QueryResult& cold, const std::string& where) {
  EXPECT_EQ(warm.intersecting, cold.intersecting) << where;
  if (std::isinf(cold.distance))  // Intersect measures no distance when apart
    EXPECT_EQ(warm.distance, cold.distance) << where;
  else
    EXPECT_NEAR(warm.distance, cold.distance, 1e-12) << where;
  EXPECT_EQ(warm.partitions_a, cold.partitions_a) << where;
  EXPECT_EQ(warm.partitions_b, cold.partitions_b) << where;
  EXPECT_NEAR(warm.depth, cold.depth, 1e-12) << where;
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(warm.direction[k], cold.direction[k], 1e-12) << where;
  // Crossing meshes: every crossing pair is at distance 0, the points and witness are any of them.
  if (cold.intersecting) return;
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(warm.point_a[k], cold.point_a[k], 1e-12) << where;
    EXPECT_NEAR(warm.point_b[k], cold.point_b[k], 1e-12) << where;
  }
  EXPECT_EQ(warm.partition_a, cold.partition_a) << where;
  EXPECT_EQ(warm.partition_b, cold.partition_b) << where;
  EXPECT_EQ(warm.triangle_a, cold.triangle_a) << where;
  EXPECT_EQ(warm.triangle_b, cold.triangle_b) << where;
}

}  // namespace

// Warm start (the default) against cold queries on the same sequence: small steps near and into
// contact, a jump, partitions switched off and on halfway, two pairs sharing a model.
TEST(Collision, WarmStartGivesTheColdAnswers) {
  const Body cylinder = make_body(BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, -5), gp::DZ()), 3, 10).Shape());
  const Body holed = make_body(BRepAlgoAPI_Cut(BRepPrimAPI_MakeBox(gp_Pnt(-6, -6, -4), 12, 12, 8).Shape(),
                                               BRepPrimAPI_MakeSphere(4.5).Shape())
                                   .Shape());
  const Body sphere = make_body(BRepPrimAPI_MakeSphere(2.5).Shape());
  CollisionPair warm_first(cylinder.model, holed.model), cold_first(cylinder.model, holed.model);
  CollisionPair warm_second(sphere.model, holed.model), cold_second(sphere.model, holed.model);
  cold_first.set_warm_start(false);
  cold_second.set_warm_start(false);
  std::mt19937 rng(11);
  // Tilted (no parallel facets: the closest pair is unique), the cylinder's lowest point 0.05 above
  // the box's top face (z = 4), then after the jump its nearest point 0.05 beyond the box's x = 6
  // wall; the random walk crosses and leaves them.
  RigidTransform start = random_placement(rng, 0), jump = random_placement(rng, 0);
  auto extreme = [&](const RigidTransform& t, int axis) {  // lowest coordinate of the placed mesh
    double low = std::numeric_limits<double>::infinity();
    for (const auto& v : cylinder.mesh.vertices)
      low = std::min(low, t.rotation[3 * axis] * v[0] + t.rotation[3 * axis + 1] * v[1] + t.rotation[3 * axis + 2] * v[2]);
    return low;
  };
  start.translation = {3.5, 0.2, 4.05 - extreme(start, 2)};
  jump.translation = {6.05 - extreme(jump, 0), 0.5, 0};
  const std::vector<RigidTransform> path = path_with_jump(rng, start, jump, 60);
  const RigidTransform fixed = RigidTransform::identity();
  const int switched = holed.mesh.triangle_partition[0];
  int intersecting = 0, apart = 0;
  for (std::size_t i = 0; i < path.size(); ++i) {
    if (i == 30 || i == 90) {  // a partition of the box off, then on again 10 ticks later
      for (CollisionPair* pair : {&warm_first, &cold_first, &warm_second, &cold_second})
        pair->set_partition_enabled(1, switched, false);
    }
    if (i == 40 || i == 100)
      for (CollisionPair* pair : {&warm_first, &cold_first, &warm_second, &cold_second}) pair->enable_all();
    RigidTransform sphere_place = path[i];
    sphere_place.translation[0] += 1.0;
    for (QueryKind kind : {QueryKind::Distance, QueryKind::Intersect, QueryKind::Penetration}) {
      QueryResult warm, cold;
      const std::string where = "tick " + std::to_string(i) + " kind " + std::to_string(static_cast<int>(kind));
      warm_first.query(path[i], fixed, kind, warm);
      cold_first.query(path[i], fixed, kind, cold);
      expect_same(warm, cold, "first pair, " + where);
      if (kind == QueryKind::Distance) (cold.intersecting ? intersecting : apart) += 1;
      warm_second.query(sphere_place, fixed, kind, warm);
      cold_second.query(sphere_place, fixed, kind, cold);
      expect_same(warm, cold, "second pair, " + where);
    }
  }
  // The path visits both states (counts fixed by the seed).
  EXPECT_GT(intersecting, 0);
  EXPECT_GT(apart, 0);
}

// Front-tracked Intersect (the default) against the warm start alone and cold queries, Intersect
// only so that the fronts carry from tick to tick: a sphere grazing another (the gap between the
// meshes a few micrometres either way, sliding), a jump to the far side, and the holed box's
// partitions switched off and on; the witness pair touches whenever the answer is "intersecting".
TEST(Collision, FrontTrackingGivesTheColdAnswers) {  // Intersect and Distance
  const Body sphere = make_body(BRepPrimAPI_MakeSphere(5).Shape());
  const Body holed = make_body(BRepAlgoAPI_Cut(BRepPrimAPI_MakeBox(gp_Pnt(-6, -6, -4), 12, 12, 8).Shape(),
                                               BRepPrimAPI_MakeSphere(4.5).Shape())
                                   .Shape());
  ASSERT_GT(holed.mesh.partition_count, 1);
  // B placed `gap` from A along `direction` (unit): the meshes' distance measured by a cold Distance
  // at a nominal placement 0.05 apart, then B moved back by that distance less the gap.
  auto at_gap = [](const Body& a, const Body& b, RigidTransform nominal, const std::array<double, 3>& direction,
                   double gap) {
    CollisionPair measure(a.model, b.model);
    measure.set_warm_start(false);
    QueryResult r;
    measure.query(RigidTransform::identity(), nominal, QueryKind::Distance, r);
    for (int k = 0; k < 3; ++k) nominal.translation[k] -= (r.distance - gap) * direction[k];
    return nominal;
  };
  struct Path {
    const Body* b;
    std::vector<RigidTransform> placements;
  };
  std::vector<Path> paths(2);
  // Sphere on sphere, B sliding round A in a slowly turning direction, the gap in [-3, 3] um.
  paths[0].b = &sphere;
  for (int i = 0; i < 240; ++i) {
    const double gap = 0.003 * std::sin(0.37 * i), angle = 0.004 * i + (i >= 120 ? 3.0 : 0.0);  // jump at 120
    const std::array<double, 3> direction{std::cos(angle), std::sin(angle), 0};
    paths[0].placements.push_back(at_gap(
        sphere, sphere, RigidTransform::translated(10.05 * direction[0], 10.05 * direction[1], 0), direction, gap));
  }
  // The holed box's bottom face (z = -4; its hole, of radius 2.06, kept off the pole) grazing the
  // sphere's pole, then (the jump) its x = -6 wall grazing the sphere's equator, sliding a little.
  paths[1].b = &holed;
  for (int i = 0; i < 240; ++i) {
    const double gap = 0.003 * std::sin(0.37 * i), slide = 0.0001 * (i % 120);
    paths[1].placements.push_back(
        i < 120 ? at_gap(sphere, holed, RigidTransform::translated(slide - 3, 0.2, 9.05), {0, 0, 1}, gap)
                : at_gap(sphere, holed, RigidTransform::translated(11.05, 0.5, slide), {1, 0, 0}, gap));
  }
  // Sphere on sphere, B spinning in place about its own z axis (0.02 rad a tick, then a jump of 1
  // rad at 120) while grazing A along x: the contact runs round B's equator, 0.1 mm a tick, by its
  // turn alone, which the motion bound of the front's separated pairs must cover.
  paths.push_back({&sphere, {}});
  for (int i = 0; i < 240; ++i) {
    const double gap = 0.003 * std::sin(0.37 * i), turn = 0.02 * i + (i >= 120 ? 1.0 : 0.0);
    RigidTransform nominal = RigidTransform::translated(10.05, 0, 0);
    nominal.rotation = {std::cos(turn), -std::sin(turn), 0, std::sin(turn), std::cos(turn), 0, 0, 0, 1};
    paths[2].placements.push_back(at_gap(sphere, sphere, nominal, {1, 0, 0}, gap));
  }
  for (std::size_t p = 0; p < paths.size(); ++p) {
    const Body& b = *paths[p].b;
    const int switched = b.mesh.triangle_partition[0];
    CollisionPair front(sphere.model, b.model), no_front(sphere.model, b.model), cold(sphere.model, b.model);
    no_front.set_front_tracking(false);
    cold.set_warm_start(false);
    int intersecting = 0, apart = 0;
    for (std::size_t i = 0; i < paths[p].placements.size(); ++i) {
      if (i == 40 || i == 160)
        for (CollisionPair* pair : {&front, &no_front, &cold}) pair->set_partition_enabled(1, switched, false);
      if (i == 60 || i == 180)
        for (CollisionPair* pair : {&front, &no_front, &cold}) pair->enable_all();
      const RigidTransform& place = paths[p].placements[i];
      QueryResult f, n, k;
      const std::string where = "path " + std::to_string(p) + " tick " + std::to_string(i);
      front.query(RigidTransform::identity(), place, QueryKind::Intersect, f);
      no_front.query(RigidTransform::identity(), place, QueryKind::Intersect, n);
      cold.query(RigidTransform::identity(), place, QueryKind::Intersect, k);
      expect_same(f, k, "front, " + where);
      expect_same(n, k, "no front, " + where);
      // Distance's own fronts, kept beside Intersect's on the same pair.
      QueryResult fd, kd;
      front.query(RigidTransform::identity(), place, QueryKind::Distance, fd);
      cold.query(RigidTransform::identity(), place, QueryKind::Distance, kd);
      expect_same(fd, kd, "front distance, " + where);  // apart: the same closest triangles too
      (k.intersecting ? intersecting : apart) += 1;
      if (!f.intersecting) continue;
      // The witness triangles, placed, measured with FCL's triangle distance: touching.
      fcl::Vector3d ta[3], tb[3], pa, pb;
      for (int v = 0; v < 3; ++v) {
        const auto& va = sphere.mesh.vertices[sphere.mesh.triangles[f.triangle_a][v]];
        const auto& vb = b.mesh.vertices[b.mesh.triangles[f.triangle_b][v]];
        ta[v] = fcl::Vector3d(va[0], va[1], va[2]);
        for (int k = 0; k < 3; ++k)
          tb[v][k] = place.rotation[3 * k] * vb[0] + place.rotation[3 * k + 1] * vb[1] + place.rotation[3 * k + 2] * vb[2] +
                     place.translation[k];
      }
      EXPECT_LE(fcl::detail::TriangleDistanced::triDistance(ta, tb, pa, pb), 1e-9) << where;
    }
    // Both answers occur along each path.
    EXPECT_GT(intersecting, 0) << "path " << p;
    EXPECT_GT(apart, 0) << "path " << p;
  }
}

// The warm Intersect's witness pair, taken from around the previous one, really touches.
TEST(Collision, WarmIntersectWitnessTouches) {
  const Body a = make_body(BRepPrimAPI_MakeSphere(5).Shape());
  CollisionPair pair(a.model, a.model);
  QueryResult result;
  for (int i = 0; i < 50; ++i) {
    const RigidTransform place = RigidTransform::translated(9.9, 0.01 * i, 0.005 * i);
    pair.query(RigidTransform::identity(), place, QueryKind::Intersect, result);
    ASSERT_TRUE(result.intersecting) << i;
    // The witness triangles, placed, measured with FCL's triangle distance: touching.
    fcl::Vector3d ta[3], tb[3], pa, pb;
    for (int k = 0; k < 3; ++k) {
      const auto& va = a.mesh.vertices[a.mesh.triangles[result.triangle_a][k]];
      const auto& vb = a.mesh.vertices[a.mesh.triangles[result.triangle_b][k]];
      ta[k] = fcl::Vector3d(va[0], va[1], va[2]);
      tb[k] = fcl::Vector3d(vb[0] + place.translation[0], vb[1] + place.translation[1], vb[2] + place.translation[2]);
    }
    EXPECT_LE(fcl::detail::TriangleDistanced::triDistance(ta, tb, pa, pb), 1e-9) << i;
    EXPECT_EQ(result.partition_a, a.mesh.triangle_partition[result.triangle_a]);
    EXPECT_EQ(result.partition_b, a.mesh.triangle_partition[result.triangle_b]);
  }
}

// With a distance limit, the distances at or below it are the exact ones and those above it are
// "farther" (infinity), warm or cold; the pruned search does less work.
TEST(Collision, DistanceLimitAnswersFartherBeyondIt) {
  const Body a = make_body(BRepPrimAPI_MakeSphere(5).Shape());
  CollisionPair exact(a.model, a.model), limited(a.model, a.model), limited_cold(a.model, a.model);
  limited.set_distance_limit(0.525);
  limited_cold.set_distance_limit(0.525);
  limited_cold.set_warm_start(false);
  int below = 0, beyond = 0;
  std::size_t exact_work = 0, limited_work = 0;  // bounding-volume tests of the placements beyond
  for (int i = 0; i < 20; ++i) {
    const double gap = -0.2 + 0.05 * i;  // the spheres' gap, from crossing to 0.75 apart
    const RigidTransform place = RigidTransform::translated(10 + gap, 0.002 * i, 0.002);
    QueryResult e, l, c;
    const std::size_t exact_before = exact.counts().bv_tests, limited_before = limited.counts().bv_tests;
    exact.query(RigidTransform::identity(), place, QueryKind::Distance, e);
    limited.query(RigidTransform::identity(), place, QueryKind::Distance, l);
    limited_cold.query(RigidTransform::identity(), place, QueryKind::Distance, c);
    for (const QueryResult* r : {&l, &c}) {
      if (e.distance <= 0.525) {
        EXPECT_NEAR(r->distance, e.distance, 1e-12) << i;
        EXPECT_EQ(r->intersecting, e.intersecting) << i;
        if (!e.intersecting)
          for (int k = 0; k < 3; ++k) EXPECT_NEAR(r->point_a[k], e.point_a[k], 1e-12) << i;
      } else {
        EXPECT_TRUE(std::isinf(r->distance)) << i;
        EXPECT_FALSE(r->intersecting) << i;
        EXPECT_EQ(r->triangle_a, -1) << i;
      }
    }
    if (e.distance <= 0.525) ++below;
    else {
      ++beyond;
      exact_work += exact.counts().bv_tests - exact_before;
      limited_work += limited.counts().bv_tests - limited_before;
    }
  }
  EXPECT_LT(limited_work, exact_work);
  // The meshes' gap exceeds the spheres' by at most twice the deflection (0.01; vertices on the
  // spheres): gaps up to 0.5 (i <= 14) stay below 0.525, gaps from 0.55 (i >= 15) beyond it.
  EXPECT_EQ(below, 15);
  EXPECT_EQ(beyond, 5);
}

// The front's box test: disjoint exactly when FCL's obbDisjoint says so, and its margin a lower
// bound of the boxes' distance (FCL's GJK distance between the same boxes), equal to the gap for
// boxes side by side.
TEST(Collision, BoxSeparationAgreesWithFclAndBoundsTheDistance) {
  using contactcore::bvh::box_separation;
  // Side by side along x: half-extents 1 and 2, centres 4 apart: a gap of exactly 1.
  const auto side = box_separation(fcl::Matrix3d::Identity(), fcl::Vector3d(4, 0.5, 0), fcl::Vector3d(1, 1, 1),
                                   fcl::Vector3d(2, 1, 1));
  EXPECT_TRUE(side.disjoint);
  // Along B's x face axis 4 - 2 - (1 + 1e-6 + 1e-6 + 1e-6), |B| widened by FCL's 1e-6 per entry
  // (along A's: 4 - 1 - (2 + 2e-6 + 1e-6 + 1e-6), smaller).
  EXPECT_NEAR(side.margin, 1.0 - 3e-6, 1e-12);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(-1, 1), size(0.01, 2);
  int disjoint = 0, from_edges = 0;
  for (int i = 0; i < 3000; ++i) {
    const auto qv = drawn_last_first<4>([&] { return unit(rng); });
    const fcl::Quaterniond q(qv[0], qv[1], qv[2], qv[3]);
    const fcl::Matrix3d B = q.normalized().toRotationMatrix();
    const auto av = drawn_last_first<3>([&] { return size(rng); });
    const auto bv = drawn_last_first<3>([&] { return size(rng); });
    const fcl::Vector3d a(av[0], av[1], av[2]), b(bv[0], bv[1], bv[2]);
    const auto tv = drawn_last_first<3>([&] { return unit(rng); });
    const fcl::Vector3d T = 3.0 * fcl::Vector3d(tv[0], tv[1], tv[2]);
    const auto separation = box_separation(B, T, a, b);
    ASSERT_EQ(separation.disjoint, fcl::obbDisjoint<double>(B, T, a, b)) << i;
    if (!separation.disjoint) continue;
    ++disjoint;
    fcl::Transform3d place = fcl::Transform3d::Identity();
    place.linear() = B;
    place.translation() = T;
    const fcl::Boxd box_a(2 * a), box_b(2 * b);
    fcl::DistanceRequestd request;
    request.gjk_solver_type = fcl::GST_INDEP;
    fcl::DistanceResultd result;
    fcl::distance(&box_a, fcl::Transform3d::Identity(), &box_b, place, request, result);
    EXPECT_LE(separation.margin, result.min_distance + 1e-6) << i;
    EXPECT_GE(separation.margin, 0) << i;
    if (separation.margin < 0.5 * result.min_distance) ++from_edges;  // separated by an edge axis, or loosely
  }
  // Seed 7: 1,898 of the 3,000 pairs are apart (each agreeing with FCL above).
  EXPECT_EQ(disjoint, 1898);
  EXPECT_LT(from_edges, disjoint / 2);  // mostly a face axis, the margin close to the distance
}

// The bodies' one tree per body (Penetration's touching pairs filtered by partition at the leaves,
// the flood's closest points, depth_inside) against one tree per partition (the reference, as
// before) on the same poses: a shaft in its line-to-line bore turned and pushed sideways (the
// tessellations cross along the whole bore, hundreds of touching pairs), random poses of a cylinder
// in a holed box, with a partition, then only the bore-shaft pair switched off, then everything on.
TEST(Collision, BodyTreesGiveThePerPartitionAnswers) {
  const Body block = make_body(BRepAlgoAPI_Cut(BRepPrimAPI_MakeBox(gp_Pnt(-10, -10, 0), 20, 20, 10).Shape(),
                                               BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, -1), gp::DZ()), 3, 12).Shape())
                                   .Shape());
  const Body shaft = make_body(BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, -5), gp::DZ()), 3, 20).Shape());
  const Body holed = make_body(BRepAlgoAPI_Cut(BRepPrimAPI_MakeBox(gp_Pnt(-6, -6, -4), 12, 12, 8).Shape(),
                                               BRepPrimAPI_MakeSphere(4.5).Shape())
                                   .Shape());
  const int bore = cylinder_partition(block), side = cylinder_partition(shaft);
  ASSERT_GE(bore, 0);
  ASSERT_GE(side, 0);
  std::mt19937 rng(20);
  std::uniform_real_distribution<double> turn(-0.2, 0.2), push(-0.3, 0.3);
  int deep = 0, touching = 0, apart = 0;
  for (int mode = 0; mode < 3; ++mode) {  // 0: all on, 1: the bore partition off, 2: only the bore-shaft pair off
    CollisionPair body_trees(block.model, shaft.model), per_partition(block.model, shaft.model);
    CollisionPair body_holed(shaft.model, holed.model), per_partition_holed(shaft.model, holed.model);
    body_trees.set_body_tree(true);
    body_holed.set_body_tree(true);
    for (CollisionPair* pair : {&body_trees, &per_partition}) {
      if (mode == 1) pair->set_partition_enabled(0, bore, false);
      if (mode == 2) pair->set_pair_enabled(bore, side, false);
    }
    for (int i = 0; i < 40; ++i) {
      const double angle = turn(rng);
      RigidTransform in_bore;
      in_bore.rotation = {std::cos(angle), -std::sin(angle), 0, std::sin(angle), std::cos(angle), 0, 0, 0, 1};
      in_bore.translation = {i % 4 == 0 ? 0.0 : push(rng), i % 4 == 0 ? 0.0 : push(rng), push(rng)};
      const RigidTransform random = random_placement(rng, 5.0);
      for (QueryKind kind : {QueryKind::Penetration, QueryKind::Distance, QueryKind::Intersect}) {
        const std::string where = "mode " + std::to_string(mode) + " pose " + std::to_string(i) + " kind " +
                                  std::to_string(static_cast<int>(kind));
        QueryResult tree, reference;
        body_trees.query(RigidTransform::identity(), in_bore, kind, tree);
        per_partition.query(RigidTransform::identity(), in_bore, kind, reference);
        expect_same(tree, reference, "shaft in bore, " + where);
        if (kind == QueryKind::Penetration) (reference.depth > 0 ? deep : reference.intersecting ? touching : apart) += 1;
        body_holed.query(random, RigidTransform::identity(), kind, tree);
        per_partition_holed.query(random, RigidTransform::identity(), kind, reference);
        expect_same(tree, reference, "cylinder in holed box, " + where);
        if (kind == QueryKind::Penetration) (reference.depth > 0 ? deep : reference.intersecting ? touching : apart) += 1;
      }
      const std::array<double, 3> point{push(rng) * 10, push(rng) * 10, push(rng) * 10};
      EXPECT_EQ(body_trees.depth_inside(1, in_bore, point), per_partition.depth_inside(1, in_bore, point));
      EXPECT_EQ(body_holed.depth_inside(1, RigidTransform::identity(), point),
                per_partition_holed.depth_inside(1, RigidTransform::identity(), point));
    }
  }
  // Both kinds of answer are exercised: of the 240 Penetration queries (3 modes x 40 poses x 2
  // pairs) 210 penetrate and 30 merely touch (the seed fixes them).
  EXPECT_EQ(deep, 210);
  EXPECT_EQ(touching, 30);
  EXPECT_EQ(apart, 0);
}

// Penetration's flood and the per-pair mask: a shaft (side meshed with edges of at most 1 mm, so
// that its side has vertices between its rims) from z = 0.1 to 9.9 in a bore through a block 10
// thick, pushed 0.2 sideways into the bore's wall. All pairs on, the side's vertices inside the
// wall are the deepest: depth 0.2 (to the bore mesh's chords), A (the block) leaving along +x. The
// bore-shaft side pair off, those vertices are that pair's overlap and skipped; what is left is the
// rims of the end discs sunk 0.1 under the block's faces next to the bore (their disc's pairs on):
// depth 0.1 exactly (to the faces z = 0 and 10), along z.
TEST(Collision, SwitchedOffPairOverlapIsNotFlooded) {
  const Body block = make_body(BRepAlgoAPI_Cut(BRepPrimAPI_MakeBox(gp_Pnt(-10, -10, 0), 20, 20, 10).Shape(),
                                               BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, -1), gp::DZ()), 3, 12).Shape())
                                   .Shape());
  Body shaft;
  shaft.shape = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, 0.1), gp::DZ()), 3, 9.8).Shape();
  shaft.partitions = partition_shape(shaft.shape, Tolerances{});
  MeshOptions options;
  options.deflection = 0.01;
  options.max_edge_length = 1.0;
  const MeshResult meshed = mesh_body(shaft.shape, shaft.partitions, options);
  ASSERT_TRUE(meshed.status.ok()) << meshed.status.describe();
  shaft.model = build_collision_model(meshed.mesh).model;
  ASSERT_TRUE(shaft.model);
  const int bore = cylinder_partition(block), side = cylinder_partition(shaft);
  ASSERT_GE(bore, 0);
  ASSERT_GE(side, 0);
  CollisionPair pair(block.model, shaft.model);
  QueryResult on, off;
  const RigidTransform pushed = RigidTransform::translated(0.2, 0, 0);
  pair.query(RigidTransform::identity(), pushed, QueryKind::Penetration, on);
  // The bore's facet the side is pushed through is the one facing +x (two facets tie, at +-theta,
  // a tessellation vertex on the x axis). Its normal n = (cos theta, +-sin theta, 0) is the
  // direction, and the deepest side vertex, at angle theta, lies 3 (1 - cos theta) + 0.2 cos theta
  // beyond that facet's plane (the plane at 3 cos theta from the axis).
  double facing = -1;
  for (std::size_t t = 0; t < block.mesh.triangles.size(); ++t) {
    if (block.mesh.triangle_partition[t] != bore) continue;
    const auto& [i0, i1, i2] = block.mesh.triangles[t];
    const auto& p0 = block.mesh.vertices[i0];
    const auto& p1 = block.mesh.vertices[i1];
    const auto& p2 = block.mesh.vertices[i2];
    const gp_Vec normal = gp_Vec(gp_Pnt(p0[0], p0[1], p0[2]), gp_Pnt(p1[0], p1[1], p1[2]))
                              .Crossed(gp_Vec(gp_Pnt(p0[0], p0[1], p0[2]), gp_Pnt(p2[0], p2[1], p2[2])));
    facing = std::max(facing, -normal.X() / normal.Magnitude());  // the block's normal points to the axis
  }
  ASSERT_GT(facing, 0.99);
  EXPECT_NEAR(on.direction[0], facing, 1e-9);
  EXPECT_NEAR(std::abs(on.direction[1]), std::sqrt(1 - facing * facing), 1e-9);
  EXPECT_NEAR(on.direction[2], 0.0, 1e-12);
  EXPECT_NEAR(on.depth, 3 * (1 - facing) + 0.2 * facing, 1e-9);
  pair.set_pair_enabled(bore, side, false);
  pair.query(RigidTransform::identity(), pushed, QueryKind::Penetration, off);
  EXPECT_TRUE(off.intersecting);
  EXPECT_NEAR(off.depth, 0.1, 1e-9);
  EXPECT_NEAR(std::abs(off.direction[2]), 1.0, 1e-9);
}
