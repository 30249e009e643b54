// Closed-form contacts between analytic partitions (analytic_distance.h),
// judged against OCCT's BRepExtrema_DistShapeShape on the partitions' faces:
// hand-placed cases (a pin in a bore with clearance, a shaft on a plane, a
// ball on a plane, a plug on its conical seat) and poses of the motor's Axis.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <BRepAlgoAPI_Common.hxx>
#include <BRepAlgoAPI_Cut.hxx>
#include <BRepAlgoAPI_Fuse.hxx>
#include <BRepGProp.hxx>
#include <GProp_GProps.hxx>
#include <Precision.hxx>
#include <BRepBuilderAPI_MakeVertex.hxx>
#include <BRepBuilderAPI_Transform.hxx>
#include <BRepExtrema_DistShapeShape.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCone.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakePrism.hxx>
#include <BRepBuilderAPI_MakePolygon.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <BRep_Builder.hxx>
#include <TopoDS_Compound.hxx>
#include <gp_Ax2.hxx>
#include <gp_Trsf.hxx>

#include "contactcore/bodies/bodies.h"
#include "contactcore/common/angles.h"
#include "contactcore/simulation/analytic_distance.h"
#include "test_helpers.h"

using namespace contactcore;
using Eigen::Vector3d;
using contactcore::testing::Partitioned;
using contactcore::testing::partitioned;
using contactcore::testing::plane_facing;

namespace {

// The faces of a partition as one compound (what OCCT measures).
TopoDS_Shape faces_of(const BodyPartitions& parts, const Partition& p) {
  BRep_Builder builder;
  TopoDS_Compound compound;
  builder.MakeCompound(compound);
  for (int f : p.faces) builder.Add(compound, parts.faces[f - 1].face);
  return compound;
}

const Partition& find(const BodyPartitions& parts, SurfaceKind kind, MaterialSide side, double radius = -1) {
  for (const Partition& p : parts.partitions)
    if (p.params.kind == kind && p.side == side && (radius < 0 || std::abs(p.params.radius - radius) < 1e-6)) return p;
  ADD_FAILURE() << "no such partition";
  return parts.partitions.front();
}


Eigen::Isometry3d isometry(const gp_Trsf& t) {
  Eigen::Isometry3d m = Eigen::Isometry3d::Identity();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) m.linear()(r, c) = t.Value(r + 1, c + 1);
    m.translation()[r] = t.Value(r + 1, 4);
  }
  return m;
}

struct Measured {
  bool handled = false;
  AnalyticContact analytic;
  double occt = 0;
  Vector3d occt_a{0, 0, 0}, occt_b{0, 0, 0};
  int occt_solutions = 0;
};

// Partition `pa` of `a` moved by `move` against partition `pb` of b: closed form and OCCT.
Measured measure(const Partitioned& a, const Partition& pa, const gp_Trsf& move, const Partitioned& b,
                 const Partition& pb) {
  Measured m;
  const AnalyticPatch patch_a = placed(analytic_patch(pa), isometry(move));
  const AnalyticPatch patch_b = analytic_patch(pb);
  m.handled = analytic_contact(patch_a, patch_b, m.analytic);
  const TopoDS_Shape moved = BRepBuilderAPI_Transform(faces_of(a.parts, pa), move, true).Shape();
  BRepExtrema_DistShapeShape dist(moved, faces_of(b.parts, pb));
  EXPECT_TRUE(dist.IsDone());
  m.occt = dist.Value();
  m.occt_solutions = dist.NbSolution();
  const gp_Pnt p1 = dist.PointOnShape1(1), p2 = dist.PointOnShape2(1);
  m.occt_a = Vector3d(p1.X(), p1.Y(), p1.Z());
  m.occt_b = Vector3d(p2.X(), p2.Y(), p2.Z());
  return m;
}

gp_Trsf translation(double x, double y, double z) {
  gp_Trsf t;
  t.SetTranslation(gp_Vec(x, y, z));
  return t;
}

// Distance of a point from a shape (OCCT): is the closed form's point on the face?
double off_shape(const Vector3d& p, const TopoDS_Shape& shape) {
  BRepExtrema_DistShapeShape dist(BRepBuilderAPI_MakeVertex(gp_Pnt(p.x(), p.y(), p.z())).Vertex(), shape);
  return dist.Value();
}

}  // namespace

// A pin of radius 5 in a bore of radius 5.05 (0.05 mm radial clearance),
// pushed off the axis: gap 0.05 - e on the side it was pushed to.
TEST(AnalyticDistance, PinInBoreWithClearanceMatchesOcct) {
  TopoDS_Shape block = BRepPrimAPI_MakeBox(gp_Pnt(-10, -10, 0), 20, 20, 20).Shape();
  block = BRepAlgoAPI_Cut(block, BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, -1), gp_Dir(0, 0, 1)), 5.05, 22).Shape())
              .Shape();
  const Partitioned bore = partitioned(block);
  const Partitioned pin = partitioned(BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, 5), gp_Dir(0, 0, 1)), 5, 25).Shape());
  const Partition& shaft = find(pin.parts, SurfaceKind::Cylinder, MaterialSide::Convex);
  const Partition& hole = find(bore.parts, SurfaceKind::Cylinder, MaterialSide::Concave);
  for (const Vector3d& offset : {Vector3d(0.02, 0.01, 0), Vector3d(-0.03, 0.0, 2.0), Vector3d(0, -0.049, -3)}) {
    const Measured m = measure(pin, shaft, translation(offset.x(), offset.y(), offset.z()), bore, hole);
    ASSERT_TRUE(m.handled);
    const double expected = 0.05 - offset.head<2>().norm();  // by hand
    EXPECT_NEAR(m.analytic.gap, expected, 1e-12);
    EXPECT_NEAR(m.analytic.gap, m.occt, 1e-6);
    // The contact's lateral position is unique (the side pushed to), its height is not.
    EXPECT_NEAR((m.analytic.point_a - m.occt_a).head<2>().norm(), 0.0, 1e-5);
    EXPECT_NEAR((m.analytic.point_b - m.occt_b).head<2>().norm(), 0.0, 1e-5);
    EXPECT_NEAR(off_shape(m.analytic.point_a, BRepBuilderAPI_Transform(faces_of(pin.parts, shaft),
                                                                      translation(offset.x(), offset.y(), offset.z()))
                                                  .Shape()),
                0.0, 1e-6);
    EXPECT_NEAR(off_shape(m.analytic.point_b, faces_of(bore.parts, hole)), 0.0, 1e-6);
    // The way out for the pin: back towards the bore's axis.
    EXPECT_NEAR(m.analytic.normal.dot(-Vector3d(offset.x(), offset.y(), 0).normalized()), 1.0, 1e-12);
  }
  // Pushed 0.08 into the wall: a signed overlap of 0.03 (OCCT says only "touching").
  const Measured in = measure(pin, shaft, translation(0.08, 0, 0), bore, hole);
  ASSERT_TRUE(in.handled);
  EXPECT_NEAR(in.analytic.gap, -0.03, 1e-12);
  EXPECT_NEAR(in.occt, 0.0, 1e-7);
  // Above the block: no band in common, the rims are closest: left to the meshes.
  EXPECT_FALSE(measure(pin, shaft, translation(0, 0, 20.5), bore, hole).handled);
}

