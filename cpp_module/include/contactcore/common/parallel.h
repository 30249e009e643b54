// Common to every stage. A parallel loop for the core's stages: items on worker threads, progress
// and cancellation from the calling thread (which may hold a GUI's or
// Python's lock to report), results written by index so the output order is
// the serial one whatever the number of threads.
#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdio>
#include <exception>
#include <mutex>
#include <system_error>
#ifdef __linux__
#include <sys/resource.h>
#include <unistd.h>
#endif
#include <thread>
#include <vector>

#include "contactcore/common/errors.h"

namespace contactcore {

// Worker threads for a `threads` option: 0 means every core.
inline int worker_count(int threads) {
  if (threads > 0) return threads;
  return std::max(1u, std::thread::hardware_concurrency());
}

// Whether `workers` new threads fit in the address space when the process
// runs under a limit on it (prlimit --as, ulimit -v): each needs its stack
// and may need a malloc arena (64 MB reserved). Short of room, glibc cannot
// give a new thread its thread-local storage and ends the process (no
// exception to catch): then the work runs in the calling thread, where
// running out of memory is a bad_alloc like any other.
inline bool address_space_allows_threads(int workers) {
#ifdef __linux__
  rlimit limit{};
  if (getrlimit(RLIMIT_AS, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) return true;
  rlimit stack{};
  const double stack_bytes = getrlimit(RLIMIT_STACK, &stack) == 0 && stack.rlim_cur != RLIM_INFINITY
                                 ? static_cast<double>(stack.rlim_cur) : 8.0 * (1 << 20);
  unsigned long pages = 0;
  if (FILE* statm = std::fopen("/proc/self/statm", "r")) {
    if (std::fscanf(statm, "%lu", &pages) != 1) pages = 0;
    std::fclose(statm);
  }
  const double used = static_cast<double>(pages) * static_cast<double>(sysconf(_SC_PAGESIZE));
  const double needed = workers * (stack_bytes + 64.0 * (1 << 20));
  return static_cast<double>(limit.rlim_cur) - used > 2 * needed;  // and room left for the work
#else
  (void)workers;
  return true;
#endif
}

// Calls work(i) for every i in [0, n), `grain` consecutive items per task, on
// worker_count(threads) threads (1: inline in the calling thread). Reports
// `stage` with the fraction done at least every 50 ms; returns false when the
// report asks to stop (items not yet started are then skipped). An exception
// escaping `work` stops the loop and is rethrown here.
template <class Work>
bool parallel_for(std::size_t n, int threads, Progress* progress, const char* stage, Work&& work,
                  std::size_t grain = 1) {
  using Clock = std::chrono::steady_clock;
  constexpr auto kReportEvery = std::chrono::milliseconds(50);
  grain = std::max<std::size_t>(grain, 1);
  if (progress && !progress->report(stage, 0.0)) return false;
  const std::size_t tasks = (n + grain - 1) / grain;
  // This thread's C++ exception state (thread-local, allocated on first use)
  // made now, not by a first throw once memory has run out (see run below).
  (void)std::uncaught_exceptions();
  int workers = static_cast<int>(std::min<std::size_t>(worker_count(threads), tasks));
  if (workers > 1 && !address_space_allows_threads(workers)) workers = 1;
  if (workers <= 1) {
    auto last = Clock::now();
    for (std::size_t i = 0; i < n; ++i) {
      if (progress && Clock::now() - last >= kReportEvery) {
        if (!progress->report(stage, static_cast<double>(i) / static_cast<double>(n))) return false;
        last = Clock::now();
      }
      work(i);
    }
    return true;
  }

  std::atomic<std::size_t> next{0}, done{0};
  std::atomic<bool> stop{false};
  std::mutex mutex;
  std::condition_variable finished;
  std::exception_ptr error;
  const auto run = [&] {
    // A new thread's C++ exception state lives in libstdc++'s thread-local
    // storage, which glibc allocates on first use: a first throw when memory
    // has run out (the bad_alloc itself) would end the process ("cannot
    // allocate memory for thread-local data"). Allocate it now.
    (void)std::uncaught_exceptions();
    for (;;) {
      const std::size_t begin = next.fetch_add(grain);
      if (begin >= n || stop.load(std::memory_order_relaxed)) break;
      const std::size_t end = std::min(n, begin + grain);
      try {
        for (std::size_t i = begin; i < end && !stop.load(std::memory_order_relaxed); ++i) work(i);
      } catch (...) {
        std::lock_guard<std::mutex> lock(mutex);
        if (!error) error = std::current_exception();
        stop = true;
      }
      if (done.fetch_add(end - begin) + (end - begin) >= n) {
        std::lock_guard<std::mutex> lock(mutex);
        finished.notify_all();
      }
    }
    std::lock_guard<std::mutex> lock(mutex);
    finished.notify_all();
  };
  std::vector<std::thread> pool;
  pool.reserve(workers);
  for (int t = 0; t < workers; ++t) {
    try {
      pool.emplace_back(run);
    } catch (const std::system_error&) {
      break;  // no thread to be had (memory or a thread limit): the ones started do the work
    }
  }
  if (pool.empty()) run();
  bool cancelled = false;
  {
    std::unique_lock<std::mutex> lock(mutex);
    while (done.load() < n && !stop.load()) {
      finished.wait_for(lock, kReportEvery);
      if (progress && done.load() < n && !stop.load()) {
        lock.unlock();
        const bool go_on = progress->report(stage, static_cast<double>(done.load()) / static_cast<double>(n));
        lock.lock();
        if (!go_on) {
          cancelled = true;
          stop = true;
        }
      }
    }
  }
  for (std::thread& thread : pool) thread.join();
  if (error) std::rethrow_exception(error);
  return !cancelled;
}


// Runs `beside` on a second thread while `here` runs on the calling thread,
// as parallel_for starts its workers: only when the address space has room
// for a thread, the new thread's exception state allocated first; with no
// thread to be had, both run here, one after the other. An exception escaping
// either is rethrown here once both have finished.
template <class Beside, class Here>
void run_beside(Beside&& beside, Here&& here) {
  std::exception_ptr error;
  const auto run = [&] {
    (void)std::uncaught_exceptions();  // see parallel_for
    try {
      beside();
    } catch (...) {
      error = std::current_exception();
    }
  };
  std::thread worker;
  if (address_space_allows_threads(1)) {
    try {
      worker = std::thread(run);
    } catch (const std::system_error&) {
      // no thread to be had: run below
    }
  }
  if (!worker.joinable()) run();
  try {
    here();
  } catch (...) {
    if (worker.joinable()) worker.join();
    throw;
  }
  if (worker.joinable()) worker.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace contactcore
