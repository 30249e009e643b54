"""Contacts_ShowSimulationModel in the real FreeCAD GUI under Xvfb: the motor's
front cover, its collision model with the front bearing's joint switched off
(tests/gui/simulation_model_session.py)."""
import os

import pytest

from freecad_session import REPO, run_session  # tests/gui is on sys.path


@pytest.fixture(scope="module")
def model_report(tmp_path_factory):
    report = run_session(tmp_path_factory, "simulation_model_session.py", "simulation_model_report.json",
                         {"CONTACTS_SAMPLE": os.path.join(REPO, "Resources", "samples", "motor.FCStd")})
    assert not report["errors"], "\n".join(report["errors"])
    return report


def test_command_adds_one_undoable_model(model_report):
    assert model_report["command_listed"]
    assert model_report["models"] == 1
    assert model_report["label"] == "Collision model of Front-cover"
    assert model_report["undo_added"] == ["Show simulation model"]
    assert model_report["undone"]


def test_the_collision_model_loses_the_small_holes_within_its_envelope(model_report):
    assert model_report["simplified"]
    assert model_report["hausdorff"] == pytest.approx(4.0, abs=1e-6)
    assert model_report["triangles"] < model_report["triangles_coarse"]  # holes gone, fewer triangles


def test_scene_has_every_triangle_with_its_partition_colour(model_report):
    r = model_report
    assert r["layers_found"] and r["legend"]
    assert r["active_triangles"] + r["off_triangles"] == r["triangles"]
    assert r["off_triangles"] > 0 and r["off_striped"]
    # Each drawn triangle's colour index is its partition, and each partition its own colour.
    assert r["material_index"] == r["drawn_partitions"]
    colours = r["colours"]
    used = sorted(set(r["material_index"]))
    assert len({tuple(round(c, 6) for c in colours[p]) for p in used}) == len(used)
    assert set(r["switched_off"]) <= set(r["mesh_partitions"]) and r["switched_off"]
    assert r["hidden_switch"] == -1 and r["shown_switch"] == -3  # SO_SWITCH_NONE, SO_SWITCH_ALL


def test_screenshots_were_taken(model_report):
    from PIL import Image
    for key in ("png", "png_top"):
        image = Image.open(model_report[key]).convert("RGB")
        assert image.width == 900 and len(set(image.getdata())) > 20


LEGEND_ROWS = 90  # the legend's three lines of text, top left of the saved images


def drawn_box(path):
    """(left, top, right, bottom) of what is drawn below the legend in a saved image: pixels off the
    white background."""
    from PIL import Image
    image = Image.open(path).convert("L")
    below = image.crop((0, LEGEND_ROWS, image.width, image.height)).point(lambda v: 255 if v < 235 else 0)
    left, top, right, bottom = below.getbbox()
    return left, top + LEGEND_ROWS, right, bottom + LEGEND_ROWS


def test_fit_all_centres_the_model_not_the_legend(model_report):
    # The centre of the model's bounding box, projected with the view's camera after Fit all,
    # lands on the view's centre: the legend's text no longer counts in the fit.
    for key in ("centre_on_screen", "centre_on_screen_top"):
        x, y = model_report[key]
        assert x == pytest.approx(0.5, abs=0.01) and y == pytest.approx(0.5, abs=0.01), (key, x, y)
    # And in the saved images: what is drawn sits around the image's centre and fills it.
    for key in ("png", "png_top"):
        left, top, right, bottom = drawn_box(model_report[key])
        assert top > LEGEND_ROWS + 5, model_report[key]  # nothing of the model hidden by the legend's band
        assert (left + right) / 2 == pytest.approx(900 / 2, abs=900 * 0.03), (key, left, right)
        assert (top + bottom) / 2 == pytest.approx(700 / 2, abs=700 * 0.03), (key, top, bottom)
        # Fit all frames the bounding sphere (diameter 69.5 mm around the 48 x 48 x 15 mm cover) in the
        # image's height: the cover's 48 mm across span about 480 px of 700 (before, with the legend's
        # text near the origin counted in, under 390).
        assert right - left == pytest.approx(48 / 69.5 * 700, rel=0.05), (key, left, right)
