// body_inertia (the mechanism export's mass properties) against hand-derived values.
#include <gtest/gtest.h>

#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRep_Builder.hxx>
#include <TopoDS_Compound.hxx>
#include <cmath>
#include <gp_Ax1.hxx>
#include <gp_Ax2.hxx>
#include <gp_Trsf.hxx>

#include "contactcore/bodies/inertia.h"

using namespace contactcore;

TEST(Inertia, BoxAboutItsCentreIsVolumeTimesSidesSquaredOverTwelve) {
  // A 10 x 20 x 30 box with its corner at (1, 2, 3): V = 6000 mm^3, centre (6, 12, 18);
  // about it Ixx = V (20^2 + 30^2) / 12 = 650000, Iyy = V (10^2 + 30^2) / 12 = 500000,
  // Izz = V (10^2 + 20^2) / 12 = 250000, no products.
  Body body;
  body.name = "Box";
  body.shape = BRepPrimAPI_MakeBox(gp_Pnt(1, 2, 3), 10, 20, 30).Shape();
  const BodyInertia inertia = body_inertia(body);
  ASSERT_TRUE(inertia.status.ok()) << inertia.status.describe();
  EXPECT_NEAR(inertia.volume, 6000.0, 1e-6);
  EXPECT_NEAR(inertia.centre[0], 6.0, 1e-9);
  EXPECT_NEAR(inertia.centre[1], 12.0, 1e-9);
  EXPECT_NEAR(inertia.centre[2], 18.0, 1e-9);
  EXPECT_NEAR(inertia.tensor[0][0], 650000.0, 1e-4);
  EXPECT_NEAR(inertia.tensor[1][1], 500000.0, 1e-4);
  EXPECT_NEAR(inertia.tensor[2][2], 250000.0, 1e-4);
  EXPECT_NEAR(inertia.tensor[0][1], 0.0, 1e-4);
  EXPECT_NEAR(inertia.tensor[0][2], 0.0, 1e-4);
  EXPECT_NEAR(inertia.tensor[1][2], 0.0, 1e-4);
}

TEST(Inertia, RotatedPlacementRotatesTheTensorIntoGlobalAxes) {
  // The same box turned 90 degrees about z (through the origin): x and y swap, so
  // Ixx = 500000 and Iyy = 650000; a located shape (a placed instance) gives the global tensor.
  gp_Trsf turn;
  turn.SetRotation(gp_Ax1(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)), M_PI / 2);
  Body body;
  body.name = "Turned";
  body.shape = BRepPrimAPI_MakeBox(gp_Pnt(1, 2, 3), 10, 20, 30).Shape().Moved(TopLoc_Location(turn));
  const BodyInertia inertia = body_inertia(body);
  ASSERT_TRUE(inertia.status.ok());
  EXPECT_NEAR(inertia.centre[0], -12.0, 1e-9);
  EXPECT_NEAR(inertia.centre[1], 6.0, 1e-9);
  EXPECT_NEAR(inertia.tensor[0][0], 500000.0, 1e-4);
  EXPECT_NEAR(inertia.tensor[1][1], 650000.0, 1e-4);
  EXPECT_NEAR(inertia.tensor[2][2], 250000.0, 1e-4);
}

TEST(Inertia, CylinderAboutItsAxisIsHalfVolumeTimesRadiusSquared) {
  // r 5, h 20 along z: V = 500 pi, Izz = V r^2 / 2, Ixx = V (3 r^2 + h^2) / 12.
  Body body;
  body.name = "Pin";
  body.shape = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(20, 10, 10), gp_Dir(0, 0, 1)), 5, 20).Shape();
  const BodyInertia inertia = body_inertia(body);
  ASSERT_TRUE(inertia.status.ok());
  const double volume = 500 * M_PI;
  EXPECT_NEAR(inertia.volume, volume, 1e-6);
  EXPECT_NEAR(inertia.tensor[2][2], volume * 25 / 2, 1e-3);
  EXPECT_NEAR(inertia.tensor[0][0], volume * (75 + 400) / 12, 1e-3);
}

TEST(Inertia, ShapeWithoutVolumeIsAFailureNamingTheBody) {
  Body body;
  body.name = "Empty";
  TopoDS_Compound empty;
  BRep_Builder().MakeCompound(empty);
  body.shape = empty;
  const BodyInertia inertia = body_inertia(body);
  EXPECT_FALSE(inertia.status.ok());
  EXPECT_EQ(inertia.status.body, "Empty");
  EXPECT_NE(inertia.status.message.find("no volume"), std::string::npos);
}