// A shaft of radius 3 lying on a 20 x 20 face, 0.4 above it, then tilted by 5 degrees.
TEST(AnalyticDistance, CylinderOnAPlaneMatchesOcct) {
  const Partitioned base = partitioned(BRepPrimAPI_MakeBox(gp_Pnt(-10, -10, -5), 20, 20, 5).Shape());
  const Partitioned shaft =
      partitioned(BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(-6, 0, 3.4), gp_Dir(1, 0, 0)), 3, 12).Shape());
  const Partition& top = plane_facing(base.parts, gp_Dir(0, 0, 1));
  const Partition& side = find(shaft.parts, SurfaceKind::Cylinder, MaterialSide::Convex);
  const Measured flat = measure(shaft, side, gp_Trsf(), base, top);
  ASSERT_TRUE(flat.handled);
  EXPECT_NEAR(flat.analytic.gap, 0.4, 1e-12);
  EXPECT_NEAR(flat.occt, 0.4, 1e-7);
  EXPECT_NEAR(flat.analytic.point_a.z(), 0.4, 1e-12);
  EXPECT_NEAR(flat.analytic.point_b.z(), 0.0, 1e-12);
  EXPECT_NEAR(flat.analytic.normal.z(), 1.0, 1e-12);
  // Tilted 5 degrees down about y through the shaft's start and lifted 1: its far end is lowest, a unique point.
  gp_Trsf tilt;
  tilt.SetRotation(gp_Ax1(gp_Pnt(-6, 0, 3.4), gp_Dir(0, 1, 0)), 5 * kPi / 180);
  const Measured tilted = measure(shaft, side, translation(0, 0, 1) * tilt, base, top);
  ASSERT_TRUE(tilted.handled);
  const double by_hand = 4.4 - 12 * std::sin(5 * kPi / 180) - 3 * std::cos(5 * kPi / 180);
  EXPECT_NEAR(tilted.analytic.gap, by_hand, 1e-12);
  EXPECT_NEAR(tilted.analytic.gap, tilted.occt, 1e-6);
  EXPECT_NEAR((tilted.analytic.point_a - tilted.occt_a).norm(), 0.0, 1e-4);
  // Beyond the face's edge (the lowest line off the outline): not a closed form.
  EXPECT_FALSE(measure(shaft, side, translation(0, 14, 0), base, top).handled);
}

// A ball of radius 4 at (3, 2, 5) over the face z = 0: gap 1 at (3, 2, 1).
TEST(AnalyticDistance, SphereOnAPlaneMatchesOcct) {
  const Partitioned base = partitioned(BRepPrimAPI_MakeBox(gp_Pnt(-10, -10, -5), 20, 20, 5).Shape());
  const Partitioned ball = partitioned(BRepPrimAPI_MakeSphere(gp_Pnt(0, 0, 0), 4).Shape());
  const Partition& top = plane_facing(base.parts, gp_Dir(0, 0, 1));
  const Partition& sphere = find(ball.parts, SurfaceKind::Sphere, MaterialSide::Convex);
  const Measured m = measure(ball, sphere, translation(3, 2, 5), base, top);
  ASSERT_TRUE(m.handled);
  EXPECT_NEAR(m.analytic.gap, 1.0, 1e-12);
  EXPECT_NEAR(m.occt, 1.0, 1e-7);
  EXPECT_NEAR((m.analytic.point_a - Vector3d(3, 2, 1)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((m.analytic.point_a - m.occt_a).norm(), 0.0, 1e-5);
  EXPECT_NEAR((m.analytic.point_b - m.occt_b).norm(), 0.0, 1e-5);
  // The same from the plane's side: the normal turns round.
  AnalyticContact reverse;
  ASSERT_TRUE(analytic_contact(analytic_patch(top), placed(analytic_patch(sphere), isometry(translation(3, 2, 5))),
                               reverse));
  EXPECT_NEAR(reverse.gap, 1.0, 1e-12);
  EXPECT_NEAR(reverse.normal.z(), -1.0, 1e-12);
}

// Two shafts side by side (parallel, radii 2 and 3, axes 6 apart: gap 1), then
// crossed at right angles 7 apart (gap 2); their ends past each other: rims, not a closed form.
TEST(AnalyticDistance, ShaftsSideBySideMatchOcct) {
  const Partitioned one = partitioned(BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)), 2, 10).Shape());
  const Partitioned two = partitioned(BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(6, 0, 3), gp_Dir(0, 0, 1)), 3, 10).Shape());
  const Partition& a = find(one.parts, SurfaceKind::Cylinder, MaterialSide::Convex);
  const Partition& b = find(two.parts, SurfaceKind::Cylinder, MaterialSide::Convex);
  const Measured parallel = measure(one, a, gp_Trsf(), two, b);
  ASSERT_TRUE(parallel.handled);
  EXPECT_NEAR(parallel.analytic.gap, 1.0, 1e-12);
  EXPECT_NEAR(parallel.occt, 1.0, 1e-7);
  EXPECT_NEAR(parallel.analytic.normal.x(), -1.0, 1e-12);
  EXPECT_NEAR(parallel.analytic.point_a.x(), 2.0, 1e-12);
  EXPECT_NEAR(parallel.analytic.point_b.x(), 3.0, 1e-12);
  // Crossed: the first shaft turned to lie along y at height 8, x = -1: axes 7 apart at (-1, 0, 8) / (6, 0, 8).
  gp_Trsf cross;
  cross.SetRotation(gp_Ax1(gp_Pnt(0, 0, 0), gp_Dir(1, 0, 0)), -kPi / 2);
  gp_Trsf lift;
  lift.SetTranslation(gp_Vec(-1, -5, 8));
  const Measured crossed = measure(one, a, lift * cross, two, b);
  ASSERT_TRUE(crossed.handled);
  EXPECT_NEAR(crossed.analytic.gap, 2.0, 1e-12);
  EXPECT_NEAR(crossed.occt, 2.0, 1e-7);
  EXPECT_NEAR((crossed.analytic.point_a - crossed.occt_a).norm(), 0.0, 1e-5);
  EXPECT_NEAR((crossed.analytic.point_b - crossed.occt_b).norm(), 0.0, 1e-5);
  gp_Trsf past;
  past.SetTranslation(gp_Vec(-1, -20, 8));
  EXPECT_FALSE(measure(one, a, past * cross, two, b).handled);
}

// A 45-degree plug over its 45-degree countersink: lifted h, gap h sin 45;
// also pushed sideways by e, gap h sin 45 - e cos 45.
TEST(AnalyticDistance, ConeSeatMatchesOcct) {
  // The seat: a block with a cone cut from radius 2 at z = 0 to 8 at z = 6 (45 degrees).
  TopoDS_Shape block = BRepPrimAPI_MakeBox(gp_Pnt(-15, -15, -5), 30, 30, 11).Shape();
  block = BRepAlgoAPI_Cut(block, BRepPrimAPI_MakeCone(gp_Ax2(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)), 2, 8, 6).Shape()).Shape();
  block = BRepAlgoAPI_Cut(block, BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, -6), gp_Dir(0, 0, 1)), 2, 7).Shape()).Shape();
  const Partitioned seat = partitioned(block);
  // The plug: radius 3 at z = 1 to 6 at z = 4 (the same cone surface, a band inside the seat's).
  const Partitioned plug =
      partitioned(BRepPrimAPI_MakeCone(gp_Ax2(gp_Pnt(0, 0, 1), gp_Dir(0, 0, 1)), 3, 6, 3).Shape());
  const Partition& seat_cone = find(seat.parts, SurfaceKind::Cone, MaterialSide::Concave);
  const Partition& plug_cone = find(plug.parts, SurfaceKind::Cone, MaterialSide::Convex);
  const double s45 = std::sin(kPi / 4);
  for (const auto& [h, e] : {std::pair{0.5, 0.0}, std::pair{1.0, 0.3}, std::pair{2.0, 0.0}}) {
    const Measured m = measure(plug, plug_cone, translation(e, 0, h), seat, seat_cone);
    ASSERT_TRUE(m.handled) << h << " " << e;
    EXPECT_NEAR(m.analytic.gap, h * s45 - e * s45, 1e-9) << h << " " << e;
    EXPECT_NEAR(m.analytic.gap, m.occt, 1e-6) << h << " " << e;
    EXPECT_NEAR(m.analytic.normal.z(), s45, 1e-9);
  }
  // Two chamfers of one angle at radii 3.6..4 and 8..8.4 (one apex): no band in common, no seat.
  const Partitioned small =
      partitioned(BRepPrimAPI_MakeCone(gp_Ax2(gp_Pnt(0, 0, 1.6), gp_Dir(0, 0, 1)), 3.6, 4, 0.4).Shape());
  const Partitioned big_block = partitioned(BRepAlgoAPI_Cut(
      BRepPrimAPI_MakeBox(gp_Pnt(-15, -15, 0), 30, 30, 8.4).Shape(),
      BRepPrimAPI_MakeCone(gp_Ax2(gp_Pnt(0, 0, 8), gp_Dir(0, 0, 1)), 8, 8.4, 0.4).Shape()).Shape());
  AnalyticContact none;
  for (double z = -1; z <= 1 + 1e-9; z += 0.25)
    EXPECT_FALSE(analytic_contact(placed(analytic_patch(find(small.parts, SurfaceKind::Cone, MaterialSide::Convex)),
                                         isometry(translation(0, 0, z))),
                                  analytic_patch(find(big_block.parts, SurfaceKind::Cone, MaterialSide::Concave)), none))
        << z;
}

