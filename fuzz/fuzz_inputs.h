// What each fuzz target does with one input, shared by the libFuzzer targets
// (fuzz_*.cpp, make fuzz) and the replay test of the committed corpus and
// crash regressions (test_fuzz_replay.cpp, make test). Besides "no crash",
// each checks the core's answer: a failure says why, and a result is
// consistent with its input; a failed check aborts (a libFuzzer crash).
#pragma once

#include <cstddef>
#include <cstdint>

namespace contactcore::fuzz {

// STEP bytes -> read_step (file checks, OCCT's XDE reader under OcctGuard,
// depth and cycle checks, the assembly walk) -> partitions -> contacts.
// read_step takes a path, as the CLI does: the bytes go to one temporary
// file per process.
void run_step_input(const std::uint8_t* data, std::size_t size);

// BRep text (FreeCAD's exportBrepToString) both ways the workbench uses it:
// partition_brep (shape_from_brep -> box -> tolerances -> partition_shape,
// under the binding's catch of Standard_Failure and std::exception), and
// bodies_from_brep -> partitions -> contacts.
void run_brep_input(const std::uint8_t* data, std::size_t size);

#ifdef CONTACTS_WITH_HAPTICS
// The SpaceMouse HID report parser and report descriptor scan. Byte 0 picks
// the model (a known one, or the generic entry of either vendor), byte 1 the
// mode; then, mode even: reports, each one length byte then its bytes, fed in
// order into one state; mode odd: the rest is a report descriptor.
void run_hid_input(const std::uint8_t* data, std::size_t size);
#endif

}  // namespace contactcore::fuzz
