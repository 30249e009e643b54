// Collision and disassembly benchmarks (make bench): query latency of two
// ~100,000-triangle bodies near contact (the haptic loop's budget is 50 us at
// p99), tessellation of the motor, disassembly of the motor and of a grid of
// touching cubes. Prints one JSON object for bench/run_benchmarks.py.
#include <algorithm>
#include <array>
#include <chrono>
#include <ctime>
#include <cmath>
#include <map>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include <BRepPrimAPI_MakeBox.hxx>

#include "contactcore/bodies/bodies.h"
#include "contactcore/simulation/collision.h"
#include "contactcore/simulation/disassembly.h"
#include "contactcore/simulation/meshes.h"

using namespace contactcore;
using Clock = std::chrono::steady_clock;

namespace {

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// A geodesic sphere: each face of an icosahedron cut into n x n triangles, projected on the
// sphere, vertices shared (watertight), n the smallest giving the target count (20 n^2). OCCT's
// BRepMesh would need a deflection of about 7e-4 mm for 100,000 triangles on this sphere, which
// takes minutes; the queries only need a closed mesh of that size with near-equilateral triangles.
TaggedMesh sphere_mesh(double radius, std::size_t target_triangles) {
  const double t = (1 + std::sqrt(5.0)) / 2;
  const std::array<std::array<double, 3>, 12> corners{{{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                                                       {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                                                       {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}}};
  const int faces[20][3] = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                            {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                            {3, 8, 9},  {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  int n = 1;
  while (20u * n * n < target_triangles) ++n;
  TaggedMesh mesh;
  std::map<std::array<long long, 3>, int> index;  // shared vertices, keyed by rounded position
  auto vertex = [&](const std::array<double, 3>& a, const std::array<double, 3>& b, const std::array<double, 3>& c,
                    int i, int j) {
    // Point (i, j) of the face's barycentric grid, on the sphere.
    const double u = static_cast<double>(i) / n, v = static_cast<double>(j) / n, w = 1 - u - v;
    std::array<double, 3> p{};
    for (int k = 0; k < 3; ++k) p[k] = w * a[k] + u * b[k] + v * c[k];
    const double length = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    for (double& x : p) x *= radius / length;
    const std::array<long long, 3> key{std::llround(p[0] * 1e7), std::llround(p[1] * 1e7), std::llround(p[2] * 1e7)};
    const auto [it, added] = index.emplace(key, static_cast<int>(mesh.vertices.size()));
    if (added) mesh.vertices.push_back(p);
    return it->second;
  };
  for (const auto& f : faces) {
    const auto &a = corners[f[0]], &b = corners[f[1]], &c = corners[f[2]];
    for (int i = 0; i < n; ++i)
      for (int j = 0; i + j < n; ++j) {
        const int p0 = vertex(a, b, c, i, j), p1 = vertex(a, b, c, i + 1, j), p2 = vertex(a, b, c, i, j + 1);
        mesh.triangles.push_back({p0, p1, p2});
        if (i + j + 1 < n) mesh.triangles.push_back({p1, vertex(a, b, c, i + 1, j + 1), p2});
      }
  }
  mesh.triangle_face.assign(mesh.triangles.size(), 1);
  mesh.triangle_partition.assign(mesh.triangles.size(), 0);
  mesh.partition_count = 1;
  return mesh;
}

struct Latency {
  double p50 = 0, p99 = 0, max = 0, per_second = 0;
  double cpu_p50 = 0, cpu_p99 = 0;  // the calling thread's CPU time: what the query costs on a busy machine
  double bv_tests = 0, triangle_tests = 0;  // per query, mean: the work, whatever the machine's load
  double bv_tests_p99 = 0;
};

double thread_cpu_micros() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return t.tv_sec * 1e6 + t.tv_nsec / 1e3;
}

Latency time_queries(CollisionPair& pair, QueryKind kind, const std::vector<RigidTransform>& placements) {
  QueryResult result;
  std::vector<double> micros, cpu;
  micros.reserve(placements.size());
  cpu.reserve(placements.size());
  const RigidTransform fixed = RigidTransform::identity();
  // Warm-up: the scratch buffers reach their steady size.
  for (std::size_t i = 0; i < std::min<std::size_t>(100, placements.size()); ++i)
    pair.query(fixed, placements[i], kind, result);
  const auto all = Clock::now();
  const CollisionPair::Counts before = pair.counts();
  std::vector<double> tests;
  tests.reserve(placements.size());
  for (const RigidTransform& place : placements) {
    const std::size_t tests_before = pair.counts().bv_tests;
    const double cpu_start = thread_cpu_micros();
    const auto start = Clock::now();
    pair.query(fixed, place, kind, result);
    micros.push_back(std::chrono::duration<double, std::micro>(Clock::now() - start).count());
    cpu.push_back(thread_cpu_micros() - cpu_start);
    tests.push_back(static_cast<double>(pair.counts().bv_tests - tests_before));
  }
  const CollisionPair::Counts after = pair.counts();
  const double total = seconds_since(all);
  std::sort(micros.begin(), micros.end());
  std::sort(cpu.begin(), cpu.end());
  Latency latency;
  latency.p50 = micros[micros.size() / 2];
  latency.p99 = micros[static_cast<std::size_t>(micros.size() * 0.99)];
  latency.max = micros.back();
  latency.per_second = placements.size() / total;
  latency.cpu_p50 = cpu[cpu.size() / 2];
  latency.cpu_p99 = cpu[static_cast<std::size_t>(cpu.size() * 0.99)];
  latency.bv_tests = static_cast<double>(after.bv_tests - before.bv_tests) / placements.size();
  latency.triangle_tests = static_cast<double>(after.triangle_tests - before.triangle_tests) / placements.size();
  std::sort(tests.begin(), tests.end());
  latency.bv_tests_p99 = tests[static_cast<std::size_t>(tests.size() * 0.99)];
  return latency;
}

void print_latency(const char* name, const Latency& l) {
  std::printf("    \"%s\": {\"p50_us\": %.2f, \"p99_us\": %.2f, \"max_us\": %.1f, \"per_second\": %.0f, "
              "\"cpu_p50_us\": %.2f, \"cpu_p99_us\": %.2f, \"bv_tests\": %.0f, \"bv_tests_p99\": %.0f, "
              "\"triangle_tests\": %.1f},\n",
              name, l.p50, l.p99, l.max, l.per_second, l.cpu_p50, l.cpu_p99, l.bv_tests, l.bv_tests_p99,
              l.triangle_tests);
}

struct Trajectory {
  std::vector<RigidTransform> placements;
  double max_step = 0, max_turn = 0;  // largest move of B's centre (mm) and turn (rad) in one tick
  int crossing = 0;                   // ticks with the surfaces' gap below 0 (meshes crossing)
};

// B's centre on a circle of radius 40 + gap about A's centre (A at the origin, radius 20), sliding
// 20 mm/s along it in a tilted plane; the gap swings between -0.05 and 0.2 mm every 2 s; B turns
// about its own axis at 0.3 rad/s. At 1 kHz: 0.02 mm and 0.0003 rad per tick, a hand moving slowly
// and carefully near contact.
Trajectory trajectory(int ticks) {
  Trajectory path;
  const double dt = 1e-3, slide = 20.0 / 40.0, spin = 0.3;  // rad/s of the centre about A, of B about itself
  std::array<double, 3> previous{};
  for (int i = 0; i < ticks; ++i) {
    const double t = i * dt;
    const double gap = 0.075 + 0.125 * std::sin(2 * M_PI * t / 2.0);
    const double r = 40 + gap, angle = slide * t, tilt = 0.3;
    RigidTransform place;
    place.translation = {r * std::cos(angle), r * std::sin(angle) * std::cos(tilt), r * std::sin(angle) * std::sin(tilt)};
    const double c = std::cos(spin * t), s = std::sin(spin * t);
    const double axis[3] = {0.6, 0.0, 0.8};  // unit
    // Rodrigues: R = c I + s [axis]x + (1 - c) axis axis^T
    for (int row = 0; row < 3; ++row)
      for (int col = 0; col < 3; ++col) {
        double value = (1 - c) * axis[row] * axis[col] + (row == col ? c : 0);
        const int cross[3][3] = {{0, -3, 2}, {3, 0, -1}, {-2, 1, 0}};  // +-(k+1): [axis]x entries
        const int k = cross[row][col];
        if (k != 0) value += s * (k > 0 ? axis[k - 1] : -axis[-k - 1]);
        place.rotation[3 * row + col] = value;
      }
    if (i > 0) {
      const double dx = place.translation[0] - previous[0], dy = place.translation[1] - previous[1],
                   dz = place.translation[2] - previous[2];
      path.max_step = std::max(path.max_step, std::sqrt(dx * dx + dy * dy + dz * dz));
    }
    previous = place.translation;
    if (gap < 0) ++path.crossing;
    path.placements.push_back(place);
  }
  path.max_turn = spin * dt;
  return path;
}

Assembly cube_grid(int side) {
  Assembly assembly;
  for (int x = 0; x < side; ++x)
    for (int y = 0; y < side; ++y)
      for (int z = 0; z < side; ++z) {
        const std::string name = "Cube_" + std::to_string(x) + "_" + std::to_string(y) + "_" + std::to_string(z);
        assembly.bodies.push_back({name, name, BRepPrimAPI_MakeBox(gp_Pnt(10 * x, 10 * y, 10 * z), 10, 10, 10).Shape()});
      }
  return assembly;
}

}  // namespace

int main(int argc, char** argv) {
  // --collision-only [TRIANGLES]: the sphere queries alone (for profiling them), optionally on
  // spheres of another size.
  const bool collision_only = argc > 1 && std::string(argv[1]) == "--collision-only";
  const std::size_t sphere_triangles = collision_only && argc > 2 ? std::stoul(argv[2]) : 100000;
  const std::string motor_path = argc > 1 && !collision_only ? argv[1] : "Resources/samples/motor.step";
  const int grid_side = argc > 2 && !collision_only ? std::atoi(argv[2]) : 10;
  std::setvbuf(stdout, nullptr, _IONBF, 0);  // each section shows as soon as it is measured
  std::printf("{\n");

  // 1. Two spheres of radius 20, about 100,000 triangles each, near contact.
  const TaggedMesh sphere = sphere_mesh(20, sphere_triangles);
  const CollisionModelResult model = build_collision_model(sphere);
  if (!model.status.ok()) {
    std::fprintf(stderr, "%s\n", model.status.describe().c_str());
    return 1;
  }
  CollisionPair pair(model.model, model.model);
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> gap(-0.05, 0.2), wobble(-0.5, 0.5);
  std::vector<RigidTransform> placements, apart;
  for (int i = 0; i < 5000; ++i) {
    // B beside A along a random-ish direction near +x, surfaces between 0.05 mm inside and 0.2 mm apart.
    const double g = gap(rng);
    const double d = 40 + g;
    double dx = 1, dy = 0.1 * wobble(rng), dz = 0.1 * wobble(rng);
    const double n = std::sqrt(dx * dx + dy * dy + dz * dz);
    placements.push_back(RigidTransform::translated(d * dx / n, d * dy / n, d * dz / n));
    if (g > 0) apart.push_back(placements.back());
  }
  // Cold: every query on its own (no warm start), as a first contact or a jump would be.
  pair.set_warm_start(false);
  const Latency distance = time_queries(pair, QueryKind::Distance, placements);
  const Latency distance_apart = time_queries(pair, QueryKind::Distance, apart);
  const Latency intersect = time_queries(pair, QueryKind::Intersect, placements);
  const Latency intersect_apart = time_queries(pair, QueryKind::Intersect, apart);
  const Latency penetration = time_queries(pair, QueryKind::Penetration, placements);
  std::printf("  \"collision\": {\"triangles\": %zu, \"watertight\": %s,\n", sphere.triangles.size(),
              mesh_quality(sphere).watertight ? "true" : "false");
  for (auto [name, l] : {std::pair<const char*, Latency>{"distance", distance}, {"distance_apart", distance_apart},
                         {"intersect", intersect}, {"intersect_apart", intersect_apart}, {"penetration", penetration}})
    print_latency(name, l);
  std::printf("    \"queries\": %zu},\n", placements.size());

  // The haptic loop: B moved at 1 kHz along a continuous path, sliding around A while it approaches,
  // touches and sinks in (the gap between the surfaces as in the cold placements), turning about its
  // own axis; the pair keeps its warm start from tick to tick.
  const Trajectory path = trajectory(5000);
  pair.set_warm_start(true);
  const Latency distance_path = time_queries(pair, QueryKind::Distance, path.placements);
  const Latency intersect_path = time_queries(pair, QueryKind::Intersect, path.placements);
  pair.set_front_tracking(false);  // the warm start alone (the cached pair's neighbourhood), for comparison
  const Latency intersect_path_no_front = time_queries(pair, QueryKind::Intersect, path.placements);
  const Latency distance_path_no_front = time_queries(pair, QueryKind::Distance, path.placements);
  pair.set_front_tracking(true);
  const Latency penetration_path = time_queries(pair, QueryKind::Penetration, path.placements);
  pair.set_warm_start(false);
  const Latency distance_path_cold = time_queries(pair, QueryKind::Distance, path.placements);
  const Latency intersect_path_cold = time_queries(pair, QueryKind::Intersect, path.placements);
  std::printf("  \"trajectory\": {\"ticks\": %zu, \"rate_hz\": 1000, \"max_step_mm\": %.4f, \"max_turn_rad\": %.5f, "
              "\"crossing_ticks\": %d,\n",
              path.placements.size(), path.max_step, path.max_turn, path.crossing);
  for (auto [name, l] : {std::pair<const char*, Latency>{"distance", distance_path}, {"intersect", intersect_path},
                         {"intersect_no_front", intersect_path_no_front}, {"distance_no_front", distance_path_no_front},
                         {"penetration", penetration_path}, {"distance_cold", distance_path_cold},
                         {"intersect_cold", intersect_path_cold}})
    print_latency(name, l);
  std::printf("    \"queries\": %zu}%s\n", path.placements.size(), collision_only ? "" : ",");
  if (collision_only) {
    std::printf("}\n");
    return 0;
  }

  // 2. The motor: tessellation (deflection 0.1) and disassembly.
  const AssemblyResult motor = read_step(motor_path);
  if (!motor.status.ok()) {
    std::fprintf(stderr, "%s\n", motor.status.describe().c_str());
    return 1;
  }
  std::vector<BodyPartitions> partitions;
  for (const Body& body : motor.assembly.bodies) partitions.push_back(partition_shape(body.shape, Tolerances{}));
  double best_mesh = 1e9;
  std::size_t triangles = 0;
  for (int repeat = 0; repeat < 3; ++repeat) {
    triangles = 0;
    const auto start = Clock::now();
    for (std::size_t i = 0; i < partitions.size(); ++i)
      triangles += mesh_body(motor.assembly.bodies[i].shape, partitions[i], MeshOptions{}).mesh.triangles.size();
    best_mesh = std::min(best_mesh, seconds_since(start));
  }
  std::printf("  \"motor_tessellation\": {\"seconds\": %.4f, \"triangles\": %zu},\n", best_mesh, triangles);
  auto start = Clock::now();
  const DisassemblyResult motor_plan = disassemble(motor.assembly, ContactOptions{}, MeshOptions{}, DisassemblyOptions{});
  std::printf("  \"motor_disassembly\": {\"seconds\": %.3f, \"steps\": %zu, \"complete\": %s},\n", seconds_since(start),
              motor_plan.steps.size(), motor_plan.complete ? "true" : "false");

  // 3. A grid of touching cubes.
  const Assembly grid = cube_grid(grid_side);
  start = Clock::now();
  const DisassemblyResult grid_plan = disassemble(grid, ContactOptions{}, MeshOptions{}, DisassemblyOptions{});
  std::printf("  \"grid_disassembly\": {\"parts\": %zu, \"seconds\": %.3f, \"steps\": %zu, \"complete\": %s}\n",
              grid.bodies.size(), seconds_since(start), grid_plan.steps.size(), grid_plan.complete ? "true" : "false");
  std::printf("}\n");
  return 0;
}
