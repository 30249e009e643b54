// Real-time contacts without phantoms: planes matched by their real outlines
// (not boxes), cones by the band of surface they share (not angle and apex
// alone), clearance fits recognised up to their gap. Small generated solids
// with hand-derived expectations, and the motor's Screw-1 over the Front-cover.
#include <gtest/gtest.h>

#include <cstdio>
#include <set>

#include <BRepAlgoAPI_Cut.hxx>
#include <BRepAlgoAPI_Fuse.hxx>
#include <BRepBuilderAPI_Transform.hxx>
#include <BRepExtrema_DistShapeShape.hxx>
#include <BRep_Builder.hxx>
#include <TopoDS_Compound.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCone.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <ShapeUpgrade_UnifySameDomain.hxx>
#include <gp_Ax2.hxx>

#include "contactcore/haptics/trial.h"
#include "test_helpers.h"

using namespace contactcore;
using namespace contactcore::haptics;

namespace {

std::unique_ptr<TrialScene> scene_of(const Assembly& assembly, const std::string& part) {
  Status status;
  auto scene = TrialScene::build(assembly, part, SceneOptions{}, status);
  EXPECT_TRUE(status.ok()) << status.describe();
  return scene;
}

std::vector<LiveContact> contacts_at(TrialScene& scene, const Vec3& translate) {
  std::vector<LiveContact> live(256);
  const int n = scene.contacts().update(offset_pose(translate, Vec3::Zero(), scene.centre()), live.data(), 256);
  live.resize(n);
  return live;
}

Pose shift(const Vec3& t) {
  Pose p = Pose::Identity();
  p.translation() = t;
  return p;
}

TopoDS_Shape unified(const TopoDS_Shape& shape) {
  ShapeUpgrade_UnifySameDomain unify(shape, true, true, true);
  unify.Build();
  return unify.Shape();
}

// A 20 x 20 x 2 base (top at z = 2) with an L-shaped wall on it (the strips
// y < 5 and x < 5, top at z = 4): the wall's top is one L-shaped face whose
// box covers the whole base. A 5 x 5 x 3 block hovers 0.3 mm above the
// wall's top plane, over the open corner (x, y in 10..15).
struct Step {
  Assembly assembly;
  std::unique_ptr<TrialScene> scene;
};
Step& step_scene() {
  static Step s = [] {
    Step out;
    TopoDS_Shape base = BRepPrimAPI_MakeBox(gp_Pnt(0, 0, 0), 20, 20, 2).Shape();
    base = BRepAlgoAPI_Fuse(base, BRepPrimAPI_MakeBox(gp_Pnt(0, 0, 2), 20, 5, 2).Shape()).Shape();
    base = unified(BRepAlgoAPI_Fuse(base, BRepPrimAPI_MakeBox(gp_Pnt(0, 0, 2), 5, 20, 2).Shape()).Shape());
    out.assembly = contactcore::testing::make_assembly(
        {{"Base", base}, {"Block", BRepPrimAPI_MakeBox(gp_Pnt(10, 10, 4.3), 5, 5, 3).Shape()}});
    out.scene = scene_of(out.assembly, "Block");
    return out;
  }();
  return s;
}

}  // namespace

