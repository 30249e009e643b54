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
