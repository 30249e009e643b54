"""GUI test of contact annotations (issue 22, item 1 in FreeCAD;
tests/gui/annotation_session.py in the real FreeCAD under Xvfb): the motor
annotated as Resources/samples/motor.annotations.json says, through
Contacts_AnnotateContact from the tree, a contact's context menu and the
contact table; one undo entry per step; saved, reopened, recomputed."""
import pytest

from freecad_session import run_session  # tests/gui is on sys.path

MOTOR_CONTACTS = 35


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    return run_session(tmp_path_factory, "annotation_session.py", "annotation_report.json",
                       screen="1400x1050x24", timeout=600)


def test_session_ran_without_errors(report):
    assert not report["errors"], "\n".join(report["errors"].values())
    assert "Traceback" not in report["report_view"], report["report_view"]


def test_unannotated_motor_is_26_dof(report):
    # docs/joints.md: 26 DOF (9 passive spins), 8 rigid groups without annotations.
    assert report["unannotated"]["contacts"] == MOTOR_CONTACTS
    assert report["unannotated"]["dof"] == [26, 8]
    assert report["unannotated"]["intents"] == ["none"]


def test_annotated_through_the_commands_is_two_groups_one_dof(report):
    annotated = report["annotated"]
    # the file's 17 entries cover 17 contacts (tests/test_mechanism.py), in 7 (intent, fit) steps
    assert annotated["marked"] == 17 and annotated["contacts"] == MOTOR_CONTACTS
    assert [(s["intent"], s["fit"], s["contacts"]) for s in annotated["steps"]] == [
        ("interference", "H7/p6", 2), ("bonded", "", 5), ("interference", "N6/h5", 2),
        ("interference", "H8/s7", 1), ("clearance", "H7/g6", 2), ("clearance", "", 1), ("threaded", "", 4)]
    assert {s["how"] for s in annotated["steps"]} == {"tree", "context menu", "table"}
    for s in annotated["steps"]:
        assert s["undo"] == "Annotate contact"
        assert s["set"] == [[s["intent"], s["fit"]]]
        assert s["seen"]["ok_enabled"]
        if s["how"] == "table":
            assert len(s["seen"]["table_selected"]) == s["contacts"]
    assert annotated["undo_names"][:7] == ["Annotate contact"] * 7
    assert annotated["dof"] == [1, 2]
    assert "Rigid group 2: Axis, Rotor-front, Rotor-back, Magnet-1, Magnet-2, Magnet-3, Magnet-4 (revolute, " \
           "1 DOF)" in annotated["mobility"] or any(
               line.startswith("Rigid group 2:") and "(revolute, 1 DOF)" in line and
               {"Axis", "Rotor-front", "Rotor-back", "Magnet-1", "Magnet-2", "Magnet-3", "Magnet-4"} ==
               set(line.split(": ", 1)[1].split(" (revolute", 1)[0].split(", ")) for line in annotated["mobility"])
    # the dialog's verdict: H7/p6 at the axis' 8 mm (ISO 286: hole 0/+15, shaft +15/+24)
    first = annotated["steps"][0]["seen"]["verdict"]
    assert "interference fit at \u00d88 mm: hole +0/+15 \u00b5m, shaft +15/+24 \u00b5m, clearance -24 to 0" in first
    assert sorted(annotated["fit_classes"]) == [
        "clearance at diameter 8 mm: clearance 5 to 29 \u00b5m",
        "interference at diameter 14 mm: clearance -46 to -1 \u00b5m",
        "interference at diameter 16 mm: clearance -20 to -1 \u00b5m",
        "interference at diameter 8 mm: clearance -24 to 0 \u00b5m"]


def test_the_annotated_motor_screenshot_shows_the_model(report):
    # The window grab leaves the OpenGL area blank (one colour); the 3D view's own render pasted
    # in shows the motor, with the selected pressed contact (Axis - Rotor-front) in the selection
    # colour.
    annotated = report["annotated"]
    assert annotated["view_pasted"]
    area = annotated["view_area"]
    assert area["colours"] > 200 and area["background"] < 0.9, area
    assert area["near"] > 0.0005, area


def test_a_fit_contradicting_the_intent_is_refused_in_the_dialog(report):
    refused = report["refused"]
    assert not refused["seen"]["ok_enabled"] and refused["unchanged"]
    assert "fit H7/g6 at diameter 8 mm is a clearance fit" in refused["seen"]["verdict"]


def test_undo_returns_to_the_unannotated_joints_and_redo_back(report):
    assert report["undone"]["dof"] == [26, 8]
    assert report["undone"]["mobility"] == report["unannotated"]["mobility"]
    assert report["undone"]["intents"] == ["none"] and report["undone"]["fits"] == [""]
    assert report["redone"] == {"dof": [1, 2], "marked": 17}


def test_annotations_saved_and_kept_after_a_recompute(report):
    reopened = report["reopened"]
    assert reopened["marks"] == 17
    assert reopened["kept_on_open"] and reopened["kept_on_recompute"]
    assert reopened["dof"] == [1, 2] and not reopened["touched"]
    # the axis moved 300 mm away: its contacts (and annotations) gone, the rotor group apart
    assert reopened["dof_moved_away"][0] > 1
