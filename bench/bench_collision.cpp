// Collision and disassembly benchmarks (make bench): query latency of two
// ~100,000-triangle bodies near contact (the haptic loop's budget is 50 us at
// p99), tessellation of the motor, disassembly of the motor and of a grid of
// touching cubes. Prints one JSON object for bench/run_benchmarks.py.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>

#include "contactcore/bodies.h"
#include "contactcore/collision.h"
#include "contactcore/disassembly.h"
#include "contactcore/meshes.h"

using namespace contactcore;
using Clock = std::chrono::steady_clock;

namespace {

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

TaggedMesh sphere_mesh(double radius, std::size_t target_triangles) {
  const TopoDS_Shape sphere = BRepPrimAPI_MakeSphere(radius).Shape();
  const BodyPartitions partitions = partition_shape(sphere, Tolerances{});
  // Area 4 pi r^2 over the target count of near-equilateral triangles gives the edge length.
  MeshOptions options;
  options.deflection = radius * 1e-3;
  double edge = std::sqrt(4 * M_PI * radius * radius / target_triangles * 4 / std::sqrt(3.0));
  MeshResult result;
  for (int attempt = 0; attempt < 8; ++attempt) {
    options.max_edge_length = edge;
    result = mesh_body(sphere, partitions, options);
    if (result.mesh.triangles.size() >= target_triangles) break;
    edge *= 0.8;
  }
  return result.mesh;
}

struct Latency {
  double p50 = 0, p99 = 0, max = 0, per_second = 0;
};

Latency time_queries(CollisionPair& pair, QueryKind kind, const std::vector<RigidTransform>& placements) {
  QueryResult result;
  std::vector<double> micros;
  micros.reserve(placements.size());
  const RigidTransform fixed = RigidTransform::identity();
  // Warm-up: the scratch buffers reach their steady size.
  for (std::size_t i = 0; i < std::min<std::size_t>(100, placements.size()); ++i)
    pair.query(fixed, placements[i], kind, result);
  const auto all = Clock::now();
  for (const RigidTransform& place : placements) {
    const auto start = Clock::now();
    pair.query(fixed, place, kind, result);
    micros.push_back(std::chrono::duration<double, std::micro>(Clock::now() - start).count());
  }
  const double total = seconds_since(all);
  std::sort(micros.begin(), micros.end());
  Latency latency;
  latency.p50 = micros[micros.size() / 2];
  latency.p99 = micros[static_cast<std::size_t>(micros.size() * 0.99)];
  latency.max = micros.back();
  latency.per_second = placements.size() / total;
  return latency;
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
  const std::string motor_path = argc > 1 ? argv[1] : "Resources/samples/motor.step";
  const int grid_side = argc > 2 ? std::atoi(argv[2]) : 10;
  std::setvbuf(stdout, nullptr, _IONBF, 0);  // each section shows as soon as it is measured
  std::printf("{\n");

  // 1. Two spheres of radius 20, about 100,000 triangles each, near contact.
  const TaggedMesh sphere = sphere_mesh(20, 100000);
  const CollisionModelResult model = build_collision_model(sphere);
  if (!model.status.ok()) {
    std::fprintf(stderr, "%s\n", model.status.describe().c_str());
    return 1;
  }
  CollisionPair pair(model.model, model.model);
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> gap(-0.05, 0.2), wobble(-0.5, 0.5);
  std::vector<RigidTransform> placements;
  for (int i = 0; i < 5000; ++i) {
    // B beside A along a random-ish direction near +x, surfaces between 0.05 mm inside and 0.2 mm apart.
    const double d = 40 + gap(rng);
    double dx = 1, dy = 0.1 * wobble(rng), dz = 0.1 * wobble(rng);
    const double n = std::sqrt(dx * dx + dy * dy + dz * dz);
    placements.push_back(RigidTransform::translated(d * dx / n, d * dy / n, d * dz / n));
  }
  const Latency distance = time_queries(pair, QueryKind::Distance, placements);
  const Latency intersect = time_queries(pair, QueryKind::Intersect, placements);
  const Latency penetration = time_queries(pair, QueryKind::Penetration, placements);
  std::printf("  \"collision\": {\"triangles\": %zu,\n", sphere.triangles.size());
  for (auto [name, l] : {std::pair<const char*, Latency>{"distance", distance}, {"intersect", intersect},
                         {"penetration", penetration}})
    std::printf("    \"%s\": {\"p50_us\": %.2f, \"p99_us\": %.2f, \"max_us\": %.1f, \"per_second\": %.0f},\n", name,
                l.p50, l.p99, l.max, l.per_second);
  std::printf("    \"queries\": %zu},\n", placements.size());

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
