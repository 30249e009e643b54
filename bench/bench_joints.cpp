// Joints stage benchmark: for each STEP file, the time to derive every pair's
// joint (find_joints), and to choose the ground (largest volume) and solve the
// assembly's mobility (passive spins, rigid groups, per-component solve),
// best of N runs on contacts found once. One JSON object per line; the
// growth over the bolted grids shows whether the solve stays near linear.
//
//   bench_joints [--repeat N] FILE.step...
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "contactcore/joints/joints.h"

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
  const AssemblyResult read = read_step(path);
  if (!read.status.ok()) {
    std::printf("{\"file\": \"%s\", \"error\": \"%s\"}\n", path.c_str(), read.status.describe().c_str());
    return 1;
  }
  double start = now();
  const ContactsResult contacts = find_contacts(read.assembly, ContactOptions{});
  const double contacts_seconds = now() - start;
  if (!contacts.status.ok()) {
    std::printf("{\"file\": \"%s\", \"error\": \"%s\"}\n", path.c_str(), contacts.status.describe().c_str());
    return 1;
  }
  double best_joints = 1e300, best_mobility = 1e300;
  JointsResult joints;
  MobilityResult mobility;
  MobilityOptions options;  // the default ground: the largest body by volume
  for (int r = 0; r < repeat; ++r) {
    start = now();
    joints = find_joints(read.assembly, contacts);
    best_joints = std::min(best_joints, now() - start);
    start = now();
    mobility = assembly_mobility(read.assembly, contacts, joints, options);
    best_mobility = std::min(best_mobility, now() - start);
  }
  std::printf(
      "{\"file\": \"%s\", \"bodies\": %zu, \"contacts\": %zu, \"joints\": %zu, \"dof\": %d, \"passive\": %d, "
      "\"groups\": %zu, \"components\": %zu, \"contacts_time\": %.6f, "
      "\"joints_time\": %.6f, \"mobility_time\": %.6f, \"peak_rss_mb\": %.1f}\n",
      path.c_str(), read.assembly.bodies.size(), contacts.contacts.size(), joints.joints.size(), mobility.dof,
      mobility.passive, mobility.groups.size(), mobility.components.size(), contacts_seconds,
      best_joints, best_mobility, peak_rss_kb() / 1024.0);
  std::fflush(stdout);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  int repeat = 3;
  std::vector<std::string> files;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--repeat") == 0 && i + 1 < argc) repeat = std::max(1, std::atoi(argv[++i]));
    else files.push_back(argv[i]);
  }
  if (files.empty()) {
    std::fprintf(stderr, "usage: bench_joints [--repeat N] FILE.step...\n");
    return 2;
  }
  int failures = 0;
  for (const std::string& file : files) failures += measure(file, repeat);
  return failures ? 1 : 0;
}
