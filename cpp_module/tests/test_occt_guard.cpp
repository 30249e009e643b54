// OCCT's signals as errors: one worker item of a guarded parallel loop that
// faults inside OCCT fails alone, the loop and the process go on, and the
// process's signal handlers are given back afterwards.
#include <gtest/gtest.h>

#include <csignal>
#include <mutex>
#include <new>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <Standard_DomainError.hxx>
#include <Standard_OutOfMemory.hxx>

#include "contactcore/common/occt_guard.h"
#include "contactcore/common/parallel.h"
#include "test_helpers.h"

using namespace contactcore;

namespace {

// The handlers of the signals OCCT takes over: handler and flags.
std::vector<std::pair<void*, int>> signal_handlers() {
  std::vector<std::pair<void*, int>> handlers;
  for (int s : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGINT}) {
    struct sigaction action;
    sigaction(s, nullptr, &action);
    handlers.emplace_back(reinterpret_cast<void*>(action.sa_sigaction), action.sa_flags);
  }
  return handlers;
}

// Stands for the caller's own handler (FreeCAD's, Python's): never called.
void callers_handler(int, siginfo_t*, void*) {}

}  // namespace

// Items 1, 4 and 7 of 9 dereference a null pointer inside OCCT: on one
// thread the same thread faults three times (the handler must unblock the
// signal each time), on two both workers may. Every other item's result is
// there, each faulting item has its SIGSEGV message and no result.
TEST(OcctGuard, AFaultingWorkerItemFailsAloneAndTheLoopCompletes) {
  // A handler never set reads back with flags 0, once set and restored with
  // SA_RESTORER (glibc's): compare from the state a first guard leaves.
  { const OcctGuard first; }
  struct sigaction callers{}, saved{};
  callers.sa_sigaction = callers_handler;
  callers.sa_flags = SA_SIGINFO;
  sigemptyset(&callers.sa_mask);
  sigaction(SIGSEGV, &callers, &saved);
  const auto before = signal_handlers();
  ASSERT_EQ(before[0].first, reinterpret_cast<void*>(callers_handler));
  for (const int threads : {1, 2}) {
    SCOPED_TRACE(threads);
    constexpr std::size_t n = 9;
    std::vector<long> results(n, -1);
    std::vector<std::string> failures(n);
    {
      const OcctGuard guard;
      ASSERT_TRUE(parallel_for(n, threads, nullptr, "test", [&](std::size_t i) {
        run_guarded([&] {
          if (i % 3 == 1) contactcore::testing::dereference_null_inside_occt();
          results[i] = static_cast<long>(i * i);
        }, failures[i], "OCCT: ");
      }));
    }
    for (std::size_t i = 0; i < n; ++i) {
      if (i % 3 == 1) {
        EXPECT_EQ(results[i], -1) << i;
        EXPECT_EQ(failures[i].rfind("OCCT: SIGSEGV", 0), 0u) << i << ": " << failures[i];
      } else {
        EXPECT_EQ(results[i], static_cast<long>(i * i)) << i;
        EXPECT_EQ(failures[i], "") << i;
      }
    }
  }
  EXPECT_EQ(signal_handlers(), before);  // the caller's SIGSEGV handler is back
  sigaction(SIGSEGV, &saved, nullptr);
}

// What run_guarded says of each kind of failure; out of memory is not a
// failed item but ends the stage (out_of_memory.h).
TEST(OcctGuard, RunGuardedNamesTheFailureAndPassesOutOfMemory) {
  std::string failure;
  EXPECT_TRUE(run_guarded([] {}, failure));
  EXPECT_EQ(failure, "");
  EXPECT_FALSE(run_guarded([] { throw Standard_DomainError("deliberate"); }, failure, "OCCT: "));
  EXPECT_EQ(failure, "OCCT: deliberate");
  // Some OCCT exceptions carry no message: their type is named.
  EXPECT_FALSE(run_guarded([] { throw Standard_DomainError(); }, failure, "OCCT: "));
  EXPECT_EQ(failure, "OCCT: Standard_DomainError");
  EXPECT_FALSE(run_guarded([] { throw std::runtime_error("not OCCT"); }, failure, "OCCT: "));
  EXPECT_EQ(failure, "not OCCT");
  EXPECT_THROW(run_guarded([] { throw std::bad_alloc(); }, failure), std::bad_alloc);
  EXPECT_THROW(run_guarded([] { throw Standard_OutOfMemory("malloc failed"); }, failure), Standard_OutOfMemory);
}

// with_occt_signals: the fault leaves as a Standard_Failure thrown from the
// caller's frame, so std::call_once sees an exception (its flag stays unset
// and a later call runs again) rather than a jump out of it.
TEST(OcctGuard, AFaultInsideCallOnceIsAnExceptionAndTheFlagStaysFree) {
  std::once_flag once;
  int runs = 0;
  const OcctGuard guard;
  EXPECT_THROW(std::call_once(once, [&] {
                 ++runs;
                 with_occt_signals([] { contactcore::testing::dereference_null_inside_occt(); });
               }),
               Standard_Failure);
  std::call_once(once, [&] { ++runs; });
  EXPECT_EQ(runs, 2);
}
