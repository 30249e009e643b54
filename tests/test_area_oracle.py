"""The area oracle: every contact the core finds, with its area, equals the
brute-force checker's (tests/bruteforce_contacts.py: FreeCAD's Boolean common
of every same-surface face pair, grouped into maximal partitions), on the
motor, every generated case and every shared file the checker reads. Bodies
are matched by their centre of mass, so files whose solids the checker can
only number (repeated instances, nested assemblies) are compared too.
Areas agree within 1e-3 relative or 1e-3 mm^2, whichever is larger."""
import glob
import math
import os
from collections import defaultdict

import pytest

import bruteforce_contacts as oracle
from contactwb import analysis

from conftest import SAMPLES, SHARED_DATA

CASES = sorted(glob.glob(os.path.join(SAMPLES, "cases", "*.step")))
SHARED_FILES = ["R01_as1-oc-214.stp", "R05_SKF_6004.stp", "R06_bearing_20x37x9_freecad.stp",
                "R08_presse_asm.step", "R09_chrono_assembly.stp", "R10_wrenchnut.stp",
                "D03_asm4_tuto2_disk_arm.step"]


def area_tolerance(area):
    return max(1e-3 * area, 1e-3)


def core_body_of(shapes, result, in_contact):
    """{checker name: core body name}, the core body at the same centre of mass.
    Every checker solid in a contact must have one; a solid that has none and no
    contact is left out (FreeCAD's plain reader places R09's legacy MAPPED_ITEM
    duplicate elsewhere, where it touches nothing)."""
    mapping = {}
    for name, shape in shapes.items():
        c = (shape.CenterOfMass.x, shape.CenterOfMass.y, shape.CenterOfMass.z)
        nearest = min(result.bodies, key=lambda b: math.dist(b.center, c))
        if math.dist(nearest.center, c) > 1e-6 * max(1.0, shape.BoundBox.DiagonalLength):
            assert name not in in_contact, f"no core body at the centre of the checker's {name}"
            continue
        assert nearest.volume == pytest.approx(shape.Volume, rel=1e-6), name
        mapping[name] = nearest.name
    return mapping


def areas_by_pair(records):
    """{(frozenset(a, b), type): sorted areas}."""
    table = defaultdict(list)
    for a, b, kind, area in records:
        table[(frozenset((a, b)), kind)].append(area)
    return {key: sorted(v) for key, v in table.items()}


def check_against_oracle(path):
    result = analysis.find_contacts_in_step(path)
    shapes = oracle.load(path)
    stats = {}
    oracle.brute_force_contacts(shapes, stats=stats)
    names = core_body_of(shapes, result, {n for a, b, _, _ in stats["areas"] for n in (a, b)})
    expected = areas_by_pair((names[a], names[b], kind, area) for a, b, kind, area in stats["areas"])
    found = areas_by_pair((c.a, c.b, c.type, c.area) for c in result.contacts)
    assert set(found) == set(expected), "contacts differ from the checker's"
    for key, areas in expected.items():
        got = found[key]
        assert len(got) == len(areas), key
        for g, e in zip(got, areas):
            assert abs(g - e) <= area_tolerance(e), f"{sorted(key[0])} {key[1]}: area {g} vs Boolean {e}"
    return result


def test_motor_areas_are_the_boolean_common_areas(sample):
    result = check_against_oracle(sample("motor.step"))
    assert len(result.contacts) == 35


@pytest.mark.parametrize("name", [os.path.basename(p) for p in CASES])
def test_generated_case_areas_are_the_boolean_common_areas(sample, name):
    check_against_oracle(sample(os.path.join("cases", name)))


@pytest.mark.parametrize("name", SHARED_FILES)
def test_shared_file_areas_are_the_boolean_common_areas(shared_step, name):
    check_against_oracle(shared_step(name))


def test_cases_are_committed():
    # The list above is read from the committed samples: it must not be empty.
    assert len(CASES) >= 14
