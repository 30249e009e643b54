// The closed forms between analytic partitions (analytic_distance.h) as the
// haptic loop uses them (issue 20, item 2): against the mesh query of the
// collision stage (collision.h) on the motor's plane and cylinder pairs, with
// the tolerances derived from the meshes themselves; and a coplanar pair off
// the outline, which must report no contact, in closed form and through the
// loop's contact query (StageCollision, a trial scene with the closed forms on).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <BRepAlgoAPI_Cut.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <gp_Ax2.hxx>

#include "contactcore/bodies/bodies.h"
#include "contactcore/common/angles.h"
#include "contactcore/haptics/trial.h"
#include "contactcore/simulation/analytic_distance.h"
#include "contactcore/simulation/collision.h"
#include "contactcore/simulation/meshes.h"
#include "path_checker.h"
#include "test_helpers.h"

using namespace contactcore;
using Eigen::Vector3d;
using contactcore::testing::Partitioned;
using contactcore::testing::partitioned;
using contactcore::testing::plane_facing;

// ---- The closed forms against the mesh query (collision.h) on the motor.
//
// The meshes are the trial's (deflection 0.01 mm, angle 0.2 rad; the moving
// part's edges at most 1 mm), one partition pair switched on at a time. Where
// the two differ is derived from the meshes themselves, not guessed: a planar
// partition's triangles lie in their plane up to `plane_deviation` (the
// largest distance of a vertex from the exact plane: rounding); a cylinder's
// vertices lie on the exact surface (to its own rounding) and its chords cut
// inside it by at most `cylinder_sagitta` (the largest radial depth of an edge
// midpoint below the radius), turning the facet's normal by at most
// acos(1 - sagitta / r) from the exact normal at that spot.

namespace {

struct MotorMeshes {
  contactcore::Assembly assembly;
  std::vector<Partitioned> bodies;
  std::vector<TaggedMesh> meshes;
  std::vector<CollisionModelPtr> models;
  int index(const std::string& name) const {
    for (std::size_t i = 0; i < assembly.bodies.size(); ++i)
      if (assembly.bodies[i].name == name) return static_cast<int>(i);
    ADD_FAILURE() << "no body " << name;
    return 0;
  }
};

// The motor meshed as the trial meshes it, `moving` with edges of at most 1 mm.
const MotorMeshes& motor_meshes(const std::string& moving) {
  static std::map<std::string, MotorMeshes> cache;
  auto found = cache.find(moving);
  if (found != cache.end()) return found->second;
  MotorMeshes& m = cache[moving];
  const auto read = read_step(contactcore::testing::sample("motor.step"));
  EXPECT_TRUE(read.status.ok()) << read.status.describe();
  m.assembly = read.assembly;
  for (const contactcore::Body& body : m.assembly.bodies) {
    m.bodies.push_back(partitioned(body.shape));
    MeshOptions options;
    options.deflection = 0.01;
    options.angle = 0.2;
    options.max_edge_length = body.name == moving ? 1.0 : 0.0;
    MeshResult mesh = mesh_body(body.shape, m.bodies.back().parts, options);
    EXPECT_TRUE(mesh.status.ok()) << body.name;
    CollisionModelResult model = build_collision_model(mesh.mesh);
    EXPECT_TRUE(model.status.ok()) << body.name;
    m.meshes.push_back(std::move(mesh.mesh));
    m.models.push_back(model.model);
  }
  return m;
}

Vector3d vertex(const TaggedMesh& mesh, int v) { return Vector3d(mesh.vertices[v][0], mesh.vertices[v][1], mesh.vertices[v][2]); }

// The largest distance of the partition's mesh vertices from its exact plane.
double plane_deviation(const TaggedMesh& mesh, const AnalyticPatch& plane) {
  double worst = 0;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k)
      worst = std::max(worst, std::abs((vertex(mesh, mesh.triangles[t][k]) - plane.location).dot(plane.axis)));
  return worst;
}

