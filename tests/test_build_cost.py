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
