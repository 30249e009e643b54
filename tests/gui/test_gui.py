"""GUI tests: the real FreeCAD GUI under Xvfb, with the workbench installed in
a throwaway home, driven by tests/gui/gui_session.py."""
import json
import os
import shutil
import subprocess
import sys

import pytest

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
BUILD_DIR = os.environ.get("CONTACTS_BUILD_DIR", os.path.join(REPO, "build"))
ORANGE = (255, 140, 26)  # the highlight colour of the workbench's icons


@pytest.fixture(scope="module")
def gui_report(tmp_path_factory):
    if not shutil.which("xvfb-run") or not shutil.which("freecad"):
        pytest.skip("xvfb-run or freecad missing (make deps)")
    home = tmp_path_factory.mktemp("home")
    out_dir = os.path.join(BUILD_DIR, "gui-tests")
    os.makedirs(out_dir, exist_ok=True)
    subprocess.run([sys.executable, os.path.join(REPO, "tools", "install_workbench.py"), "--build-dir", BUILD_DIR,
                    "--mod-dir", str(home / ".local/share/FreeCAD/Mod/Contacts"), "--bin-dir", str(home / "bin")],
                   check=True, capture_output=True)
    result = os.path.join(out_dir, "gui_report.json")
    if os.path.exists(result):
        os.remove(result)
    env = dict(os.environ, HOME=str(home), QTWEBENGINE_DISABLE_SANDBOX="1", CONTACTS_GUI_OUT=out_dir,
               CONTACTS_GUI_RESULT=result,
               CONTACTS_SAMPLE=os.path.join(REPO, "Resources", "samples", "motor.FCStd"))
    env.pop("CONTACTS_PYTHON_DIR", None)  # the GUI must use the installed extension
    proc = subprocess.run(["xvfb-run", "-a", "-s", "-screen 0 1280x1024x24", "freecad",
                           os.path.join(REPO, "tests", "gui", "gui_session.py")],
                          env=env, capture_output=True, text=True, timeout=300)
    assert os.path.exists(result), f"FreeCAD wrote no report:\n{proc.stdout[-3000:]}\n{proc.stderr[-3000:]}"
    with open(result) as stream:
        report = json.load(stream)
    assert not report["errors"], "\n".join(report["errors"])
    return report


def test_workbench_is_listed_and_activates(gui_report):
    assert gui_report["workbench_listed"]
    assert gui_report["active_workbench"] == "ContactsWorkbench"


def test_toolbar_shows_only_working_commands(gui_report):
    assert gui_report["toolbar_visible"]
    assert gui_report["toolbar_actions"] == ["Find contacts"]


def test_find_contacts_command_fills_the_tree(gui_report):
    assert gui_report["analyses"] == 1
    assert gui_report["contacts"] == 35
    assert sorted(gui_report["summary"]) == ["CLJ: 21", "PLF: 14"]
    assert "Find contacts" in gui_report["undo_names"]
    assert gui_report["selected_faces"] >= 2


def test_screenshot_shows_the_toolbar(gui_report):
    from PIL import Image
    window_png, view_png = gui_report["screenshots"]
    image = Image.open(window_png).convert("RGB")
    scale = image.width / gui_report["window_width"]
    x, y, w, h = (round(v * scale) for v in gui_report["first_button_rect"])
    button = image.crop((x, y, x + w, y + h))
    orange = sum(1 for p in button.getdata() if all(abs(a - b) < 40 for a, b in zip(p, ORANGE)))
    assert orange >= 10, f"the Find contacts icon is not visible at {x},{y} in {window_png}"
    view = Image.open(view_png).convert("RGB")
    colours = len(set(view.resize((100, 75)).getdata()))
    assert colours > 20, f"the 3D view looks empty: {view_png}"
