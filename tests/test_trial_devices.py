"""Device front ends of `contacts trial` without hardware: --device
spacemouse / hid-ff with nothing plugged in (exit 3 and the HID devices
seen), replays of recorded raw HID reports through the device's parser
(deterministic, lockstep), the recording file's errors, and the panel's
session on a replay."""
import json
import os
import subprocess
import sys

import pytest

from conftest import REPO, SAMPLES

MOTOR = os.path.join(SAMPLES, "motor.step")
SCRIPT = os.path.join(REPO, "Resources", "trials", "motor_axis_insertion.json")
COMPACT = (0x256F, 0xC635)  # SpaceMouse Compact: six axes in report 1, y/z swapped and inverted


def run_cli(*args):
    env = dict(os.environ, PYTHONPATH=REPO)
    return subprocess.run([sys.executable, "-m", "contactwb.cli", "trial", *args],
                          capture_output=True, text=True, env=env, cwd=REPO)


def haptics():
    from contactwb import trial
    return trial.haptics()


def six_axes(tx=0, ty=0, tz=0, rx=0, ry=0, rz=0):
    """A SpaceMouse Compact report 1: six int16 little-endian axes."""
    out = bytearray([1])
    for v in (tx, ty, tz, rx, ry, rz):
        out += int(v).to_bytes(2, "little", signed=True)
    return bytes(out)


def write_recording(path, reports):
    haptics().write_hid_recording(str(path), "spacemouse", *COMPACT, "SpaceMouse Compact", reports)
    return str(path)


@pytest.mark.parametrize("device", ["spacemouse", "hid-ff"])
def test_no_device_plugged_exits_3_with_the_devices_seen(device):
    seen = haptics().hid_devices_seen()
    done = run_cli(MOTOR, "--part", "Axis", "--device", device, "--script", SCRIPT, "--json")
    assert done.returncode == 3, done.stderr
    assert done.stdout == ""
    assert f"contacts trial: no {device} device: " in done.stderr
    if seen:
        assert "HID devices seen:\n" in done.stderr
        for d in seen:
            assert d.path in done.stderr
    else:  # this machine: no /dev/hidraw, and the message says so
        assert "HID devices seen: none" in done.stderr


def test_device_arguments_are_checked():
    done = run_cli(MOTOR, "--part", "Axis", "--device", "replay", "--script", SCRIPT)
    assert done.returncode == 2 and "--device replay needs --hid-file FILE" in done.stderr
    done = run_cli(MOTOR, "--part", "Axis", "--device", "sim", "--script", SCRIPT, "--record-hid", "x.hid")
    assert done.returncode == 2 and "--record-hid records a HID device" in done.stderr
    done = run_cli(MOTOR, "--part", "Axis", "--device", "sim")
    assert done.returncode == 2 and "--script is required with --device sim" in done.stderr
    done = run_cli(MOTOR, "--part", "Axis", "--device", "joystick", "--script", SCRIPT)
    assert done.returncode == 2 and "invalid choice: 'joystick'" in done.stderr


def test_replay_drives_the_axis_through_the_spacemouse_parser(tmp_path):
    # The axis starts 30 mm out (the script's start) and is captured on its
    # bores' axis; the recorded SpaceMouse is pushed down at full deflection
    # (HID Ty = +350 is the screen -z after spacenavd's swap and inversion)
    # from 0.1005 s to 0.6005 s, reporting every 10 ms: 500 ticks at 40 mm/s
    # in rate control, 20 mm down the axis.
    reports = [(0.1005 + 0.01 * i, six_axes(ty=350)) for i in range(50)] + [(0.6005, six_axes())]
    recording = write_recording(tmp_path / "push.hid", reports)
    done = run_cli(MOTOR, "--part", "Axis", "--device", "replay", "--hid-file", recording, "--script", SCRIPT,
                   "--json")
    assert done.returncode == 0, done.stderr
    result = json.loads(done.stdout)
    assert result["ticks"] == 2101  # the last report at 0.6005 s + 1.5 s of settling, at 1 kHz
    done_json = run_cli(MOTOR, "--part", "Axis", "--device", "replay", "--hid-file", recording, "--script", SCRIPT,
                        "--record", str(tmp_path / "path.json"))
    assert done_json.returncode == 0, done_json.stderr
    with open(tmp_path / "path.json") as stream:
        path = json.load(stream)
    # Captured at the first tick (snapped onto the axis, 30 mm out), then 20 mm down it.
    assert path[0]["translate"][2] == pytest.approx(30.0, abs=0.01)
    assert path[0]["translate"][2] - result["final"]["translate"][2] == pytest.approx(20.0, abs=1e-6)
    assert result["final"]["translate"][:2] == pytest.approx([0, 0], abs=0.05)  # on the bores' axis
    assert [j["type"] for j in result["joints_engaged"]][:1] == ["CLJ"]


