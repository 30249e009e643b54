"""Headless haptic trials: `contacts trial` on the motor (the acceptance
insertion of its axis), the script checks, the recorded path, and the
SpaceMouse parser through the binding."""
import json
import math
import os
import subprocess
import sys

import pytest

from conftest import REPO, SAMPLES

MOTOR = os.path.join(SAMPLES, "motor.step")
SCRIPT = os.path.join(REPO, "Resources", "trials", "motor_axis_insertion.json")
SHAFT_BORES = {"Rotor-front", "Rotor-back", "Bearing-front", "Bearing-back", "Seal"}


def run_cli(*args):
    env = dict(os.environ, PYTHONPATH=REPO)
    return subprocess.run([sys.executable, "-m", "contactwb.cli", "trial", *args],
                          capture_output=True, text=True, env=env, cwd=REPO)


@pytest.fixture(scope="module")
def insertion(tmp_path_factory):
    record = str(tmp_path_factory.mktemp("trial") / "path.csv")
    done = run_cli(MOTOR, "--part", "Axis", "--device", "sim", "--script", SCRIPT, "--json", "--record", record)
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout), record


def test_json_has_the_issue_fields(insertion):
    result, _ = insertion
    assert set(result) == {"mode", "ticks", "sim_time_s", "rate_hz", "step_us", "jitter_us", "overruns",
                           "realtime_priority", "success", "failure", "joints_engaged", "final",
                           "max_penetration_mm", "start_penetration_mm", "final_penetration_mm", "max_force_n"}
    assert set(result["final"]) == {"translate", "rotate_deg"}
    # 3 s of script and 1.5 s to settle, at 1 kHz in lockstep: no wall-time figures.
    assert result["mode"] == "lockstep"
    assert result["ticks"] == 4500
    assert result["sim_time_s"] == pytest.approx(4.5, abs=1e-9)
    assert result["rate_hz"] is None and result["step_us"] is None and result["jitter_us"] is None
    assert result["realtime_priority"] is False
    assert result["success"] is True and result["failure"] is None
    assert result["start_penetration_mm"] == 0.0


def test_motor_axis_ends_seated(insertion):
    """Started 30 mm out of its bearings and misaligned (0.32 mm, 0.5 deg), the
    hand itself off by up to 0.36 mm and 0.64 deg on the way: the axis ends at its
    assembled placement within 0.05 mm and 0.1 deg, never penetrating 0.05 mm."""
    result, _ = insertion
    final = result["final"]
    assert math.dist(final["translate"], (0, 0, 0)) < 0.05
    assert math.dist(final["rotate_deg"], (0, 0, 0)) < 0.1
    assert result["max_penetration_mm"] <= 0.05
    # The shaft's five bores, each a cylindrical joint (motor.expected.json: the Axis's contacts).
    assert sorted(j["with"] for j in result["joints_engaged"]) == sorted(SHAFT_BORES)
    assert {j["type"] for j in result["joints_engaged"]} == {"CLJ"}
    assert 0 < result["max_force_n"] <= 12.0  # the simulated device's force limit


def _shaft_deviation(sample, centre):
    """Largest distance from the motor's z axis of the shaft's own axis (x = y = 0,
    z 4.5..69.5 assembled) at the sample's placement, computed here from the
    recorded offset alone (rotations about global x, y, z through the centre)."""
    rx, ry, rz = (math.radians(a) for a in sample["rotate_deg"])

    def rotate(p):
        x, y, z = p
        y, z = y * math.cos(rx) - z * math.sin(rx), y * math.sin(rx) + z * math.cos(rx)
        x, z = x * math.cos(ry) + z * math.sin(ry), -x * math.sin(ry) + z * math.cos(ry)
        x, y = x * math.cos(rz) - y * math.sin(rz), x * math.sin(rz) + y * math.cos(rz)
        return x, y, z

    worst = 0.0
    for z in (4.5, 69.5):
        local = (0 - centre[0], 0 - centre[1], z - centre[2])
        x, y, _ = (c + r + t for c, r, t in zip(centre, rotate(local), sample["translate"]))
        worst = max(worst, math.hypot(x, y))
    return worst


