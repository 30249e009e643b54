#include <gtest/gtest.h>

#include "contactcore/errors.h"

using namespace contactcore;

TEST(Errors, SuccessIsOk) {
  EXPECT_TRUE(Status::success().ok());
  EXPECT_FALSE(Status::failure(StatusCode::ReadError, "x").ok());
}

TEST(Errors, DescribeNamesFileBodyAndFace) {
  Status s = Status::failure(StatusCode::GeometryError, "cannot evaluate surface");
  s.file = "motor.step";
  s.body = "Axis";
  s.face = 7;
  EXPECT_EQ(s.describe(), "cannot evaluate surface (file 'motor.step', body 'Axis', Face7)");
}

TEST(Errors, DescribeWithoutContextIsTheMessage) {
  EXPECT_EQ(Status::failure(StatusCode::Cancelled, "").describe(), "cancelled");
}
