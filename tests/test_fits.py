"""ISO 286 fits (contactwb.core.iso286) against values read by hand from
ISO 286-1 table 1 (IT grades) and ISO 286-2 (fundamental deviations), and
the fits of an annotations file checked against their intents."""
import json
import os
import subprocess
import sys

import pytest

import FreeCAD
import Part
from contactwb import core, joints
from contactwb.core import annotations, iso286

from conftest import REPO, SAMPLES

V = FreeCAD.Vector


@pytest.mark.parametrize("code, diameter, hole, shaft, clearance, fit_class", [
    # Ø20 (18-30): IT7 21, IT6 13; g es -7 -> g6 -20/-7; clearance 0-(-7)=7 .. 21-(-20)=41.
    ("H7/g6", 20, (0, 21), (-20, -7), (7, 41), "clearance"),
    # Ø40 (30-50): IT7 25, IT6 16; p ei +26 -> p6 +26/+42: -42 .. 25-26=-1.
    ("H7/p6", 40, (0, 25), (26, 42), (-42, -1), "interference"),
    # Ø10 (over 6 up to 10): IT7 15, IT6 9; k ei +1 -> k6 +1/+10: -10 .. 14.
    ("H7/k6", 10, (0, 15), (1, 10), (-10, 14), "transition"),
    # Ø25 (18-30): IT8 33, IT7 21; f es -20 -> f7 -41/-20: 20 .. 74.
    ("H8/f7", 25, (0, 33), (-41, -20), (20, 74), "clearance"),
    # Ø50 (40-50): IT6 16; s ei +43 -> s6 +43/+59 (the textbook H7/s6 at 50).
    ("H7/s6", 50, (0, 25), (43, 59), (-59, -18), "interference"),
    # Ø60 (50-65): c es -140, IT11 190 -> c11 -330/-140.
    ("H11/c11", 60, (0, 190), (-330, -140), (140, 520), "clearance"),
    # Ø20: js7 with IT7 21 (odd) rounded down to 20: +-10.
    ("H7/js7", 20, (0, 21), (-10, 10), (-10, 31), "transition"),
    # Ø30 (18-30) hole K6: ES = -ei(k) + delta = -2 + (13 - 9) = +2, EI = 2 - 13 = -11.
    ("K6/h5", 30, (-11, 2), (-9, 0), (-11, 11), "transition"),
    # Ø20 hole P7: ES = -22 + (21 - 13) = -14, EI = -35; h6 -13/0.
    ("P7/h6", 20, (-35, -14), (-13, 0), (-35, -1), "interference"),
    # Ø20 hole N7: ES = -15 + 8 = -7, EI = -28.
    ("N7/h6", 20, (-28, -7), (-13, 0), (-28, 6), "transition"),
    # Ø300 (280-315) hole M6: the standard's special case ES -9, EI -9 - 32 = -41.
    ("M6/h5", 300, (-41, -9), (-23, 0), (-41, 14), "transition"),
    # Ø30 hole F8: EI = -es(f) = +20, ES = 20 + 33 = 53.
    ("F8/h7", 30, (20, 53), (-21, 0), (20, 74), "clearance"),
    # Ø2 (up to 3): p ei +6, IT7 10: H7/p6 is only a transition fit there.
    ("H7/p6", 2, (0, 10), (6, 12), (-12, 4), "transition"),
    # Ø16 (10-18) hole N6: ES = -12 + (11 - 8) = -9, EI = -20; h5 -8/0 (the motor's bearings).
    ("N6/h5", 16, (-20, -9), (-8, 0), (-20, -1), "interference"),
    # Ø8 (6-10): H7/p6 with p ei +15 = IT7 15: largest clearance 0, an interference fit (the motor's rotor).
    ("H7/p6", 8, (0, 15), (15, 24), (-24, 0), "interference"),
    # Ø100 (80-100): u ei +124, IT6 22.
    ("H7/u6", 100, (0, 35), (124, 146), (-146, -89), "interference"),
])
def test_fits_against_the_standards_tables(code, diameter, hole, shaft, clearance, fit_class):
    fit = iso286.fit(code, diameter)
    assert fit.hole == pytest.approx(hole, abs=1e-9)
    assert fit.shaft == pytest.approx(shaft, abs=1e-9)
    assert fit.clearance == pytest.approx(clearance, abs=1e-9)
    assert fit.fit_class == fit_class


def test_range_limits_belong_to_the_lower_range():
    # ISO 286 ranges are "over a up to and including b": 10 mm is in 6-10, a
    # radius read as 4.99999999 is still the drawing's 10 mm.
    assert iso286.tolerance("7", 10) == 15 and iso286.tolerance("7", 10.000001) == 18
    assert iso286.fit("H7/g6", 9.99999999).hole == (0, 15)
    assert iso286.tolerance("01", 500) == 4 and iso286.tolerance("18", 1) == 1400


