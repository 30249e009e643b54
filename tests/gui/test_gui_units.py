"""Issue 21 item 11 in the real FreeCAD GUI under Xvfb (tests/gui/units_session.py):
tolerances in mm and degrees, one area written alike in the tree, the
property editor and the table, the preferences page's icon, STEP imports
named from the file's products with sizes in mm (an inch file too)."""
import math
import os
import re

import pytest

from freecad_session import REPO, run_session  # tests/gui is on sys.path

SHARED = os.path.join(os.path.dirname(REPO), "shared", "data")
MOTOR_PARTS = 18


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    return run_session(tmp_path_factory, "units_session.py", "units_report.json",
                       {"CONTACTS_REPO": REPO, "CONTACTS_SHARED_DATA": SHARED if os.path.isdir(SHARED) else ""},
                       screen="1400x1050x24", timeout=560)


def no_error(report, *steps):
    for name in steps:
        assert name not in report["errors"], report["errors"][name]


def test_preferences_page_has_an_icon_and_the_real_default(run):
    no_error(run, "preferences_dialog")
    seen = run["preferences"]
    assert "error" not in seen, seen.get("error")
    assert "Contacts" in seen["groups"]
    assert seen["icon"] and seen["icon_pixels"] > 200  # drawn (48 x 48), not an empty icon
    # 1e-4 rad, the core's default, is 0.0057296 deg: shown as such, not "0.01"
    assert seen["fields"] == ["scaled to the model", "default (0.00573 \u00b0)"]


def test_panel_tolerances_in_mm_and_degrees(run):
    no_error(run, "task_panel_units")
    panel = run["panel"]
    assert panel["linear"] == pytest.approx(panel["model_linear"], abs=1e-12)
    # the model's linear default in mm with its digits (never "975.09 nm")
    number, unit = panel["linear_text"].split(" ")
    assert unit == "mm" and float(number) == pytest.approx(panel["model_linear"], rel=1e-3)
    assert panel["angular_text"] == "0.00573 \u00b0"
    assert panel["angular"] == pytest.approx(math.degrees(panel["model_angular"]), rel=1e-9)
    # other units typed are converted
    assert panel["typed_um"] == pytest.approx(0.0005) and panel["typed_um_text"] == "0.0005 mm"
    assert panel["accepted"] is True


def test_an_area_reads_alike_in_tree_property_editor_and_table(run):
    no_error(run, "areas_alike")
    largest, smallest = sorted(run["areas"], key=lambda a: a["area"], reverse=True)
    for entry in (largest, smallest):
        assert entry["type_id"] == "App::PropertyArea"
        assert entry["editor"] is not None, "the property editor was not found"
        assert entry["label2"].split(",")[0] == entry["editor"] == entry["table"], entry
    # the Standard schema: the motor's largest contact in cm^2, its smallest in mm^2, as FreeCAD writes them
    assert largest["area"] >= 100 and largest["editor"] == f"{largest['area'] / 100:.2f} cm^2"
    assert smallest["area"] < 100 and smallest["editor"] == f"{smallest['area']:.2f} mm^2"


def test_every_quantity_reads_alike_in_property_editor_panel_tree_and_table(run):
    """Issue 21 item 11: the tolerances, areas, spans and radii say the same thing wherever they show,
    as the user's unit preferences say (FreeCAD's defaults here: the Standard schema, 2 decimals), never
    rounded to zero or contradicting each other."""
    no_error(run, "quantities_alike")
    seen = run["quantities"]
    assert (seen["schema"], seen["decimals"]) == (0, 2)
    linear, angular = seen["used"]
    # the tolerances in mm and degrees with their digits, the property editor as the panel (FreeCAD's
    # quantity properties wrote "787.91 nm" and "0.01 °")
    linear_text = f"{linear:.{3 - math.floor(math.log10(linear))}f}".rstrip("0") + " mm"
    assert angular == pytest.approx(math.degrees(1e-4), rel=1e-12)  # the core's default, 1e-4 rad
    assert seen["editor"] == {"Linear Tolerance": linear_text, "Angular Tolerance": "0.00573 °",
                              "Linear Tolerance Setting": "scaled to the model",
                              "Angular Tolerance Setting": "default"}
    assert seen["panel"] == [linear_text, "0.00573 °"]
    assert float(linear_text.split()[0]) == pytest.approx(linear, rel=5e-4)
    # a setting typed in micrometres reads in mm, as the panel would write it
    assert seen["typed_setting"] == "0.0005 mm"
    assert seen["default_setting"] == "scaled to the model"
    smallest, largest = seen["contacts"]
    assert smallest["radius"] < largest["radius"]
    for contact in (smallest, largest):
        # the Standard schema: an area under 100 mm^2 in mm^2, above in cm^2; angles in degrees; lengths in mm
        area = contact["area"]
        area_text = f"{area:.2f} mm^2" if area < 100 else f"{area / 100:.2f} cm^2"
        span_text, radius_text = f"{contact['span']:.2f} \u00b0", f"{contact['radius']:.2f} mm"
        assert contact["editor"] == {"Area": area_text, "Span": span_text, "Radius": radius_text}, contact
        assert contact["table"] == contact["editor"], contact
        # the tree's description: the area (a full turn: no span)
        assert not contact["partial"] and contact["label2"] == area_text
        assert contact["span"] == pytest.approx(360)


