// Stage 1 (bodies): OCCT's STEP scanner fed its text in blocks.
// Debian's OCCT 7.6.3 ships a flex scanner (lex.step.cxx) whose LexerInput
// takes one character per call (std::istream::get), and flex then re-runs its
// automaton over the token read so far at every call (yy_get_previous_state):
// the scanner was 35 to 40 % of the read of 10,000 instances of one part.
// step_scanner_input.cpp defines that member function itself, so the dynamic
// linker binds OCCT's scanner to it (OCCT's library calls it through its
// vtable, bound by symbol): while a BlockReadScope is open on a thread, the
// scanner on that thread takes its text from the scope's buffer in blocks, as
// flex's default skeleton does (the same characters, so the same tokens);
// otherwise it calls OCCT's own function. Where OCCT's library was loaded
// before ours (FreeCAD's GUI), OCCT's function stays bound: the read is the
// same, only slower.
#pragma once

#include <cstddef>
#include <streambuf>

namespace contactcore::detail {

// While alive, OCCT's STEP scanner on this thread reads `text` in blocks. The
// stream handed to OCCT's parser must read from `text` (nothing else reads it).
class BlockReadScope {
 public:
  explicit BlockReadScope(std::streambuf& text);
  ~BlockReadScope();
  BlockReadScope(const BlockReadScope&) = delete;
  BlockReadScope& operator=(const BlockReadScope&) = delete;

 private:
  std::streambuf* previous_;
};

// Calls of the scanner's input served from a BlockReadScope's buffer since the
// process started (tests: proves the scanner is bound to the block reads).
std::size_t step_scanner_block_reads();

}  // namespace contactcore::detail
