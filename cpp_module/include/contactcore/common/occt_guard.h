// Common to every stage. Running OCCT readers on untrusted files without crashing or printing:
// OCCT 7.6 dereferences null handles on some damaged STEP files and prints
// its syntax messages to stdout (which breaks `contacts --json`).
#pragma once

#include <exception>
#include <memory>
#include <string>
#include <vector>

#include <Standard_ErrorHandler.hxx>
#include <Standard_Failure.hxx>

#include "contactcore/common/errors.h"
#include "contactcore/common/out_of_memory.h"

namespace contactcore {

// While alive: OCCT's signal handler is installed (SIGSEGV, SIGFPE, ... become
// Standard_Failure inside OCC_CATCH_SIGNALS), the process's previous handlers
// are restored on destruction (Python's SIGINT, FreeCAD's own), and OCCT's
// default messenger prints nothing: its messages are kept in `messages()`.
// OCCT's SIGSEGV and SIGBUS handlers run on a signal stack of their own (the
// thread's if it has one, else one the guard sets up and removes), so a stack
// overflow inside OCCT is an exception too, not a killed process.
// Reads are serialised: signal handlers and the messenger are process-wide.
//
// Make it in the thread that calls a stage, around the stage's loops, never
// inside a worker item: its lock is held by that thread, which waits for the
// item. A signal becomes an exception only in a thread that is inside
// OCC_CATCH_SIGNALS (each worker item: run_guarded below).
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

// An OCCT failure's message, or its type when it has none (some carry none).
std::string occt_failure_text(const Standard_Failure& failure);

// The Status of the exception being handled (call it inside a catch block):
// the one place where an exception that reached a boundary becomes a value.
// OCCT's Standard_OutOfMemory and std::bad_alloc: OutOfMemory; any other OCCT
// failure: GeometryError "OCCT <type>: <text>"; any other exception, C++ or
// not: Internal (a bug, the CLI's exit 5), with its what().
Status status_of_current_exception();

// Runs work() (returning a Status) and returns its Status, or the Status of
// what it threw (status_of_current_exception).
template <class Work>
Status status_of(Work&& work) {
  try {
    return work();
  } catch (...) {
    return status_of_current_exception();
  }
}

// Runs fn() with OCCT's signals (SIGSEGV, SIGFPE, ... while an OcctGuard is
// alive) turned into Standard_Failure exceptions in this thread; they and C++
// exceptions propagate. For code whose own frame must be left by an exception,
// never by the signal's jump (inside std::call_once, a lock).
template <class Fn>
decltype(auto) with_occt_signals(Fn&& fn) {
  OCC_CATCH_SIGNALS
  return fn();
}

// One worker item (a body, a pair) under OCCT's signal handler: true when
// fn() returned; false when it threw or faulted, with `failure` saying why:
// an OCCT failure (a signal included: "SIGSEGV 'segmentation violation'
// detected ...") as occt_prefix + its text, a C++ exception as its what().
// Out of memory is not a failed item: it propagates (out_of_memory.h). A
// setjmp per call: per body or pair, never per triangle or servo tick.
template <class Fn>
bool run_guarded(Fn&& fn, std::string& failure, const char* occt_prefix = "") {
  try {
    with_occt_signals(fn);
    return true;
  } CONTACTS_PASS_OUT_OF_MEMORY catch (const Standard_Failure& error) {
    failure = occt_prefix + occt_failure_text(error);
  } catch (const std::exception& error) {
    failure = *error.what() ? error.what() : "C++ exception without a message";
  }
  return false;
}

}  // namespace contactcore
