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


def test_joint_picker_holds_the_part_to_the_chosen_joint(haptic_report):
    # The axis' assembled joints (joints stage): cylindrical with each body it goes through.
    assert sorted(haptic_report["joint_choices"]) == sorted(
        f"Cylindrical with {b} (axis 0, 0, 1)" for b in ("Rotor-front", "Rotor-back", "Bearing-front",
                                                         "Bearing-back", "Seal"))
    assert haptic_report["joint_combo_items"][0] == "the joint found (engagement)"
    # Found: engagement holds it on the bores of all five; chosen: the loop holds it to the back bearing's.
    found = haptic_report["found_joint"]
    assert not found["held"] and sorted(found["with"]) == sorted(
        ["Rotor-front", "Rotor-back", "Bearing-front", "Bearing-back", "Seal"])
    chosen = haptic_report["chosen_joint"]
    assert chosen["held"] and chosen["with"] == ["Bearing-back"] and chosen["joint"] == "Cylindrical"
    assert chosen["axis"] == pytest.approx([0, 0, 1], abs=1e-9)
    assert chosen["point"][:2] == pytest.approx([0, 0], abs=1e-9)
    assert chosen["label"].endswith("(chosen)")
    # Pulled out and sideways by the hand: it slides out along the chosen axis only.
    pulled = haptic_report["chosen_pulled"]
    assert pulled["held"]
    assert pulled["translate"][0] == pytest.approx(0.0, abs=0.05)  # the D-flat's centre turns about the axis
    assert pulled["translate"][1] == pytest.approx(0.0, abs=0.05)
    assert pulled["rotate_deg"][:2] == pytest.approx([0, 0], abs=1e-6)
    assert not haptic_report["released_joint"]["held"]


def test_chosen_joint_lets_the_part_slide_out(haptic_report):
    # The hand 12 mm up: held to Bearing-back's bore the axis slides out (it stopped 2.9 mm out while the
    # chosen joint switched off the wrong surfaces and left its bores' rims in); all the way to the hand.
    assert haptic_report["chosen_pulled"]["translate"][2] == pytest.approx(12.0, abs=0.05)


def test_screenshots_were_taken(haptic_report):
    from PIL import Image
    assert haptic_report["view_pasted"]
    for key in ("mid_png", "end_png", "panel_png", "picker_png"):
        image = Image.open(haptic_report[key]).convert("RGB")
        assert image.width > 300 and len(set(image.getdata())) > 20


def test_parts_inside_containers_and_links(haptic_report):
    block = haptic_report["container_block"]
    assert block["object"] == "Block"
    # Moved 5 mm along global x by the hand (on the plate: a planar joint) ...
    assert block["global_move"] == pytest.approx([5, 0, 0], abs=0.05)
    # ... committed to the block in its part's frame (the part is turned 90 degrees about z).
    assert block["local"] == pytest.approx([block["global_move"][1], 5 - block["global_move"][0], 0], abs=1e-6)
    assert block["local"] == pytest.approx(block["expected_local"], abs=0.05)
    assert block["local_angle"] == pytest.approx(0, abs=1e-9)
    assert block["global_base"] == pytest.approx([95 + block["global_move"][0], block["global_move"][1], 0], abs=1e-6)
    assert block["link"] == [0, 0, 50]  # the link beside it stays
    assert haptic_report["container_undo"]
    link = haptic_report["container_link"]
    assert link["object"] == "BlockLink"
    assert link["link"] == pytest.approx([0, 3, 50], abs=0.05)
    assert link["block"] == pytest.approx([0, 5, 0], abs=1e-9)  # the original does not move
    assert "inside the linked container 'AssemblyLink'" in haptic_report["linked_container_refused"]
