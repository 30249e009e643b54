"""Issue 14: interferences (any overlap, with its volume, never a contact) and
invalid solids (named with their faces), through the Python API and the CLI's
JSON; checked against hand-derived volumes and FreeCAD's own Boolean."""
import json
import math
import os
import subprocess
import sys

import pytest

from contactwb import analysis

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CLI = [sys.executable, "-c", "import sys; sys.path.insert(0, %r); from contactwb import cli; sys.exit(cli.main())" % REPO]


def _part():
    import FreeCAD  # noqa: F401  (before Part)
    import Part
    return Part


def _bowtie_prism():
    import FreeCAD
    Part = _part()
    points = [FreeCAD.Vector(0, 0, 0), FreeCAD.Vector(10, 10, 0), FreeCAD.Vector(10, 0, 0),
              FreeCAD.Vector(0, 10, 0), FreeCAD.Vector(0, 0, 0)]
    return Part.Face(Part.makePolygon(points)).extrude(FreeCAD.Vector(0, 0, 5))


def test_overlapping_boxes_are_one_interference_with_their_common_volume():
    import FreeCAD
    Part = _part()
    a = Part.makeBox(10, 10, 10)
    b = Part.makeBox(10, 10, 10, FreeCAD.Vector(9, 0.5, 0.5))
    result = analysis.find_contacts_in_shapes([("a", a), ("b", b)])
    assert [(x, y) for x, y, _ in result.interferences] == [("a", "b")]
    assert result.interferences[0][2] == pytest.approx(1 * 9.5 * 9.5, rel=1e-9)
    assert result.interferences[0][2] == pytest.approx(a.common(b).Volume, rel=1e-6)
    assert result.contacts == []


def test_pin_through_plate_without_hole():
    import FreeCAD
    Part = _part()
    plate = Part.makeBox(40, 40, 5, FreeCAD.Vector(-20, -20, 0))
    pin = Part.makeCylinder(3, 30, FreeCAD.Vector(0, 0, -10))
    result = analysis.find_contacts_in_shapes([("plate", plate), ("pin", pin)])
    assert len(result.interferences) == 1
    assert result.interferences[0][2] == pytest.approx(math.pi * 3 ** 2 * 5, rel=1e-9)
    assert result.contacts == []


def _single_interference(named_shapes):
    result = analysis.find_contacts_in_shapes(named_shapes)
    assert len(result.interferences) == 1
    assert result.contacts == []
    return result.interferences[0][2]


def test_thin_plate_crossing_a_pin_between_its_samples():
    # The pin's samples sit at z = -10, 5, 20 and the plate's middle off the
    # pin: only the boundaries' crossing shows the overlap, pi r^2 t.
    import FreeCAD
    Part = _part()
    plate = Part.makeBox(40, 40, 1, FreeCAD.Vector(-10, -20, 7))
    pin = Part.makeCylinder(3, 30, FreeCAD.Vector(0, 0, -10))
    volume = _single_interference([("plate", plate), ("pin", pin)])
    assert volume == pytest.approx(math.pi * 3 ** 2 * 1, rel=1e-9)
    assert volume == pytest.approx(plate.common(pin).Volume, rel=1e-6)


def test_two_balls_overlapping_in_a_lens():
    # R = 5, centres d = 6 apart: pi (4R + d)(2R - d)^2 / 12.
    import FreeCAD
    Part = _part()
    a = Part.makeSphere(5)
    b = Part.makeSphere(5, FreeCAD.Vector(0, 6, 0))
    volume = _single_interference([("a", a), ("b", b)])
    assert volume == pytest.approx(math.pi * (4 * 5 + 6) * (2 * 5 - 6) ** 2 / 12, rel=1e-7)


def test_perpendicular_cylinders_crossing_inside_their_lengths():
    # The Steinmetz bicylinder of radius r: 16 r^3 / 3.
    import FreeCAD
    Part = _part()
    upright = Part.makeCylinder(3, 50, FreeCAD.Vector(0, 0, -40))
    crossbar = Part.makeCylinder(3, 50, FreeCAD.Vector(-40, 0, 0), FreeCAD.Vector(1, 0, 0))
    volume = _single_interference([("upright", upright), ("crossbar", crossbar)])
    assert volume == pytest.approx(16 * 3 ** 3 / 3, rel=1e-7)


def test_touching_bodies_give_no_interference():
    # Face to face (a block on a plate, overhanging it), a shaft in the
    # plate's bore with 0.5 mm clearance, a ball resting on the plate.
    import FreeCAD
    Part = _part()
    plate = Part.makeBox(40, 40, 10, FreeCAD.Vector(-20, -20, 0)).cut(Part.makeCylinder(5, 10))
    shapes = [("plate", plate),
              ("block", Part.makeBox(15, 5, 5, FreeCAD.Vector(10, -15, 10))),
              ("shaft", Part.makeCylinder(4.5, 30, FreeCAD.Vector(0, 0, -10))),
              ("ball", Part.makeSphere(5, FreeCAD.Vector(12, 12, 15)))]
    result = analysis.find_contacts_in_shapes(shapes)
    assert result.interferences == []
    assert dict(result.counts()) == {"PLF": 1}


def test_self_intersecting_solid_is_named_in_json(tmp_path):
    # An .FCStd keeps the shape as it is (a STEP reader heals it into 8 faces).
    import FreeCAD
    Part = _part()
    doc = FreeCAD.newDocument("bowtie")
    try:
        bowtie = doc.addObject("Part::Feature", "Bowtie")
        bowtie.Shape = _bowtie_prism()
        block = doc.addObject("Part::Feature", "Block")
        block.Shape = Part.makeBox(10, 10, 5, FreeCAD.Vector(0, 20, 0))
        path = str(tmp_path / "bowtie.FCStd")
        doc.saveAs(path)
    finally:
        FreeCAD.closeDocument(doc.Name)
    done = subprocess.run(CLI + [path, "--json"], capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    report = json.loads(done.stdout)
    assert len(report["invalid_bodies"]) == 1
    invalid = report["invalid_bodies"][0]
    assert invalid["body"] == "Bowtie"
    assert invalid["reason"] == "self-intersecting boundary"
    # The bowtie's bottom and top: the faces FreeCAD's own check finds.
    expected = sorted(f"Face{i + 1}" for i, face in enumerate(_bowtie_prism().Faces) if not face.isValid())
    assert sorted(invalid["faces"]) == expected and len(expected) == 2
    assert sum("'Bowtie' is not a valid solid" in m for m in report["messages"]) == 1


def test_valid_solids_have_no_invalid_bodies():
    import FreeCAD
    Part = _part()
    result = analysis.find_contacts_in_shapes([("a", Part.makeBox(10, 10, 10)),
                                               ("b", Part.makeBox(10, 10, 5, FreeCAD.Vector(0, 0, 10)))])
    assert result.invalid_bodies == []
    assert result.to_json()["invalid_bodies"] == []
    assert dict(result.counts()) == {"PLF": 1}
