// Contacts stage benchmark: for each STEP file given, the time of each stage
// (read, partitions, broad phase, candidates, common area) and the peak
// memory, each file measured in its own child process so peaks don't mix.
// Prints one JSON object per line; bench/run_benchmarks.py makes the table
// with the brute-force baseline measured in the same run.
//
//   bench_contacts [--repeat N] FILE.step...
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include <TopExp_Explorer.hxx>

#include "contactcore/contacts.h"

using namespace contactcore;

namespace {

double now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

long peak_rss_kb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss;
}

int measure(const std::string& path, int repeat) {
  const double t0 = now();
  const AssemblyResult read = read_step(path);
  const double read_seconds = now() - t0;
  if (!read.status.ok()) {
    std::printf("{\"file\": \"%s\", \"error\": \"%s\"}\n", path.c_str(), read.status.describe().c_str());
    return 1;
  }
  size_t faces = 0;
  for (const Body& body : read.assembly.bodies)
    for (TopExp_Explorer it(body.shape, TopAbs_FACE); it.More(); it.Next()) ++faces;
  // Best of `repeat` runs from shapes in memory: stage times of the fastest.
  ContactsResult best;
  double best_total = 1e300;
  for (int r = 0; r < repeat; ++r) {
    const double start = now();
    ContactsResult result = find_contacts(read.assembly, ContactOptions{});
    const double total = now() - start;
    if (!result.status.ok()) {
      std::printf("{\"file\": \"%s\", \"error\": \"%s\"}\n", path.c_str(), result.status.describe().c_str());
      return 1;
    }
    if (total < best_total) best_total = total, best = std::move(result);
  }
  std::printf(
      "{\"file\": \"%s\", \"bodies\": %zu, \"faces\": %zu, \"contacts\": %zu, \"body_pairs\": %zu, "
      "\"candidates\": %zu, \"read\": %.6f, \"partitions\": %.6f, \"broad_phase\": %.6f, "
      "\"candidates_time\": %.6f, \"area\": %.6f, \"total\": %.6f, \"peak_rss_mb\": %.1f}\n",
      path.c_str(), read.assembly.bodies.size(), faces, best.contacts.size(), best.body_pairs.size(),
      best.candidates, read_seconds, best.times.partitions, best.times.broad_phase, best.times.candidates,
      best.times.area, best_total, peak_rss_kb() / 1024.0);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  int repeat = 5;
  std::vector<std::string> files;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--repeat") == 0 && i + 1 < argc) {
      repeat = std::max(1, std::atoi(argv[++i]));
    } else {
      files.emplace_back(argv[i]);
    }
  }
  if (files.empty()) {
    std::fprintf(stderr, "usage: %s [--repeat N] FILE.step...\n", argv[0]);
    return 2;
  }
  int failures = 0;
  for (const std::string& file : files) {
    std::fflush(stdout);
    const pid_t child = fork();
    if (child == 0) {
      const int rc = measure(file, repeat);
      std::fflush(stdout);  // _exit skips stdio flushing
      _exit(rc);
    }
    int status = 0;
    waitpid(child, &status, 0);
    failures += !(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  }
  return failures ? 1 : 0;
}
