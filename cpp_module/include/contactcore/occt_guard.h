// Running OCCT readers on untrusted files without crashing or printing:
// OCCT 7.6 dereferences null handles on some damaged STEP files and prints
// its syntax messages to stdout (which breaks `contacts --json`).
#pragma once

#include <memory>
#include <string>
#include <vector>

namespace contactcore {

// While alive: OCCT's signal handler is installed (SIGSEGV, SIGFPE, ... become
// Standard_Failure inside OCC_CATCH_SIGNALS), the process's previous handlers
// are restored on destruction (Python's SIGINT, FreeCAD's own), and OCCT's
// default messenger prints nothing: its messages are kept in `messages()`.
// OCCT's SIGSEGV and SIGBUS handlers run on a signal stack of their own (the
// thread's if it has one, else one the guard sets up and removes), so a stack
// overflow inside OCCT is an exception too, not a killed process.
// Reads are serialised: signal handlers and the messenger are process-wide.
class OcctGuard {
 public:
  OcctGuard();
  ~OcctGuard();
  OcctGuard(const OcctGuard&) = delete;
  OcctGuard& operator=(const OcctGuard&) = delete;

  // Warnings and failures OCCT sent to its default messenger, in order.
  std::vector<std::string> messages() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace contactcore
