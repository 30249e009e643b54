"""The haptic panel without hardware, in the real FreeCAD GUI under Xvfb
(tests/gui/haptic_hand_session.py): the motor with its contact analysis
drawn, the simulated hand driven by the panel's sliders, the contact overlay
not redrawn while the part moves, the active-constraints readout, Replay of
the bundled trial script, OK committing the placement. The panel's display
rate is measured and printed (not asserted: a timing on a shared machine)."""
import os

import pytest

from freecad_session import REPO, run_session  # tests/gui is on sys.path


@pytest.fixture(scope="module")
def hand_report(tmp_path_factory):
    report = run_session(tmp_path_factory, "haptic_hand_session.py", "haptic_hand_report.json",
                         {"CONTACTS_SAMPLE": os.path.join(REPO, "Resources", "samples", "motor.FCStd"),
                          "CONTACTS_TRIAL_SCRIPT": os.path.join(REPO, "Resources", "trials",
                                                                "motor_axis_insertion.json")},
                         timeout=900)  # a software renderer on a loaded machine: about 1 s a frame
    assert not report["errors"], "\n".join(report["errors"])
    return report


def test_the_sliders_drive_the_simulated_hand(hand_report):
    assert hand_report["panel_open"]
    assert hand_report["contacts"] > 0
    assert hand_report["hand_enabled"]
    assert hand_report["sliders"] == ["rx", "ry", "rz", "x", "y", "z"]
    assert hand_report["slider_label"] == "15.0 mm"
    # Pulled 15 mm up by the hand: the axis slides out along its bores (engaged), in the document too.
    assert hand_report["pulled_snapshot"][2] == pytest.approx(15.0, abs=0.5)
    assert hand_report["pulled_offset"][2] == pytest.approx(hand_report["pulled_snapshot"][2], abs=0.5)
    assert hand_report["pulled_offset"][:2] == pytest.approx([0, 0], abs=0.05)
    assert hand_report["constraints_pulled"].startswith("Cylindrical joint with ")
    assert hand_report["constraints_pulled"].endswith("(found); no stops")


def test_no_contact_redraw_while_the_part_moves(hand_report):
    print(f"\n[ measured ] panel display rate with the contact analysis drawn: "
          f"{hand_report['update_rate_hz']:.1f} Hz while dragging ({hand_report['frames']} frames in "
          f"{hand_report['seconds']:.2f} s, the panel's own update {hand_report['update_ms']:.2f} ms a frame), "
          f"{hand_report['replay_rate_hz']:.1f} Hz while replaying; without the analysis "
          f"{hand_report['baseline_rate_hz']:.1f} Hz (update {hand_report['baseline_update_ms']:.2f} ms)")
    assert hand_report["frames"] > 0
    assert hand_report["redraws_while_moving"] == 0
    # only the moving part's placement changes: no contact, analysis or joint object, nor its view provider
    assert hand_report["result_changes_while_moving"] == []
    assert hand_report["provider_calls_while_moving"] == []
    assert hand_report["redraws_while_replaying"] == 0
    # Closing the panel redraws the contacts once, at the committed placement.
    assert 1 <= hand_report["redraws_after_ok"] <= 2


def test_the_3d_view_update_rate_while_the_hand_moves(hand_report):
    # Renders of the 3D view counted by a SoCallback first in its scene graph (every SoGLRenderAction)
    # while the Z slider pulls the axis out (4 s), the contact analysis present. Printed, not asserted:
    # Xvfb's software renderer on a shared machine (docs/haptics.md gives the figure).
    print(f"\n[ measured ] 3D view: {hand_report['view_renders']} renders in {hand_report['seconds']:.2f} s "
          f"= {hand_report['view_rate_hz']:.1f} Hz while the hand moves the axis (panel updates "
          f"{hand_report['update_rate_hz']:.1f} Hz)")
    assert hand_report["view_renders"] > 0


def test_replay_of_the_bundled_script_seats_the_axis(hand_report):
    assert hand_report["replay_error"] is None
    assert hand_report["replayed_snapshot"] == pytest.approx([0, 0, 0], abs=0.05)
    assert hand_report["replayed_offset"] == pytest.approx([0, 0, 0], abs=0.05)
    # The sliders show where the script left the hand (its last key: the assembled placement).
    assert hand_report["sliders_after_replay"] == pytest.approx([0, 0, 0, 0, 0, 0], abs=1e-9)
    assert hand_report["constraints_seated"].startswith("Cylindrical joint with ")
    assert set(hand_report["readouts"]) >= {"constraints", "depth", "force", "watchdog"}


def test_ok_commits_the_trial(hand_report):
    assert hand_report["panel_closed"]
    assert hand_report["final_offset"] == pytest.approx([0, 0, 0], abs=0.05)
    assert hand_report["undo_added"] == ["Haptic trial"]


def test_screenshots_were_taken(hand_report):
    from PIL import Image
    for key in ("sliders_png", "replay_png", "ok_png"):
        image = Image.open(hand_report[key]).convert("RGB")
        assert image.width > 300 and len(set(image.getdata())) > 20
