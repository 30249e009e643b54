"""Contact identification through the Python API and the CLI: the paper's
motor pair by pair, the shared real-world files, documents, cancellation."""
import json
import os
import subprocess
import sys
from collections import Counter

import pytest

import FreeCAD
import Part
from contactwb import analysis, core, freecad_setup
from contactwb.document import shapes as document_shapes

from conftest import REPO

# The seed paper's section 5, as printed: (body, body, type, count).
PAPER_MOTOR = [
    ("Rotor-back", "Magnet-1", "PLF", 1), ("Rotor-back", "Magnet-2", "PLF", 1),
    ("Rotor-back", "Magnet-3", "PLF", 1), ("Rotor-back", "Magnet-4", "PLF", 1),
    ("Rotor-front", "Rotor-back", "PLF", 1), ("Rotor-front", "Bearing-front", "PLF", 1),
    ("Back-cover", "Bearing-back", "PLF", 1),
    ("Body", "Back-cover", "PLF", 1), ("Body", "Stator", "PLF", 1), ("Body", "Front-cover", "PLF", 1),
    ("Screw-1", "Front-cover", "PLF", 1), ("Screw-2", "Front-cover", "PLF", 1),
    ("Screw-3", "Front-cover", "PLF", 1), ("Screw-4", "Front-cover", "PLF", 1),
    ("Axis", "Rotor-front", "CLJ", 1), ("Axis", "Rotor-back", "CLJ", 1),
    ("Axis", "Bearing-front", "CLJ", 1), ("Axis", "Bearing-back", "CLJ", 1), ("Axis", "Seal", "CLJ", 1),
    ("Back-cover", "Bearing-back", "CLJ", 1),
    ("Front-cover", "Bearing-front", "CLJ", 1), ("Front-cover", "Seal", "CLJ", 1),
    ("Stator", "Body", "CLJ", 1),
] + [(f"Screw-{i}", other, "CLJ", 1) for i in range(1, 5) for other in ("Body", "Back-cover", "Front-cover")]


def unordered_pairs(result):
    """Counter of (frozenset{a, b}, type)."""
    return Counter((frozenset((c.a, c.b)), c.type) for c in result.contacts)


def test_motor_gives_exactly_the_papers_contacts(sample):
    result = analysis.find_contacts_in_step(sample("motor.step"))
    expected = Counter()
    for a, b, kind, n in PAPER_MOTOR:
        expected[(frozenset((a, b)), kind)] += n
    assert unordered_pairs(result) == expected
    assert result.counts() == Counter({"CLJ": 21, "PLF": 14})
    assert len(result.bodies) == 18  # the paper lists 18 parts (the issue says 19 but lists 18)


@pytest.mark.parametrize("name, expected", [
    ("R01_as1-oc-214.stp", {"PLF": 16, "CLJ": 22}),
    ("D03_asm4_tuto2_disk_arm.step", {"PLF": 3, "CLJ": 1}),
    ("R09_chrono_assembly.stp", {"PLF": 1, "CLJ": 1}),
    ("R10_wrenchnut.stp", {}),
    ("R08_presse_asm.step", {"PLF": 8, "CLJ": 7}),
    ("R05_SKF_6004.stp", {"SPT": 18}),
    ("R06_bearing_20x37x9_freecad.stp", {"SPT": 28}),
])
def test_shared_files_exact_counts(shared_step, name, expected):
    result = analysis.find_contacts_in_step(shared_step(name))
    assert dict(result.counts()) == expected


@pytest.mark.parametrize("name, balls", [("R05_SKF_6004.stp", 9), ("R06_bearing_20x37x9_freecad.stp", 14)])
def test_every_bearing_ball_touches_both_raceways(shared_step, name, balls):
    # R06's raceway faces have their u range shifted by a turn (u in [pi, 3 pi]).
    result = analysis.find_contacts_in_step(shared_step(name))
    per_body = Counter(n for c in result.contacts for n in (c.a, c.b))
    rings = [n for n, k in per_body.items() if k == balls]
    assert len(rings) == 2, per_body
    assert sorted(k for n, k in per_body.items() if n not in rings) == [2] * balls


def test_chrono_is_one_body_pair(shared_step):
    result = analysis.find_contacts_in_step(shared_step("R09_chrono_assembly.stp"))
    assert len(result.by_pair()) == 1


def test_native_document_through_links(shared_fcstd):
    doc = freecad_setup.open_document(shared_fcstd("Asm4_Tutorial2/asm_tuto2.FCStd"))
    try:
        result, found = analysis.find_contacts_in_document(doc)
        assert result.counts() == Counter({"PLF": 3, "CLJ": 1})
        for contact in result.contacts:
            assert all(name.startswith("Face") for name in contact.faces_a + contact.faces_b)
    finally:
        FreeCAD.closeDocument(doc.Name)


def test_contact_faces_are_the_objects_faces():
    lower = Part.makeBox(10, 10, 10)
    upper = Part.makeBox(4, 4, 4, FreeCAD.Vector(2, 2, 10))
    (contact,) = analysis.find_contacts_in_shapes([("lower", lower), ("upper", upper)]).contacts
    top = lower.getElement(contact.faces_a[0])
    bottom = upper.getElement(contact.faces_b[0])
    assert top.normalAt(0, 0).z == pytest.approx(1) and top.BoundBox.ZMin == pytest.approx(10)
    assert bottom.normalAt(0, 0).z == pytest.approx(-1) and bottom.BoundBox.ZMin == pytest.approx(10)