// The motor's Axis, lifted 0.3 mm and pushed 0.01 mm aside: every pair of its
// partitions with a neighbour's that has a closed form and a positive gap
// agrees with OCCT on the faces.
TEST(AnalyticDistance, MotorAxisPosesMatchOcct) {
  const auto read = read_step(contactcore::testing::sample("motor.step"));
  ASSERT_TRUE(read.status.ok()) << read.status.describe();
  std::vector<Partitioned> bodies;
  int axis = -1;
  for (std::size_t i = 0; i < read.assembly.bodies.size(); ++i) {
    bodies.push_back(partitioned(read.assembly.bodies[i].shape));
    if (read.assembly.bodies[i].name == "Axis") axis = static_cast<int>(i);
  }
  ASSERT_EQ(axis, 0);  // the STEP file's first product
  int compared = 0, handled_touching = 0;
  for (const gp_Trsf& move : {translation(0.01, 0, 0.3), translation(0, -0.004, 1.5)}) {
    for (std::size_t b = 0; b < bodies.size(); ++b) {
      if (static_cast<int>(b) == axis) continue;
      for (const Partition& pa : bodies[axis].parts.partitions)
        for (const Partition& pb : bodies[b].parts.partitions) {
          AnalyticContact c;
          const AnalyticPatch a = placed(analytic_patch(pa), isometry(move));
          if (!analytic_contact(a, analytic_patch(pb), c)) continue;
          if (c.gap > 2.0) continue;  // only near pairs: OCCT's time
          const Measured m = measure(bodies[axis], pa, move, bodies[b], pb);
          const bool planes = pa.params.kind == SurfaceKind::Plane && pb.params.kind == SurfaceKind::Plane;
          if (planes && c.gap < -1e-6) {  // parallel faces overlapping: OCCT gives their separation
            EXPECT_NEAR(m.occt, -c.gap, 1e-5) << read.assembly.bodies[b].name;
            ++compared;
            continue;
          }
          if (c.gap <= 1e-6) {
            ++handled_touching;
            EXPECT_NEAR(m.occt, 0.0, 1e-6) << read.assembly.bodies[b].name;
            continue;
          }
          ++compared;
          EXPECT_NEAR(c.gap, m.occt, 1e-5) << read.assembly.bodies[b].name << " partitions " << pa.id << " "
                                           << pb.id;
        }
    }
  }
  std::printf("[ measured ] %d pairs compared with OCCT, %d touching or overlapping\n", compared, handled_touching);
  // The poses are fixed (no randomness): 22 pairs with a positive gap, 14 touching or overlapping (the Axis in
  // its line-to-line bores, pushed aside). Before the annuli and the shaft through a face's hole (27 Nov):
  // 2 and 10; the 12 and 4 more are the Axis's shoulders against the bearings' and the seal's rings, and its
  // cylinders through their holes.
  // 22 and 14 before the round holes of any outline, the chamfers, the shafts beside bores and the ends on
  // faces (27 Nov, morning): the 8 and 16 more are the Axis through the rotors' faces (their holes split
  // between two faces, or among bolt holes), past the rotors' bolt holes, through the bearings' chamfers
  // and its chamfered end in Bearing-back's bore.
  EXPECT_EQ(compared, 30);
  EXPECT_EQ(handled_touching, 30);
}