// Of partition `id`'s triangles: the largest distance of a vertex off the exact
// cylinder (rounding), and the deepest edge midpoint below it (the chords' sagitta).
void cylinder_deviation(const TaggedMesh& mesh, int id, const AnalyticPatch& cylinder, double& off_surface,
                        double& sagitta) {
  off_surface = sagitta = 0;
  auto radial = [&](const Vector3d& p) {
    const Vector3d d = p - cylinder.location;
    return (d - d.dot(cylinder.axis) * cylinder.axis).norm();
  };
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    if (mesh.triangle_partition[t] != id) continue;
    for (int k = 0; k < 3; ++k) {
      const Vector3d p = vertex(mesh, mesh.triangles[t][k]), q = vertex(mesh, mesh.triangles[t][(k + 1) % 3]);
      off_surface = std::max(off_surface, std::abs(radial(p) - cylinder.radius));
      sagitta = std::max(sagitta, cylinder.radius - radial(0.5 * (p + q)));
    }
  }
}

// A mesh holding the triangles of one partition only.
TaggedMesh partition_mesh(const TaggedMesh& mesh, int id) {
  TaggedMesh out;
  out.partition_count = mesh.partition_count;
  out.vertices = mesh.vertices;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    if (mesh.triangle_partition[t] == id) {
      out.triangles.push_back(mesh.triangles[t]);
      out.triangle_face.push_back(mesh.triangle_face[t]);
      out.triangle_partition.push_back(id);
    }
  return out;
}

RigidTransform shifted(const Vector3d& v) { return RigidTransform::translated(v.x(), v.y(), v.z()); }

// The mesh query of one partition pair (every other partition off).
QueryResult mesh_pair_distance(const MotorMeshes& m, int body_a, int pa, const RigidTransform& place_a, int body_b,
                               int pb) {
  CollisionPair pair(m.models[body_a], m.models[body_b]);
  for (int p = 0; p < m.models[body_a]->partition_count(); ++p) pair.set_partition_enabled(0, p, p == pa);
  for (int p = 0; p < m.models[body_b]->partition_count(); ++p) pair.set_partition_enabled(1, p, p == pb);
  QueryResult r;
  pair.query(place_a, RigidTransform::identity(), QueryKind::Distance, r);
  return r;
}

}  // namespace

