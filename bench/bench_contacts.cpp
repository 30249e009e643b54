// End-to-end benchmark of the contacts pipeline against its floor: for each
// STEP file, (1) a bare XDE read of the file (STEPCAFControl_Reader, the same
// modes as read_step: names on, colours, layers and properties off), and
// (2) our whole pipeline from the file: read_step, then find_contacts. Each
// run is its own child process, so peak memory (getrusage max RSS) is the
// run's own; times are the best of --repeat runs. Prints one JSON object per
// line; bench/run_benchmarks.py makes the tables.
//
//   bench_contacts [--repeat N] [--threads N] [--reference] [--no-bare] [--read-as-written] FILE.step...
//
// --reference: the pipeline's child also times the whole-solid Boolean pass
// the interference pass replaced (whole_solid_interferences, issue 24) on the
// same result, after the measured run: "reference_interferences" seconds and
// both passes' interference counts.
// --no-bare: our pipeline only (files whose bare XDE read would take hours:
// the 100,000-part grid, issue 24).
// --read-as-written: read_step's product read on the file's text as written
// (StepReadMode::ProductsAsWritten: assemblies' lists of placements not
// shortened for OCCT's parser), to measure what the shortening saves.
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

#include <IFSelect_ReturnStatus.hxx>
#include <Interface_Static.hxx>
#include <STEPCAFControl_Reader.hxx>
#include <TDocStd_Document.hxx>
#include <TopExp_Explorer.hxx>
#include <XCAFApp_Application.hxx>

#include "contactcore/contacts/contacts.h"
#include "contacts/interferences.h"

using namespace contactcore;

namespace {

double now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

double peak_rss_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024.0;
}

std::string json_escape(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    out += (c == '\n') ? ' ' : c;
  }
  return out;
}

// The floor: what OCCT alone takes to bring the file into an XDE document.
int bare_read(const std::string& path) {
  const double start = now();
  Interface_Static::SetCVal("xstep.cascade.unit", "MM");
  Handle(XCAFApp_Application) app = XCAFApp_Application::GetApplication();
  Handle(TDocStd_Document) doc;
  app->NewDocument("MDTV-XCAF", doc);
  STEPCAFControl_Reader reader;
  reader.SetNameMode(true);
  reader.SetColorMode(false);
  reader.SetLayerMode(false);
  reader.SetPropsMode(false);
  const bool ok = reader.ReadFile(path.c_str()) == IFSelect_RetDone && reader.Transfer(doc);
  const double seconds = now() - start;
  app->Close(doc);
  if (!ok) {
    std::printf("{\"file\": \"%s\", \"error\": \"bare read failed\"}\n", json_escape(path).c_str());
    return 1;
  }
  std::printf("{\"file\": \"%s\", \"run\": \"bare\", \"seconds\": %.6f, \"peak_rss_mb\": %.1f}\n",
              json_escape(path).c_str(), seconds, peak_rss_mb());
  return 0;
}

// Asks to stop at a given moment (the user's click): the latency is from
// that moment to find_contacts returning.
struct CancelAt : Progress {
  explicit CancelAt(double at) : at(at) {}
  bool report(const char*, double) override { return now() < at; }
  double at;
};