// The motor's Axis's annular faces (its shoulders and ends) against every
// facing annular face of a neighbour within 6 mm (the bearings', the seal's,
// the rotors'), decided by their radii (AnalyticPatch::annuli): coincident
// circles no longer leave the pair to the meshes. Judged by OCCT on the
// partitions' faces: BRepExtrema's distance is the closed form's gap (the
// planes' gap where the annuli share area, the rims' distance where they do
// not), and on one plane the faces' Boolean common has area exactly where the
// closed form says they share some (concentric: pi (min outer^2 - max
// inner^2)). Tolerances: the outline circles are fitted within
// kCircleTolerance and OCCT's extrema converge to Precision::Confusion(), so
// distances agree within their sum, the closed form's points lie on the faces
// within it; areas within 1e-6 of their size (OCCT's Boolean on arcs).
TEST(AnalyticDistance, MotorAxisAnnuliMatchOcct) {
  const auto read = read_step(contactcore::testing::sample("motor.step"));
  ASSERT_TRUE(read.status.ok()) << read.status.describe();
  std::vector<Partitioned> bodies;
  for (const contactcore::Body& body : read.assembly.bodies) bodies.push_back(partitioned(body.shape));
  const int axis = 0;  // the STEP file's first product
  ASSERT_EQ(read.assembly.bodies[axis].name, "Axis");
  const double tolerance = Precision::Confusion() + kCircleTolerance;
  int pairs = 0, overlapping = 0, apart = 0, rims_touching = 0, coplanar_areas = 0, shared_areas = 0;
  for (std::size_t j = 0; j < bodies.size(); ++j) {
    if (static_cast<int>(j) == axis) continue;
    for (const Partition& pa : bodies[axis].parts.partitions)
      for (const Partition& pb : bodies[j].parts.partitions) {
        const AnalyticPatch a = analytic_patch(pa), b = analytic_patch(pb);
        if (a.kind != SurfaceKind::Plane || b.kind != SurfaceKind::Plane || a.annuli.empty() || b.annuli.empty())
          continue;
        const double gap = (a.location - b.location).dot(b.axis);
        if (a.axis.dot(b.axis) > -1 + 1e-9 || gap < 0 || gap > 6) continue;  // facing, within 6 mm
        ++pairs;
        const std::string name = read.assembly.bodies[j].name + " p" + std::to_string(pa.id) + "/p" +
                                 std::to_string(pb.id);
        std::printf("[ annuli ] Axis / %s: gap %.4f, %zu / %zu annuli, outer %.4f / %.4f, inner %.4f / %.4f\n",
                    name.c_str(), gap, a.annuli.size(), b.annuli.size(), a.annuli[0].outer, b.annuli[0].outer,
                    a.annuli[0].inner, b.annuli[0].inner);
        const TopoDS_Shape face_b = faces_of(bodies[j].parts, pb);
        // Along the axis (z: the planes' normal) and across it; brought onto one plane (-gap along b's
        // normal), there pushed 0.3 and 1 mm across.
        const Vector3d onto = -gap * b.axis;
        for (const Vector3d& move : {Vector3d(0, 0, 0), Vector3d(0, 0, 0.02), Vector3d(0.3, 0, 0),
                                     Vector3d(0.3, 0.1, -0.02), Vector3d(0, 0, 5), Vector3d(40, 0, 0.5), onto,
                                     Vector3d(onto + Vector3d(0.3, 0, 0)), Vector3d(onto + Vector3d(1.0, 0, 0))}) {
          const Measured m = measure(bodies[axis], pa, translation(move.x(), move.y(), move.z()), bodies[j], pb);
          const TopoDS_Shape moved_a =
              BRepBuilderAPI_Transform(faces_of(bodies[axis].parts, pa), translation(move.x(), move.y(), move.z()), true)
                  .Shape();
          const AnalyticContact& c = m.analytic;
          const double plane_gap = gap + move.dot(b.axis);
          const bool coplanar = std::abs(plane_gap) < 1e-9;
          double common_area = 0;
          if (coplanar) {
            GProp_GProps props;
            BRepGProp::SurfaceProperties(BRepAlgoAPI_Common(moved_a, face_b).Shape(), props);
            common_area = props.Mass();
          }
          if (!m.handled) {
            // Left to the meshes only where the rims touch on one plane: OCCT finds them touching, no area.
            ++rims_touching;
            EXPECT_TRUE(coplanar) << name << " moved " << move.transpose();
            EXPECT_NEAR(m.occt, 0.0, tolerance) << name;
            EXPECT_LT(common_area, 1e-6) << name;
            continue;
          }
          // Along the normal: the planes' gap (sharing area, or rims touching in the plane); else the
          // rims' closest pair, apart in the plane too.
          const bool along_normal = (c.normal - (plane_gap >= 0 ? 1.0 : -1.0) * b.axis).norm() < 1e-12 &&
                                    std::abs(c.gap - std::abs(plane_gap)) < 1e-12;
          EXPECT_NEAR(c.gap, m.occt, tolerance) << name << " moved " << move.transpose();
          EXPECT_NEAR(off_shape(c.point_a, moved_a), 0.0, tolerance) << name;
          EXPECT_NEAR(off_shape(c.point_b, face_b), 0.0, tolerance) << name;
          EXPECT_NEAR((c.point_a - c.point_b - c.gap * c.normal).norm(), 0.0, 1e-12) << name;
          if (along_normal) {
            ++overlapping;
          } else {
            ++apart;
            EXPECT_GT(c.gap, std::abs(plane_gap)) << name;
          }
          if (coplanar) {
            ++coplanar_areas;
            // On one plane the closed form answers a shared area (gap 0) or rims apart (gap > 0).
            if (c.gap < 1e-9) {
              ++shared_areas;
              EXPECT_GT(common_area, 1e-3) << name << " moved " << move.transpose();
              if (move.head<2>().norm() == 0 && a.annuli.size() == 1 && b.annuli.size() == 1) {
                const double outer = std::min(a.annuli[0].outer, b.annuli[0].outer),
                             inner = std::max(a.annuli[0].inner, b.annuli[0].inner);
                EXPECT_NEAR(common_area, kPi * (outer * outer - inner * inner), 1e-6 * common_area) << name;
              }
            } else {
              EXPECT_LT(common_area, 1e-6) << name << " moved " << move.transpose();
            }
          }
        }
      }
  }
  std::printf("[ measured ] %d annulus pairs: %d poses answered along the normal, %d apart in the plane too, %d on "
              "one plane (%d sharing area), %d rims touching (the meshes)\n",
              pairs, overlapping, apart, coplanar_areas, shared_areas, rims_touching);
  // The shoulder (3.6..4) facing Bearing-back's three rings (4.3..5.2, 5.2..6.8, 6.8..7.7), 2.1 to 2.4 mm
  // away; 9 poses each. On one plane pushed 0.3 mm it touches the inner ring's rim (the meshes), pushed
  // 1 mm it shares area with the inner ring.
  EXPECT_EQ(pairs, 3);
  EXPECT_EQ(overlapping + apart + rims_touching, 27);
  EXPECT_EQ(rims_touching, 1);
  EXPECT_EQ(shared_areas, 1);
  EXPECT_EQ(coplanar_areas, 8);
}

namespace {
// A tube (inner 0: a rod) on the z axis from z0 to z1, its axis moved by (x, 0).
TopoDS_Shape tube(double inner, double outer, double z0, double z1, double x = 0) {
  TopoDS_Shape rod = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(x, 0, z0), gp_Dir(0, 0, 1)), outer, z1 - z0).Shape();
  if (inner <= 0) return rod;
  return BRepAlgoAPI_Cut(rod, BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(x, 0, z0 - 1), gp_Dir(0, 0, 1)), inner,
                                                       z1 - z0 + 2).Shape())
      .Shape();
}
Eigen::Isometry3d shifted_by(double x, double y, double z) {
  Eigen::Isometry3d m = Eigen::Isometry3d::Identity();
  m.translation() = Vector3d(x, y, z);
  return m;
}
double radial(const Vector3d& p, double cx = 0) { return std::hypot(p.x() - cx, p.y()); }
}  // namespace

// Plane outlines made of circles become exact annuli (AnalyticPatch::annuli):
// a tube's end face (inner 4, outer 6), a rod's (a disk of 2); not a
// hexagon's (its vertices on a circle, its chords straight) nor a plate with
// a hole off its outer circle's centre.
TEST(AnalyticDistance, CircularOutlinesBecomeAnnuli) {
  const Partitioned t = partitioned(tube(4, 6, 0, 5)), rod = partitioned(tube(0, 2, 0, 5));
  const AnalyticPatch end = analytic_patch(plane_facing(t.parts, gp_Dir(0, 0, 1)));
  ASSERT_EQ(end.annuli.size(), 1u);
  EXPECT_NEAR(end.annuli[0].inner, 4.0, kCircleTolerance);
  EXPECT_NEAR(end.annuli[0].outer, 6.0, kCircleTolerance);
  const Vector3d centre = end.location + end.annuli[0].cx * end.ref_dir + end.annuli[0].cy * end.axis.cross(end.ref_dir);
  EXPECT_NEAR(radial(centre), 0.0, kCircleTolerance);  // on the tube's axis
  const AnalyticPatch disk = analytic_patch(plane_facing(rod.parts, gp_Dir(0, 0, -1)));
  ASSERT_EQ(disk.annuli.size(), 1u);
  EXPECT_EQ(disk.annuli[0].inner, 0.0);
  EXPECT_NEAR(disk.annuli[0].outer, 2.0, kCircleTolerance);
  BRepBuilderAPI_MakePolygon hexagon;
  for (int k = 0; k < 6; ++k) hexagon.Add(gp_Pnt(3 * std::cos(k * kPi / 3), 3 * std::sin(k * kPi / 3), 0));
  hexagon.Close();
  const Partitioned prism =
      partitioned(BRepPrimAPI_MakePrism(BRepBuilderAPI_MakeFace(hexagon.Wire()).Face(), gp_Vec(0, 0, 2)).Shape());
  EXPECT_TRUE(analytic_patch(plane_facing(prism.parts, gp_Dir(0, 0, 1))).annuli.empty());
  const Partitioned plate = partitioned(BRepAlgoAPI_Cut(tube(0, 10, 0, 2), tube(0, 2, -1, 3, 5)).Shape());
  const AnalyticPatch holed = analytic_patch(plane_facing(plate.parts, gp_Dir(0, 0, 1)));
  EXPECT_EQ(holed.loops.size(), 2u);
  EXPECT_TRUE(holed.annuli.empty());
}