def test_unknown_codes_and_diameters_are_refused():
    with pytest.raises(iso286.FitError, match="not an ISO 286 fit code"):
        iso286.fit("H7-g6", 20)
    with pytest.raises(iso286.FitError, match="upper case"):
        iso286.fit("h7/g6", 20)
    with pytest.raises(iso286.FitError, match="shaft letter 'x' is not covered"):
        iso286.fit("H7/x6", 20)
    with pytest.raises(iso286.FitError, match="outside ISO 286's tables"):
        iso286.fit("H7/g6", 600)
    with pytest.raises(iso286.FitError, match="outside ISO 286's tables"):
        iso286.fit("H7/g6", 0)
    with pytest.raises(iso286.FitError, match="not defined at 20 mm"):
        iso286.fit("H7/t6", 20)  # t starts over 24 mm


def _shaft_in_bore(radius=10.0):
    side = 6 * radius
    plate = Part.makeBox(side, side, 10).cut(Part.makeCylinder(radius, 10, V(side / 2, side / 2, 0)))
    shaft = Part.makeCylinder(radius, 30, V(side / 2, side / 2, -10))
    return [("Plate", plate), ("Shaft", shaft)]


def test_annotated_fit_echoed_with_its_class_and_limits():
    # Ø20 H7/g6 on the shaft's CLJ: clearance 7..41 um (above); the pair's
    # other contacts (none here) would get the intent only.
    result, found = joints.joints_in_shapes(_shaft_in_bore(), annotations=[
        {"a": "Plate", "b": "Shaft", "intent": "clearance", "fit": "H7/g6"}])
    (contact,) = [c for c in result.to_json()["contacts"] if c["type"] == "CLJ"]
    assert (contact["intent"], contact["fit"], contact["fit_class"]) == ("clearance", "H7/g6", "clearance")
    assert contact["fit_limits"] == {"code": "H7/g6", "diameter": 20.0, "hole": [0, 21], "shaft": [-20, -7],
                                     "clearance": [7, 41], "class": "clearance"}
    (joint,) = found.joints
    assert joint.type == "cylindrical" and not joint.annotated_rigid


def test_an_intent_contradicting_its_fit_is_an_error_naming_the_entry():
    with pytest.raises(core.ArgumentError) as error:
        joints.joints_in_shapes(_shaft_in_bore(), annotations=[
            {"a": "Plate", "b": "Shaft", "intent": "bonded"},
            {"a": "Plate", "b": "Shaft", "type": "CLJ", "intent": "interference", "fit": "H7/g6"}])
    assert "entry 2 ('Plate' - 'Shaft' CLJ, interference): fit H7/g6 at diameter 20 mm is a clearance fit " \
           "(clearance 7 to 41 µm" in str(error.value)
    # bonded with a fit: the fit is echoed with its class, the pair rigid.
    result, found = joints.joints_in_shapes(_shaft_in_bore(), annotations=[
        {"a": "Plate", "b": "Shaft", "intent": "bonded", "fit": "H7/g6"}])
    assert result.to_json()["contacts"][0]["fit_class"] == "clearance"
    assert found.joints[0].annotated_rigid


def test_a_fit_without_a_cylinder_or_out_of_range_is_an_error_naming_the_entry():
    boxes = [("Lower", Part.makeBox(10, 10, 10)), ("Upper", Part.makeBox(10, 10, 10, V(0, 0, 10)))]
    with pytest.raises(core.ArgumentError, match=r"entry 1 \('Lower' - 'Upper', interference\): fit H7/p6 needs "
                                                 r"a cylindrical contact"):
        joints.joints_in_shapes(boxes, annotations=[{"a": "Lower", "b": "Upper", "intent": "interference",
                                                     "fit": "H7/p6"}])
    with pytest.raises(core.ArgumentError, match=r"entry 1 .*fit H7/g6 at the CLJ contact of diameter 1200 mm: "
                                                 r"diameter 1200 mm is outside"):
        joints.joints_in_shapes(_shaft_in_bore(600.0), annotations=[
            {"a": "Plate", "b": "Shaft", "intent": "clearance", "fit": "H7/g6"}])
    with pytest.raises(core.ArgumentError, match="entry 1 .*shaft letter 'v' is not covered"):
        joints.joints_in_shapes(_shaft_in_bore(), annotations=[
            {"a": "Plate", "b": "Shaft", "intent": "interference", "fit": "H7/v6"}])
    with pytest.raises(core.ArgumentError, match="entry 1: an ignored contact has no fit"):
        annotations.parse([{"a": "A", "b": "B", "intent": "ignored", "fit": "H7/g6"}])