def test_a_new_unit_schema_rewrites_the_tree_as_the_property_editor(run):
    """The user switches Preferences -> Units to "Metric small parts & CNC" and back: the tree's
    description column follows the property editor at once (no recompute), the table too; nothing enters
    the undo stack, nothing needs a recompute."""
    no_error(run, "schema_changed")
    seen = run["schema"]
    area = seen["area"]
    assert area == pytest.approx(2907.0192476168304, rel=1e-9)  # the Stator - Body CLJ (the CLI's figure)
    assert seen["6"] == {"label2": f"{area:.2f} mm^2", "editor": f"{area:.2f} mm^2", "table": f"{area:.2f} mm^2"}
    standard = f"{area / 100:.2f} cm^2"
    assert seen["0"] == {"label2": standard, "editor": standard, "table": standard}
    assert seen["undo_after"] == seen["undo"] and seen["touched"] == []


def test_a_selections_tolerance_reads_alike_in_panel_and_property_editor(run):
    """Each body's default tolerance is scaled to its own box and the coarsest analysed body's is reported:
    for Screw-1 and Back-cover, smaller than the whole motor's. The panel shows that figure, not the
    document's."""
    no_error(run, "selection_tolerance_alike")
    seen = run["selection_tolerance"]
    assert seen["scope"] == "Selection" and seen["accepted"] is True
    assert seen["panel"] == seen["editor"] == seen["reopened"]
    assert seen["editor"] != seen["document"]
    number, unit = seen["editor"].split()
    assert unit == "mm" and float(number) == pytest.approx(seen["used"], rel=5e-4)
    assert float(number) < float(seen["document"].split()[0])


def test_a_partial_span_and_a_circle_radius_read_alike_in_tree_property_editor_and_table(run):
    no_error(run, "cases_alike")
    (cradle,), circles = run["cases"]["cradle_120"], run["cases"]["ball_in_bore"]
    # the 120° cradle: a partial cylinder contact, its span in the tree as in the editor and the table
    assert (cradle["type"], cradle["partial"]) == ("CLJ", True)
    assert cradle["span"] == pytest.approx(120, abs=1e-6)
    assert cradle["editor"] == {"Area": f"{cradle['area']:.2f} mm^2" if cradle["area"] < 100 else
                                f"{cradle['area'] / 100:.2f} cm^2", "Span": "120.00 \u00b0",
                                "Radius": f"{cradle['radius']:.2f} mm"}
    assert cradle["table"] == cradle["editor"]
    assert cradle["label2"] == f"{cradle['editor']['Area']}, span 120.00 \u00b0"
    # the ball in its bore: a circle contact, its radius in the tree as in the editor and the table
    assert [(c["type"], c["partial"]) for c in circles] == [("LAF", False)]  # the ball on the bore's edge
    (circle,) = circles
    assert circle["radius"] == pytest.approx(5.0) and circle["area"] == 0  # a circle: no area
    assert circle["editor"]["Radius"] == "5.00 mm"
    assert circle["table"] == circle["editor"]
    assert circle["label2"] == f"circle r {circle['editor']['Radius']}"


def test_step_import_names_parts_after_the_products(run):
    no_error(run, "imports")
    motor = run["imports"]["motor"]
    # motor.step was written from motor.FCStd: the same 18 names, none after the file
    assert len(motor["labels"]) == MOTOR_PARTS and motor["labels"] == motor["fcstd_labels"]
    assert motor["containers"] == ["motor"]
    assert motor["undo"] == ["Import STEP"]


def test_inch_step_import_in_mm_and_its_areas(run):
    inch = run["imports"]["inch"]
    assert inch["labels"] == ["Plate", "Block", "Pin"]  # inch.expected.json's bodies, in the file's order
    # the volumes FreeCAD's own reader and the millimetre document give: an inch read as a millimetre
    # would be 25.4^3 = 16387 times smaller
    for mine, part_read, fcstd in zip(inch["volumes"], inch["part_read_volumes"], inch["fcstd_volumes"]):
        assert mine == pytest.approx(part_read, rel=1e-9) and mine == pytest.approx(fcstd, rel=1e-6)
    contacts = inch["contacts"]
    assert sorted((c[0], c[1], c[2]) for c in contacts) == sorted((c[0], c[1], c[2]) for c in inch["fcstd_contacts"])
    assert sorted(c[0] for c in contacts) == ["CLJ", "CLJ", "PLF", "PLF"]
    for (kind, a, b, area, brute, label2, editor), reference in zip(contacts, inch["fcstd_contacts"]):
        assert area == pytest.approx(reference[3], rel=1e-6)  # as in the millimetre document
        assert area == pytest.approx(brute, rel=1e-3)         # the two sides' common area by OCCT's Boolean
        assert label2.split(",")[0] == editor and "e+" not in label2


def test_shared_step_files_named_after_their_products(run):
    no_error(run, "shared_imports")
    if run["shared"] is None:
        pytest.skip(f"shared data absent: {SHARED}")
    for name, entry in run["shared"].items():
        labels = entry["labels"]
        assert labels and len(set(labels)) == len(labels), name
        assert all(count == 1 for count in entry["solids"]), name  # one solid per part
        for label in labels:
            base = re.sub(r"\.\d+$", "", label)  # repeated instances: "Ball.2"
            assert not label.startswith("Undefined"), (name, label)
            assert base not in ("SOLID", "SHELL", "COMPOUND"), (name, label)  # OCCT's names, not the file's
            assert base != entry["stem"], (name, label)  # never named after the file
            assert base in entry["products"], (name, label)  # a name the file declares
