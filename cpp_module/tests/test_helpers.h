// Shared by the test files: locating the shared real-world data.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <unistd.h>

#include <BRep_Tool.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Shape.hxx>
#include <gp_Dir.hxx>

#include "contactcore/contacts/contacts.h"
#include "contactcore/partitions/partitions.h"

namespace contactcore::testing {

inline std::string shared_step(const std::string& name) {
  return std::string(CONTACTS_SHARED_DATA) + "/step/" + name;
}

// A null dereference inside OCCT's own code (BRep_Tool::Surface of a face
// without a TShape reads through a null pointer): a real SIGSEGV, as OCCT
// faults on damaged shapes; in OCCT's code, not ours, so `make sanitize`'s
// UBSan leaves it to the signal handler.
inline void dereference_null_inside_occt() {
  const TopoDS_Face none;
  BRep_Tool::Surface(none);
}

inline std::string sample(const std::string& name) { return std::string(CONTACTS_SAMPLES) + "/" + name; }

// A file in the temp directory named for this process: two test runs side by side (two clean
// clones, CI beside a developer) never write or remove each other's files.
inline std::string temp_file(const std::string& name) {
  return (std::filesystem::temp_directory_path() / (std::to_string(::getpid()) + "_" + name)).string();
}

// A file's whole text, as written (binary: no newline translation).
inline std::string file_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// A shape with its partitions at the default tolerances.
struct Partitioned {
  TopoDS_Shape shape;
  BodyPartitions parts;
};

inline Partitioned partitioned(const TopoDS_Shape& shape) { return {shape, partition_shape(shape, Tolerances{})}; }

// The plane partition whose outward normal is `normal`.
inline const Partition& plane_facing(const BodyPartitions& parts, const gp_Dir& normal) {
  for (const Partition& p : parts.partitions)
    if (p.params.kind == SurfaceKind::Plane && p.params.axis.IsEqual(normal, 1e-9)) return p;
  ADD_FAILURE() << "no such plane";
  return parts.partitions.front();
}

// An assembly of named shapes placed as they are (name doubles as path).
inline Assembly make_assembly(std::vector<std::pair<std::string, TopoDS_Shape>> shapes) {
  Assembly a;
  for (auto& [name, shape] : shapes) a.bodies.push_back({name, name, shape});
  return a;
}

// The contacts with default options; a failed status fails the calling test.
inline ContactsResult contacts_of(const Assembly& assembly) {
  ContactsResult result = find_contacts(assembly, ContactOptions{});
  EXPECT_TRUE(result.status.ok()) << result.status.describe();
  return result;
}

}  // namespace contactcore::testing

// Skips the test cleanly when a data file is absent (../shared/data is not
// always beside the checkout).
#define CONTACTS_REQUIRE_FILE(path)                                                  \
  do {                                                                               \
    if (!std::filesystem::exists(path)) GTEST_SKIP() << "data file absent: " << (path); \
  } while (0)