def test_motor_example_fits_agree_with_their_intents():
    # motor.annotations.json: the axis Ø8 (H7/p6 interference, H7/g6
    # clearance), bearings Ø16 in the covers (N6/h5 interference), the seal
    # Ø14 (H8/s7: s ei +28, IT7 18 / IT8 27 -> -46..-1, interference).
    done = subprocess.run([sys.executable, "-m", "contactwb.cli", os.path.join(SAMPLES, "motor.step"),
                           "--annotations", os.path.join(SAMPLES, "motor.annotations.json"), "--json"],
                          cwd=REPO, capture_output=True, text=True, env=dict(os.environ, PYTHONPATH=REPO))
    assert done.returncode == 0, done.stderr
    fitted = {(c["a"], c["b"]): (c["fit"], c["fit_class"], c["fit_limits"]["diameter"],
                                 c["fit_limits"]["clearance"])
              for c in json.loads(done.stdout)["contacts"] if "fit_class" in c}
    assert fitted == {
        ("Axis", "Rotor-front"): ("H7/p6", "interference", 8.0, [-24, 0]),
        ("Axis", "Rotor-back"): ("H7/p6", "interference", 8.0, [-24, 0]),
        ("Axis", "Bearing-front"): ("H7/g6", "clearance", 8.0, [5, 29]),
        ("Axis", "Bearing-back"): ("H7/g6", "clearance", 8.0, [5, 29]),
        ("Bearing-front", "Front-cover"): ("N6/h5", "interference", 16.0, [-20, -1]),
        ("Bearing-back", "Back-cover"): ("N6/h5", "interference", 16.0, [-20, -1]),
        ("Seal", "Front-cover"): ("H8/s7", "interference", 14.0, [-46, -1]),
    }


def _pin_in_bore(pin_radius):
    # A block 40 x 40 x 20 bored r 10 through at (20, 20); a pin of the given
    # radius through it, 30 long.
    block = Part.makeBox(40, 40, 20).cut(Part.makeCylinder(10, 40, V(20, 20, -10)))
    return [("Block", block), ("Pin", Part.makeCylinder(pin_radius, 30, V(20, 20, -5)))]


def test_a_small_radial_gap_is_proposed_as_a_clearance_fit():
    # r 9.95 in r 10: no contact, a 0.05 mm radial gap < 0.1: proposed clearance.
    result, found = joints.joints_in_shapes(_pin_in_bore(9.95), clearance_gap=0.1)
    assert result.contacts == [] and result.interferences == []
    (entry,) = found.clearances
    assert (entry["a"], entry["b"], entry["kind"], entry["proposed_intent"]) == ("Block", "Pin", "Cylinder",
                                                                                 "clearance")
    assert entry["gap"] == pytest.approx(0.05, abs=1e-9)
    assert "Clearance fits (gap < 0.1 mm, not contacts; proposed intent clearance): 1" in found.table()
    assert joints.joints_in_shapes(_pin_in_bore(9.95), clearance_gap=0.04)[1].clearances == []


def test_an_oversize_coaxial_pin_is_proposed_as_an_interference_fit(tmp_path):
    # r 10.02 in r 10: the material overlaps (2 pi 10.01 0.02 20 = 25.16 mm3,
    # the OCCT common checks it), radial overlap 0.02 mm: proposed
    # interference, a negative gap; through the CLI's --json as well.
    shapes = _pin_in_bore(10.02)
    result, found = joints.joints_in_shapes(shapes, clearance_gap=0.1)
    ((a, b, volume),) = result.interferences
    assert volume == pytest.approx(shapes[0][1].common(shapes[1][1]).Volume, rel=1e-6)
    (entry,) = found.clearances
    assert (entry["kind"], entry["proposed_intent"]) == ("Cylinder", "interference")
    assert entry["gap"] == pytest.approx(-0.02, abs=1e-9)
    assert "Coaxial overlaps (radial overlap < 0.1 mm; proposed intent interference): 1" in found.table()
    assert "Block  <->  Pin   Cylinder overlap 0.02 mm" in found.table()
    compound = tmp_path / "pin.step"
    Part.makeCompound([s for _, s in shapes]).exportStep(str(compound))
    done = subprocess.run([sys.executable, "-m", "contactwb.cli", str(compound), "--joints", "--json",
                           "--clearance-gap", "0.1"], cwd=REPO, capture_output=True, text=True,
                          env=dict(os.environ, PYTHONPATH=REPO))
    assert done.returncode == 0, done.stderr
    (listed,) = json.loads(done.stdout)["clearances"]
    assert listed["proposed_intent"] == "interference" and listed["gap"] == pytest.approx(-0.02, abs=1e-6)
