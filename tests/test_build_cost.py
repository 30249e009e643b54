"""bench/build_cost.py, the idle-wall estimate of a cold `make run` build
(docs/benchmarks.md, issue 23): its schedules and bounds on a hand-made
compile log whose figures are worked out by hand below."""
import importlib.util
import os

import pytest

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


@pytest.fixture(scope="module")
def build_cost():
    spec = importlib.util.spec_from_file_location("build_cost", os.path.join(REPO, "bench", "build_cost.py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


CORE = "cpp_module/CMakeFiles/contactcore.dir"
PY = "cpp_module/CMakeFiles/contactcore_py.dir"

# user sys wall output, as bench/timecc.sh writes them (g++'s header suffix).
LOG = f"""\
9.0 1.0 30.0 {CORE}/cmake_pch.hxx.gch
30.0 0.0 99.0 {CORE}/Unity/unity_contactcore_a_cxx.cxx.o
20.0 0.0 99.0 {CORE}/Unity/unity_contactcore_b_cxx.cxx.o
Command exited with non-zero status 1
4.0 1.0 9.0 {PY}/cmake_pch.hxx.gch
15.0 0.0 50.0 {PY}/Unity/unity_contactcore_py_c_cxx.cxx.o
"""

# The same objects from clang (.pch), in another order, one of them missing.
OTHER = f"""\
2.0 0.0 5.0 {CORE}/cmake_pch.hxx.pch
10.0 0.0 40.0 {CORE}/Unity/unity_contactcore_b_cxx.cxx.o
24.0 0.0 80.0 {CORE}/Unity/unity_contactcore_a_cxx.cxx.o
"""


@pytest.fixture
def rows(build_cost, tmp_path):
    path = tmp_path / "gcc.log"
    path.write_text(LOG)
    return build_cost.read_log(str(path))


def test_log_rows_are_user_plus_sys_without_other_lines(rows):
    assert [s for _, s in rows] == [10.0, 30.0, 20.0, 5.0, 15.0]


def test_ninja_schedule_by_hand(build_cost, rows):
    # Headers: core's on core 1 (0-10), the bindings' on core 2 (0-5).
    # a (30 s) waits for its header: core 2 is free first (5) but a starts at
    # 10, ends 40; b on core 1 at 10, ends 30; c on core 1 at 30, ends 45.
    # Core 2 idle from 40: a 5 s tail.
    assert build_cost.ninja_schedule(rows, 2) == (45.0, 5.0)
    assert build_cost.ninja_estimate(rows, 1) == 80.0


def test_make_schedule_by_hand(build_cost, rows):
    # Target after target: core header 10, a and b side by side (10-40),
    # then the bindings' header 5 (45), c 15 (60); haptics has nothing.
    assert build_cost.make_estimate(rows, 2) == 60.0


def test_bounds(build_cost, rows):
    assert build_cost.cpu_bound(rows, 2) == 40.0
    # core: 10 + 30; bindings: 5 + 15.
    assert build_cost.critical_path(rows) == (40.0, "contactcore")


def test_compare_lines_up_gch_and_pch(build_cost, rows, tmp_path):
    other = tmp_path / "clang.log"
    other.write_text(OTHER)
    pairs = build_cost.compare(rows, build_cost.read_log(str(other)))
    assert pairs == [(f"{CORE}/cmake_pch.hxx", 10.0, 2.0),
                     (f"{CORE}/Unity/unity_contactcore_a_cxx.cxx.o", 30.0, 24.0),
                     (f"{CORE}/Unity/unity_contactcore_b_cxx.cxx.o", 20.0, 10.0)]


def test_shared_schedule_alone_by_hand(build_cost, rows):
    # Ninja starts the first ready compile in log order: the core's header
    # (0-10) and the bindings' (0-5); at 5 only c is ready (5-20); a at 10
    # (10-40), b when c ends (20-40).
    assert build_cost.shared_schedule(rows, 2) == (40.0, 0.0)


def test_shared_schedule_with_packages_beside_by_hand(build_cost, rows):
    # 12 s of dpkg from 0: three processes on two cores, 2/3 of a core each.
    # Bindings' header done at 7.5 (5 / (2/3)); c starts. Core header done at
    # 15 (5 more at 2/3); dpkg has 2 left, a starts. dpkg done at 18 (c: 8
    # left, a: 28). c done at 26, b starts (a: 20 left); both end at 46.
    assert build_cost.shared_schedule(rows, 2, beside_cpu=12.0) == (46.0, 18.0)
    # The packages' download first (10 s, no CPU): dpkg from 10.
    # 0-5 headers at full speed, c from 5; at 10 the core header is done, a
    # starts, dpkg starts: c has 10, a 30, dpkg 12 at 2/3 each. c done at 25
    # (a: 20, dpkg: 2); dpkg done at 28 (a: 18, b started at 25: 18); a and b
    # end at 46.
    assert build_cost.shared_schedule(rows, 2, beside_cpu=12.0, beside_start=10.0) == (46.0, 28.0)
    # The whole `make run`: 7 s of packages before, the link 3 s, 2 s after.
    assert build_cost.make_run_estimate(rows, 2, 7.0, 12.0, 0.0, 3.0, 2.0) == 58.0
    # Packages beside that outlast the compiles: the install waits for them.
    # c ends at 30 (a: 20 left, dpkg: 180), a and b at 60 (dpkg: 160), then
    # dpkg alone until 220; the link (60-63) is long done.
    assert build_cost.make_run_estimate(rows, 2, 0.0, 200.0, 0.0, 3.0, 0.0) == 220.0
