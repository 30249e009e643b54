"""contactwb.export: a ContactAnalysis group to JSON or CSV (headless)."""
import csv
import json
import os

import pytest

import FreeCAD

from contactwb import export
from contactwb.analysis import find_contacts_in_document
from contactwb.make import make_contact_analysis


@pytest.fixture
def stacked_boxes():
    """A 6 x 4 block standing on a 10 x 10 one: one PLF of area 24 at z = 10."""
    doc = FreeCAD.newDocument("ExportTest")
    base = doc.addObject("Part::Box", "Base")
    base.Length = base.Width = base.Height = 10
    top = doc.addObject("Part::Box", "Top")
    top.Length, top.Width, top.Height = 6, 4, 5
    top.Placement.Base = FreeCAD.Vector(2, 3, 10)
    doc.recompute()
    group = make_contact_analysis(doc)
    yield doc, group
    FreeCAD.closeDocument(doc.Name)


def test_json_has_the_cli_schema_and_values(stacked_boxes, tmp_path):
    doc, group = stacked_boxes
    path = tmp_path / "contacts.json"
    assert export.export_contacts(group, str(path)) == 1
    data = json.loads(path.read_text())
    assert data["units"] == "mm"
    assert data["totals"] == {"PLF": 1}
    assert data["tolerances"]["linear"] == group.LinearToleranceValue.Value  # the exact value, not its text
    assert group.LinearTolerance == f"{float(group.LinearTolerance.split()[0]):g} mm"
    (contact,) = data["contacts"]
    assert list(contact) == export.CONTACT_KEYS
    assert (contact["type"], contact["a"], contact["b"]) == ("PLF", "Base", "Top")
    assert (contact["faces_a"], contact["faces_b"]) == (["Face6"], ["Face5"])  # Base's top, Top's bottom
    assert contact["area"] == pytest.approx(24.0)
    assert contact["partial"] is False
    assert contact["point"][2] == pytest.approx(10.0)
    assert contact["direction"] == pytest.approx([0.0, 0.0, 1.0])  # outward normal of Base
    # the same entries as the analysis (the CLI's --json) gives; objects named
    # because the contacts' links make the boxes non-root objects now
    result, _ = find_contacts_in_document(doc, [doc.getObject("Base"), doc.getObject("Top")])
    cli = result.to_json()["contacts"][0]
    assert contact == pytest.approx({key: cli[key] for key in export.CONTACT_KEYS})


def test_csv_has_a_header_and_one_row_per_contact(stacked_boxes, tmp_path):
    _, group = stacked_boxes
    path = tmp_path / "contacts.CSV"  # the extension is case-insensitive
    assert export.export_contacts(group, str(path)) == 1
    with open(path, newline="") as stream:
        reader = csv.reader(stream)
        header = next(reader)
        rows = list(reader)
    assert header == export.CSV_COLUMNS
    assert len(rows) == 1
    row = dict(zip(header, rows[0]))
    assert (row["type"], row["a"], row["b"]) == ("PLF", "Base", "Top")
    assert (row["faces_a"], row["faces_b"], row["partial"]) == ("Face6", "Face5", "false")
    assert float(row["area"]) == pytest.approx(24.0)
    assert float(row["point_z"]) == pytest.approx(10.0)
    assert [float(row[f"direction_{axis}"]) for axis in "xyz"] == pytest.approx([0, 0, 1])


def test_other_extensions_and_objects_are_refused(stacked_boxes, tmp_path):
    doc, group = stacked_boxes
    path = tmp_path / "contacts.txt"
    with pytest.raises(ValueError, match="json or .csv"):
        export.export_contacts(group, str(path))
    assert not path.exists()
    with pytest.raises(ValueError, match="not a contact analysis"):
        export.export_contacts(doc.getObject("Base"), str(tmp_path / "contacts.json"))
    assert not os.path.exists(tmp_path / "contacts.json")


def test_analyses_lists_the_groups(stacked_boxes):
    doc, group = stacked_boxes
    assert export.analyses(doc) == [group]
    assert export.analyses(None) == []
