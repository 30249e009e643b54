// libFuzzer target (make fuzz): see run_brep_input in fuzz_inputs.h.
#include "fuzz_inputs.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  contactcore::fuzz::run_brep_input(data, size);
  return 0;
}