// Screw-1's head underside on the Front-cover's face (the plane pair a seated
// screw leans on, coplanar when assembled), the screw lifted 0.001 to 0.5 mm
// and slid 0.3 mm along the face: the closed form's gap is the meshes'
// distance within the two faces' mesh deviations from their planes; its
// normal is the direction between the meshes' closest points within what
// those deviations can tilt it over the gap; its two points are h apart along
// it and lie in both outlines.
TEST(AnalyticDistance, MotorScrewHeadOnTheCoverMatchesTheMeshQuery) {
  const MotorMeshes& m = motor_meshes("Screw-1");
  const int screw = m.index("Screw-1"), cover = m.index("Front-cover");
  // The seated plane pair: facing planes with a closed form at the assembled placement.
  int pa = -1, pb = -1;
  AnalyticContact seated;
  for (const Partition& a : m.bodies[screw].parts.partitions)
    for (const Partition& b : m.bodies[cover].parts.partitions) {
      if (a.params.kind != SurfaceKind::Plane || b.params.kind != SurfaceKind::Plane) continue;
      AnalyticContact c;
      if (analytic_contact(analytic_patch(a), analytic_patch(b), c) && std::abs(c.gap) < 1e-6) {
        EXPECT_EQ(pa, -1) << "one seated plane pair";
        pa = a.id;
        pb = b.id;
        seated = c;
      }
    }
  ASSERT_EQ(pa, 3);  // the head's underside
  ASSERT_EQ(pb, 19);  // the cover's face under it
  const AnalyticPatch head = analytic_patch(m.bodies[screw].parts.partitions[pa]);
  const AnalyticPatch face = analytic_patch(m.bodies[cover].parts.partitions[pb]);
  const double deviation = plane_deviation(partition_mesh(m.meshes[screw], pa), head) +
                           plane_deviation(partition_mesh(m.meshes[cover], pb), face);
  std::printf("[ measured ] head/face partitions %d/%d, assembled gap %.3g, meshes off their planes %.3g mm\n", pa, pb,
              seated.gap, deviation);
  EXPECT_LT(deviation, 1e-9);  // planar facets lie in their plane up to rounding
  const Vector3d n = face.axis;                          // the cover's outward normal: up, out of it
  const Vector3d along = face.ref_dir;                   // in the face's plane
  int compared = 0;
  for (double h : {0.001, 0.02, 0.5})
    for (double slide : {0.0, 0.3}) {
      const Vector3d move = h * n + slide * along;
      Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
      motion.translation() = move;
      AnalyticContact c;
      ASSERT_TRUE(analytic_contact(placed(head, motion), face, c)) << h << " " << slide;
      EXPECT_NEAR(c.gap, seated.gap + h, 1e-12);
      const QueryResult r = mesh_pair_distance(m, screw, pa, shifted(move), cover, pb);
      ASSERT_TRUE(std::isfinite(r.distance));
      EXPECT_NEAR(c.gap, r.distance, deviation + 1e-12) << h << " " << slide;
      const Vector3d mesh_a(r.point_a[0], r.point_a[1], r.point_a[2]), mesh_b(r.point_b[0], r.point_b[1], r.point_b[2]);
      // The meshes' direction between their closest points: the closed form's
      // normal within the tilt the deviations allow over the distance, and the
      // points' rounding (coordinates up to 100 mm: 1e-13 mm) over it.
      EXPECT_LE(((mesh_a - mesh_b).normalized() - c.normal).norm(), (2 * deviation + 1e-13) / r.distance);
      EXPECT_NEAR((c.point_a - c.point_b - c.gap * c.normal).norm(), 0.0, 1e-12);
      EXPECT_TRUE(within_patch(face, c.point_b)) << "the closed form's point on the cover's face";
      // The meshes' closest points (a tie over the overlap) lie on the two faces' planes.
      EXPECT_LE(std::abs((mesh_b - face.location).dot(face.axis)), deviation + 1e-12);
      EXPECT_LE(std::abs((mesh_a - motion * head.location).dot(head.axis)), deviation + 1e-12);
      ++compared;
    }
  EXPECT_EQ(compared, 6);
}