// Facing annular faces decided by their radii, by hand: a tube (4..6) on a
// tube (4..7) shares the band 4..6 (its middle, radius 5, is the contact),
// lifted h: gap h; a shoulder (3.6..4) on the bore's face (4..7) only touches
// its rim on one plane (left to the meshes), lifted 0.5 it is 0.5 above that
// rim, sunk 0.5 into the bore 0.5 below it; pushed 0.3 sideways, lifted 0.5, it
// shares the band 4..4.3 about the bore's axis: the contact 4.15 from that
// axis and (law of cosines) 3.925 from its own. A rod (r 3) in the tube's hole
// is 1 from its rim in the plane: lifted 0.2, sqrt(1.04) apart; two rods of 2,
// 5 apart, lifted 0.5: sqrt(1 + 0.25) between their rims along x.
TEST(AnalyticDistance, AnnuliDecideCoincidentCircles) {
  const Partitioned lower = partitioned(tube(4, 7, -5, 0)), upper = partitioned(tube(4, 6, 0, 5)),
                    shoulder = partitioned(tube(3.6, 4, 0, 5)), rod3 = partitioned(tube(0, 3, 0, 5)),
                    rod2 = partitioned(tube(0, 2, 0, 5)), base2 = partitioned(tube(0, 2, -5, 0));
  const AnalyticPatch seat = analytic_patch(plane_facing(lower.parts, gp_Dir(0, 0, 1)));
  const auto bottom = [](const Partitioned& p) { return analytic_patch(plane_facing(p.parts, gp_Dir(0, 0, -1))); };
  AnalyticContact c;
  ASSERT_TRUE(analytic_contact(bottom(upper), seat, c));
  EXPECT_NEAR(c.gap, 0.0, 1e-12);
  EXPECT_NEAR((c.normal - Vector3d(0, 0, 1)).norm(), 0.0, 1e-12);
  EXPECT_NEAR(radial(c.point_b), 5.0, 1e-9);
  ASSERT_TRUE(analytic_contact(placed(bottom(upper), shifted_by(0, 0, 0.25)), seat, c));
  EXPECT_NEAR(c.gap, 0.25, 1e-12);
  EXPECT_NEAR(c.point_a.z() - c.point_b.z(), 0.25, 1e-12);

  EXPECT_FALSE(analytic_contact(bottom(shoulder), seat, c)) << "rims touching on one plane: gap " << c.gap;
  ASSERT_TRUE(analytic_contact(placed(bottom(shoulder), shifted_by(0, 0, 0.5)), seat, c));
  EXPECT_NEAR(c.gap, 0.5, 1e-12);
  EXPECT_NEAR((c.normal - Vector3d(0, 0, 1)).norm(), 0.0, 1e-12);
  EXPECT_NEAR(radial(c.point_b), 4.0, 1e-9);
  EXPECT_NEAR(radial(c.point_a), 4.0, 1e-9);
  ASSERT_TRUE(analytic_contact(placed(bottom(shoulder), shifted_by(0, 0, -0.5)), seat, c));
  EXPECT_NEAR(c.gap, 0.5, 1e-12);
  EXPECT_NEAR((c.normal - Vector3d(0, 0, -1)).norm(), 0.0, 1e-12);
  ASSERT_TRUE(analytic_contact(placed(bottom(shoulder), shifted_by(0.3, 0, 0.5)), seat, c));
  EXPECT_NEAR(c.gap, 0.5, 1e-12);
  EXPECT_NEAR((c.normal - Vector3d(0, 0, 1)).norm(), 0.0, 1e-12);
  EXPECT_NEAR(radial(c.point_b), 4.15, 1e-9);
  EXPECT_NEAR(radial(c.point_a, 0.3), 3.925, 1e-9);

  ASSERT_TRUE(analytic_contact(placed(bottom(rod3), shifted_by(0, 0, 0.2)), seat, c));
  EXPECT_NEAR(c.gap, std::sqrt(1.04), 1e-12);
  EXPECT_NEAR(radial(c.point_a), 3.0, 1e-9);
  EXPECT_NEAR(radial(c.point_b), 4.0, 1e-9);
  EXPECT_NEAR(c.normal.z(), 0.2 / std::sqrt(1.04), 1e-12);
  const AnalyticPatch base = analytic_patch(plane_facing(base2.parts, gp_Dir(0, 0, 1)));
  ASSERT_TRUE(analytic_contact(placed(bottom(rod2), shifted_by(5, 0, 0.5)), base, c));
  EXPECT_NEAR(c.gap, std::sqrt(1.25), 1e-12);
  EXPECT_NEAR((c.normal - Vector3d(1, 0, 0.5) / std::sqrt(1.25)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((c.point_b - Vector3d(2, 0, 0)).norm(), 0.0, 1e-9);
  EXPECT_NEAR((c.point_a - Vector3d(3, 0, 0.5)).norm(), 0.0, 1e-9);
}

// A shaft of radius 4 through a plate's hole of 4.05 (the face an annulus 4.05
// .. 10), pushed e off the hole's axis: the shaft's side is 0.05 - e from the
// hole's rim at the face (OCCT on the faces: the cylinder and the annulus; 0
// once they cross), on the side pushed to; tilted 0.01 rad the closed form is
// a lower bound, within R (1 - cos) below OCCT's. A shaft ending above the face
// (its rim, not its side, nearest) or through the plate's material: no closed
// form here.
TEST(AnalyticDistance, ShaftThroughAFaceHoleMatchesOcct) {
  const Partitioned plate = partitioned(tube(4.05, 10, -5, 0)), rod = partitioned(tube(0, 4, -20, 20));
  const Partition& face = plane_facing(plate.parts, gp_Dir(0, 0, 1));
  const Partition& side = find(rod.parts, SurfaceKind::Cylinder, MaterialSide::Convex);
  int compared = 0;
  for (double e : {0.0, 0.02, 0.049, 0.07})
    for (double turn = 0; turn < 6.28; turn += 1.3) {
      const Vector3d u(std::cos(turn), std::sin(turn), 0);
      const Measured m = measure(rod, side, translation(e * u.x(), e * u.y(), 0), plate, face);
      ASSERT_TRUE(m.handled) << e << " " << turn;
      EXPECT_NEAR(m.analytic.gap, 0.05 - e, 1e-12);
      EXPECT_NEAR(m.occt, std::max(0.0, 0.05 - e), 1e-6) << e << " " << turn;
      if (e > 0) EXPECT_NEAR((m.analytic.normal + u).norm(), 0.0, 1e-12);
      if (e > 0 && e < 0.05) {  // one closest pair (concentric: a whole circle of them)
        EXPECT_NEAR((m.analytic.point_a - m.occt_a).norm(), 0.0, 1e-5) << e << " " << turn;
        EXPECT_NEAR((m.analytic.point_b - m.occt_b).norm(), 0.0, 1e-5) << e << " " << turn;
      }
      ++compared;
    }
  EXPECT_EQ(compared, 20);
  gp_Trsf tilt;
  tilt.SetRotation(gp_Ax1(gp_Pnt(0, 0, 0), gp_Dir(1, 0, 0)), 0.01);
  const Measured tilted = measure(rod, side, tilt, plate, face);
  ASSERT_TRUE(tilted.handled);
  EXPECT_LE(tilted.analytic.gap, tilted.occt + 1e-9);
  EXPECT_GE(tilted.analytic.gap, tilted.occt - 4.05 * (1 - std::cos(0.01)) - 1e-9);
  AnalyticContact c;
  const Partitioned above = partitioned(tube(0, 4, 1, 20)), beside = partitioned(tube(0, 1, -20, 20, 7));
  EXPECT_FALSE(analytic_contact(analytic_patch(find(above.parts, SurfaceKind::Cylinder, MaterialSide::Convex)),
                                analytic_patch(face), c));
  EXPECT_FALSE(analytic_contact(analytic_patch(find(beside.parts, SurfaceKind::Cylinder, MaterialSide::Convex)),
                                analytic_patch(face), c));
}

namespace {
// A 20 x 20 x 5 plate under z = 0 (two 10 x 20 halves fused when `halves`: its faces split
// along x = 0) with a hole of radius `hole` at the origin and four of radius 1 at (+-7, +-7).
TopoDS_Shape plate_with_holes(double hole, bool halves) {
  TopoDS_Shape plate = BRepPrimAPI_MakeBox(gp_Pnt(-10, -10, -5), 20, 20, 5).Shape();
  if (halves)
    plate = BRepAlgoAPI_Fuse(BRepPrimAPI_MakeBox(gp_Pnt(-10, -10, -5), 10, 20, 5).Shape(),
                             BRepPrimAPI_MakeBox(gp_Pnt(0, -10, -5), 10, 20, 5).Shape())
                .Shape();
  plate = BRepAlgoAPI_Cut(plate, BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, -6), gp_Dir(0, 0, 1)), hole, 7).Shape())
              .Shape();
  for (double x : {-7.0, 7.0})
    for (double y : {-7.0, 7.0})
      plate = BRepAlgoAPI_Cut(plate, BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(x, y, -6), gp_Dir(0, 0, 1)), 1, 7).Shape())
                  .Shape();
  return plate;
}