TEST(RealtimeContacts, PlanesMatchByOutlinesNotBoxes) {
  TrialScene& scene = *step_scene().scene;
  // The precondition of a phantom: one plane of the base at z = 4 whose box
  // covers the block's footprint, and its outline does not.
  const SurfaceProxy* wall_top = nullptr;
  for (const SurfaceProxy& o : scene.contacts().surfaces(0))
    if (o.kind == SurfaceKind::Plane && std::abs(o.location.z() - 4) < 1e-9 && o.axis.z() > 0.5) wall_top = &o;
  ASSERT_NE(wall_top, nullptr);
  EXPECT_TRUE(wall_top->box.contains(Vec3(12.5, 12.5, 4)));

  // Over the open corner, 0.3 mm above the wall's plane and 2.3 mm above the
  // surface below it: no contact (by boxes: a face on the wall, 0.3 mm off).
  EXPECT_TRUE(contacts_at(scene, Vec3::Zero()).empty());
  JointState joint;
  EXPECT_FALSE(scene.finder().capture(Pose::Identity(), joint));

  // Lowered 2 mm, 0.3 mm above the real surface: one face on a plane.
  auto low = contacts_at(scene, Vec3(0, 0, -2));
  ASSERT_EQ(low.size(), 1u);
  EXPECT_EQ(low[0].type, ContactType::PLF);
  EXPECT_NEAR(low[0].distance, 0.3, 1e-9);
  ASSERT_TRUE(scene.finder().capture(shift(Vec3(0, 0, -2)), joint));
  EXPECT_EQ(joint.kind, JointKind::Planar);
  EXPECT_NEAR(joint.point.z(), 2.0, 1e-9);

  // Over the wall's arm (x 10..15, y 0..5), 0.3 mm above its top: one face on it.
  auto arm = contacts_at(scene, Vec3(0, -10, 0));
  ASSERT_EQ(arm.size(), 1u);
  EXPECT_EQ(arm[0].type, ContactType::PLF);
  EXPECT_NEAR(arm[0].distance, 0.3, 1e-9);
  // Half over the arm's edge (y -2.5 .. 2.5 over the edge at y = 5 - ... ): the
  // outlines cross; over nothing but the arm's box corner: none.
  EXPECT_EQ(contacts_at(scene, Vec3(0, -7.5, 0)).size(), 1u);   // block y 2.5 .. 7.5: half on the arm
  EXPECT_EQ(contacts_at(scene, Vec3(0, -4.9, 0)).size(), 0u);   // block y 5.1 .. 10.1: beside it
}

TEST(RealtimeContacts, OutlinesOverlapCrossingRectangles) {
  // Two rectangles in a cross: no vertex of one inside the other, edges cross.
  SurfaceProxy a, b;
  a.kind = b.kind = SurfaceKind::Plane;
  a.axis = Vec3(0, 0, -1);
  b.axis = Vec3(0, 0, 1);
  a.loops = {{Vec3(-5, -1, 0), Vec3(5, -1, 0), Vec3(5, 1, 0), Vec3(-5, 1, 0)}};
  b.loops = {{Vec3(-1, -5, 0), Vec3(1, -5, 0), Vec3(1, 5, 0), Vec3(-1, 5, 0)}};
  EXPECT_TRUE(outlines_overlap(a, Pose::Identity(), b));
  EXPECT_FALSE(outlines_overlap(a, shift(Vec3(0, 7, 0)), b));
  // A disc inside a hole does not overlap the face around the hole.
  SurfaceProxy face;
  face.kind = SurfaceKind::Plane;
  face.axis = Vec3(0, 0, 1);
  std::vector<Vec3> outer = {Vec3(-10, -10, 0), Vec3(10, -10, 0), Vec3(10, 10, 0), Vec3(-10, 10, 0)}, hole, disc;
  for (int i = 0; i < 64; ++i) {
    const double t = -2 * kPi * i / 64;  // the hole runs clockwise
    hole.push_back(Vec3(3 * std::cos(t), 3 * std::sin(t), 0));
    disc.push_back(Vec3(2 * std::cos(-t), 2 * std::sin(-t), 0));
  }
  face.loops = {outer, hole};
  SurfaceProxy small;
  small.kind = SurfaceKind::Plane;
  small.axis = Vec3(0, 0, -1);
  small.loops = {disc};
  EXPECT_FALSE(outlines_overlap(small, Pose::Identity(), face));
  EXPECT_TRUE(outlines_overlap(small, shift(Vec3(2.5, 0, 0)), face));  // reaches past the hole's edge
}

