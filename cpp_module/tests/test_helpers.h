// Shared by the test files: locating the shared real-world data.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace contactcore::testing {

inline std::string shared_step(const std::string& name) {
  return std::string(CONTACTS_SHARED_DATA) + "/step/" + name;
}

inline std::string sample(const std::string& name) { return std::string(CONTACTS_SAMPLES) + "/" + name; }

}  // namespace contactcore::testing

// Skips the test cleanly when a data file is absent (../shared/data is not
// always beside the checkout).
#define CONTACTS_REQUIRE_FILE(path)                                                  \
  do {                                                                               \
    if (!std::filesystem::exists(path)) GTEST_SKIP() << "data file absent: " << (path); \
  } while (0)