int pipeline(const std::string& path, int threads, bool reference, bool as_written) {
  const double start = now();
  const AssemblyResult read =
      read_step(path, nullptr, as_written ? StepReadMode::ProductsAsWritten : StepReadMode::Products);
  const double read_seconds = now() - start;
  if (!read.status.ok()) {
    std::printf("{\"file\": \"%s\", \"error\": \"%s\"}\n", json_escape(path).c_str(),
                json_escape(read.status.describe()).c_str());
    return 1;
  }
  ContactOptions options;
  options.threads = threads;
  const ContactsResult result = find_contacts(read.assembly, options);
  const double total = now() - start;
  if (!result.status.ok()) {
    std::printf("{\"file\": \"%s\", \"error\": \"%s\"}\n", json_escape(path).c_str(),
                json_escape(result.status.describe()).c_str());
    return 1;
  }
  const double peak = peak_rss_mb();  // before the second run below
  // Cancelled halfway through a second run.
  const double after_read = total - read_seconds;
  CancelAt cancel(0);
  const double cancel_start = now();
  cancel.at = cancel_start + after_read / 2;
  const ContactsResult stopped = find_contacts(read.assembly, options, &cancel);
  const double cancel_latency = stopped.status.code == StatusCode::Cancelled ? now() - cancel.at : -1;
  double reference_seconds = -1;
  std::size_t reference_count = 0;
  if (reference) {
    const double reference_start = now();
    reference_count = whole_solid_interferences(read.assembly, result, threads).size();
    reference_seconds = now() - reference_start;
  }
  size_t faces = 0;
  for (const BodyPartitions& body : result.partitions) faces += body.faces.size();
  std::printf(
      "{\"file\": \"%s\", \"run\": \"ours\", \"reader\": \"%s\", \"bodies\": %zu, \"faces\": %zu, \"contacts\": %zu, "
      "\"body_pairs\": %zu, \"candidates\": %zu, \"skipped\": %zu, \"read\": %.6f, \"partitions\": %.6f, "
      "\"broad_phase\": %.6f, \"candidates_time\": %.6f, \"area\": %.6f, \"validity\": %.6f, "
      "\"interferences\": %.6f, \"after_read\": %.6f, "
      "\"total\": %.6f, \"cancel_latency\": %.6f, \"peak_rss_mb\": %.1f, \"interference_count\": %zu, "
      "\"reference_interferences\": %.6f, \"reference_count\": %zu}\n",
      json_escape(path).c_str(), read.assembly.reader.c_str(), read.assembly.bodies.size(), faces, result.contacts.size(),
      result.body_pairs.size(), result.candidates, result.skipped.size(), read_seconds,
      result.times.partitions, result.times.broad_phase, result.times.candidates, result.times.area,
      result.times.validity, result.times.interferences, after_read, total, cancel_latency, peak,
      result.interferences.size(), reference_seconds, reference_count);
  return 0;
}

// Runs `work` in a child process; its stdout line is the measurement.
template <class Work>
bool in_child(Work&& work) {
  std::fflush(stdout);
  const pid_t child = fork();
  if (child == 0) {
    const int rc = work();
    std::fflush(stdout);  // _exit skips stdio flushing
    _exit(rc);
  }
  int status = 0;
  waitpid(child, &status, 0);
  return WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

}  // namespace

int main(int argc, char** argv) {
  int repeat = 3, threads = 0;
  bool reference = false, bare = true, as_written = false;
  std::vector<std::string> files;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--repeat") == 0 && i + 1 < argc) {
      repeat = std::max(1, std::atoi(argv[++i]));
    } else if (std::strcmp(argv[i], "--reference") == 0) {
      reference = true;
    } else if (std::strcmp(argv[i], "--no-bare") == 0) {
      bare = false;
    } else if (std::strcmp(argv[i], "--read-as-written") == 0) {
      as_written = true;
    } else if (std::strcmp(argv[i], "--threads") == 0 && i + 1 < argc) {
      threads = std::max(0, std::atoi(argv[++i]));
    } else {
      files.emplace_back(argv[i]);
    }
  }
  if (files.empty()) {
    std::fprintf(stderr, "usage: %s [--repeat N] [--threads N] [--reference] [--no-bare] [--read-as-written] FILE.step...\n",
                 argv[0]);
    return 2;
  }
  int failures = 0;
  for (const std::string& file : files) {
    // Interleaved, so a burst of load on the machine hits both alike.
    for (int r = 0; r < repeat; ++r) {
      if (bare) failures += !in_child([&] { return bare_read(file); });
      failures += !in_child([&] { return pipeline(file, threads, reference, as_written); });
    }
  }
  return failures ? 1 : 0;
}