// `part` of `moving` pushed e off its axis towards each of `turns` (radians about z), against
// `other` of `fixed`: the closed form's gap is clearance - e (by hand), OCCT's max(0, that), its
// normal back towards the axis, and while apart its point on `fixed` (on_fixed) or on `moving` is
// OCCT's (1e-5), at height `rim_z` when given. Returns the poses compared.
int expect_pushed_gaps(const Partitioned& moving, const Partition& part, const Partitioned& fixed,
                       const Partition& other, double clearance, const std::vector<double>& offsets,
                       const std::vector<double>& turns, bool on_fixed, double rim_z = std::nan("")) {
  int compared = 0;
  for (double e : offsets)
    for (double turn : turns) {
      const Vector3d u(std::cos(turn), std::sin(turn), 0);
      const Measured m = measure(moving, part, translation(e * u.x(), e * u.y(), 0), fixed, other);
      EXPECT_TRUE(m.handled) << e << " " << turn;
      if (!m.handled) continue;
      EXPECT_NEAR(m.analytic.gap, clearance - e, 1e-12) << e << " " << turn;
      EXPECT_NEAR(m.occt, std::max(0.0, clearance - e), 1e-6) << e << " " << turn;
      const Vector3d& point = on_fixed ? m.analytic.point_b : m.analytic.point_a;
      const Vector3d& occt_point = on_fixed ? m.occt_b : m.occt_a;
      if (!std::isnan(rim_z)) EXPECT_NEAR(point.z(), rim_z, 1e-12);
      if (e > 0) EXPECT_NEAR((m.analytic.normal + u).norm(), 0.0, 1e-12);
      if (e > 0 && e < clearance) EXPECT_NEAR((point - occt_point).norm(), 0.0, 1e-5) << e << " " << turn;
      ++compared;
    }
  return compared;
}
}  // namespace

// A shaft of radius 4 through a square plate's hole of 4.05 among four bolt
// holes (no annuli: the outline is a square), and through the same plate made
// of two fused halves, its face two faces each holding half of the hole (the
// motor's Rotor-back): round holes (AnalyticPatch::round_holes), and pushed e
// off the axis the shaft is 0.05 - e from the rim, as OCCT measures.
TEST(AnalyticDistance, ShaftThroughARoundHoleOfAnyOutlineMatchesOcct) {
  const Partitioned rod = partitioned(tube(0, 4, -20, 20));
  const Partition& side = find(rod.parts, SurfaceKind::Cylinder, MaterialSide::Convex);
  int compared = 0;
  for (bool halves : {false, true}) {
    const Partitioned plate = partitioned(plate_with_holes(4.05, halves));
    const Partition& face = plane_facing(plate.parts, gp_Dir(0, 0, 1));
    EXPECT_EQ(face.faces.size(), halves ? 2u : 1u);
    const AnalyticPatch patch = analytic_patch(face);
    EXPECT_TRUE(patch.annuli.empty());
    ASSERT_EQ(patch.round_holes.size(), 5u);
    compared += expect_pushed_gaps(rod, side, plate, face, 0.05, {0.0, 0.02, 0.049, 0.07}, {0.2, 1.7, 3.2, 4.7, 6.2},
                                   true);
  }
  EXPECT_EQ(compared, 40);
}

// A shaft of radius 3.95 in a bore of 4 whose mouth has a 45-degree chamfer 0.3
// deep (a concave cone from radius 4 to 4.3): the chamfer's small rim is
// nearest, 0.05 - e from the shaft pushed e aside (OCCT on the cone's face);
// a shaft ending above the small rim, inside the chamfer: no closed form.
TEST(AnalyticDistance, ShaftThroughAChamferMatchesOcct) {
  TopoDS_Shape block = BRepPrimAPI_MakeBox(gp_Pnt(-10, -10, -10), 20, 20, 10).Shape();
  block = BRepAlgoAPI_Cut(block, BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, -11), gp_Dir(0, 0, 1)), 4, 12).Shape())
              .Shape();
  block = BRepAlgoAPI_Cut(block, BRepPrimAPI_MakeCone(gp_Ax2(gp_Pnt(0, 0, -0.3), gp_Dir(0, 0, 1)), 4, 4.6, 0.6).Shape())
              .Shape();
  const Partitioned bore = partitioned(block), rod = partitioned(tube(0, 3.95, -20, 20));
  const Partition& chamfer = find(bore.parts, SurfaceKind::Cone, MaterialSide::Concave);
  const Partition& side = find(rod.parts, SurfaceKind::Cylinder, MaterialSide::Convex);
  // On the small rim, z = -0.3.
  EXPECT_EQ(expect_pushed_gaps(rod, side, bore, chamfer, 0.05, {0.0, 0.03, 0.08}, {0.4, 2.4, 4.4}, true, -0.3), 9);
  AnalyticContact c;
  const Partitioned short_rod = partitioned(tube(0, 3.95, -0.1, 20));
  EXPECT_FALSE(analytic_contact(analytic_patch(find(short_rod.parts, SurfaceKind::Cylinder, MaterialSide::Convex)),
                                analytic_patch(chamfer), c));
}

// A shaft of radius 4 whose end has a 45-degree chamfer 0.3 long (a convex cone
// from radius 3.7 to 4), 3 mm down a bore of 4.05 and pushed e aside: the
// chamfer's large rim is nearest the wall, 0.05 - e (OCCT on the two faces);
// with that rim above the bore's mouth, no closed form.
TEST(AnalyticDistance, ChamferedEndInABoreMatchesOcct) {
  const TopoDS_Shape shaft =
      BRepAlgoAPI_Fuse(BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, -2.7), gp_Dir(0, 0, 1)), 4, 22.7).Shape(),
                       BRepPrimAPI_MakeCone(gp_Ax2(gp_Pnt(0, 0, -3), gp_Dir(0, 0, 1)), 3.7, 4, 0.3).Shape())
          .Shape();
  TopoDS_Shape block = BRepPrimAPI_MakeBox(gp_Pnt(-10, -10, -10), 20, 20, 10).Shape();
  block = BRepAlgoAPI_Cut(block, BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, -11), gp_Dir(0, 0, 1)), 4.05, 12).Shape())
              .Shape();
  const Partitioned rod = partitioned(shaft), bore = partitioned(block);
  const Partition& chamfer = find(rod.parts, SurfaceKind::Cone, MaterialSide::Convex);
  const Partition& wall = find(bore.parts, SurfaceKind::Cylinder, MaterialSide::Concave);
  // On the large rim, z = -2.7.
  EXPECT_EQ(expect_pushed_gaps(rod, chamfer, bore, wall, 0.05, {0.0, 0.03, 0.08}, {0.4, 2.4, 4.4}, false, -2.7), 9);
  EXPECT_FALSE(measure(rod, chamfer, translation(0, 0, 3.5), bore, wall).handled);
}