def test_recorded_path_stays_on_the_bore_axis(insertion):
    """Independent of the loop's own measure: a shaft of the bores' radius can be
    off their common axis only by penetrating them."""
    from contactwb import trial
    import Part
    _, record = insertion
    path = trial.read_path(record)
    assert len(path) == 451  # every 10th tick and the last
    assert path[0]["t"] == 0.0
    axis = next(s for s in Part.read(MOTOR).Solids if abs(s.Volume - _axis_volume()) < 1e-6)
    centre = tuple(axis.CenterOfMass)
    engaged = [s for s in path if s["engaged"]]
    assert len(engaged) == len(path)  # captured at the first tick, never broken away
    assert max(_shaft_deviation(s, centre) for s in engaged) <= 0.05
    assert max(s["penetration"] for s in path) <= 0.05
    # It moved in: 30 mm out at the start, seated at the end.
    assert path[0]["translate"][2] > 29.0
    assert abs(path[-1]["translate"][2]) < 0.05


def _axis_volume():
    from contactwb import core
    assembly = core.contactcore.read_step(MOTOR)
    return next(b.volume for b in assembly.bodies if b.name == "Axis")


def test_lockstep_is_deterministic(insertion):
    result, _ = insertion
    again = run_cli(MOTOR, "--part", "Axis", "--script", SCRIPT, "--json")
    assert again.returncode == 0, again.stderr
    second = json.loads(again.stdout)
    assert second["final"] == result["final"]
    assert second["max_penetration_mm"] == result["max_penetration_mm"]


def test_table_output(tmp_path):
    done = run_cli(MOTOR, "--part", "Axis", "--script", SCRIPT)
    assert done.returncode == 0, done.stderr
    assert "engaged CLJ (Cylindrical) with Bearing-back" in done.stdout
    assert "final offset" in done.stdout


@pytest.mark.parametrize("script, message", [
    ({"start": {"translate": [0, 0, 30]}}, "'hand' must be a non-empty list"),
    ({"hand": [{"t": 0, "translate": [0, 0]}]}, "hand[0].translate: three numbers expected"),
    ({"hand": [{"t": 1}, {"t": 0.5}]}, "hand[1].t = 0.5 must be >= 0 and not decrease"),
    ({"start": {"rotate_deg": "x"}, "hand": [{"t": 0}]}, "start.rotate_deg: three numbers expected"),
    ([1, 2], "a JSON object expected"),
])
def test_bad_scripts_are_named(tmp_path, script, message):
    path = tmp_path / "bad.json"
    path.write_text(json.dumps(script))
    done = run_cli(MOTOR, "--part", "Axis", "--script", str(path), "--json")
    assert done.returncode == 3  # the script is an input: refused
    assert message in done.stderr
    assert str(path) in done.stderr
    assert done.stdout == ""


def test_unknown_part_lists_the_bodies():
    done = run_cli(MOTOR, "--part", "Crankshaft", "--script", SCRIPT)
    assert done.returncode == 3
    assert "no body named 'Crankshaft'" in done.stderr and "Bearing-front" in done.stderr


def test_missing_files_are_named(tmp_path):
    done = run_cli(str(tmp_path / "none.step"), "--part", "Axis", "--script", SCRIPT)
    assert done.returncode == 3 and "none.step" in done.stderr
    done = run_cli(MOTOR, "--part", "Axis", "--script", str(tmp_path / "none.json"))
    assert done.returncode == 3 and "none.json" in done.stderr