namespace {

// A 40 x 40 x 10 housing with an 8 mm bore and a 45-degree countersink (radius
// 8 at z = 9.6 to 8.4 at z = 10; its apex at z = 1.6). Two moving parts with a
// 45-degree cone whose apex is there too: a shaft of radius 4 with a chamfer
// (radius 3.6 at z = 5.2 to 4 at z = 5.6: same angle and apex, another band:
// two chamfers, no seat), and a plug whose cone (7.95 at z = 9.55 to 8.4 at
// z = 10) lies on the countersink (a seat).
struct Chamfers {
  Assembly shaft, plug;
  std::unique_ptr<TrialScene> shaft_scene, plug_scene;
};
Chamfers& chamfer_scenes() {
  static Chamfers c = [] {
    Chamfers out;
    TopoDS_Shape housing = BRepPrimAPI_MakeBox(gp_Pnt(-20, -20, 0), 40, 40, 10).Shape();
    housing = BRepAlgoAPI_Cut(housing, BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, -1), gp_Dir(0, 0, 1)), 8, 12).Shape()).Shape();
    housing = BRepAlgoAPI_Cut(housing, BRepPrimAPI_MakeCone(gp_Ax2(gp_Pnt(0, 0, 9.6), gp_Dir(0, 0, 1)), 8, 8.9, 0.9).Shape()).Shape();
    TopoDS_Shape shaft = BRepPrimAPI_MakeCone(gp_Ax2(gp_Pnt(0, 0, 5.2), gp_Dir(0, 0, 1)), 3.6, 4.0, 0.4).Shape();
    shaft = unified(BRepAlgoAPI_Fuse(shaft, BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, 5.6), gp_Dir(0, 0, 1)), 4, 10).Shape()).Shape());
    TopoDS_Shape plug = BRepPrimAPI_MakeCone(gp_Ax2(gp_Pnt(0, 0, 9.55), gp_Dir(0, 0, 1)), 7.95, 8.4, 0.45).Shape();
    plug = unified(BRepAlgoAPI_Fuse(plug, BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, 10), gp_Dir(0, 0, 1)), 8.4, 4).Shape()).Shape());
    out.shaft = contactcore::testing::make_assembly({{"Housing", housing}, {"Shaft", shaft}});
    out.plug = contactcore::testing::make_assembly({{"Housing", housing}, {"Plug", plug}});
    out.shaft_scene = scene_of(out.shaft, "Shaft");
    out.plug_scene = scene_of(out.plug, "Plug");
    return out;
  }();
  return c;
}

}  // namespace

TEST(RealtimeContacts, ConesNeedABandInCommonNotJustAngleAndApex) {
  Chamfers& c = chamfer_scenes();
  // The shaft's chamfer and the countersink: 45 degrees both, one apex, bands
  // at radii 3.6..4 and 8..8.4: no contact, no seat, anywhere along the axis.
  for (double z = -1.0; z <= 1.0 + 1e-9; z += 0.1) {
    for (const LiveContact& l : contacts_at(*c.shaft_scene, Vec3(0, 0, z))) EXPECT_NE(l.type, ContactType::CJU) << z;
    JointState joint;
    EXPECT_FALSE(c.shaft_scene->finder().capture(shift(Vec3(0, 0, z)), joint)) << "a seat from two chamfers at z " << z;
  }
  // The plug's cone lies on the countersink: one CJU (and no face on the
  // housing's top: the plug's bottom disc, 0.45 mm under it, is inside the hole).
  auto seated = contacts_at(*c.plug_scene, Vec3::Zero());
  ASSERT_EQ(seated.size(), 1u);
  EXPECT_EQ(seated[0].type, ContactType::CJU);
  EXPECT_NEAR(seated[0].distance, 0.0, 1e-9);
  JointState joint;
  ASSERT_TRUE(c.plug_scene->finder().capture(shift(Vec3(0, 0, 0.3)), joint));
  EXPECT_EQ(joint.contact_type, static_cast<int>(ContactType::CJU));
  ASSERT_GE(joint.stop_count, 1);
  // The seat stop: the plug may not go below its modelled placement.
  const Vec3 centre = c.plug_scene->centre();
  EXPECT_NEAR(joint.stops[0].normal.dot(centre) - joint.stops[0].limit, 0.0, 1e-9);
}

