// Partitions benchmark: contactcore::partition_shape (typing, recognition of
// free-form faces, extents, merging into maximal partitions) against OCCT's
// ShapeUpgrade_UnifySameDomain (what FreeCAD's removeSplitter runs: faces and
// edges unified), on the same bodies in the same run:
//   motor      Resources/samples/motor.step (skipped when absent)
//   press      ../shared/data/step/R08_presse_asm.step (skipped when absent)
//   plate10k   a generated 10,006-face plate: 5,000 holes, each bored as two
//              half-cylinder faces (built once, no Booleans)
// After the Google Benchmark run, prints a table: faces, our time (per body
// and per face), UnifySameDomain's time and the ratio.
//
//   bench_partitions [--data=DIR] [--samples=DIR] [Google Benchmark flags]
// DIR defaults: the CONTACTS_SHARED_DATA and CONTACTS_SAMPLES macros.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <BRepBndLib.hxx>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakePolygon.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepPrimAPI_MakePrism.hxx>
#include <ShapeUpgrade_UnifySameDomain.hxx>
#include <TopExp.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <gp_Circ.hxx>
#include <gp_Pln.hxx>

#include "contactcore/bodies/bodies.h"
#include "contactcore/partitions/partitions.h"

using namespace contactcore;

namespace {

#ifdef CONTACTS_SHARED_DATA
std::string shared_data_dir = CONTACTS_SHARED_DATA;
#else
std::string shared_data_dir = "../shared/data";
#endif
#ifdef CONTACTS_SAMPLES
std::string samples_dir = CONTACTS_SAMPLES;
#else
std::string samples_dir = "Resources/samples";
#endif

struct Case {
  std::string name;
  std::vector<TopoDS_Shape> bodies;
  Tolerances tolerances;  // default_tolerances of the whole case, as the contacts stage uses
  int faces = 0;
  int partitions = 0;     // ours, from a first run
  int unified_faces = 0;  // faces left by UnifySameDomain, from a first run
};

int face_count(const TopoDS_Shape& shape) {
  TopTools_IndexedMapOfShape faces;
  TopExp::MapShapes(shape, TopAbs_FACE, faces);
  return faces.Extent();
}

TopoDS_Shape unify_same_domain(const TopoDS_Shape& body) {
  ShapeUpgrade_UnifySameDomain unify(body, /*UnifyEdges=*/Standard_True, /*UnifyFaces=*/Standard_True,
                                     /*ConcatBSplines=*/Standard_False);
  unify.Build();
  return unify.Shape();
}

Case make_case(const std::string& name, std::vector<TopoDS_Shape> bodies) {
  Case c;
  c.name = name;
  c.bodies = std::move(bodies);
  Bnd_Box box;
  for (const TopoDS_Shape& body : c.bodies) {
    BRepBndLib::Add(body, box);
    c.faces += face_count(body);
  }
  c.tolerances = default_tolerances(box);
  for (const TopoDS_Shape& body : c.bodies) {
    c.partitions += static_cast<int>(partition_shape(body, c.tolerances).partitions.size());
    c.unified_faces += face_count(unify_same_domain(body));
  }
  return c;
}

// Bodies of a STEP file through the project's reader (XDE: instances placed).
bool read_bodies(const std::string& path, std::vector<TopoDS_Shape>& bodies) {
  if (!std::filesystem::exists(path)) {
    std::fprintf(stderr, "skipped: %s not found\n", path.c_str());
    return false;
  }
  const AssemblyResult read = read_step(path);
  if (!read.status.ok()) {
    std::fprintf(stderr, "skipped: %s\n", read.status.describe().c_str());
    return false;
  }
  for (const Body& body : read.assembly.bodies) bodies.push_back(body.shape);
  return !bodies.empty();
}

// A plate of columns x rows holes of radius 3 at pitch 10, 8 thick. Each hole
// wire is two half circles, so each bore is two half-cylinder faces: the
// split faces Booleans leave, built directly (a prism of a holed face).
TopoDS_Shape holed_plate(int columns, int rows) {
  const double pitch = 10, radius = 3, thickness = 8;
  const double width = columns * pitch, depth = rows * pitch;
  BRepBuilderAPI_MakePolygon outline(gp_Pnt(0, 0, 0), gp_Pnt(width, 0, 0), gp_Pnt(width, depth, 0),
                                     gp_Pnt(0, depth, 0), Standard_True);
  BRepBuilderAPI_MakeFace face(gp_Pln(gp::XOY()), outline.Wire());
  for (int i = 0; i < columns; ++i) {
    for (int j = 0; j < rows; ++j) {
      const gp_Circ circle(gp_Ax2(gp_Pnt((i + 0.5) * pitch, (j + 0.5) * pitch, 0), gp::DZ()), radius);
      BRepBuilderAPI_MakeWire hole(BRepBuilderAPI_MakeEdge(circle, 0, M_PI).Edge(),
                                   BRepBuilderAPI_MakeEdge(circle, M_PI, 2 * M_PI).Edge());
      face.Add(TopoDS::Wire(hole.Wire().Reversed()));  // holes run clockwise
    }
  }
  return BRepPrimAPI_MakePrism(face.Face(), gp_Vec(0, 0, thickness)).Shape();
}

std::vector<Case>& cases() {
  static std::vector<Case> all;
  return all;
}

void BM_Partitions(benchmark::State& state, const Case* c) {
  for (auto _ : state) {
    for (const TopoDS_Shape& body : c->bodies) {
      BodyPartitions result = partition_shape(body, c->tolerances);
      benchmark::DoNotOptimize(result.partitions.data());
    }
  }
  state.counters["faces"] = c->faces;
  state.counters["faces_after"] = c->partitions;  // one partition is one merged face
}

void BM_UnifySameDomain(benchmark::State& state, const Case* c) {
  for (auto _ : state) {
    for (const TopoDS_Shape& body : c->bodies) {
      TopoDS_Shape unified = unify_same_domain(body);
      benchmark::DoNotOptimize(unified);
    }
  }
  state.counters["faces"] = c->faces;
  state.counters["faces_after"] = c->unified_faces;
}

// Keeps the real time per iteration of every run, in milliseconds, for the
// table printed after the run.
class RecordingReporter : public benchmark::ConsoleReporter {
 public:
  // Colours only on a terminal (a custom reporter does not see --benchmark_color).
  RecordingReporter() : ConsoleReporter(isatty(fileno(stdout)) ? OO_ColorTabular : OO_Tabular) {}
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& run : runs) {
      if (run.error_occurred || run.run_type != Run::RT_Iteration) continue;
      const double seconds_per_unit = 1.0 / benchmark::GetTimeUnitMultiplier(run.time_unit);
      milliseconds[run.benchmark_name()] = run.GetAdjustedRealTime() * seconds_per_unit * 1e3;
    }
    ConsoleReporter::ReportRuns(runs);
  }
  std::map<std::string, double> milliseconds;
};