def test_spacemouse_report_through_the_binding():
    from contactwb import trial
    h = trial.haptics()
    # SpaceMouse Compact: six axes in report 1; HID y/z swapped and inverted (spacenavd).
    parsed = h.parse_spacemouse_report(0x256f, 0xc635, bytes([1, 0x5e, 0x01, 0, 0, 0xa2, 0xfe, 0, 0, 0, 0, 0x5e, 0x01]))
    assert parsed.understood and parsed.model == "SpaceMouse Compact"
    assert parsed.raw == [350, 0, -350, 0, 0, 350]
    assert parsed.axes == [1.0, 1.0, -0.0, 0.0, -1.0, -0.0]
    assert h.parse_spacemouse_report(0x046d, 0xc626, bytes([9, 0, 0])).understood is False
    # Without hardware (no /dev/hidraw here) an empty list, not an error.
    assert all(d.vendor in (0x046d, 0x256f) for d in h.spacemouse_devices())


# ---- engagement on a plane and in a cone: generated cases (written at test time)

def _write_step(tmp_path, name, parts):
    """A flat STEP assembly of (label, shape) pairs, product names = labels."""
    sys.path.insert(0, os.path.join(REPO, "tools"))
    from samples_common import Part_ as Component, export_assembly
    return export_assembly([Component(label, shape) for label, shape in parts], str(tmp_path), name,
                           write_fcstd=False)[0]


def _run_generated(tmp_path, step, part, script):
    path = tmp_path / f"{part}.json"
    path.write_text(json.dumps(script))
    done = run_cli(step, "--part", part, "--device", "sim", "--script", str(path), "--json")
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout)


def test_block_slides_on_a_plate(tmp_path):
    import FreeCAD
    import Part
    # A 10 mm cube on a 40 x 40 x 5 plate (its top at z = 0), started 0.3 mm above
    # it, tilted (1, -0.5) degrees: the face snaps parallel, slides to (8, -5),
    # turns to 30 degrees about z and stays on the plate though the hand pushes 1 mm into it.
    step = _write_step(tmp_path, "plate", [
        ("Plate", Part.makeBox(40, 40, 5, FreeCAD.Vector(-20, -20, -5))),
        ("Block", Part.makeBox(10, 10, 10, FreeCAD.Vector(-5, -5, 0)))])
    result = _run_generated(tmp_path, step, "Block", {
        "start": {"translate": [3, 2, 0.3], "rotate_deg": [1, -0.5, 10]},
        "hand": [{"t": 0, "translate": [3, 2, 0.3], "rotate_deg": [1, -0.5, 10]},
                 {"t": 2, "translate": [8, -5, -1], "rotate_deg": [0, 0, 30]}]})
    assert result["joints_engaged"] == [{"with": "Plate", "type": "PLF"}]
    assert result["final"]["translate"] == pytest.approx([8, -5, 0], abs=1e-6)
    assert result["final"]["rotate_deg"] == pytest.approx([0, 0, 30], abs=1e-6)
    assert result["max_penetration_mm"] <= 1e-9


def test_friction_holds_a_block_below_mu_times_the_push(tmp_path):
    import FreeCAD
    import Part
    # A 10 mm cube on a plate, the hand 1 mm into the plate and 0.4 or 0.6 mm along x, mu 0.5:
    # the hand's pull along (0.4 of its push) is inside the friction cone: the block stays; at 0.6 it
    # slides until the pull is on the cone's edge, 0.5 behind the hand: 0.1 mm. (The simulated hand's own
    # spring scales its offset along and across alike: the ratio, and so the threshold, is the same.)
    step = _write_step(tmp_path, "friction", [
        ("Plate", Part.makeBox(40, 40, 5, FreeCAD.Vector(-20, -20, -5))),
        ("Block", Part.makeBox(10, 10, 10, FreeCAD.Vector(-5, -5, 0)))])
    finals = {}
    for along in (0.4, 0.6):
        script = tmp_path / f"push_{along}.json"
        script.write_text(json.dumps({"hand": [{"t": 0}, {"t": 0.2, "translate": [along, 0, -1]}]}))
        done = run_cli(step, "--part", "Block", "--device", "sim", "--script", str(script), "--json",
                       "--friction", "0.5")
        assert done.returncode == 0, done.stderr
        finals[along] = json.loads(done.stdout)["final"]["translate"]
    assert finals[0.4] == pytest.approx([0, 0, 0], abs=1e-6)
    assert finals[0.6][0] == pytest.approx(0.1, abs=0.002)
    assert finals[0.6][1:] == pytest.approx([0, 0], abs=0.002)
    # Without --friction (0, the default) the block follows the hand along.
    script = tmp_path / "push_0.4.json"
    done = run_cli(step, "--part", "Block", "--device", "sim", "--script", str(script), "--json")
    assert json.loads(done.stdout)["final"]["translate"][0] == pytest.approx(0.4, abs=1e-6)
    refused = run_cli(step, "--part", "Block", "--device", "sim", "--script", str(script), "--friction", "-1")
    assert refused.returncode == 2 and "--friction" in refused.stderr


