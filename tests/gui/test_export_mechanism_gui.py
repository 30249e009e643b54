"""Contacts_ExportMechanism in the real FreeCAD GUI under Xvfb: the motor's
mechanism (its sidecar annotations: two rigid groups) written as URDF and
MJCF through the command's dialog (tests/gui/export_mechanism_session.py);
the files checked here as the CLI's are (tests/test_mechanism_export.py)."""
import os
import re
import shutil
import subprocess

import pytest

from freecad_session import REPO, run_session  # tests/gui is on sys.path

SAMPLES = os.path.join(REPO, "Resources", "samples")


@pytest.fixture(scope="module")
def export_report(tmp_path_factory):
    report = run_session(tmp_path_factory, "export_mechanism_session.py", "export_mechanism_report.json",
                         {"CONTACTS_SAMPLE": os.path.join(SAMPLES, "motor.FCStd")})
    assert not report["errors"], "\n".join(report["errors"])
    return report


def test_command_is_listed_on_the_toolbar_and_needs_an_analysis(export_report):
    assert export_report["command_listed"] and export_report["toolbar_has_command"]
    assert export_report["active_before"] is False and export_report["active_after"] is True


def test_dialog_offers_both_formats_and_the_sidecar_annotations(export_report):
    urdf, mjcf = export_report["dialogs"]
    assert urdf["title"] == "Export mechanism"
    assert [f.split(":")[0].split(" ")[0] for f in urdf["formats"]] == ["URDF", "MJCF"]
    assert urdf["annotations"] == os.path.join(SAMPLES, "motor.annotations.json")
    assert urdf["density"] == 7850.0
    assert urdf["grounds"] == 1 + 18  # "the group with the most bodies" and the motor's 18 bodies
    assert urdf["suggested"] == os.path.join(SAMPLES, "motor_urdf")
    assert mjcf["suggested"] == os.path.join(SAMPLES, "motor.xml")
    for dialog in (urdf, mjcf):
        assert os.path.getsize(dialog["png"]) > 0


def test_urdf_written_by_the_command_is_the_motor_s_two_links(export_report):
    assert export_report["urdf_files"] == ["meshes", "motor.urdf"]
    text = open(os.path.join(export_report["urdf_dir"], "motor.urdf")).read()
    assert re.findall(r'<link name="([^"]+)"', text) == ["world", "Body", "Axis"]
    assert '<joint name="Body__Axis" type="continuous">' in text
    assert len(os.listdir(os.path.join(export_report["urdf_dir"], "meshes"))) == 18
    tool = shutil.which("check_urdf")
    if tool:
        done = subprocess.run([tool, os.path.join(export_report["urdf_dir"], "motor.urdf")], capture_output=True,
                              text=True)
        assert done.returncode == 0, done.stdout + done.stderr


def test_mjcf_written_by_the_command_has_one_hinge(export_report):
    assert export_report["mjcf_files"] == ["motor.xml", "motor_meshes"]
    text = open(export_report["mjcf"]).read()
    assert re.findall(r'<joint name="([^"]+)" type="(\w+)"', text) == [("Body__Axis", "hinge")]
    assert export_report["undo_unchanged"]