void print_table(const std::map<std::string, double>& ms) {
  std::printf("\n%-9s %6s %7s %10s %10s %9s %9s %10s %10s %9s\n", "case", "bodies", "faces", "partitions",
              "ours [ms]", "us/body", "us/face", "USD [ms]", "USD faces", "USD/ours");
  for (const Case& c : cases()) {
    const auto ours = ms.find("partitions/" + c.name), usd = ms.find("unify_same_domain/" + c.name);
    if (ours == ms.end() || usd == ms.end()) continue;
    std::printf("%-9s %6zu %7d %10d %10.3f %9.1f %9.2f %10.2f %10d %8.1fx\n", c.name.c_str(), c.bodies.size(),
                c.faces, c.partitions, ours->second, ours->second * 1e3 / c.bodies.size(),
                ours->second * 1e3 / c.faces, usd->second, c.unified_faces, usd->second / ours->second);
  }
}

}  // namespace

int main(int argc, char** argv) {
  // Our own flags first; the rest goes to Google Benchmark.
  std::vector<char*> remaining{argv[0]};
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg.rfind("--data=", 0) == 0)
      shared_data_dir = arg.substr(7);
    else if (arg.rfind("--samples=", 0) == 0)
      samples_dir = arg.substr(10);
    else
      remaining.push_back(argv[i]);
  }
  int remaining_count = static_cast<int>(remaining.size());
  benchmark::Initialize(&remaining_count, remaining.data());
  if (benchmark::ReportUnrecognizedArguments(remaining_count, remaining.data())) return 1;

  std::vector<TopoDS_Shape> bodies;
  if (read_bodies(samples_dir + "/motor.step", bodies)) cases().push_back(make_case("motor", bodies));
  bodies.clear();
  if (read_bodies(shared_data_dir + "/step/R08_presse_asm.step", bodies))
    cases().push_back(make_case("press", bodies));
  cases().push_back(make_case("plate10k", {holed_plate(100, 50)}));

  for (const Case& c : cases()) {
    benchmark::RegisterBenchmark(("partitions/" + c.name).c_str(), BM_Partitions, &c)
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("unify_same_domain/" + c.name).c_str(), BM_UnifySameDomain, &c)
        ->Unit(benchmark::kMillisecond);
  }
  RecordingReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();
  print_table(reporter.milliseconds);
  return 0;
}
