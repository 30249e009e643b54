#include <gtest/gtest.h>

#include <new>

#include <BRepPrimAPI_MakeBox.hxx>
#include <Standard_OutOfMemory.hxx>

#include "contactcore/contacts/contacts.h"
#include "contactcore/common/errors.h"
#include "test_helpers.h"

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

// Out of memory in a candidate pair's test (on a worker thread or not) ends
// the call with OutOfMemory: never a skipped pair with the rest kept.
TEST(Errors, OutOfMemoryInACandidateTestEndsTheCall) {
  const Assembly assembly = contactcore::testing::make_assembly({{"a", BRepPrimAPI_MakeBox(10, 10, 10).Shape()},
                                                    {"b", BRepPrimAPI_MakeBox(gp_Pnt(0, 0, 10), 10, 10, 5).Shape()}});
  for (int threads : {1, 2}) {
    for (bool occt : {false, true}) {
      ContactOptions options;
      options.threads = threads;
      options.candidate_hook = [occt](int, int, int, int) {
        if (occt) throw Standard_OutOfMemory("Standard_MMgrRaw::Allocate(): malloc failed");
        throw std::bad_alloc();
      };
      const ContactsResult result = find_contacts(assembly, options);
      EXPECT_EQ(result.status.code, StatusCode::OutOfMemory) << result.status.describe();
      EXPECT_EQ(result.status.describe(), "out of memory");
      EXPECT_TRUE(result.skipped.empty());
    }
  }
}