def test_replayed_silence_stops_the_part_after_the_watchdog_timeout(tmp_path):
    # One deflected report at 0.1005 s, then nothing until 1 s: the stale
    # watchdog (0.25 s without a report while deflected) stops the part at
    # 0.3505 s: 250 ticks at 40 mm/s, 10 mm.
    recording = write_recording(tmp_path / "silent.hid", [(0.1005, six_axes(ty=350)), (1.0, six_axes())])
    from contactwb import core, trial
    scene = trial.make_scene(core.contactcore.read_step(MOTOR), "Axis")
    result = trial.run(scene, trial.read_script(SCRIPT), device="replay", hid_file=recording)
    assert result.device == "replay"
    assert "Replaying 2 recorded reports of SpaceMouse Compact" in result.device_message
    assert result.path[0].translate[2] - result.final.translate[2] == pytest.approx(10.0, abs=1e-6)
    stalled = [p.translate[2] for p in result.path if 0.36 <= p.t <= 0.99]
    assert len(stalled) > 50 and max(stalled) - min(stalled) < 1e-9  # held still while stale


def test_recording_round_trip_and_errors(tmp_path):
    reports = [(0.0125, six_axes(tx=-175)), (0.5, b""), (0.75, b""), (1.25, six_axes())]
    path = write_recording(tmp_path / "r.hid", reports)
    back = haptics().read_hid_recording(path)
    assert back.kind == "spacemouse" and (back.vendor, back.product) == COMPACT
    assert back.name == "SpaceMouse Compact"
    assert back.reports == reports
    with open(path) as stream:
        assert stream.readline() == "contacts-hid-recording 1\n"
    bad = tmp_path / "bad.hid"
    bad.write_text("contacts-hid-recording 1\ndevice spacemouse 256f c635 x\n0.5 zz\n")
    done = run_cli(MOTOR, "--part", "Axis", "--device", "replay", "--hid-file", str(bad))
    assert done.returncode == 3  # an unreadable input (the exit-code contract)
    assert f"line 3: report bytes must be hexadecimal (file '{bad}')" in done.stderr


def test_panel_session_on_a_recording(tmp_path):
    # The panel's session plays a recording on the loop's thread; a missing
    # device is never an error there (the simulated hand, and why).
    recording = write_recording(tmp_path / "p.hid", [(0.0105, six_axes(ty=350)), (0.0505, six_axes())])
    from contactwb import core, trial
    scene = trial.make_scene(core.contactcore.read_step(MOTOR), "Axis")
    session = haptics().HapticSession(scene, "replay", [0, 0, 30], [0, 0, 0], hid_file=recording)
    assert session.message == "Replaying 2 recorded reports of SpaceMouse Compact."
    assert session.capabilities.control == "rate"
    session.step(1)  # lockstep, thread stopped: captured on the axis
    z0 = session.snapshot().translate[2]
    session.step(99)
    s = session.snapshot()
    # 40 ticks deflected at 40 mm/s (a collision bisection may keep 1023/1024 of one tick's step).
    assert z0 - s.translate[2] == pytest.approx(0.04 * 40, abs=1e-4)
    assert s.late_wakeups == 0 and s.memory_locked is False
    assert s.joint == "Cylindrical" and s.stops == []  # on the bores' axis; the shaft has no shoulder
    fallback = haptics().HapticSession(scene, "spacemouse")
    assert fallback.message.startswith("No SpaceMouse found (")
