// OCCT's STEP scanner fed in blocks (bodies/step_scanner_input.h): under a
// BlockReadScope the scanner takes its text through the buffer's block read
// (every character once, none through the one-character path OCCT's build
// uses), and the parsed model is the one OCCT's own input gives.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <istream>
#include <sstream>
#include <streambuf>
#include <string>
#include <vector>

#include <StepData_StepModel.hxx>
#include <XSControl_Reader.hxx>
#include <STEPControl_Reader.hxx>

#include "bodies/step_scanner_input.h"
#include "test_helpers.h"

using namespace contactcore;

namespace {

// A buffer without a get area: a character taken alone goes through uflow
// (counted), a block through xsgetn (counted, with the characters it gave).
class CountingText : public std::streambuf {
 public:
  explicit CountingText(std::string text) : text_(std::move(text)) {}
  std::size_t single_reads = 0, block_reads = 0, block_chars = 0;

 protected:
  int_type underflow() override {
    return at_ < text_.size() ? traits_type::to_int_type(text_[at_]) : traits_type::eof();
  }
  int_type uflow() override {
    if (at_ >= text_.size()) return traits_type::eof();
    ++single_reads;
    return traits_type::to_int_type(text_[at_++]);
  }
  std::streamsize xsgetn(char* out, std::streamsize count) override {
    ++block_reads;
    const std::size_t n = std::min<std::size_t>(static_cast<std::size_t>(count), text_.size() - at_);
    std::memcpy(out, text_.data() + at_, n);
    at_ += n;
    block_chars += n;
    return static_cast<std::streamsize>(n);
  }

 private:
  std::string text_;
  std::size_t at_ = 0;
};

struct Parsed {
  bool ok = false;
  Handle(StepData_StepModel) model;
};

Parsed parse(CountingText& text, bool in_blocks) {
  STEPControl_Reader reader;
  std::istream stream(&text);
  Parsed out;
  if (in_blocks) {
    const detail::BlockReadScope blocks(text);
    out.ok = reader.ReadStream("counted.step", stream) == IFSelect_RetDone;
  } else {
    out.ok = reader.ReadStream("counted.step", stream) == IFSelect_RetDone;
  }
  out.model = reader.StepModel();
  return out;
}

}  // namespace

TEST(StepScannerInput, TheScannerTakesEveryCharacterInBlocksUnderTheScope) {
  const std::string text = contactcore::testing::file_text(contactcore::testing::sample("families/bolted_grid_100.step"));
  ASSERT_EQ(text.size(), 95154u);  // many of the scanner's blocks
  const std::size_t before = detail::step_scanner_block_reads();
  CountingText counted(text);
  const Parsed parsed = parse(counted, true);
  ASSERT_TRUE(parsed.ok);
  EXPECT_EQ(counted.single_reads, 0u);
  EXPECT_EQ(counted.block_chars, text.size());
  EXPECT_EQ(counted.block_reads, 13u);  // 12 of flex's 8,192-byte reads (95,154 bytes), then its end
  EXPECT_EQ(detail::step_scanner_block_reads() - before, counted.block_reads);
}

TEST(StepScannerInput, WithoutTheScopeOcctsOwnInputReadsACharacterPerCall) {
  const std::string text = contactcore::testing::file_text(contactcore::testing::sample("families/bolted_grid_100.step"));
  const std::size_t before = detail::step_scanner_block_reads();
  CountingText counted(text);
  const Parsed parsed = parse(counted, false);
  ASSERT_TRUE(parsed.ok);
  EXPECT_EQ(counted.block_reads, 0u);
  EXPECT_EQ(counted.single_reads, text.size());
  EXPECT_EQ(detail::step_scanner_block_reads(), before);
}

TEST(StepScannerInput, BundledFilesParseToTheSameModelsEitherWay) {
  // Every bundled STEP file: the same entities (number, type, #label) with
  // OCCT's input and with the block reads; the bodies are compared by
  // test_step_read.cpp (the read by products parses in blocks, the XDE read not).
  std::vector<std::string> files;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(std::string(CONTACTS_SAMPLES))) {
    const std::string ext = entry.path().extension().string();
    if (entry.is_regular_file() && (ext == ".step" || ext == ".stp" || ext == ".STEP" || ext == ".STP"))
      files.push_back(entry.path().string());
  }
  std::sort(files.begin(), files.end());
  ASSERT_EQ(files.size(), 17u);
  for (const std::string& path : files) {
    SCOPED_TRACE(path);
    const std::string text = contactcore::testing::file_text(path);
    CountingText by_blocks(text), by_characters(text);
    const Parsed blocks = parse(by_blocks, true), characters = parse(by_characters, false);
    ASSERT_TRUE(blocks.ok);
    ASSERT_TRUE(characters.ok);
    EXPECT_EQ(by_blocks.single_reads, 0u);
    ASSERT_EQ(blocks.model->NbEntities(), characters.model->NbEntities());
    for (Standard_Integer i = 1; i <= blocks.model->NbEntities(); ++i) {
      const Handle(Standard_Transient) a = blocks.model->Value(i), b = characters.model->Value(i);
      ASSERT_EQ(a.IsNull(), b.IsNull()) << "entity " << i;
      if (a.IsNull()) continue;
      EXPECT_STREQ(a->DynamicType()->Name(), b->DynamicType()->Name()) << "entity " << i;
      EXPECT_EQ(blocks.model->IdentLabel(a), characters.model->IdentLabel(b)) << "entity " << i;
    }
  }
}