// Screw-1's shank in its Front-cover hole and the Axis in Bearing-front's bore
// (the motor's cylinder pairs), pushed sideways: the closed form's signed gap
// R_b - R_a - e against the meshes. The meshes' vertices lie on the exact
// cylinders, their chords up to the sagitta s inside: the shaft's facets up
// to s_a farther from the wall, the bore's up to s_b nearer, so the meshes'
// distance (0 when they cross) lies in [g - s_b, g + s_a] clamped at 0; the
// direction between the meshes' closest points is the closed form's normal
// within the facets' turn (acos(1 - s / r) each).
TEST(AnalyticDistance, MotorShaftInBorePairsMatchTheMeshQuery) {
  int compared = 0;
  for (const auto& [part, other] : {std::pair<std::string, std::string>{"Screw-1", "Front-cover"},
                                    std::pair<std::string, std::string>{"Axis", "Bearing-front"}}) {
    const MotorMeshes& m = motor_meshes(part);
    const int a_body = m.index(part), b_body = m.index(other);
    // The shaft-in-bore pairs at the assembled placement.
    for (const Partition& a : m.bodies[a_body].parts.partitions)
      for (const Partition& b : m.bodies[b_body].parts.partitions) {
        if (a.params.kind != SurfaceKind::Cylinder || b.params.kind != SurfaceKind::Cylinder) continue;
        if (a.side != MaterialSide::Convex || b.side != MaterialSide::Concave) continue;
        const AnalyticPatch shaft = analytic_patch(a), bore = analytic_patch(b);
        AnalyticContact assembled;
        if (!analytic_contact(shaft, bore, assembled) || assembled.gap > 0.5) continue;
        double off_a, sag_a, off_b, sag_b;
        cylinder_deviation(m.meshes[a_body], a.id, shaft, off_a, sag_a);
        cylinder_deviation(m.meshes[b_body], b.id, bore, off_b, sag_b);
        const double turn = std::acos(1 - sag_a / shaft.radius) + std::acos(1 - sag_b / bore.radius);
        const double clearance = bore.radius - shaft.radius;
        std::printf("[ measured ] %s/%s partitions %d/%d: r %.4f in %.4f, sagitta %.2g / %.2g mm, off %.2g / %.2g\n",
                    part.c_str(), other.c_str(), a.id, b.id, shaft.radius, bore.radius, sag_a, sag_b, off_a, off_b);
        const Vector3d side = bore.axis.unitOrthogonal();
        const double error = sag_a + sag_b + 2 * (off_a + off_b);  // the meshes' gap off the exact one, at most
        for (double e : {0.0, 0.5 * clearance, clearance + 0.004}) {
          for (double turn_about = 0; turn_about < 6.28; turn_about += 1.3) {
            const Vector3d u = Eigen::AngleAxisd(turn_about, bore.axis) * side;
            Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
            motion.translation() = e * u;
            AnalyticContact c;
            ASSERT_TRUE(analytic_contact(placed(shaft, motion), bore, c)) << part << " e " << e;
            // The closed form (parallel axes): the radial clearance less the axes' distance.
            const Vector3d apart = shaft.location + e * u - bore.location;
            const double offset = (apart - apart.dot(bore.axis) * bore.axis).norm();
            EXPECT_NEAR(c.gap, clearance - offset, 1e-12) << part << " e " << e;
            const QueryResult r = mesh_pair_distance(m, a_body, a.id, shifted(e * u), b_body, b.id);
            const double low = std::max(0.0, c.gap - sag_b - 2 * (off_a + off_b)),
                         high = std::max(0.0, c.gap + sag_a + 2 * (off_a + off_b));
            EXPECT_GE(r.distance, low - 1e-12) << part << " e " << e << " turn " << turn_about;
            EXPECT_LE(r.distance, high + 1e-12) << part << " e " << e << " turn " << turn_about;
            if (r.distance > 1e-6) {
              const Vector3d mesh_a(r.point_a[0], r.point_a[1], r.point_a[2]),
                  mesh_b(r.point_b[0], r.point_b[1], r.point_b[2]);
              // The meshes' closest spot is where the exact gap c - e cos(phi) is within their error of
              // its least: cos(phi) >= 1 - error / e about the side pushed to, plus the facets' turn.
              const double angle = std::acos(std::clamp((mesh_a - mesh_b).normalized().dot(c.normal), -1.0, 1.0));
              const double spread = offset > 0 ? std::acos(std::max(-1.0, 1 - error / offset)) : kPi;
              EXPECT_LE(angle, spread + turn + 1e-9) << part << " e " << e;
            }
            ++compared;
          }
        }
      }
  }
  EXPECT_EQ(compared, 30);  // 2 shaft-in-bore pairs, 3 offsets, 5 turns
}