def test_plug_seats_in_a_cone(tmp_path):
    import FreeCAD
    import Part
    # A conical hole of half-angle 30 degrees (radius 5 at z = 0) and a plug of
    # the same angle 0.1 mm larger in radius: pushed 2 mm below its modelled
    # placement it stops on the seat, 0.1 / tan 30 = 0.1732 mm above it, on the axis.
    t = math.tan(math.radians(30))
    box = Part.makeBox(40, 40, 20, FreeCAD.Vector(-20, -20, 0))
    hole = Part.makeCone(5 - t, 5 + 21 * t, 22, FreeCAD.Vector(0, 0, -1))
    plug = Part.makeCone(5.1 - 3 * t, 5.1 + 12 * t, 15, FreeCAD.Vector(0, 0, -3))
    step = _write_step(tmp_path, "cone", [("Seat", box.cut(hole)), ("Plug", plug)])
    result = _run_generated(tmp_path, step, "Plug", {
        "start": {"translate": [0.2, -0.1, 15], "rotate_deg": [0.5, 0, 0]},
        "hand": [{"t": 0, "translate": [0.2, -0.1, 15], "rotate_deg": [0.5, 0, 0]},
                 {"t": 2, "translate": [0.3, 0.2, -2]}]})
    assert result["joints_engaged"] == [{"with": "Seat", "type": "CJU"}]
    seat = 0.1 / t
    assert result["final"]["translate"] == pytest.approx([0, 0, seat], abs=1e-6)
    assert result["final"]["rotate_deg"][:2] == pytest.approx([0, 0], abs=1e-6)
    assert result["max_penetration_mm"] <= 1e-6


def test_hid_force_feedback_capabilities_from_a_descriptor():
    from contactwb import trial
    h = trial.haptics()
    # A SpaceMouse-like descriptor (Generic Desktop only): no force output, and why.
    plain = bytes([0x05, 0x01, 0x09, 0x08, 0xA1, 0x01, 0x85, 0x01, 0x09, 0x30, 0x16, 0xA2, 0xFE,
                   0x26, 0x5E, 0x01, 0x75, 0x10, 0x95, 0x01, 0x81, 0x02, 0xC0])
    caps = h.hid_pid_capabilities(plain)
    assert caps.to_dict() == {"force_output": False, "why": "no PID usage page (0x0F): no force feedback",
                              "capabilities": None, "axes": 0}
    # Without hardware: an empty list, not an error.
    assert isinstance(h.hid_force_feedback_devices(), list)


def test_hid_force_feedback_session_without_hardware():
    from contactwb import core, trial
    scene = trial.make_scene(core.contactcore.read_step(MOTOR), "Axis")
    session = trial.haptics().HapticSession(scene, "hid-ff")
    # No PID device here: the simulated hand, and a message saying why, not an error.
    assert session.message.startswith("No force-feedback device (")
    assert session.message.endswith("using the simulated hand.")
    assert session.capabilities.name == trial.haptics().simulated_capabilities().name


