"""Issue 25, item 8: fuzz/run_fuzzers.sh runs fuzz_step in libFuzzer's fork
mode (a fresh child process per job, so what OCCT's reader keeps in a
process cannot build up over a run) and still fails on a crash. Checked
with two small libFuzzer programs standing in for fuzz_step (built here with
clang 14, no OCCT): one recording the process of every input, one aborting
on the committed STEP seeds."""
import os
import shutil
import subprocess

import pytest

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCRIPT = os.path.join(REPO, "fuzz", "run_fuzzers.sh")
CLANG = shutil.which("clang++-14")

RECORDING = r"""
#include <cstdint>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <unistd.h>
extern "C" int LLVMFuzzerTestOneInput(const uint8_t*, size_t) {
  if (FILE* f = std::fopen(std::getenv("PID_LOG"), "a")) { std::fprintf(f, "%d\n", (int)getpid()); std::fclose(f); }
  return 0;
}
"""

ABORTING = r"""
#include <cstdint>
#include <cstddef>
#include <cstdlib>
extern "C" int LLVMFuzzerTestOneInput(const uint8_t* d, size_t n) {
  if (n >= 3 && d[0] == 'I' && d[1] == 'S' && d[2] == 'O') std::abort();  // every STEP seed
  return 0;
}
"""

pytestmark = pytest.mark.skipif(CLANG is None, reason="clang++-14 (DEB_TEST_PACKAGES) absent")


def _build(tmp_path, source):
    (tmp_path / "fuzz").mkdir()
    (tmp_path / "target.cpp").write_text(source)
    subprocess.run([CLANG, "-O1", "-fsanitize=fuzzer", str(tmp_path / "target.cpp"), "-o",
                    str(tmp_path / "fuzz" / "fuzz_step")], check=True)


def _run(tmp_path, seconds, env=None):
    return subprocess.run(["bash", SCRIPT, str(tmp_path), str(seconds), "fuzz_step"], capture_output=True,
                          text=True, timeout=seconds + 120, env={**os.environ, **(env or {})})


def test_fuzz_step_runs_a_child_process_per_job(tmp_path):
    _build(tmp_path, RECORDING)
    log = tmp_path / "pids.txt"
    out = _run(tmp_path, 6, {"PID_LOG": str(log)})
    assert out.returncode == 0, out.stdout + out.stderr
    assert "a child process per job (-fork=1)" in out.stdout
    summary = [line for line in out.stdout.splitlines() if line.startswith("fuzz_step: 6 s,")]
    assert summary and "findings 0" in summary[-1] and "exit 0" in summary[-1], out.stdout
    jobs = int(summary[-1].split(" child processes")[0].rsplit(", ", 1)[1])
    pids = set(log.read_text().split())
    # One process per job (jobs of 1, 2, 3 s in 6 s), and one more: libFuzzer's first pass over the
    # seeds runs in a child of its own too (a crash-resistant merge).
    assert jobs >= 2
    assert len(pids) == jobs + 1


def test_fuzz_step_in_fork_mode_still_fails_on_a_crash(tmp_path):
    _build(tmp_path, ABORTING)
    out = _run(tmp_path, 10)
    assert out.returncode == 1, out.stdout + out.stderr
    artifacts = os.listdir(tmp_path / "fuzz-artifacts" / "fuzz_step")
    assert artifacts and all(name.startswith("crash-") for name in artifacts)
    summary = [line for line in out.stdout.splitlines() if line.startswith("fuzz_step: 10 s,")]
    assert summary and f"findings {len(artifacts)}" in summary[-1]


def test_one_process_when_fork_mode_is_off(tmp_path):
    _build(tmp_path, RECORDING)
    log = tmp_path / "pids.txt"
    out = _run(tmp_path, 3, {"PID_LOG": str(log), "FUZZ_FORK_TARGETS": ""})
    assert out.returncode == 0, out.stdout + out.stderr
    assert "one process" in out.stdout
    assert len(set(log.read_text().split())) == 1
