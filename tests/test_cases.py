"""Every generated case and grid gives its expected contacts through the
pipeline (C++ STEP reader, partitions, contacts), pair by pair, partial flags
included; the inch copy of a case gives the same list as the mm original."""
import glob
import json
import os
from collections import Counter

import pytest

from contactwb import analysis

from conftest import SAMPLES

EXPECTED = sorted(glob.glob(os.path.join(SAMPLES, "cases", "*.expected.json")) +
                  glob.glob(os.path.join(SAMPLES, "families", "*.expected.json")))


def load_expected(path):
    with open(path) as stream:
        data = json.load(stream)
    contacts, partial = Counter(), Counter()
    for c in data["contacts"]:
        key = (frozenset((c["a"], c["b"])), c["type"])
        contacts[key] += c["count"]
        partial[key] += c.get("partial", 0)
    return data, contacts, +partial


def found(result):
    contacts, partial = Counter(), Counter()
    for c in result.contacts:
        key = (frozenset((c.a, c.b)), c.type)
        contacts[key] += 1
        partial[key] += c.partial
    return contacts, +partial


@pytest.mark.parametrize("expected_path", EXPECTED, ids=lambda p: os.path.basename(p).split(".")[0])
def test_case_gives_its_expected_contacts(expected_path):
    data, contacts, partial = load_expected(expected_path)
    step = expected_path.replace(".expected.json", ".step")
    result = analysis.find_contacts_in_step(step)
    assert [b.name for b in result.bodies] == data["bodies"]
    got_contacts, got_partial = found(result)
    assert got_contacts == contacts
    assert got_partial == partial


def test_inch_case_matches_its_mm_original():
    inch = analysis.find_contacts_in_step(os.path.join(SAMPLES, "cases", "inch.step"))
    mm = analysis.find_contacts_in_step(os.path.join(SAMPLES, "cases", "pin_block.step"))
    assert inch.units == "in" and mm.units == "mm"
    assert found(inch) == found(mm)
    areas = sorted(round(c.area, 3) for c in inch.contacts)
    assert areas == pytest.approx(sorted(round(c.area, 3) for c in mm.contacts), rel=1e-4)