def test_progress_reports_and_cancels():
    shapes = [("a", Part.makeBox(1, 1, 1)), ("b", Part.makeBox(1, 1, 1, FreeCAD.Vector(1, 0, 0)))]
    stages = []
    analysis.find_contacts_in_shapes(shapes, progress=lambda stage, f: stages.append(stage) or True)
    assert "partitions" in stages and "contacts" in stages
    with pytest.raises(core.Cancelled):
        analysis.find_contacts_in_shapes(shapes, progress=lambda stage, f: False)


def test_make_contact_analysis_records_contacts_in_the_tree(shared_fcstd):
    from contactwb.make import make_contact_analysis
    doc = freecad_setup.open_document(shared_fcstd("Asm4_Tutorial2/asm_tuto2.FCStd"))
    try:
        group = make_contact_analysis(doc)
        assert len(group.Group) == 4
        assert sorted(group.Summary) == ["CLJ: 1", "PLF: 3"]
        for contact in group.Group:
            (root, subnames), = contact.FacesA
            for subname in subnames:
                face = root.getSubObject(subname)
                assert face is not None and face.ShapeType == "Face", subname
    finally:
        FreeCAD.closeDocument(doc.Name)


def test_find_contacts_again_after_an_analysis(shared_fcstd):
    """Contacts link to the bodies; the bodies must still be found next time."""
    from contactwb.make import make_contact_analysis
    doc = freecad_setup.open_document(shared_fcstd("Asm4_Tutorial2/asm_tuto2.FCStd"))
    try:
        first = make_contact_analysis(doc)
        second = make_contact_analysis(doc)
        assert len(second.Group) == len(first.Group) == 4
    finally:
        FreeCAD.closeDocument(doc.Name)


def run_cli(*args):
    env = dict(os.environ, PYTHONPATH=REPO)
    return subprocess.run([sys.executable, "-m", "contactwb.cli", *args], capture_output=True, text=True,
                          env=env, cwd=REPO, timeout=300)


def test_cli_json_schema(sample):
    out = run_cli(sample("motor.step"), "--json")
    assert out.returncode == 0, out.stderr
    data = json.loads(out.stdout)
    assert data["units"] == "mm"
    assert len(data["bodies"]) == 18
    assert {"name", "volume", "center"} <= set(data["bodies"][0])
    assert len(data["contacts"]) == 35
    assert {"type", "a", "b", "area", "partial"} <= set(data["contacts"][0])
    names = {b["name"] for b in data["bodies"]}
    assert all(c["a"] in names and c["b"] in names for c in data["contacts"])


def test_cli_table_has_totals(sample):
    out = run_cli(sample("motor.step"))
    assert out.returncode == 0, out.stderr
    assert "Planar fits (PLF): 14" in out.stdout
    assert "Cylindrical joints (CLJ): 21" in out.stdout
    assert "Total: 35 contacts" in out.stdout


def test_cli_bad_file_is_a_clear_error(tmp_path):
    bad = tmp_path / "broken.step"
    bad.write_text("ISO-10303-21;\nnot really\n")
    out = run_cli(str(bad))
    assert out.returncode == 3  # unreadable input
    assert "broken.step" in out.stderr


def test_cli_reads_freecad_documents(shared_fcstd):
    out = run_cli(shared_fcstd("Asm4_Tutorial2/asm_tuto2.FCStd"), "--json")
    assert out.returncode == 0, out.stderr
    data = json.loads(out.stdout)
    assert Counter(c["type"] for c in data["contacts"]) == Counter({"PLF": 3, "CLJ": 1})
    assert sorted(b["name"] for b in data["bodies"]) == ["arm001", "base001", "disk001"]


def test_surface_models_in_documents_are_skipped_with_a_message():
    doc = FreeCAD.newDocument("surfaces")
    try:
        solid = doc.addObject("Part::Feature", "Block")
        solid.Shape = Part.makeBox(10, 10, 10)
        sheet = doc.addObject("Part::Feature", "Sheet")
        sheet.Shape = Part.makePlane(4, 4, FreeCAD.Vector(2, 2, 10))  # a surface, lying on the block
        result, found = analysis.find_contacts_in_document(doc)
        assert [b.name for b in found] == ["Block"]
        assert any("Sheet" in message and "no solid" in message for message in result.messages)
    finally:
        FreeCAD.closeDocument(doc.Name)


def test_faces_that_failed_typing_are_reported():
    """A body whose partitions carry a failure note (a face OCCT could not
    evaluate) is named in the analysis messages, with the face."""
    from types import SimpleNamespace
    shapes = [("a", Part.makeBox(1, 1, 1)), ("b", Part.makeBox(1, 1, 1, FreeCAD.Vector(1, 0, 0)))]
    assembly = document_shapes.assembly_from_shapes(shapes)
    real = core.contactcore.find_contacts(assembly)
    failed = SimpleNamespace(status="surface cannot be evaluated (Face3)")
    fake = SimpleNamespace(contacts=real.contacts, times=real.times, tolerances=real.tolerances,
                           body_pairs=real.body_pairs, candidates=real.candidates,
                           skipped=real.skipped, messages=real.messages, interferences=real.interferences,
                           partitions=[real.partitions[0], failed])
    result = analysis._analysis("test", assembly, fake)
    assert result.messages == ["body 'b': surface cannot be evaluated (Face3)"]