PULL_15_UP = {"start": {"translate": [0, 0, 0], "rotate_deg": [0, 0, 0]},
              "hand": [{"t": 0.0, "translate": [0, 0, 0], "rotate_deg": [0, 0, 0]},
                       {"t": 3.0, "translate": [0, 0, 15], "rotate_deg": [0, 0, 0]},
                       {"t": 4.0, "translate": [0, 0, 15], "rotate_deg": [0, 0, 0]}]}


def _placed(shape, centre, sample):
    """The body's shape moved by a recorded offset (rotations about global x, then y,
    then z through `centre`, then the translation), as the trial applies it."""
    import FreeCAD
    rx, ry, rz = sample["rotate_deg"]
    rotation = FreeCAD.Rotation(rz, ry, rx)  # yaw (z), pitch (y), roll (x): Rz Ry Rx
    c = FreeCAD.Vector(*centre)
    base = c + FreeCAD.Vector(*sample["translate"]) - rotation.multVec(c)
    moved = shape.copy()
    moved.Placement = FreeCAD.Placement(base, rotation).multiply(shape.Placement)
    return moved


def test_motor_fcstd_axis_pulled_15mm_up_comes_out(tmp_path):
    """motor.FCStd's Axis, the hand going 15 mm straight up in 3 s and held for
    1 s: nothing holds it in its bores, so it ends at the hand (z = 15.000).
    With the closed forms on this once stopped at z = 4.999 on the FreeCAD
    document's shapes (a phantom plane-pair contact of the outline test's
    rounding, motor.step never showed it). Judged by OCCT Booleans along the
    recorded path: no overlap with any other body at any judged sample."""
    import Part
    from contactwb.core import trial
    from contactwb.document.files import load_assembly
    fcstd = os.path.join(SAMPLES, "motor.FCStd")
    script = tmp_path / "pull15.json"
    script.write_text(json.dumps(PULL_15_UP))
    record = str(tmp_path / "path.csv")
    done = run_cli(fcstd, "--part", "Axis", "--script", str(script), "--json", "--record", record)
    assert done.returncode == 0, done.stderr
    result = json.loads(done.stdout)
    x, y, z = result["final"]["translate"]
    assert z == pytest.approx(15.0, abs=1e-3)
    assert math.hypot(x, y) < 1e-3
    assert max(abs(a) for a in result["final"]["rotate_deg"]) < 1e-3
    path = trial.read_path(record)
    # The part follows the hand up: never more than the coupling's lag below it, never stopping on the way.
    hand = [min(15.0, 5.0 * s["t"]) for s in path]
    assert max(h - s["translate"][2] for h, s in zip(hand, path)) < 0.5
    assert all(b["translate"][2] >= a["translate"][2] - 1e-9 for a, b in zip(path, path[1:]))
    # OCCT's judgement along the path: the Axis placed at every 25th sample (each 0.25 s) and at the end.
    shapes = {}
    for body in load_assembly(fcstd).bodies:
        shape = Part.Shape()
        shape.importBrepFromString(body.brep)
        shapes[body.name] = shape
    axis = shapes.pop("Axis")
    centre = tuple(axis.Solids[0].CenterOfMass) if len(axis.Solids) == 1 else None
    assert centre is not None
    judged = path[::25] + [path[-1]]
    worst = (0.0, None, None)
    for sample in judged:
        moved = _placed(axis, centre, sample)
        for name, other in shapes.items():
            if not moved.BoundBox.intersect(other.BoundBox):
                continue
            volume = moved.common(other).Volume
            if volume > worst[0]:
                worst = (volume, name, sample["t"])
    assert len(judged) == 24  # 551 samples (every 10th tick of the 4 s script and 1.5 s settling, and the last)
    assert worst[0] <= 1e-6, f"overlap {worst[0]:.3g} mm3 with {worst[1]} at t = {worst[2]}"
