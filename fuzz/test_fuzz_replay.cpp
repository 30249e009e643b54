// Replays the committed fuzz corpus (fuzz/corpus/<target>/) and every input
// that once crashed (fuzz/regressions/<target>/) through the fuzz targets'
// own code, in the ordinary test build (make test): a crash or a failed check
// aborts the test program.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "contactcore/bodies.h"
#include "fuzz_inputs.h"

namespace {

namespace fs = std::filesystem;

// Files of fuzz/corpus/<target> and fuzz/regressions/<target>, sorted.
std::vector<fs::path> inputs_of(const std::string& target, const std::string& folder) {
  std::vector<fs::path> files;
  const fs::path dir = fs::path(CONTACTS_FUZZ_DIR) / folder / target;
  if (fs::is_directory(dir))
    for (const auto& entry : fs::directory_iterator(dir))
      if (entry.is_regular_file()) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

std::vector<std::uint8_t> bytes_of(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

template <typename Run>
int replay(const std::string& target, const std::string& folder, Run run) {
  int count = 0;
  for (const fs::path& path : inputs_of(target, folder)) {
    SCOPED_TRACE(path.string());
    const std::vector<std::uint8_t> data = bytes_of(path);
    run(data.data(), data.size());
    ++count;
  }
  return count;
}

}  // namespace

// The seed corpora are committed: exact counts, so a lost file fails.
TEST(FuzzReplay, StepCorpus) { EXPECT_EQ(replay("fuzz_step", "corpus", contactcore::fuzz::run_step_input), 6); }
TEST(FuzzReplay, BrepCorpus) { EXPECT_EQ(replay("fuzz_brep", "corpus", contactcore::fuzz::run_brep_input), 4); }
#ifdef CONTACTS_WITH_HAPTICS
TEST(FuzzReplay, HidCorpus) { EXPECT_EQ(replay("fuzz_hid", "corpus", contactcore::fuzz::run_hid_input), 4); }
#endif

// The seeds are what they claim: FreeCAD's exportBrepToString and
// exportStep of two solids each (make_seeds.py) read back as two bodies.
TEST(FuzzReplay, SeedsFromFreeCADReadAsTwoBodies) {
  for (const char* name : {"boxes", "shaft_in_bore", "ball_in_cup"}) {
    SCOPED_TRACE(name);
    const std::vector<std::uint8_t> brep =
        bytes_of(fs::path(CONTACTS_FUZZ_DIR) / "corpus/fuzz_brep" / (std::string("seed_") + name + ".brep"));
    const contactcore::AssemblyResult from_brep = contactcore::bodies_from_brep(std::string(brep.begin(), brep.end()), {});
    ASSERT_TRUE(from_brep.status.ok()) << from_brep.status.describe();
    EXPECT_EQ(from_brep.assembly.bodies.size(), 2u);
    const contactcore::AssemblyResult from_step = contactcore::read_step(
        (fs::path(CONTACTS_FUZZ_DIR) / "corpus/fuzz_step" / (std::string("seed_") + name + ".step")).string());
    ASSERT_TRUE(from_step.status.ok()) << from_step.status.describe();
    EXPECT_EQ(from_step.assembly.bodies.size(), 2u);
  }
}

// Inputs the fuzzers once crashed or hung on, each replayed through its
// target (a hang fails by the test's timeout), then checked for its error.
TEST(FuzzReplay, StepRegressions) { replay("fuzz_step", "regressions", contactcore::fuzz::run_step_input); }
TEST(FuzzReplay, BrepRegressions) { replay("fuzz_brep", "regressions", contactcore::fuzz::run_brep_input); }
#ifdef CONTACTS_WITH_HAPTICS
TEST(FuzzReplay, HidRegressions) { replay("fuzz_hid", "regressions", contactcore::fuzz::run_hid_input); }
#endif

// A damaged number inside an edge record made OCCT 7.6's BRep reader loop
// forever on its failed stream (make fuzz, fuzz_brep): now a clear error.
TEST(FuzzRegressions, BrepEdgeRecordWithADamagedNumberIsAnError) {
  const std::vector<std::uint8_t> data =
      bytes_of(fs::path(CONTACTS_FUZZ_DIR) / "regressions/fuzz_brep/edge_record_damaged_number.brep");
  ASSERT_FALSE(data.empty());
  TopoDS_Shape shape;
  const contactcore::Status status = contactcore::shape_from_brep(std::string(data.begin(), data.end()), shape);
  EXPECT_EQ(status.code, contactcore::StatusCode::InvalidInput);
  EXPECT_NE(status.message.find("damaged text"), std::string::npos) << status.message;
}

// A damaged number in a pcurve ("@6.28...") was read by OCCT as 0 and the
// Boolean common of the sphere face then ran for minutes (make fuzz): now
// the text check names it.
TEST(FuzzRegressions, BrepDamagedNumberInTheGeometryIsAnError) {
  const std::vector<std::uint8_t> data =
      bytes_of(fs::path(CONTACTS_FUZZ_DIR) / "regressions/fuzz_brep/sphere_pcurve_damaged_number.brep");
  ASSERT_FALSE(data.empty());
  TopoDS_Shape shape;
  const contactcore::Status status = contactcore::shape_from_brep(std::string(data.begin(), data.end()), shape);
  EXPECT_EQ(status.code, contactcore::StatusCode::InvalidInput);
  EXPECT_NE(status.message.find("damaged number '@6.2831853071795862' on line 35"), std::string::npos) << status.message;
}