// Two faces coplanar (0.001 mm apart, facing) whose outlines do not meet: a
// block over a plate's hole, its bottom inside the hole's outline, and beside
// the plate. No closed-form contact (the even-odd test sees the hole), and the
// loop's contact query (closed forms on, as the trial runs) reports none
// within its reach; on the plate's face 0.001 above it, it reports the plane
// contact at that gap.
TEST(AnalyticDistance, CoplanarFacesOffTheOutlineReportNoContact) {
  const TopoDS_Shape plate_block = BRepPrimAPI_MakeBox(gp_Pnt(-30, -30, -5), 60, 60, 5).Shape();
  const TopoDS_Shape hole = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, -10), gp_Dir(0, 0, 1)), 8, 20).Shape();
  const TopoDS_Shape plate = BRepAlgoAPI_Cut(plate_block, hole).Shape();
  const TopoDS_Shape block = BRepPrimAPI_MakeBox(gp_Pnt(-4, -4, 0.001), 8, 8, 5).Shape();  // its corners 5.66 from the axis
  const Partitioned p = partitioned(plate), b = partitioned(block);
  const AnalyticPatch top = analytic_patch(plane_facing(p.parts, gp_Dir(0, 0, 1)));
  const AnalyticPatch bottom = analytic_patch(plane_facing(b.parts, gp_Dir(0, 0, -1)));
  ASSERT_EQ(top.loops.size(), 2u);  // the outer square and the hole
  AnalyticContact c;
  Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
  EXPECT_FALSE(analytic_contact(bottom, top, c)) << "over the hole";
  motion.translation() = Vector3d(40, 0, 0);  // beside the plate: x 36..44
  EXPECT_FALSE(analytic_contact(placed(bottom, motion), top, c)) << "beside the plate";
  motion.translation() = Vector3d(20, 0, 0);  // on the plate's face
  ASSERT_TRUE(analytic_contact(placed(bottom, motion), top, c));
  EXPECT_NEAR(c.gap, 0.001, 1e-12);
  EXPECT_NEAR((c.normal - Vector3d(0, 0, 1)).norm(), 0.0, 1e-15);

  // The loop's query on a trial scene with the closed forms on (off by default).
  contactcore::Status status;
  const contactcore::Assembly assembly = contactcore::testing::make_assembly({{"Plate", plate}, {"Block", block}});
  haptics::SceneOptions closed_forms;
  closed_forms.analytic = true;
  auto scene = haptics::TrialScene::build(assembly, "Block", closed_forms, status);
  ASSERT_TRUE(scene) << status.describe();
  ASSERT_TRUE(scene->collision().analytic());
  haptics::ContactPoint contacts[haptics::kMaxContacts];
  const double reach = 0.05;  // the block's rim is 8 - 5.66 = 2.3 mm from the hole's wall
  EXPECT_EQ(scene->collision().contacts(haptics::Pose::Identity(), -1, reach, contacts, haptics::kMaxContacts), 0);
  haptics::Pose beside = haptics::Pose::Identity();
  beside.translation() = Vector3d(40, 0, 0);
  EXPECT_EQ(scene->collision().contacts(beside, -1, reach, contacts, haptics::kMaxContacts), 0);
  haptics::Pose on_face = haptics::Pose::Identity();
  on_face.translation() = Vector3d(20, 0, 0);
  ASSERT_EQ(scene->collision().contacts(on_face, -1, reach, contacts, haptics::kMaxContacts), 1);
  EXPECT_NEAR(contacts[0].gap, 0.001, 1e-12);
  EXPECT_NEAR((contacts[0].normal - Vector3d(0, 0, 1)).norm(), 0.0, 1e-12);
  // The partition pairs whose bounding spheres come within the reach, by hand: the block's six
  // faces against the plate's top, bottom and side x = 30 (18), and its faces x = 16 and y = +-4
  // against the plate's sides y = +-30 (4). The bottom pair in closed form and 17 by their bounds
  // (faces above the plate's top, behind its bottom or sides); the block's four sides, standing
  // 0.001 over the plate's top, have neither and are left to the meshes.
  EXPECT_EQ(scene->collision().last_closed_form_pairs(), 18);
  EXPECT_EQ(scene->collision().last_mesh_fallback_pairs(), 4);
}

