// Haptic trial benchmark (stage 6), printing a Markdown table:
//  1. incremental contact update of the moving part (real-time contacts from
//     partitions) against the batch contact stage on the same assembly;
//  2. servo step time p50/p99 of the scripted insertion of the motor's axis
//     in lockstep, with collision models refined to >= 100,000 triangles;
//  3. the loop on its own thread for 10 s: rate, jitter, overruns;
//  4. the proxy in contact: the collision stage's contact query (the proxy's
//     constraint source) with the Axis seated and every partition switched on
//     (in contact with all its neighbours), and the ticks of a trial where the
//     Axis is pushed sideways in its bores, then pulled out (thread CPU time);
//     and Screw-1 seated, the hand pushing 0.2 mm into the seat and circling
//     0.3 mm sideways (bench_realtime_loop.py's hand), in lockstep: its ticks'
//     CPU time and the contact queries each makes.
//
//   bench_haptics [--seconds S] [--triangles N] [--proxy-only | --screw-only] [--closed-forms | --meshes-only] [MOTOR.step]
// (--proxy-only: sections 4 and 5; --screw-only: section 5; --closed-forms: the
// trial scenes with SceneOptions::analytic on, the default; --meshes-only: off)
#include <time.h>

#include <algorithm>
#include <cmath>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include <BRepTools.hxx>

#include "bench_timing.h"
#include "contactcore/contacts/contacts.h"
#include "contactcore/haptics/spacemouse.h"
#include "contactcore/haptics/trial.h"

using namespace contactcore;
using namespace contactcore::haptics;

namespace {

double now() { return steady_seconds(); }

double cpu_seconds() { return bench::thread_cpu_seconds(); }
using bench::percentile;

TrialScript insertion() {
  TrialScript s;
  s.start = {0, Vec3(0.25, -0.2, 30), Vec3(0.4, -0.3, 0)};
  s.hand = {{0.0, Vec3(0.25, -0.2, 30), Vec3(0.4, -0.3, 0)},
            {2.5, Vec3(0.3, 0.2, 0), Vec3(-0.5, 0.4, 2)},
            {3.0, Vec3(0, 0, 0), Vec3(0, 0, 0)}};
  return s;
}

// The loop's collision query, counted: contact queries per tick and their CPU time.
class CountingQuery final : public CollisionQuery {
 public:
  explicit CountingQuery(CollisionQuery& inner) : inner_(inner) {}
  bool collides(const Pose& pose, int group) noexcept override { return inner_.collides(pose, group); }
  int contacts(const Pose& pose, int group, double reach, ContactPoint* out, int capacity) noexcept override {
    ++queries;
    const double t0 = bench::thread_cpu_seconds();
    const int n = inner_.contacts(pose, group, reach, out, capacity);
    query_seconds.push_back(bench::thread_cpu_seconds() - t0);
    return n;
  }
  double radius_about(const Vec3& centre) const noexcept override { return inner_.radius_about(centre); }
  long queries = 0;
  std::vector<double> query_seconds;

 private:
  CollisionQuery& inner_;
};

// bench_realtime_loop.py's hand: the part starts seated, the hand pushes 0.2 mm
// into the seat and circles 0.3 mm sideways (keys every 50 ms).
std::vector<HandKey> pushing_hand(double seconds, const Vec3& centre) {
  std::vector<HandKey> keys;
  const int steps = static_cast<int>(std::lround(seconds / 0.05));
  for (int i = 0; i <= steps; ++i) {
    const double t = i * 0.05;
    keys.push_back({t, offset_pose(Vec3(0.3 * std::sin(2 * t), 0.3 * std::cos(2 * t), -0.2), Vec3::Zero(), centre)});
  }
  return keys;
}

std::string load_average() {
  std::ifstream in("/proc/loadavg");
  std::string a;
  in >> a;
  return a;
}

}  // namespace

