#include "bodies/step_scanner_input.h"

#include <dlfcn.h>

#include <atomic>
#include <istream>

#include <StepData_Protocol.hxx>
#include <StepData_StepModel.hxx>
#include <StepFile_Read.hxx>

namespace contactcore::detail {

namespace {

thread_local std::streambuf* block_source = nullptr;
std::atomic<std::size_t> block_reads{0};

// `int stepFlexLexer::LexerInput(char*, int)`: `this` comes first, as for a
// free function (x86-64 and AArch64 C++ ABI).
using LexerInputFunction = int (*)(void*, char*, int);
constexpr const char* kLexerInput = "_ZN13stepFlexLexer10LexerInputEPci";

// OCCT's own LexerInput, looked up in the library that holds its parser.
LexerInputFunction occt_lexer_input() {
  static const LexerInputFunction function = []() -> LexerInputFunction {
    using ReadFunction = Standard_Integer (*)(const char*, std::istream*, const Handle(StepData_StepModel)&,
                                              const Handle(StepData_Protocol)&);
    const ReadFunction read = &StepFile_Read;
    Dl_info info;
    if (dladdr(reinterpret_cast<void*>(read), &info) == 0 || info.dli_fname == nullptr) return nullptr;
    void* library = dlopen(info.dli_fname, RTLD_NOW | RTLD_NOLOAD);
    if (library == nullptr) return nullptr;
    // dlsym on the library's handle searches the library before its dependencies: OCCT's definition.
    void* symbol = dlsym(library, kLexerInput);
    dlclose(library);  // NOLOAD took a reference; the library stays loaded (it is linked)
    return reinterpret_cast<LexerInputFunction>(symbol);
  }();
  return function;
}

}  // namespace

BlockReadScope::BlockReadScope(std::streambuf& text) : previous_(block_source) { block_source = &text; }
BlockReadScope::~BlockReadScope() { block_source = previous_; }

std::size_t step_scanner_block_reads() { return block_reads.load(); }

}  // namespace contactcore::detail

// The scanner's input (see step_scanner_input.h). Exported from the Python
// module too (built with hidden visibility), so the binding is the same there.
extern "C" __attribute__((visibility("default"))) int contacts_step_lexer_input(void* scanner, char* buffer,
                                                                               int max_size) __asm__(
    "_ZN13stepFlexLexer10LexerInputEPci");

extern "C" int contacts_step_lexer_input(void* scanner, char* buffer, int max_size) {
  using namespace contactcore::detail;
  if (block_source != nullptr) {
    ++block_reads;
    const std::streamsize got = block_source->sgetn(buffer, max_size);
    return got < 0 ? -1 : static_cast<int>(got);
  }
  const LexerInputFunction occt = occt_lexer_input();
  return occt != nullptr ? occt(scanner, buffer, max_size) : -1;
}
