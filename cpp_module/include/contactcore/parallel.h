// A parallel loop for the core's stages: items on worker threads, progress
// and cancellation from the calling thread (which may hold a GUI's or
// Python's lock to report), results written by index so the output order is
// the serial one whatever the number of threads.
#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

#include "contactcore/errors.h"

namespace contactcore {

// Worker threads for a `threads` option: 0 means every core.
inline int worker_count(int threads) {
  if (threads > 0) return threads;
  return std::max(1u, std::thread::hardware_concurrency());
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
  const int workers = static_cast<int>(std::min<std::size_t>(worker_count(threads), tasks));
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
  for (int t = 0; t < workers; ++t) pool.emplace_back(run);
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

}  // namespace contactcore
