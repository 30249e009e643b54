"""The driver seen from Python: parallel runs equal serial ones contact for
contact, volumes and centres computed lazily and once, unique names from the
one implementation in the core, skipped pairs in the table and JSON, the
pair limit through the API and the CLI."""
import json

import pytest

import FreeCAD
import Part
from contactwb import analysis, bodies, cli, core


def contact_rows(result):
    return [(c.type, c.a, c.b, c.faces_a, c.faces_b, c.area, c.partial, c.span, c.radius, c.point, c.direction)
            for c in result.contacts]


def test_parallel_equals_serial_on_the_motor(sample):
    assembly = core.contactcore.read_step(sample("motor.step"))
    serial = analysis.find_contacts_in_assembly(assembly, threads=1)
    assert len(serial.contacts) == 35
    for threads in (0, 2, 5):
        parallel = analysis.find_contacts_in_assembly(assembly, threads=threads)
        assert contact_rows(parallel) == contact_rows(serial), threads
        assert (parallel.body_pairs, parallel.candidates) == (serial.body_pairs, serial.candidates)


def test_parallel_equals_serial_on_the_shared_press(shared_step):
    assembly = core.contactcore.read_step(shared_step("R08_presse_asm.step"))
    serial = analysis.find_contacts_in_assembly(assembly, threads=1)
    parallel = analysis.find_contacts_in_assembly(assembly, threads=3)
    assert contact_rows(parallel) == contact_rows(serial)


def test_volumes_and_centres_are_lazy_and_right(sample):
    result = analysis.find_contacts_in_step(sample("motor.step"))
    table = result.bodies[0]._mass
    assert table._values is None  # the table and contacts need no mass properties
    result.table()
    assert table._values is None
    shapes = Part.read(sample("motor.step")).Solids  # same order as the core's read
    assert len(shapes) == len(result.bodies)
    for body, solid in zip(result.bodies, shapes):
        assert body.volume == pytest.approx(solid.Volume, rel=1e-9)
        assert body.center == pytest.approx(tuple(solid.CenterOfMass), abs=1e-6)
    assert table._values is not None and table._assembly is None  # computed once, the assembly let go
    data = result.to_json()
    assert data["bodies"][0]["volume"] == pytest.approx(shapes[0].Volume, rel=1e-9)


def test_document_names_come_from_the_core_rule():
    class Named:
        def __init__(self, name):
            self.name = name
    named = [Named(n) for n in ["Screw", "Screw.3", "Screw", "Screw", "Nut"]]
    bodies._make_names_unique(named)
    assert [b.name for b in named] == ["Screw", "Screw.3", "Screw.2", "Screw.4", "Nut"]
    assert core.contactcore.unique_names(["a"] * 3) == ["a", "a.2", "a.3"]


def test_skipped_pairs_show_in_the_table_and_the_json():
    result = analysis.Analysis(
        source="s", units="mm", linear_tolerance=1e-3, angular_tolerance=1e-4, bodies=[], contacts=[],
        messages=["skipped the candidate pair 'a' Face6 / 'b' Face5: OCCT: boom"],
        skipped=[analysis.SkippedRecord("a", "b", ["Face6"], ["Face5"], "OCCT: boom")])
    table = result.table()
    assert "note: skipped the candidate pair 'a' Face6 / 'b' Face5: OCCT: boom" in table
    assert table.splitlines()[-1] == ("Skipped 1 candidate pair(s) whose test failed, the rest kept "
                                      "(see the notes): a <-> b")
    assert result.to_json()["skipped"] == [
        {"a": "a", "b": "b", "faces_a": ["Face6"], "faces_b": ["Face5"], "message": "OCCT: boom"}]


def test_no_skipped_pairs_on_the_motor(sample):
    data = analysis.find_contacts_in_step(sample("motor.step")).to_json()
    assert data["skipped"] == []


def overlapping_copies(count):
    return [(f"copy{i}", Part.makeBox(10, 10, 10)) for i in range(count)]


def test_too_many_overlapping_bodies_raise_a_clear_error():
    with pytest.raises(core.ContactsError, match=r"more than 100 body pairs .*--max-pairs"):
        analysis.find_contacts_in_shapes(overlapping_copies(30), max_pairs=100)  # 435 pairs
    # Raised above the real count, the same input goes through.
    result = analysis.find_contacts_in_shapes(overlapping_copies(30), max_pairs=435)
    assert result.body_pairs == 435


def test_cli_max_pairs(tmp_path, capsys):
    path = str(tmp_path / "copies.step")
    Part.makeCompound([shape for _, shape in overlapping_copies(30)]).exportStep(path)
    assert cli.main([path, "--max-pairs", "100"]) == cli.EXIT_INPUT  # heavily overlapping input
    assert "more than 100 body pairs" in capsys.readouterr().err
    assert cli.main([path, "--max-pairs", "1000", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert len(data["bodies"]) == 30 and data["skipped"] == []
