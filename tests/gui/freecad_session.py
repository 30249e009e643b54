"""Runs one session script in the real FreeCAD GUI under Xvfb, with the
workbench installed in a throwaway home, and returns the JSON report the
script wrote to $CONTACTS_GUI_RESULT. Shared by the GUI test files."""
import json
import os
import shutil
import subprocess
import sys

import pytest

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
BUILD_DIR = os.environ.get("CONTACTS_BUILD_DIR", os.path.join(REPO, "build"))
# screenshots and reports, kept to look at (CONTACTS_GUI_OUT_DIR: elsewhere than the build, e.g. when
# several worktrees run their tests against one build)
OUT_DIR = os.environ.get("CONTACTS_GUI_OUT_DIR") or os.path.join(BUILD_DIR, "gui-tests")


def run_session(tmp_path_factory, script, report_name, env_extra=None, screen="1280x1024x24", timeout=300,
                install=True):
    """install=False: a FreeCAD without the workbench (a home lacking Mod/Contacts)."""
    if not shutil.which("xvfb-run") or not shutil.which("freecad"):
        pytest.skip("xvfb-run or freecad missing (make deps)")
    home = tmp_path_factory.mktemp("home")
    os.makedirs(OUT_DIR, exist_ok=True)
    if install:
        subprocess.run([sys.executable, os.path.join(REPO, "tools", "install_workbench.py"), "--build-dir", BUILD_DIR,
                        "--mod-dir", str(home / ".local/share/FreeCAD/Mod/Contacts"), "--bin-dir", str(home / "bin")],
                       check=True, capture_output=True)
    result = os.path.join(OUT_DIR, report_name)
    if os.path.exists(result):
        os.remove(result)
    env = dict(os.environ, HOME=str(home), QTWEBENGINE_DISABLE_SANDBOX="1", CONTACTS_GUI_OUT=OUT_DIR,
               CONTACTS_GUI_RESULT=result, **(env_extra or {}))
    env.pop("CONTACTS_PYTHON_DIR", None)  # the GUI must use the installed extension
    proc = subprocess.run(["xvfb-run", "-a", "-s", f"-screen 0 {screen}", "freecad",
                           os.path.join(REPO, "tests", "gui", script)],
                          env=env, capture_output=True, text=True, timeout=timeout)
    assert os.path.exists(result), f"FreeCAD wrote no report:\n{proc.stdout[-3000:]}\n{proc.stderr[-3000:]}"
    with open(result) as stream:
        return json.load(stream)