// A shaft of radius 4 beside a block's bolt hole of radius 1 whose axis is 5.5
// away (the Axis past a rotor's bolt holes): the hole's near wall is 0.5 - e
// from the shaft moved e towards it, as OCCT measures on the two faces; a
// shaft reaching into the hole's room: no closed form.
TEST(AnalyticDistance, ShaftBesideABoreMatchesOcct) {
  TopoDS_Shape block = BRepPrimAPI_MakeBox(gp_Pnt(-10, -10, -10), 20, 20, 10).Shape();
  block = BRepAlgoAPI_Cut(block, BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(5.5, 0, -11), gp_Dir(0, 0, 1)), 1, 12).Shape())
              .Shape();
  const Partitioned holed = partitioned(block), rod = partitioned(tube(0, 4, -20, 20));
  const Partition& hole = find(holed.parts, SurfaceKind::Cylinder, MaterialSide::Concave);
  const Partition& side = find(rod.parts, SurfaceKind::Cylinder, MaterialSide::Convex);
  for (double e : {0.0, 0.2, 0.45}) {
    const Measured m = measure(rod, side, translation(e, 0, 0), holed, hole);
    ASSERT_TRUE(m.handled) << e;
    EXPECT_NEAR(m.analytic.gap, 0.5 - e, 1e-12);
    EXPECT_NEAR(m.occt, 0.5 - e, 1e-6) << e;
    EXPECT_NEAR((m.analytic.normal - Vector3d(-1, 0, 0)).norm(), 0.0, 1e-12);
    EXPECT_NEAR(m.analytic.point_b.x(), 4.5, 1e-12);
  }
  EXPECT_FALSE(measure(rod, side, translation(0.6, 0, 0), holed, hole).handled);
}

// A screw's head (a cylinder of radius 2.75) standing h above a plate's face
// with its shank's hole of 1.5 among bolt holes, and a washer's underside (an
// annulus 1.5 .. 2.75) h above a plate's bore of 1.5, line to line: each is h
// from the face along the normal (OCCT on the faces), centred or e aside, and
// pressed 0.0005 in, -0.0005. A head as wide as the whole plate stands on
// nothing of it it could measure: no closed form.
TEST(AnalyticDistance, EndsOnAFaceMatchOcct) {
  const Partitioned plate = partitioned(plate_with_holes(1.5, false));
  const Partition& face = plane_facing(plate.parts, gp_Dir(0, 0, 1));
  TopoDS_Shape block = BRepPrimAPI_MakeBox(gp_Pnt(-10, -10, -10), 20, 20, 10).Shape();
  block = BRepAlgoAPI_Cut(block, BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, -11), gp_Dir(0, 0, 1)), 1.5, 12).Shape())
              .Shape();
  const Partitioned bored = partitioned(block);
  const Partition& bore = find(bored.parts, SurfaceKind::Cylinder, MaterialSide::Concave);
  const Partitioned head = partitioned(tube(0, 2.75, 0, 2.7)), washer = partitioned(tube(1.5, 2.75, 0, 1));
  const Partition& head_side = find(head.parts, SurfaceKind::Cylinder, MaterialSide::Convex);
  const Partition& underside = plane_facing(washer.parts, gp_Dir(0, 0, -1));
  int compared = 0;
  for (double h : {-0.0005, 0.0, 0.0005, 0.2})
    for (double e : {0.0, 0.004}) {
      const gp_Trsf move = translation(e, 0.5 * e, h);
      for (const Measured& m : {measure(head, head_side, move, plate, face), measure(washer, underside, move, bored, bore)}) {
        ASSERT_TRUE(m.handled) << h << " " << e;
        EXPECT_NEAR(m.analytic.gap, h, 1e-12) << h << " " << e;
        EXPECT_NEAR(m.occt, std::max(0.0, h), 1e-6) << h << " " << e;
        EXPECT_NEAR(std::abs(m.analytic.normal.z()), 1.0, 1e-12);
        ++compared;
      }
    }
  EXPECT_EQ(compared, 16);
  const Partitioned wide = partitioned(tube(0, 30, 0.0005, 3));
  AnalyticContact c;
  EXPECT_FALSE(analytic_contact(analytic_patch(find(wide.parts, SurfaceKind::Cylinder, MaterialSide::Convex)),
                                analytic_patch(face), c));
}

// Out of the caller's reach (AnalyticTolerances::reach), a pair is answered by
// a lower bound of its gap found before any outline test: two facing faces 5
// apart whose outlines miss each other in the plane (no closed form without a
// reach), a cylinder standing 3 above a face beside it. OCCT's distance is at
// least the bound; within the reach nothing changes.
TEST(AnalyticDistance, OutOfReachPairsAreAnsweredByABound) {
  const Partitioned low = partitioned(BRepPrimAPI_MakeBox(gp_Pnt(0, 0, -1), 10, 10, 1).Shape());
  const Partitioned high = partitioned(BRepPrimAPI_MakeBox(gp_Pnt(20, 0, 5), 10, 10, 1).Shape());
  const Partitioned post = partitioned(tube(0, 2, 3, 6, 40));
  const Partition& top = plane_facing(low.parts, gp_Dir(0, 0, 1));
  const Partition& bottom = plane_facing(high.parts, gp_Dir(0, 0, -1));
  const Partition& side = find(post.parts, SurfaceKind::Cylinder, MaterialSide::Convex);
  AnalyticTolerances near;
  near.reach = 0.2;
  for (const Partition* upper : {&bottom, &side}) {
    const Partitioned& body = upper == &bottom ? high : post;
    const Measured m = measure(body, *upper, gp_Trsf(), low, top);
    EXPECT_FALSE(m.handled);  // no reach: the outlines decide, and they miss
    AnalyticContact c;
    ASSERT_TRUE(analytic_contact(analytic_patch(*upper), analytic_patch(top), c, near));
    EXPECT_NEAR(c.gap, upper == &bottom ? 5.0 : 3.0, 1e-12);
    EXPECT_NEAR(c.normal.z(), 1.0, 1e-12);
    // OCCT, by hand: the faces' nearest edges 10 apart across and 5 up; the post's rim at (38, 0, 3)
    // and the face's corner (10, 0, 0).
    EXPECT_NEAR(m.occt, upper == &bottom ? std::hypot(10.0, 5.0) : std::hypot(28.0, 3.0), 1e-6);
  }
  // A shaft of radius 4 through a ring whose outer surface has radius 8, pushed 0.3 aside (nested: at
  // least 8 - 4 - 0.3 from it), and a shaft above the ring's bore, its end 2 over the bore's top
  // (axially apart): bounds at most OCCT's distances, and no closed form without a reach.
  const Partitioned ring = partitioned(tube(4.5, 8, -10, 0));
  const Partitioned through = partitioned(tube(0, 4, -20, 20)), above = partitioned(tube(0, 4, 2, 20));
  struct Case {
    const Partitioned& shaft;
    const Partition& other;
    double bound, occt;  // OCCT by hand: the nested bound is exact; above, the rim 2 up and 0.2 in
  };
  const Case cases[] = {
      {through, find(ring.parts, SurfaceKind::Cylinder, MaterialSide::Convex), 8 - 4 - 0.3, 8 - 4 - 0.3},
      {above, find(ring.parts, SurfaceKind::Cylinder, MaterialSide::Concave), 2.0, std::hypot(2.0, 0.2)}};
  for (const Case& k : cases) {
    const gp_Trsf aside = translation(0.3, 0, 0);
    const Partition& rod = find(k.shaft.parts, SurfaceKind::Cylinder, MaterialSide::Convex);
    const Measured m = measure(k.shaft, rod, aside, ring, k.other);
    EXPECT_FALSE(m.handled) << k.bound;
    AnalyticContact c;
    ASSERT_TRUE(analytic_contact(placed(analytic_patch(rod), isometry(aside)), analytic_patch(k.other), c, near));
    EXPECT_NEAR(c.gap, k.bound, 1e-12);
    EXPECT_NEAR(m.occt, k.occt, 1e-6);
  }
  // A rod's end face (a disk of 3.5) 5 down the ring's bore of 4.5, pushed 0.3 aside: the face lies
  // within 3.5 + 0.3 of the bore's axis, so at least 4.5 - 3.8 from its wall.
  const Partitioned rod_end = partitioned(tube(0, 3.5, -5, 20));
  const Partition& end_face = plane_facing(rod_end.parts, gp_Dir(0, 0, -1));
  const Partition& ring_bore = find(ring.parts, SurfaceKind::Cylinder, MaterialSide::Concave);
  const Measured inside = measure(rod_end, end_face, translation(0.3, 0, 0), ring, ring_bore);
  EXPECT_FALSE(inside.handled);
  AnalyticContact face_bound;
  ASSERT_TRUE(analytic_contact(placed(analytic_patch(end_face), isometry(translation(0.3, 0, 0))),
                               analytic_patch(ring_bore), face_bound, near));
  EXPECT_NEAR(face_bound.gap, 4.5 - 3.5 - 0.3, 1e-9);
  EXPECT_NEAR(inside.occt, 4.5 - 3.5 - 0.3, 1e-6);  // exact here: the disk's rim against the wall
  // Within the reach the outline test still decides.
  AnalyticTolerances far;
  far.reach = 10;
  AnalyticContact c;
  EXPECT_FALSE(analytic_contact(analytic_patch(bottom), analytic_patch(top), c, far));
}

