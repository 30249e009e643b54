#include <gtest/gtest.h>

#include <iterator>
#include <new>
#include <set>
#include <stdexcept>
#include <string>
#include <system_error>

#include <BRepPrimAPI_MakeBox.hxx>
#include <Standard_DomainError.hxx>
#include <Standard_OutOfMemory.hxx>

#include "contactcore/contacts/contacts.h"
#include "contactcore/common/errors.h"
#include "contactcore/common/occt_guard.h"
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

// The one place where an exception reaching a boundary becomes a Status
// (bindings' guarded()): one StatusCode per kind of exception.
TEST(Errors, EachExceptionBecomesItsStatusCode) {
  const auto status_of_throwing = [](auto thrower) {
    return status_of([&]() -> Status {
      thrower();
      return Status::success();
    });
  };
  Status s = status_of_throwing([] { throw Standard_OutOfMemory("Standard_MMgrRaw::Allocate(): malloc failed"); });
  EXPECT_EQ(s.code, StatusCode::OutOfMemory);
  EXPECT_EQ(s.message, "out of memory");
  s = status_of_throwing([] { throw std::bad_alloc(); });
  EXPECT_EQ(s.code, StatusCode::OutOfMemory);
  s = status_of_throwing([] { throw Standard_Failure("no surface"); });
  EXPECT_EQ(s.code, StatusCode::GeometryError);
  EXPECT_EQ(s.message, "OCCT Standard_Failure: no surface");
  s = status_of_throwing([] { throw Standard_DomainError(""); });  // OCCT's without a text: its type
  EXPECT_EQ(s.code, StatusCode::GeometryError);
  EXPECT_EQ(s.message, "OCCT Standard_DomainError");
  // A plain C++ exception is a bug: Internal, never GeometryError.
  s = status_of_throwing([] { throw std::out_of_range("vector::_M_range_check: __n (which is 7)"); });
  EXPECT_EQ(s.code, StatusCode::Internal);
  EXPECT_EQ(s.message, "vector::_M_range_check: __n (which is 7)");
  s = status_of_throwing([] { throw std::system_error(std::make_error_code(std::errc::resource_unavailable_try_again)); });
  EXPECT_EQ(s.code, StatusCode::OutOfMemory);  // no thread could be started: memory, not a bug
  s = status_of_throwing([] { throw std::system_error(std::make_error_code(std::errc::invalid_argument)); });
  EXPECT_EQ(s.code, StatusCode::Internal);
  s = status_of_throwing([] { throw 42; });
  EXPECT_EQ(s.code, StatusCode::Internal);
  EXPECT_EQ(s.describe(), "an exception that is not a C++ std::exception");
  // A returned Status passes through as it is.
  s = status_of([] { return Status::failure(StatusCode::ReadError, "no such file"); });
  EXPECT_EQ(s.code, StatusCode::ReadError);
  EXPECT_EQ(s.message, "no such file");
  EXPECT_TRUE(status_of([] { return Status::success(); }).ok());
}

TEST(Errors, EveryCodeHasItsOwnName) {
  const StatusCode codes[] = {StatusCode::Ok,        StatusCode::InvalidInput,    StatusCode::ReadError,
                              StatusCode::GeometryError, StatusCode::Cancelled, StatusCode::InvalidArgument,
                              StatusCode::OutOfMemory, StatusCode::Internal};
  std::set<std::string> names;
  for (StatusCode code : codes) names.insert(to_string(code));
  EXPECT_EQ(names.size(), std::size(codes));
  EXPECT_STREQ(to_string(StatusCode::Internal), "internal error");
  EXPECT_EQ(Status::failure(StatusCode::Internal, "").describe(), "internal error");
}