// The motor's Axis pulled 15 mm straight up along its bores with the closed
// forms on (the hand 0 -> +15 mm in z over 3 s, then held): nothing blocks it,
// so it ends at the hand, as with the meshes alone; judged by OCCT along the
// path. With motor.FCStd's shapes it stopped at z = 4.999: a phantom
// plane-pair contact (OutlineVertexOnTheRayCountsOnce holds its numbers; the
// STEP sample's frames round differently and never hit it). Printed: every
// closed-form pair within 0.05 mm with the Axis 5 mm up.
TEST(AnalyticDistance, MotorAxisPulled15mmUpAlongItsBoresComesOut) {
  const auto read = read_step(contactcore::testing::sample("motor.step"));
  ASSERT_TRUE(read.status.ok()) << read.status.describe();
  const contactcore::Assembly& assembly = read.assembly;
  contactcore::Status status;
  haptics::SceneOptions closed_forms;
  closed_forms.analytic = true;
  auto scene = haptics::TrialScene::build(assembly, "Axis", closed_forms, status);
  ASSERT_TRUE(scene) << status.describe();
  ASSERT_TRUE(scene->collision().analytic());

  // Every closed-form pair of the Axis's partitions with a neighbour's, Axis 5 mm up.
  std::vector<BodyPartitions> parts;
  int axis = -1;
  for (std::size_t i = 0; i < assembly.bodies.size(); ++i) {
    parts.push_back(partition_shape(assembly.bodies[i].shape, Tolerances{}));
    if (assembly.bodies[i].name == "Axis") axis = static_cast<int>(i);
  }
  ASSERT_EQ(axis, 0);  // the STEP file's first product
  Eigen::Isometry3d up5 = Eigen::Isometry3d::Identity();
  up5.translation() = Vector3d(0, 0, 5.0);
  for (std::size_t j = 0; j < assembly.bodies.size(); ++j) {
    if (static_cast<int>(j) == axis) continue;
    for (const Partition& a : parts[axis].partitions)
      for (const Partition& b : parts[j].partitions) {
        AnalyticContact c;
        if (!analytic_contact(placed(analytic_patch(a), up5), analytic_patch(b), c) || c.gap > 0.05) continue;
        std::printf("[ z = 5 ] Axis p%d (kind %d) / %s p%d (kind %d): gap %.6f normal %.3f %.3f %.3f at %.3f %.3f %.3f\n",
                    a.id, static_cast<int>(a.params.kind), assembly.bodies[j].name.c_str(), b.id,
                    static_cast<int>(b.params.kind), c.gap, c.normal.x(), c.normal.y(), c.normal.z(), c.point_b.x(),
                    c.point_b.y(), c.point_b.z());
      }
  }

  haptics::TrialScript script;
  script.start = haptics::ScriptKey{0, haptics::Vec3::Zero(), haptics::Vec3::Zero()};
  script.hand = {haptics::ScriptKey{0.0, haptics::Vec3::Zero(), haptics::Vec3::Zero()},
                 haptics::ScriptKey{3.0, haptics::Vec3(0, 0, 15), haptics::Vec3::Zero()},
                 haptics::ScriptKey{4.0, haptics::Vec3(0, 0, 15), haptics::Vec3::Zero()}};
  haptics::TrialOptions options;
  options.record_every = 10;
  const haptics::TrialResult r = haptics::run_trial(*scene, script, options);
  ASSERT_TRUE(r.status.ok()) << r.status.message;
  std::printf("[ figures ] final %.6f %.6f %.6f mm\n", r.final_translate.x(), r.final_translate.y(),
              r.final_translate.z());
  EXPECT_NEAR(r.final_translate.z(), 15.0, 0.05) << r.final_translate.transpose();
  EXPECT_LT(r.final_translate.head<2>().norm(), 0.05) << r.final_translate.transpose();
  EXPECT_LT(r.final_rotate_deg.norm(), 0.1) << r.final_rotate_deg.transpose();
  const contactcore::testing::PathOverlap o =
      contactcore::testing::check_path(assembly, "Axis", scene->centre(), r.path, 15);
  std::printf("[ judge ] deepest %.6f mm with %s at t = %.3f (%d samples)\n", o.max_depth, o.worst_body.c_str(),
              o.worst_t, o.samples_checked);
  EXPECT_LE(o.max_depth, 0.01) << o.worst_body << " at t = " << o.worst_t;
  EXPECT_EQ(o.samples_checked, 38);  // every 15th of the path's 4 s recorded every 10 ticks, and its end
}