namespace {

// A 20 mm block with a through bore of radius 5.05, a pin of radius 5 (0.05 mm
// radial clearance) 5 mm into it, and a thinner pin of radius 4.8 (0.25 mm:
// not a fit, a loose hole).
struct ClearanceFit {
  Assembly fit, loose;
  std::unique_ptr<TrialScene> fit_scene, loose_scene;
};
ClearanceFit& clearance_scenes() {
  static ClearanceFit c = [] {
    ClearanceFit out;
    TopoDS_Shape block = BRepPrimAPI_MakeBox(gp_Pnt(-10, -10, 0), 20, 20, 20).Shape();
    block = BRepAlgoAPI_Cut(block, BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, -1), gp_Dir(0, 0, 1)), 5.05, 22).Shape()).Shape();
    const gp_Ax2 axis(gp_Pnt(0, 0, 15), gp_Dir(0, 0, 1));
    out.fit = contactcore::testing::make_assembly({{"Block", block}, {"Pin", BRepPrimAPI_MakeCylinder(axis, 5, 20).Shape()}});
    out.loose = contactcore::testing::make_assembly({{"Block", block}, {"Pin", BRepPrimAPI_MakeCylinder(axis, 4.8, 20).Shape()}});
    out.fit_scene = scene_of(out.fit, "Pin");
    out.loose_scene = scene_of(out.loose, "Pin");
    return out;
  }();
  return c;
}

}  // namespace

TEST(RealtimeContacts, ClearanceFitsUpToTheGap) {
  ClearanceFit& c = clearance_scenes();
  auto centred = contacts_at(*c.fit_scene, Vec3::Zero());
  ASSERT_EQ(centred.size(), 1u);
  EXPECT_EQ(centred[0].type, ContactType::CLJ);
  EXPECT_NEAR(centred[0].clearance, 0.05, 1e-9);
  EXPECT_NEAR(centred[0].distance, 0.0, 1e-9);
  // Against the bore's wall (0.05 off the axis) and tilted within the gap: still the fit.
  auto wall = contacts_at(*c.fit_scene, Vec3(0.05, 0, 0));
  ASSERT_EQ(wall.size(), 1u);
  EXPECT_NEAR(wall[0].distance, 0.05, 1e-9);
  // Off the axis by more than the gap and the capture distance: none.
  EXPECT_TRUE(contacts_at(*c.fit_scene, Vec3(0.56, 0, 0)).empty());
  EXPECT_EQ(contacts_at(*c.fit_scene, Vec3(0.54, 0, 0)).size(), 1u);
  // Captured on the bore's axis.
  JointState joint;
  ASSERT_TRUE(c.fit_scene->finder().capture(shift(Vec3(0.03, -0.02, 0)), joint));
  EXPECT_EQ(joint.kind, JointKind::Cylindrical);
  EXPECT_NEAR(joint.point.head<2>().norm(), 0.0, 1e-9);
  // 0.25 mm of clearance is a loose hole, not a fit.
  EXPECT_TRUE(contacts_at(*c.loose_scene, Vec3::Zero()).empty());
}

// The motor's Screw-1, seated on the Front-cover, then lifted along the
// normal of the face it sits on: from 0.6 mm (beyond the capture distance)
// to 3 mm up, no face of the screw is on any plane of the cover.
TEST(RealtimeContacts, MotorScrewLiftedOffTheCoverHasNoPhantomPlane) {
  const auto read = read_step(contactcore::testing::sample("motor.step"));
  ASSERT_TRUE(read.status.ok()) << read.status.describe();
  auto scene = scene_of(read.assembly, "Screw-1");
  ASSERT_NE(scene, nullptr);
  int cover = -1;
  for (std::size_t i = 0; i < scene->body_names().size(); ++i)
    if (scene->body_names()[i] == "Front-cover") cover = static_cast<int>(i);
  ASSERT_GE(cover, 0);
  const auto seated = contacts_at(*scene, Vec3::Zero());
  const LiveContact* face = nullptr;
  for (const LiveContact& l : seated)
    if (l.type == ContactType::PLF && l.body == cover && l.distance < 1e-6) face = &l;
  ASSERT_NE(face, nullptr) << "the head's underside on the cover";
  const Vec3 up = scene->contacts().surfaces(cover)[face->other_index].axis;  // the cover face's outward normal
  int phantoms = 0;
  for (double h = 0.6; h <= 3.0 + 1e-9; h += 0.05)
    for (const LiveContact& l : contacts_at(*scene, h * up))
      if (l.type == ContactType::PLF && l.body == cover) {
        ++phantoms;
        ADD_FAILURE() << "a face on the cover's plane at " << h << " mm up (distance " << l.distance << ")";
      }
  EXPECT_EQ(phantoms, 0);
}

