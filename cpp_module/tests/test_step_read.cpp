// The fast STEP read (each product transferred once, its instances placed)
// against OCCT's XDE read, on every bundled and shared STEP file: the same
// bodies in the same order, with the same names, paths, units, placements
// (to 1e-9) and volumes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gp_Trsf.hxx>

#include "contactcore/bodies/bodies.h"
#include "test_helpers.h"

using namespace contactcore;

namespace {

std::vector<std::string> step_files_under(const std::string& dir) {
  std::vector<std::string> files;
  if (!std::filesystem::is_directory(dir)) return files;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(dir)) {
    std::string ext = entry.path().extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
    if (entry.is_regular_file() && (ext == ".step" || ext == ".stp")) files.push_back(entry.path().string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

// Reads `path` both ways and compares; returns the fast read's reader ("products" or "xde").
std::string expect_same_read(const std::string& path) {
  SCOPED_TRACE(path);
  const AssemblyResult xde = read_step(path, nullptr, StepReadMode::Xde);
  const AssemblyResult fast = read_step(path, nullptr, StepReadMode::Products);
  EXPECT_EQ(xde.status.ok(), fast.status.ok()) << xde.status.describe() << " / " << fast.status.describe();
  if (!xde.status.ok() || !fast.status.ok()) return fast.assembly.reader;
  EXPECT_EQ(xde.assembly.reader, "xde");
  EXPECT_EQ(fast.assembly.units, xde.assembly.units);
  EXPECT_EQ(fast.assembly.source_unit_in_mm, xde.assembly.source_unit_in_mm);
  const std::vector<Body>& a = xde.assembly.bodies;
  const std::vector<Body>& b = fast.assembly.bodies;
  EXPECT_EQ(b.size(), a.size());
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
    SCOPED_TRACE("body " + std::to_string(i) + " '" + a[i].name + "'");
    EXPECT_EQ(b[i].name, a[i].name);
    EXPECT_EQ(b[i].path, a[i].path);
    const gp_Trsf ta = a[i].shape.Location().Transformation(), tb = b[i].shape.Location().Transformation();
    for (int r = 1; r <= 3; ++r)
      for (int c = 1; c <= 4; ++c) EXPECT_NEAR(tb.Value(r, c), ta.Value(r, c), 1e-9) << "row " << r << " column " << c;
    const MassProperties& ma = a[i].mass();
    const MassProperties& mb = b[i].mass();
    EXPECT_NEAR(mb.volume, ma.volume, 1e-9 * std::max(1.0, std::abs(ma.volume)));
    EXPECT_NEAR(mb.centre.Distance(ma.centre), 0.0, 1e-9 * std::max(1.0, ma.centre.XYZ().Modulus()));
  }
  // The fast read says when it falls back, and only then.
  const bool said = std::any_of(fast.assembly.messages.begin(), fast.assembly.messages.end(), [](const std::string& m) {
    return m.find("fast product read cannot serve this file") != std::string::npos;
  });
  EXPECT_EQ(said, fast.assembly.reader == "xde");
  return fast.assembly.reader;
}

}  // namespace

TEST(StepRead, BundledFilesReadAsXdeReadsThem) {
  const std::vector<std::string> files = step_files_under(std::string(CONTACTS_SAMPLES));
  ASSERT_EQ(files.size(), 17u);
  for (const std::string& file : files) EXPECT_EQ(expect_same_read(file), "products") << file;
}

TEST(StepRead, SharedFilesReadAsXdeReadsThem) {
  const std::string dir = std::string(CONTACTS_SHARED_DATA) + "/step";
  CONTACTS_REQUIRE_FILE(dir);
  const std::vector<std::string> files = step_files_under(dir);
  ASSERT_FALSE(files.empty());
  // Hybrid models (a solid's representation beside a surface model's, which
  // XDE makes a sub-assembly) and mapped items of products are XDE's.
  const std::map<std::string, std::string> expected = {
      {"D03_asm4_tuto2_disk_arm.step", "products"}, {"R01_as1-oc-214.stp", "products"},
      {"R05_SKF_6004.stp", "products"},             {"R06_bearing_20x37x9_freecad.stp", "products"},
      {"R08_presse_asm.step", "xde"},                {"R09_chrono_assembly.stp", "xde"},
      {"R10_wrenchnut.stp", "products"}};
  for (const std::string& file : files) {
    const std::string name = std::filesystem::path(file).filename().string();
    const std::string reader = expect_same_read(file);
    const auto known = expected.find(name);
    if (known != expected.end()) EXPECT_EQ(reader, known->second) << name;
  }
}

namespace {
struct StageLog : Progress {
  bool report(const char* stage, double) override {
    if (stages.empty() || stages.back() != stage) stages.emplace_back(stage);
    return true;
  }
  std::vector<std::string> stages;
};
}  // namespace

TEST(StepRead, UnknownProductStructureFallsBackToXdeAndSaysSo) {
  // pin_block.step with a placement (CONTEXT_DEPENDENT_SHAPE_REPRESENTATION)
  // of a product rather than of an occurrence: the fast read does not know it.
  std::ifstream in(contactcore::testing::sample("cases/pin_block.step"));
  std::stringstream text;
  text << in.rdbuf();
  std::string step = text.str();
  const std::size_t end = step.rfind("ENDSEC;");
  ASSERT_NE(end, std::string::npos);
  step.insert(end, "#99990 = CONTEXT_DEPENDENT_SHAPE_REPRESENTATION(#461,#34);\n");
  const std::string path = (std::filesystem::temp_directory_path() / "contacts_fallback_pin_block.step").string();
  std::ofstream(path) << step;
  StageLog log;
  const AssemblyResult fast = read_step(path, &log, StepReadMode::Products);
  ASSERT_TRUE(fast.status.ok()) << fast.status.describe();
  EXPECT_EQ(fast.assembly.reader, "xde");
  ASSERT_FALSE(fast.assembly.messages.empty());
  EXPECT_EQ(fast.assembly.messages.front(),
            "STEP read: the fast product read cannot serve this file (a placement of no assembly occurrence "
            "(#99990)): read through OCCT's XDE reader");
  EXPECT_NE(std::find(log.stages.begin(), log.stages.end(), "read (XDE fallback)"), log.stages.end());
  EXPECT_EQ(expect_same_read(path), "xde");
  ASSERT_EQ(fast.assembly.bodies.size(), 3u);
  EXPECT_EQ(fast.assembly.bodies[0].name, "Plate");
  std::filesystem::remove(path);
}

TEST(StepRead, InstancesOfOneProductShareItsShape) {
  // The bolted grid of 100: two products (plate, bolt) placed 100 times; the
  // fast read transfers each once, so every plate shares one TShape.
  const AssemblyResult fast = read_step(contactcore::testing::sample("families/bolted_grid_100.step"));
  ASSERT_TRUE(fast.status.ok()) << fast.status.describe();
  EXPECT_EQ(fast.assembly.reader, "products");
  ASSERT_EQ(fast.assembly.bodies.size(), 100u);
  std::set<const void*> shapes;
  for (const Body& body : fast.assembly.bodies) shapes.insert(body.shape.TShape().get());
  EXPECT_EQ(shapes.size(), 2u);
}