int main(int argc, char** argv) {
  std::string path = std::string(CONTACTS_SAMPLES) + "/motor.step";
  double seconds = 10;
  std::size_t want_triangles = 100000;
  bool proxy_only = false, screw_only = false;
  SceneOptions scene_options;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--seconds") && i + 1 < argc) seconds = std::atof(argv[++i]);
    else if (!std::strcmp(argv[i], "--triangles") && i + 1 < argc) want_triangles = std::atol(argv[++i]);
    else if (!std::strcmp(argv[i], "--proxy-only")) proxy_only = true;
    else if (!std::strcmp(argv[i], "--screw-only")) proxy_only = screw_only = true;
    else if (!std::strcmp(argv[i], "--meshes-only")) scene_options.analytic = false;
    else if (!std::strcmp(argv[i], "--closed-forms")) scene_options.analytic = true;
    else path = argv[i];
  }
  const AssemblyResult read = read_step(path);
  if (!read.status.ok()) {
    std::fprintf(stderr, "%s\n", read.status.describe().c_str());
    return 1;
  }
  std::printf("Machine load average at start: %s (2 cores shared)\n\n", load_average().c_str());

  // 1. Incremental contact update vs the batch stage.
  Status status;
  std::printf("Contact queries: %s\n\n", scene_options.analytic
                                              ? "closed forms between analytic partitions, meshes for the rest (the default)"
                                              : "meshes only (--meshes-only)");
  auto scene = TrialScene::build(read.assembly, "Axis", scene_options, status);
  if (!scene) {
    std::fprintf(stderr, "%s\n", status.describe().c_str());
    return 1;
  }
  if (!proxy_only) {
  std::vector<double> batch;
  for (int r = 0; r < 5; ++r) {
    const double t0 = now();
    const ContactsResult all = find_contacts(read.assembly, ContactOptions{});
    batch.push_back(now() - t0);
  }
  std::vector<LiveContact> live(256);
  std::vector<double> updates;
  const int samples = 20000;
  int found = 0;
  for (int i = 0; i < samples; ++i) {
    const double z = 30.0 * (1.0 - double(i) / samples);
    const Pose pose = offset_pose(Vec3(0.1 * std::sin(i * 0.01), 0, z), Vec3(0, 0, 0.001 * i), scene->centre());
    const double t0 = now();
    found += scene->contacts().update(pose, live.data(), 256);
    updates.push_back(now() - t0);
  }
  const double batch_ms = *std::min_element(batch.begin(), batch.end()) * 1e3;
  std::printf("| incremental contacts (motor, Axis moving) | p50 | p99 | max | batch stage (all pairs) | ratio batch/p50 |\n");
  std::printf("|---|---|---|---|---|---|\n");
  std::printf("| update of the moving part, %d poses along the insertion (%.1f contacts each) | %.2f us | %.2f us | %.1f us | %.1f ms | %.0fx |\n\n",
              samples, double(found) / samples, percentile(updates, 50) * 1e6, percentile(updates, 99) * 1e6,
              *std::max_element(updates.begin(), updates.end()) * 1e6, batch_ms,
              batch_ms * 1e3 / (percentile(updates, 50) * 1e6));

  // 2. Servo steps with >= 100,000 triangles of collision models.
  SceneOptions fine = scene_options;
  double deflection = 0.01;
  std::unique_ptr<TrialScene> dense;
  for (int attempt = 0; attempt < 8; ++attempt) {
    fine.deflection = deflection;
    fine.angle = 0.1;
    for (const Body& b : read.assembly.bodies) BRepTools::Clean(b.shape);
    dense = TrialScene::build(read.assembly, "Axis", fine, status);
    if (!dense || dense->collision().triangle_count() >= want_triangles) break;
    deflection *= 0.5;
  }
  if (!dense) {
    std::fprintf(stderr, "%s\n", status.describe().c_str());
    return 1;
  }
  TrialOptions options;
  const TrialResult lockstep = run_trial(*dense, insertion(), options, false);
  // The same steps timed in CPU time of this thread: the step's own cost,
  // without the waits of a machine shared with other jobs.
  std::vector<double> cpu_steps;
  {
    const Vec3 c = dense->centre();
    const TrialScript script = insertion();
    std::vector<HandKey> keys;
    for (const ScriptKey& k : script.hand)
      keys.push_back({k.t, offset_pose(k.translate, Vec3(rad(k.rotate_deg.x()), rad(k.rotate_deg.y()), rad(k.rotate_deg.z())), c)});
    const Pose start = keys.front().pose;
    SimulatedHand hand(HandScript(keys), HandParameters{}, c, start);
    ServoConfig config;
    config.centre = c;
    config.lockstep = true;
    ServoLoop loop(hand, config, start);
    loop.set_joint_finder(&dense->finder());
    loop.set_collision(&dense->collision());
    for (int i = 0; i < 4500; ++i) {
      const double t0 = cpu_seconds();
      loop.step_lockstep();
      cpu_steps.push_back(cpu_seconds() - t0);
    }
  }
  std::printf("| servo step, scripted insertion in lockstep | triangles (moving part) | ticks | p50 | p99 | max | steps over 1 ms | final offset |\n");
  std::printf("|---|---|---|---|---|---|---|---|\n");
  std::printf("| motor, deflection %.4f mm, wall clock | %zu (%zu) | %llu | %.1f us | %.1f us | %.0f us | %llu | %.1e mm |\n",
              deflection, dense->collision().triangle_count(), dense->collision().moving_triangle_count(),
              static_cast<unsigned long long>(lockstep.ticks), lockstep.step_p50_us, lockstep.step_p99_us,
              lockstep.step_max_us, static_cast<unsigned long long>(lockstep.overruns), lockstep.final_translate.norm());
  std::size_t cpu_over = 0;
  for (double t : cpu_steps) cpu_over += t > 1e-3;
  std::printf("| the same steps, thread CPU time | | %zu | %.1f us | %.1f us | %.0f us | %zu | |\n\n", cpu_steps.size(),
              percentile(cpu_steps, 50) * 1e6, percentile(cpu_steps, 99) * 1e6,
              *std::max_element(cpu_steps.begin(), cpu_steps.end()) * 1e6, cpu_over);

  // 3. The loop on its thread: the hand keeps inserting and extracting.
  std::printf("| loop thread, %.0f s, insert/extract every second | ticks | rate | jitter (sd of period) | step p50 | step p99 | overruns |\n", seconds);
  std::printf("|---|---|---|---|---|---|---|\n");
  for (int priority : {0, 80}) {
    std::vector<HandKey> keys;
    const Vec3 c = dense->centre();
    for (int k = 0; k <= static_cast<int>(seconds / 2) + 1; ++k) {
      keys.push_back({2.0 * k, offset_pose(Vec3(0, 0, 30), Vec3::Zero(), c)});
      keys.push_back({2.0 * k + 1.0, offset_pose(Vec3(0, 0, 0), Vec3::Zero(), c)});
    }
    SimulatedHand hand(HandScript(keys), HandParameters{}, c, offset_pose(Vec3(0, 0, 30), Vec3::Zero(), c));
    ServoConfig config;
    config.centre = c;
    config.realtime_priority = priority;
    ServoLoop loop(hand, config, offset_pose(Vec3(0, 0, 30), Vec3::Zero(), c));
    loop.set_joint_finder(&dense->finder());
    loop.set_collision(&dense->collision());
    loop.start();
    std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
    loop.stop();
    if (priority > 0 && !loop.got_realtime_priority()) {
      std::printf("| SCHED_FIFO %d refused (no CAP_SYS_NICE) | | | | | | |\n", priority);
      continue;
    }
    std::printf("| motor, %zu triangles, %s | %llu | %.1f Hz | %.1f us | %.1f us | %.1f us | %llu |\n",
                dense->collision().triangle_count(), priority > 0 ? "SCHED_FIFO 80" : "normal priority",
                static_cast<unsigned long long>(loop.ticks()), loop.rate_hz(), loop.jitter_us(),
                loop.step_percentile_us(50), loop.step_percentile_us(99),
                static_cast<unsigned long long>(loop.overruns()));
  }
  std::printf("\n");
  }  // !proxy_only

  // 4. The proxy in contact (default scene: deflection 0.01 mm).
  if (!screw_only) {
    ContactPoint contacts[kMaxContacts];
    std::vector<double> query_cpu;
    int touching = 0;
    for (int i = 0; i < 2000; ++i) {
      const Pose pose = offset_pose(Vec3(0, 0, 0.001 * (i % 10)), Vec3(0, 0, 0.01 * i), scene->centre());
      const double t0 = cpu_seconds();
      touching += scene->collision().contacts(pose, -1, 0.2, contacts, kMaxContacts);
      query_cpu.push_back(cpu_seconds() - t0);
    }
    TrialScript sideways;
    sideways.start = {0, Vec3::Zero(), Vec3::Zero()};
    sideways.hand = {{0.0, Vec3::Zero(), Vec3::Zero()}, {0.5, Vec3(20, 0, 0), Vec3::Zero()},
                     {1.0, Vec3(20, 0, 0), Vec3::Zero()}, {2.0, Vec3(20, 0, 90), Vec3::Zero()}};
    const Vec3 c = scene->centre();
    std::vector<HandKey> keys;
    for (const ScriptKey& k : sideways.hand) keys.push_back({k.t, offset_pose(k.translate, Vec3::Zero(), c)});
    SimulatedHand hand(HandScript(keys), HandParameters{}, c, Pose::Identity());
    ServoConfig config;
    config.centre = c;
    config.lockstep = true;
    config.inertia_per_mass = scene->inertia_per_mass();
    ServoLoop loop(hand, config, Pose::Identity());
    loop.set_joint_finder(&scene->finder());
    loop.set_collision(&scene->collision());
    std::vector<double> tick_cpu, contact_tick_cpu;
    for (int i = 0; i < 3000; ++i) {
      const double t0 = cpu_seconds();
      loop.step_lockstep();
      const double dt = cpu_seconds() - t0;
      tick_cpu.push_back(dt);
      if (loop.last().contact_count > 0 || loop.last().blocked) contact_tick_cpu.push_back(dt);
    }
    std::printf("| proxy in contact (motor, thread CPU time) | samples | p50 | p99 | max |\n");
    std::printf("|---|---|---|---|---|\n");
    std::printf("| contact query, Axis seated, all partitions on (%.1f contacts each) | %zu | %.1f us | %.1f us | %.0f us |\n",
                double(touching) / query_cpu.size(), query_cpu.size(), percentile(query_cpu, 50) * 1e6,
                percentile(query_cpu, 99) * 1e6, *std::max_element(query_cpu.begin(), query_cpu.end()) * 1e6);
    std::printf("| servo tick, Axis pushed sideways in its bores then pulled out, all ticks | %zu | %.1f us | %.1f us | %.0f us |\n",
                tick_cpu.size(), percentile(tick_cpu, 50) * 1e6, percentile(tick_cpu, 99) * 1e6,
                *std::max_element(tick_cpu.begin(), tick_cpu.end()) * 1e6);
    if (!contact_tick_cpu.empty())
      std::printf("| the same, ticks with an active contact or stop | %zu | %.1f us | %.1f us | %.0f us |\n",
                  contact_tick_cpu.size(), percentile(contact_tick_cpu, 50) * 1e6, percentile(contact_tick_cpu, 99) * 1e6,
                  *std::max_element(contact_tick_cpu.begin(), contact_tick_cpu.end()) * 1e6);
    std::printf("\n");
  }

  // 5. Screw-1 seated, the realtime bench's pushing hand, in lockstep.
  {
    auto screw = TrialScene::build(read.assembly, "Screw-1", scene_options, status);
    if (!screw) {
      std::fprintf(stderr, "%s\n", status.describe().c_str());
      return 1;
    }
    const Vec3 c = screw->centre();
    SimulatedHand hand(HandScript(pushing_hand(3.0, c)), HandParameters{}, c, Pose::Identity());
    ServoConfig config;
    config.centre = c;
    config.lockstep = true;
    config.inertia_per_mass = screw->inertia_per_mass();
    CountingQuery counted(screw->collision());
    ServoLoop loop(hand, config, Pose::Identity());
    loop.set_joint_finder(&screw->finder());
    loop.set_collision(&counted);
    std::vector<double> tick_cpu;
    const int ticks = 3000;
    int engaged = 0;
    counted.query_seconds.reserve(20 * ticks);
    for (int i = 0; i < ticks; ++i) {
      const double t0 = cpu_seconds();
      loop.step_lockstep();
      tick_cpu.push_back(cpu_seconds() - t0);
      engaged += loop.last().engaged;
    }
    std::printf("| Screw-1 seated, hand pushing 0.2 mm into the seat and circling 0.3 mm (lockstep, thread CPU time) "
                "| samples | p50 | p99 | max |\n");
    std::printf("|---|---|---|---|---|\n");
    std::printf("| servo tick (%.2f contact queries per tick, end-pose query skipped on %llu ticks, engaged %d of %d "
                "ticks) | %zu | %.1f us | %.1f us | %.0f us |\n",
                double(counted.queries) / ticks, static_cast<unsigned long long>(loop.end_checks_skipped()), engaged, ticks, tick_cpu.size(), percentile(tick_cpu, 50) * 1e6,
                percentile(tick_cpu, 99) * 1e6, *std::max_element(tick_cpu.begin(), tick_cpu.end()) * 1e6);
    if (!counted.query_seconds.empty())
      std::printf("| its contact queries | %zu | %.1f us | %.1f us | %.0f us |\n", counted.query_seconds.size(),
                  percentile(counted.query_seconds, 50) * 1e6, percentile(counted.query_seconds, 99) * 1e6,
                  *std::max_element(counted.query_seconds.begin(), counted.query_seconds.end()) * 1e6);
    const Vec3 end = loop.last().proxy * c - c;
    std::printf("| (final offset of the centre: %.6f, %.6f, %.6f mm) | | | | |\n\n", end.x(), end.y(), end.z());
  }
  std::printf("Machine load average at end: %s\n", load_average().c_str());
  return 0;
}