namespace {

// The faces of partition `id` of `shape` (partitioned as TrialScene does), moved by `pose`.
TopoDS_Shape partition_faces(const TopoDS_Shape& shape, int id, const Pose& pose) {
  const ContactOptions defaults;
  Tolerances tol;
  EXPECT_TRUE(body_tolerances(shape, defaults.linear, defaults.angular, tol).ok());
  const BodyPartitions parts = partition_shape(shape, tol);
  BRep_Builder builder;
  TopoDS_Compound compound;
  builder.MakeCompound(compound);
  for (int f : parts.partitions.at(id).faces) builder.Add(compound, parts.faces[f - 1].face);
  gp_Trsf move;
  const Mat3 r = pose.linear();
  const Vec3 t = pose.translation();
  move.SetValues(r(0, 0), r(0, 1), r(0, 2), t.x(), r(1, 0), r(1, 1), r(1, 2), t.y(), r(2, 0), r(2, 1), r(2, 2), t.z());
  return BRepBuilderAPI_Transform(compound, move, true).Shape();
}

}  // namespace

// Issue 20's second phantom: the motor's Axis moved along its axis from 1 mm
// above to 1 mm below its seat: every conical contact the real-time contacts
// report (and every seat they capture) is between cones OCCT finds within the
// capture distance of each other, never two chamfers of one angle at radii 4
// and 8.4 some 2.38 mm apart.
TEST(RealtimeContacts, MotorAxisChamfersMakeNoPhantomSeat) {
  const auto read = read_step(contactcore::testing::sample("motor.step"));
  ASSERT_TRUE(read.status.ok()) << read.status.describe();
  auto scene = scene_of(read.assembly, "Axis");
  ASSERT_NE(scene, nullptr);
  const double capture = scene->contacts().tolerances().distance;
  int conical = 0;
  for (double z = -1.0; z <= 1.0 + 1e-9; z += 0.1) {
    const Pose pose = offset_pose(Vec3(0, 0, z), Vec3::Zero(), scene->centre());
    bool true_cone = false;  // a conical contact OCCT confirms at this pose
    for (const LiveContact& l : contacts_at(*scene, Vec3(0, 0, z))) {
      if (l.type != ContactType::CJU) continue;
      ++conical;
      const SurfaceProxy& m = scene->contacts().moving_surfaces()[l.moving_index];
      const SurfaceProxy& o = scene->contacts().surfaces(l.body)[l.other_index];
      BRepExtrema_DistShapeShape dist(partition_faces(read.assembly.bodies[scene->moving()].shape, m.partition, pose),
                                      partition_faces(read.assembly.bodies[l.body].shape, o.partition, Pose::Identity()));
      ASSERT_TRUE(dist.IsDone());
      EXPECT_LE(dist.Value(), capture + 1e-6) << "a conical contact between cones " << dist.Value()
                                              << " mm apart at z " << z;
      true_cone = true_cone || dist.Value() <= capture + 1e-6;
    }
    JointState joint;
    if (scene->finder().capture(pose, joint) && joint.contact_type == static_cast<int>(ContactType::CJU) && !true_cone)
      ADD_FAILURE() << "a conical seat captures the Axis at z " << z;
  }
  std::printf("[ measured ] %d conical contacts checked along the Axis' travel\n", conical);
}
