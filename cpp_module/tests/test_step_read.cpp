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
#include <unordered_map>
#include <vector>

#include <gp_Trsf.hxx>

#include "bodies/step_placement_lists.h"
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

// The same bodies in the same order: names, paths, placements (to 1e-9), volumes and centres.
void expect_same_bodies(const Assembly& expected, const Assembly& got) {
  EXPECT_EQ(got.units, expected.units);
  EXPECT_EQ(got.source_unit_in_mm, expected.source_unit_in_mm);
  const std::vector<Body>& a = expected.bodies;
  const std::vector<Body>& b = got.bodies;
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
}

// Reads `path` both ways and compares; returns the fast read's reader ("products" or "xde").
std::string expect_same_read(const std::string& path) {
  SCOPED_TRACE(path);
  const AssemblyResult xde = read_step(path, nullptr, StepReadMode::Xde);
  const AssemblyResult fast = read_step(path, nullptr, StepReadMode::Products);
  EXPECT_EQ(xde.status.ok(), fast.status.ok()) << xde.status.describe() << " / " << fast.status.describe();
  if (!xde.status.ok() || !fast.status.ok()) return fast.assembly.reader;
  EXPECT_EQ(xde.assembly.reader, "xde");
  expect_same_bodies(xde.assembly, fast.assembly);
  // The same skipped shells, by the same paths.
  const auto skipped = [](const Assembly& assembly) {
    std::vector<std::string> out;
    for (const std::string& message : assembly.messages)
      if (message.rfind("skipped", 0) == 0) out.push_back(message);
    return out;
  };
  EXPECT_EQ(skipped(fast.assembly), skipped(xde.assembly));
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
  // All served by the read by products, R08's hybrid models (a solid's
  // representation beside a surface model's, which XDE makes a sub-assembly)
  // and R09's products placed by MAPPED_ITEMs included.
  const std::map<std::string, std::string> expected = {
      {"D03_asm4_tuto2_disk_arm.step", "products"}, {"R01_as1-oc-214.stp", "products"},
      {"R05_SKF_6004.stp", "products"},             {"R06_bearing_20x37x9_freecad.stp", "products"},
      {"R08_presse_asm.step", "products"},           {"R09_chrono_assembly.stp", "products"},
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
  std::string step = contactcore::testing::file_text(contactcore::testing::sample("cases/pin_block.step"));
  const std::size_t end = step.rfind("ENDSEC;");
  ASSERT_NE(end, std::string::npos);
  step.insert(end, "#99990 = CONTEXT_DEPENDENT_SHAPE_REPRESENTATION(#461,#34);\n");
  const std::string path = contactcore::testing::temp_file("contacts_fallback_pin_block.step");
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


TEST(StepPlacementLists, TheGridsAssemblyListIsShortenedToItsFirstItem) {
  // bolted_grid_100.step (FreeCAD's export): the assembly's #10 lists its
  // origin #11 and the 100 parts' placements #15, #19, ... #411; nothing else
  // is a list of placements only (the parts' representations hold a solid).
  const std::string text = contactcore::testing::file_text(contactcore::testing::sample("families/bolted_grid_100.step"));
  const ShortenedPlacementLists shortened = shorten_placement_lists(text);
  ASSERT_TRUE(shortened.changed());
  ASSERT_EQ(shortened.removed.size(), 1u);
  std::vector<int> expected;
  for (int item = 15; item <= 411; item += 4) expected.push_back(item);
  EXPECT_EQ(shortened.removed.at(10), expected);
  // The text is the file's with that one list replaced.
  const std::size_t open = text.find("#10 = SHAPE_REPRESENTATION('',(") + 30;
  const std::size_t close = text.find("),#415);", open);
  ASSERT_NE(close, std::string::npos);
  EXPECT_EQ(shortened.text, text.substr(0, open) + "(#11" + text.substr(close));
}

TEST(StepPlacementLists, OnlyListsOfPlacementsInSimpleRecordsAreShortened) {
  const std::string text =
      "ISO-10303-21;\nHEADER;\nFILE_NAME('a;b','',(''),(''),'','','');\nENDSEC;\nDATA;\n"
      "#1 = AXIS2_PLACEMENT_3D('',#3,$,$);\n"
      "#2=AXIS2_PLACEMENT_3D ( 'it''s' , #3 , $ , $ ) ;\n"
      "#3 = CARTESIAN_POINT('',(0.,0.,0.));\n"
      // a name holding '', ';' and '/*'; a comment between items: shortened
      "#10 = SHAPE_REPRESENTATION('it''s; /*',(#1, /* #3; */\n #2,#1),#20);\n"
      "#11 = SHAPE_REPRESENTATION('',(#1,#3),#20);\n"             // a point among them
      "#12 = SHAPE_REPRESENTATION('',(#2),#20);\n"                // one item
      "#13 = ( SHAPE_REPRESENTATION('',(#1,#2),#20) REPRESENTATION_ITEM('') );\n"  // complex
      "#14 = ADVANCED_BREP_SHAPE_REPRESENTATION('',(#1,#2),#20);\n"  // another type
      // OCCT's lexer ends a string only at a quote followed by ',' or ')':
      // this PRODUCT's name runs over the ';' and what looks like #15.
      "#16 = PRODUCT('a'b; #15 = SHAPE_REPRESENTATION(' x' ,(#1,#2),#20);\n"
      "#17 = SHAPE_REPRESENTATION('',(#2,#1),#20)\n;\n"
      "ENDSEC;\nEND-ISO-10303-21;\n";
  const ShortenedPlacementLists shortened = shorten_placement_lists(text);
  ASSERT_EQ(shortened.removed.size(), 2u);
  EXPECT_EQ(shortened.removed.at(10), (std::vector<int>{2, 1}));
  EXPECT_EQ(shortened.removed.at(17), (std::vector<int>{1}));
  std::string expected = text;
  const std::string list10 = "(#1, /* #3; */\n #2,#1)";
  expected.replace(expected.find(list10), list10.size(), "(#1)");
  expected.replace(expected.find("(#2,#1),#20)\n;"), 7, "(#2)");
  EXPECT_EQ(shortened.text, expected);
  // Nothing to shorten: no text.
  const ShortenedPlacementLists none = shorten_placement_lists("DATA;\n#11 = SHAPE_REPRESENTATION('',(#1,#3),#20);\n");
  EXPECT_FALSE(none.changed());
  EXPECT_TRUE(none.text.empty());
}

TEST(StepRead, AShortenedListOutsideAnAssemblyIsReadAsWritten) {
  // pin_block.step with a second representation of the part Plate holding
  // two placements only: the list is shortened, it is no assembly's, so the
  // read by products parses the file as written and reads it as XDE does.
  std::string step = contactcore::testing::file_text(contactcore::testing::sample("cases/pin_block.step"));
  const std::size_t end = step.rfind("ENDSEC;");
  ASSERT_NE(end, std::string::npos);
  step.insert(end,
              "#99990 = SHAPE_REPRESENTATION('',(#11,#15),#455);\n"
              "#99991 = SHAPE_DEFINITION_REPRESENTATION(#34,#99990);\n");
  ASSERT_NE(step.find("#34 = PRODUCT_DEFINITION_SHAPE('','',#35);"), std::string::npos);
  ASSERT_NE(step.find("#37 = PRODUCT('Plate'"), std::string::npos);
  const std::string path = contactcore::testing::temp_file("contacts_leaf_placements.step");
  std::ofstream(path) << step;
  const ShortenedPlacementLists shortened = shorten_placement_lists(step);
  ASSERT_EQ(shortened.removed.size(), 2u);  // the assembly's #10 and the part's #99990
  EXPECT_EQ(shortened.removed.at(99990), (std::vector<int>{15}));
  EXPECT_EQ(expect_same_read(path), "products");
  const AssemblyResult fast = read_step(path, nullptr, StepReadMode::Products);
  ASSERT_TRUE(fast.status.ok()) << fast.status.describe();
  EXPECT_EQ(fast.assembly.bodies.size(), 3u);
  std::filesystem::remove(path);
}

TEST(StepRead, BigGridReadsTheSameWithItsPlacementListShortened) {
  // A 3,000-part bolted grid written by bench/big_grid_step.py: the
  // assembly's one list of 3,001 placements, shortened for OCCT's parser,
  // gives the same bodies, names, paths, placements and volumes as the read
  // of the file as written.
  const std::string path = contactcore::testing::temp_file("contacts_big_grid_3000.step");
  const std::string command = "/usr/bin/python3 " + std::string(CONTACTS_SOURCE_DIR) + "/bench/big_grid_step.py 3000 " +
                              path + " --template " + contactcore::testing::sample("families/bolted_grid_100.step");
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  const ShortenedPlacementLists shortened = shorten_placement_lists(contactcore::testing::file_text(path));
  ASSERT_EQ(shortened.removed.size(), 1u);
  EXPECT_EQ(shortened.removed.begin()->second.size(), 3000u);
  const AssemblyResult as_written = read_step(path, nullptr, StepReadMode::ProductsAsWritten);
  const AssemblyResult shortened_read = read_step(path, nullptr, StepReadMode::Products);
  ASSERT_TRUE(as_written.status.ok()) << as_written.status.describe();
  ASSERT_TRUE(shortened_read.status.ok()) << shortened_read.status.describe();
  EXPECT_EQ(as_written.assembly.reader, "products");
  EXPECT_EQ(shortened_read.assembly.reader, "products");
  ASSERT_EQ(shortened_read.assembly.bodies.size(), 3000u);
  expect_same_bodies(as_written.assembly, shortened_read.assembly);
  EXPECT_EQ(shortened_read.assembly.messages, as_written.assembly.messages);
  std::filesystem::remove(path);
}