// The even-odd count at a vertex on the query point's ray, with the numbers of
// the phantom contact that stopped the motor's Axis at z = 4.999 (motor.FCStd,
// closed forms on): Rotor-back's downward face (partition 0) has its bore's rim
// vertex at (4, 5e-17) in its plane frame, and the Axis's upward shoulder
// annulus (partition 3, 5 mm below it assembled) a vertex mapped to y = 5e-17
// exactly, left of the rim, in the bore: outside the face. The chord into the
// rim vertex rebuilt as start + delta ends at y = 5.55e-17, above the ray,
// while the next chord starts at 5e-17, on it: neither crossed, the point came
// out inside, and the plane pair reported a contact 0.0005 mm apart 5 mm out.
// Here a quadrilateral notched at that vertex (the rim's chords exactly): left
// of the vertex is outside, right of it inside.
TEST(AnalyticDistance, OutlineVertexOnTheRayCountsOnce) {
  AnalyticPatch face;
  face.kind = SurfaceKind::Plane;
  face.location = Vector3d(0, 0, 0);
  face.axis = Vector3d(0, 0, 1);
  face.ref_dir = Vector3d(1, 0, 0);  // plane frame = world x, y
  const double rim_y = 4.9999999999999999e-17;
  const Point2 below{3.998795274784817, -0.098164914091649097}, rim{4.0, rim_y},
      above{3.998795274784817, 0.098164914091649846};
  face.loops = {{below, Point2{10, -1}, Point2{10, 1}, above, rim}};  // counter-clockwise
  prepare_outline(face);
  // The premise: the chord above -> rim rebuilt by its delta misses the rim's y.
  ASSERT_NE(above.y + (rim.y - above.y), rim.y);
  EXPECT_FALSE(within_patch(face, Vector3d(3.999, rim_y, 0))) << "left of the rim vertex: outside";
  EXPECT_FALSE(within_patch(face, Vector3d(3.999, 0.01, 0)));
  EXPECT_TRUE(within_patch(face, Vector3d(5, rim_y, 0))) << "right of it: inside";
  EXPECT_TRUE(within_patch(face, Vector3d(5, 0.01, 0)));

  // The plane pair: a small face 0.001 above, facing down, one vertex at
  // (3.999, rim_y) in the lower face's frame; none of its vertices is inside
  // the face and none of the face's inside it: no closed-form contact.
  AnalyticPatch pad;
  pad.kind = SurfaceKind::Plane;
  pad.location = Vector3d(0, 0, 0.001);
  pad.axis = Vector3d(0, 0, -1);
  pad.ref_dir = Vector3d(1, 0, 0);  // its frame's y is world -y
  pad.loops = {{Point2{3.9985, -rim_y}, Point2{3.9985, -0.0005}, Point2{3.999, -0.0005}, Point2{3.999, -rim_y}}};
  prepare_outline(pad);
  AnalyticContact c;
  EXPECT_FALSE(analytic_contact(pad, face, c)) << "phantom contact, gap " << c.gap;
  // Slid 1.5 mm right (x 5.4985..5.5), it is on the face: the contact at 0.001.
  Eigen::Isometry3d slide = Eigen::Isometry3d::Identity();
  slide.translation() = Vector3d(1.5, 0, 0);
  ASSERT_TRUE(analytic_contact(placed(pad, slide), face, c));
  EXPECT_NEAR(c.gap, 0.001, 1e-12);
}
