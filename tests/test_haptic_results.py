"""The haptics binding's results are classes (issue 23): read-only documented
fields, to_dict() from the same list, and `contacts trial --json` with the
field names, order and nesting other tools read."""
import json
import os
import subprocess
import sys

import pytest

from conftest import REPO, SAMPLES
from contactwb.core import extension as core

MOTOR = os.path.join(SAMPLES, "motor.step")
SCRIPT = os.path.join(REPO, "Resources", "trials", "motor_axis_insertion.json")

# `contacts trial --json` as other tools read it: keys in this order, nested keys likewise.
TRIAL_JSON_KEYS = ["mode", "ticks", "sim_time_s", "rate_hz", "step_us", "jitter_us", "overruns",
                   "realtime_priority", "success", "failure", "joints_engaged", "final",
                   "max_penetration_mm", "start_penetration_mm", "final_penetration_mm", "max_force_n"]

# run_trial's TrialResult.to_dict(), key for key what the binding's dict held before it was a class.
TRIAL_RESULT_KEYS = ["mode", "ticks", "sim_time_s", "rate_hz", "step_us", "jitter_us", "overruns", "long_steps",
                     "late_wakeups", "realtime_priority", "success", "failure", "memory_locked", "device",
                     "device_message", "joints_engaged", "final", "max_penetration_mm", "start_penetration_mm",
                     "final_penetration_mm", "max_force_n", "path"]
SNAPSHOT_KEYS = ["translate", "rotate_deg", "matrix", "target", "force", "torque", "force_n", "engaged", "held",
                 "joint", "joint_axis", "joint_point", "joint_with", "stops", "insertion_depth", "penetration",
                 "max_penetration", "max_force", "rate_hz", "jitter_us", "step_us", "ticks", "overruns", "watchdog",
                 "connected", "enabled", "blocked", "axes", "time", "realtime_priority", "late_wakeups",
                 "max_wake_latency_us", "memory_locked"]


def haptics():
    module = getattr(core.contactcore, "haptics", None)
    if module is None:
        pytest.skip("this build has no haptic trials")
    return module


def result_classes(h):
    return [getattr(h, name) for name in dir(h) if isinstance(getattr(h, name), type)
            and hasattr(getattr(h, name), "to_dict") and hasattr(getattr(h, name), "fields")]


def test_every_result_class_documents_its_fields():
    h = haptics()
    classes = result_classes(h)
    assert sorted(c.__name__ for c in classes) == sorted([
        "DeviceCapabilities", "EngagedJoint", "HeldJoint", "HidDeviceSeen", "HidPidFound", "HidRecording",
        "JitterTimes", "LiveContact", "Offset", "PidCapabilities", "SessionSnapshot", "SpaceMouseFound",
        "SpaceMouseReport", "StepTimes", "StopState", "TrialResult", "TrialSample"])
    for cls in classes:
        assert cls.__doc__, cls.__name__
        for name in cls.fields:
            prop = getattr(cls, name)
            assert isinstance(prop, property), f"{cls.__name__}.{name}"
            assert prop.fset is None, f"{cls.__name__}.{name} is writable"
            assert prop.__doc__ and prop.__doc__.strip(), f"{cls.__name__}.{name} has no docstring"


@pytest.fixture(scope="module")
def motor_trial():
    from contactwb.core import trial
    h = haptics()
    scene = trial.make_scene(core.contactcore.read_step(MOTOR), "Axis")
    script = {"start": {"translate": [0, 0, 5], "rotate_deg": [0, 0, 0]},
              "hand": [{"t": 0.0, "translate": [0, 0, 5]}, {"t": 0.2, "translate": [0, 0, 0]}]}
    return h, scene, trial.run(scene, script)


def test_trial_result_fields_and_to_dict(motor_trial):
    h, _, result = motor_trial
    assert type(result).__name__ == "TrialResult"
    data = result.to_dict()
    assert list(data) == TRIAL_RESULT_KEYS
    json.dumps(data)  # plain values all the way down
    # Each key is its field's value, nested results as their dicts.
    assert data["ticks"] == result.ticks == 1700  # 0.2 s of script + 1.5 s settling at 1 kHz, lockstep
    assert data["mode"] == result.mode == "lockstep"
    assert data["rate_hz"] is None and result.step_us is None and result.jitter_us is None
    assert data["final"] == {"translate": result.final.translate, "rotate_deg": result.final.rotate_deg}
    assert data["device"] == "sim" and data["device_message"] == "Simulated hand."
    assert [j["with"] for j in data["joints_engaged"]] == [j.with_body for j in result.joints_engaged]
    assert list(data["joints_engaged"][0]) == ["with", "type", "joint", "t"]
    assert len(data["path"]) == len(result.path) == 171  # every 10th tick and the last
    assert list(data["path"][0]) == ["t", "translate", "rotate_deg", "force", "engaged", "penetration"]
    assert data["path"][-1]["translate"] == result.path[-1].translate
    with pytest.raises(AttributeError):
        result.ticks = 3


def test_session_snapshot_and_scene_results(motor_trial):
    h, scene, _ = motor_trial
    session = h.HapticSession(scene, "sim", [0, 0, 5], [0, 0, 0])
    session.step(5)
    s = session.snapshot()
    assert list(s.to_dict()) == SNAPSHOT_KEYS
    assert s.ticks == 5 and s.to_dict()["ticks"] == 5
    assert s.translate[2] == pytest.approx(5.0, abs=0.6)
    assert list(s.target.to_dict()) == ["translate", "rotate_deg"]
    assert len(s.matrix) == 4 and all(len(row) == 4 for row in s.matrix)
    json.dumps(s.to_dict())
    caps = session.capabilities
    assert caps.to_dict()["name"] == caps.name == h.simulated_capabilities().name
    contacts = scene.contacts_at([0, 0, 0], [0, 0, 0])
    assert contacts and all(type(c).__name__ == "LiveContact" for c in contacts)
    assert list(contacts[0].to_dict()) == ["type", "with", "distance", "angle_deg"]
    with pytest.raises(core.ArgumentError, match="translate"):
        scene.contacts_at([0, 0], [0, 0, 0])


def _cli_trial_json():
    env = dict(os.environ, PYTHONPATH=REPO)
    done = subprocess.run([sys.executable, "-m", "contactwb.cli", "trial", MOTOR, "--part", "Axis", "--script",
                           SCRIPT, "--json"], capture_output=True, text=True, env=env, cwd=REPO, timeout=600)
    assert done.returncode == 0, done.stderr
    return done.stdout


def test_cli_trial_json_keeps_its_names_order_and_nesting():
    haptics()
    text = _cli_trial_json()
    out = json.loads(text)
    assert list(out) == TRIAL_JSON_KEYS
    assert list(out["final"]) == ["translate", "rotate_deg"]
    assert out["joints_engaged"] and all(list(j) == ["with", "type"] for j in out["joints_engaged"])
    # As json.dump writes a dict of plain values, indented by 2 (lists of numbers one per line).
    assert text == json.dumps(out, indent=2) + "\n"
    assert text.startswith('{\n  "mode": "lockstep",\n  "ticks": 4500,\n  "sim_time_s": 4.5')
