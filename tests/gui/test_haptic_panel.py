"""The haptic trial panel in the real FreeCAD GUI under Xvfb: a scripted
insertion of the motor's axis into its bearings (tests/gui/haptic_session.py)."""
import os

import pytest

from freecad_session import REPO, run_session  # tests/gui is on sys.path


@pytest.fixture(scope="module")
def haptic_report(tmp_path_factory):
    report = run_session(tmp_path_factory, "haptic_session.py", "haptic_report.json",
                         {"CONTACTS_SAMPLE": os.path.join(REPO, "Resources", "samples", "motor.FCStd"),
                          "CONTACTS_TRIAL_SCRIPT": os.path.join(REPO, "Resources", "trials", "motor_axis_insertion.json")})
    assert not report["errors"], "\n".join(report["errors"])
    return report


def test_panel_opens_on_the_selected_part(haptic_report):
    assert haptic_report["command_listed"]
    assert haptic_report["panel_open"]
    assert "Simulated hand" in haptic_report["device_message"]
    assert haptic_report["stiffness_max"] == 2.0  # the simulated device's limit


def test_scripted_insertion_moves_the_axis_in_the_view(haptic_report):
    # Captured on the bores' axis from the start; halfway in after 1.2 s of 2.5.
    assert haptic_report["z_first"] > 25.0
    assert 5.0 < haptic_report["mid_offset"][2] < 25.0
    assert haptic_report["mid_joint"].startswith("Cylindrical with")
    assert haptic_report["engaged_all"]
    assert haptic_report["max_penetration"] <= 0.05
    # Recorded at display rate (fewer frames on a loaded machine): the whole script and settling.
    assert haptic_report["samples"] >= 10
    assert haptic_report["recorded_times_increase"]
    assert haptic_report["recorded_span_s"] >= 3.0


def test_ok_commits_one_undoable_placement(haptic_report):
    assert haptic_report["panel_closed"]
    assert haptic_report["final_offset_mm"] < 0.05
    assert haptic_report["final_angle_deg"] < 0.1
    assert haptic_report["undo_added"] == ["Haptic trial"]
    assert haptic_report["undo_restores"]


def test_screenshots_were_taken(haptic_report):
    from PIL import Image
    for key in ("mid_png", "end_png", "panel_png"):
        image = Image.open(haptic_report[key]).convert("RGB")
        assert image.width > 300 and len(set(image.getdata())) > 20
