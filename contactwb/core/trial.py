"""Haptic trials, headless and without FreeCAD: build the trial scene for one
part of an assembly, check a script, run it with the simulated hand, write
and read the path. (Loading the assembly from a file:
contactwb.document.files.load_assembly.)

Used by `contacts trial` (contactwb/cli/trial.py) and the panel
(contactwb/gui/panels/haptic_panel.py)."""
import csv
import json

from contactwb import core

SCRIPT_HELP = ('{"start": {"translate": [x, y, z], "rotate_deg": [rx, ry, rz]}, '
               '"hand": [{"t": s, "translate": [...], "rotate_deg": [...]}, ...]}')


def haptics():
    """The extension's haptics module, or a clear error when it was built without it."""
    module = getattr(core.contactcore, "haptics", None)
    if module is None:
        raise core.ContactsError("this build has no haptic trials (configure with -DCONTACTS_WITH_HAPTICS=ON)")
    return module


def _vector(value, where):
    if (not isinstance(value, (list, tuple)) or len(value) != 3
            or not all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in value)):
        raise core.ContactsError(f"{where}: three numbers expected, got {value!r}")
    return [float(v) for v in value]


def check_script(script, source="script"):
    """The script with every field checked (clear errors naming the field)."""
    if not isinstance(script, dict):
        raise core.ContactsError(f"{source}: a JSON object expected ({SCRIPT_HELP})")
    start = script.get("start", {})
    if not isinstance(start, dict):
        raise core.ContactsError(f"{source}: 'start' must be an object")
    checked = {"start": {"translate": _vector(start.get("translate", [0, 0, 0]), f"{source}: start.translate"),
                         "rotate_deg": _vector(start.get("rotate_deg", [0, 0, 0]), f"{source}: start.rotate_deg")}}
    hand = script.get("hand")
    if not isinstance(hand, list) or not hand:
        raise core.ContactsError(f"{source}: 'hand' must be a non-empty list of keys ({SCRIPT_HELP})")
    keys, last = [], None
    for i, key in enumerate(hand):
        if not isinstance(key, dict) or not isinstance(key.get("t"), (int, float)):
            raise core.ContactsError(f"{source}: hand[{i}] needs a time 't' in seconds")
        t = float(key["t"])
        if t < 0 or (last is not None and t < last):
            raise core.ContactsError(f"{source}: hand[{i}].t = {t} must be >= 0 and not decrease")
        last = t
        keys.append({"t": t,
                     "translate": _vector(key.get("translate", [0, 0, 0]), f"{source}: hand[{i}].translate"),
                     "rotate_deg": _vector(key.get("rotate_deg", [0, 0, 0]), f"{source}: hand[{i}].rotate_deg")})
    checked["hand"] = keys
    return checked


def read_script(path):
    try:
        with open(path, encoding="utf-8") as stream:
            return check_script(json.load(stream), f"script '{path}'")
    except OSError as error:
        raise core.ContactsError(f"cannot read script '{path}': {error.strerror}") from error
    except json.JSONDecodeError as error:
        raise core.ContactsError(f"script '{path}': not JSON ({error})") from error


def make_scene(assembly, part, progress=None, **options):
    return haptics().TrialScene(assembly, part, progress=progress, **options)


def run(scene, script, realtime=False, record_every=10, **options):
    """The trial's result dict (see `contacts trial --json`) with its 'path'."""
    return haptics().run_trial(scene, check_script(script), realtime=realtime, record_every=record_every, **options)


def write_path(path_samples, target):
    """Writes the recorded path: CSV (t, translate, rotate_deg, force, engaged,
    penetration) or, for a .json target, a JSON list."""
    if target.lower().endswith(".json"):
        with open(target, "w", encoding="utf-8") as stream:
            json.dump(path_samples, stream, indent=1)
        return
    with open(target, "w", newline="", encoding="utf-8") as stream:
        writer = csv.writer(stream)
        writer.writerow(["t_s", "x_mm", "y_mm", "z_mm", "rx_deg", "ry_deg", "rz_deg",
                         "fx_n", "fy_n", "fz_n", "engaged", "penetration_mm"])
        for s in path_samples:
            writer.writerow([f"{s['t']:.4f}", *(f"{v:.6f}" for v in s["translate"]),
                             *(f"{v:.6f}" for v in s["rotate_deg"]), *(f"{v:.5f}" for v in s["force"]),
                             int(s["engaged"]), f"{s['penetration']:.6f}"])


def read_path(source):
    """A path written by write_path (CSV or JSON), as a list of dicts."""
    if source.lower().endswith(".json"):
        with open(source, encoding="utf-8") as stream:
            return json.load(stream)
    samples = []
    with open(source, newline="", encoding="utf-8") as stream:
        for row in csv.DictReader(stream):
            samples.append({"t": float(row["t_s"]),
                            "translate": [float(row[k]) for k in ("x_mm", "y_mm", "z_mm")],
                            "rotate_deg": [float(row[k]) for k in ("rx_deg", "ry_deg", "rz_deg")],
                            "force": [float(row[k]) for k in ("fx_n", "fy_n", "fz_n")],
                            "engaged": row["engaged"] == "1",
                            "penetration": float(row["penetration_mm"])})
    return samples
