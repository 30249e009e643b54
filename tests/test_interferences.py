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