// Pairs whose kinds have no closed form (a wall across a face or across a cylinder's axis, a cone
// beside a bore, two bores), out of reach: answered by a bound at most OCCT's distance, none
// without a reach. A wall behind a face's plane (where the face's body is), or a bore beside
// another bore, by less than any contact's depth is not answered: it may be sunk into that
// body, an overlap the meshes must see.
TEST(AnalyticDistance, PairsWithoutAClosedFormAreBoundedOutOfReach) {
  AnalyticTolerances near;
  near.reach = 0.2;
  const Partitioned low = partitioned(BRepPrimAPI_MakeBox(gp_Pnt(0, 0, -1), 10, 10, 1).Shape());
  const Partition& top = plane_facing(low.parts, gp_Dir(0, 0, 1));
  // A block's side (x = 4, y 2..4, 1 high) over the face, or behind it: the circle holding its
  // outline is centred at the wall's middle height with radius hypot(1, 0.5), which bounds its
  // lowest and highest points.
  const double circle = std::hypot(1.0, 0.5);
  struct Case {
    const char* name;
    double up;          // the wall's bottom over the face's plane
    bool answered;
    double bound, occt;  // OCCT by hand: the wall's bottom edge over the face, or under it
  };
  const Case walls[] = {{"over the face", 5, true, 5.5 - circle, 5.0},
                        {"deep behind it", -11, true, 10.5 - circle, 10.0},
                        {"just behind it", -1.3, false, 0, 0.3}};
  for (const Case& k : walls) {
    const Partitioned block = partitioned(BRepPrimAPI_MakeBox(gp_Pnt(2, 2, k.up), 2, 2, 1).Shape());
    const Partition& wall = plane_facing(block.parts, gp_Dir(1, 0, 0));
    const Measured m = measure(block, wall, gp_Trsf(), low, top);
    EXPECT_FALSE(m.handled) << k.name;
    EXPECT_NEAR(m.occt, k.occt, 1e-6) << k.name;
    AnalyticContact c;
    EXPECT_EQ(analytic_contact(analytic_patch(wall), analytic_patch(top), c, near), k.answered) << k.name;
    if (!k.answered) continue;
    EXPECT_NEAR(c.gap, k.bound, 1e-8) << k.name;  // the outline's arcs' swing allows 1e-9
    EXPECT_LE(c.gap, m.occt + 1e-9) << k.name;
  }
  // The wall x = 0 (y -1..1, z 5..6) above a ring's outer surface (radius 8, z -10..0): across its
  // axis, so neither side of the wall's plane; its extent along the axis misses the ring's by
  // 5.5 - hypot(1, 0.5). OCCT: the wall's corner (0, 1, 5) to the ring's top rim.
  const Partitioned ring = partitioned(tube(4.5, 8, -10, 0));
  const Partitioned crossing = partitioned(BRepPrimAPI_MakeBox(gp_Pnt(-1, -1, 5), 1, 2, 1).Shape());
  const Partition& crossing_wall = plane_facing(crossing.parts, gp_Dir(1, 0, 0));
  const Partition& outer = find(ring.parts, SurfaceKind::Cylinder, MaterialSide::Convex);
  const Measured above = measure(crossing, crossing_wall, gp_Trsf(), ring, outer);
  EXPECT_FALSE(above.handled);
  EXPECT_NEAR(above.occt, std::hypot(7.0, 5.0), 1e-6);
  AnalyticContact c;
  ASSERT_TRUE(analytic_contact(analytic_patch(crossing_wall), analytic_patch(outer), c, near));
  EXPECT_NEAR(c.gap, 5.5 - circle, 1e-8);
  EXPECT_NEAR(c.normal.z(), 1.0, 1e-12);
  // A frustum (radii 2 to 6 over z -10..-6, axis at x = 20) beside the ring's bore (4.5): their
  // cores 20 apart, at least 20 - 6 - 4.5 (exact: the frustum's wide rim faces the bore's wall).
  const Partitioned frustum =
      partitioned(BRepPrimAPI_MakeCone(gp_Ax2(gp_Pnt(20, 0, -10), gp_Dir(0, 0, 1)), 2, 6, 4).Shape());
  const Partition& cone = find(frustum.parts, SurfaceKind::Cone, MaterialSide::Convex);
  const Partition& bore = find(ring.parts, SurfaceKind::Cylinder, MaterialSide::Concave);
  const Measured beside = measure(frustum, cone, gp_Trsf(), ring, bore);
  EXPECT_FALSE(beside.handled);
  EXPECT_NEAR(beside.occt, 20 - 6 - 4.5, 1e-6);
  ASSERT_TRUE(analytic_contact(analytic_patch(cone), analytic_patch(bore), c, near));
  EXPECT_NEAR(c.gap, 20 - 6 - 4.5, 1e-9);
  EXPECT_NEAR(c.normal.x(), 1.0, 1e-12);
  // Two bores side by side (no closed form for two concave surfaces): 20 - 4.5 - 4.5 apart, a
  // bound; 0.3 apart, their bodies may overlap between them (each lies outside its bore): none.
  for (double x : {20.0, 9.3}) {
    const Partitioned other_ring = partitioned(tube(4.5, 8, -10, 0, x));
    const Partition& other_bore = find(other_ring.parts, SurfaceKind::Cylinder, MaterialSide::Concave);
    const Measured bores = measure(other_ring, other_bore, gp_Trsf(), ring, bore);
    EXPECT_FALSE(bores.handled) << x;
    EXPECT_NEAR(bores.occt, x - 9, 1e-6) << x;
    const bool bounded = analytic_contact(analytic_patch(other_bore), analytic_patch(bore), c, near);
    EXPECT_EQ(bounded, x > 10) << x;
    if (bounded) EXPECT_NEAR(c.gap, x - 9, 1e-9);
  }
}
