// Timing helpers the haptic benchmarks share: the calling thread's CPU time
// and a percentile of a sample.
#pragma once

#include <time.h>

#include <algorithm>
#include <cstddef>
#include <vector>

namespace contactcore::bench {

// CPU seconds this thread has used (CLOCK_THREAD_CPUTIME_ID).
inline double thread_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return ts.tv_sec + ts.tv_nsec * 1e-9;
}

// The p-th percentile (0..100) of v, nearest rank; 0 for an empty sample.
inline double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<std::size_t>(p / 100.0 * (v.size() - 1) + 0.5))];
}

}  // namespace contactcore::bench
