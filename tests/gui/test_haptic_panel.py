"""The haptic trial panel in the real FreeCAD GUI under Xvfb: a scripted
insertion of the motor's axis into its bearings (tests/gui/haptic_session.py)."""
import json
import os
import shutil
import subprocess
import sys

import pytest

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
BUILD_DIR = os.environ.get("CONTACTS_BUILD_DIR", os.path.join(REPO, "build"))


@pytest.fixture(scope="module")
def haptic_report(tmp_path_factory):
    if not shutil.which("xvfb-run") or not shutil.which("freecad"):
        pytest.skip("xvfb-run or freecad missing (make deps)")
    home = tmp_path_factory.mktemp("home")
    out_dir = os.path.join(BUILD_DIR, "gui-tests")
    os.makedirs(out_dir, exist_ok=True)
    subprocess.run([sys.executable, os.path.join(REPO, "tools", "install_workbench.py"), "--build-dir", BUILD_DIR,
                    "--mod-dir", str(home / ".local/share/FreeCAD/Mod/Contacts"), "--bin-dir", str(home / "bin")],
                   check=True, capture_output=True)
    result = os.path.join(out_dir, "haptic_report.json")
    if os.path.exists(result):
        os.remove(result)
    env = dict(os.environ, HOME=str(home), QTWEBENGINE_DISABLE_SANDBOX="1", CONTACTS_GUI_OUT=out_dir,
               CONTACTS_GUI_RESULT=result,
               CONTACTS_SAMPLE=os.path.join(REPO, "Resources", "samples", "motor.FCStd"),
               CONTACTS_TRIAL_SCRIPT=os.path.join(REPO, "Resources", "trials", "motor_axis_insertion.json"))
    env.pop("CONTACTS_PYTHON_DIR", None)
    proc = subprocess.run(["xvfb-run", "-a", "-s", "-screen 0 1280x1024x24", "freecad",
                           os.path.join(REPO, "tests", "gui", "haptic_session.py")],
                          env=env, capture_output=True, text=True, timeout=300)
    assert os.path.exists(result), f"FreeCAD wrote no report:\n{proc.stdout[-3000:]}\n{proc.stderr[-3000:]}"
    with open(result) as stream:
        report = json.load(stream)
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
    assert haptic_report["samples"] > 60


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
