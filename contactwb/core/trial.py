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


# Limits of a script file, checked before the trial starts (issue 25): the
# lockstep loop simulates every millisecond of the script before it answers.
MAX_SCRIPT_BYTES = 1_000_000      # the file
MAX_SCRIPT_KEYS = 10_000          # hand keys
MAX_SCRIPT_DURATION_S = 600.0     # the last key's time
MAX_SCRIPT_NESTING = 16           # arrays and objects inside each other
MAX_SCRIPT_OFFSET = 1e6           # |translate| in mm, |rotate_deg| in degrees
MAX_SCRIPT_DIGITS = 30            # digits of one number


def _nesting_depth(text):
    """The deepest nesting of arrays and objects, strings skipped (json
    would recurse into 200,000 nested arrays until RecursionError)."""
    depth = deepest = 0
    in_string = escaped = False
    for char in text:
        if in_string:
            if escaped:
                escaped = False
            elif char == "\\":
                escaped = True
            elif char == '"':
                in_string = False
        elif char == '"':
            in_string = True
        elif char in "[{":
            depth += 1
            deepest = max(deepest, depth)
            if deepest > MAX_SCRIPT_NESTING:
                return deepest
        elif char in "]}":
            depth -= 1
    return deepest


def read_script(path):
    """The script file, checked: UTF-8 JSON of at most MAX_SCRIPT_BYTES, nested at most
    MAX_SCRIPT_NESTING deep, numbers finite and short, at most MAX_SCRIPT_KEYS hand keys over at
    most MAX_SCRIPT_DURATION_S seconds, offsets within MAX_SCRIPT_OFFSET. Raises InputError naming
    the file and what is wrong."""
    where = f"script '{path}'"

    def refuse(message):
        return core.InputError(f"{where}: {message}")
    try:
        with open(path, "rb") as stream:
            data = stream.read(MAX_SCRIPT_BYTES + 1)
    except OSError as error:
        raise core.InputError(f"cannot read script '{path}': {error.strerror}") from error
    if len(data) > MAX_SCRIPT_BYTES:
        raise refuse(f"larger than {MAX_SCRIPT_BYTES} bytes")
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as error:
        raise refuse(f"not UTF-8 text (byte 0x{data[error.start]:02x} at offset {error.start})") from None
    if _nesting_depth(text) > MAX_SCRIPT_NESTING:
        raise refuse(f"nested deeper than {MAX_SCRIPT_NESTING} levels")

    def number(literal):
        if len(literal.lstrip("-").replace(".", "").split("e")[0].split("E")[0]) > MAX_SCRIPT_DIGITS:
            raise refuse(f"the number {literal[:20]}... has more than {MAX_SCRIPT_DIGITS} digits")
        value = float(literal)
        if value != value or value in (float("inf"), float("-inf")):
            raise refuse(f"the number {literal[:40]} is not finite")
        return value

    def constant(name):
        raise refuse(f"{name} is not a number a script may hold (finite numbers only)")
    try:
        loaded = json.loads(text, parse_int=number, parse_float=number, parse_constant=constant)
    except json.JSONDecodeError as error:
        raise refuse(f"not JSON ({error})") from error
    except RecursionError:
        raise refuse(f"nested deeper than {MAX_SCRIPT_NESTING} levels") from None
    if isinstance(loaded, dict) and isinstance(loaded.get("hand"), list) and len(loaded["hand"]) > MAX_SCRIPT_KEYS:
        raise refuse(f"{len(loaded['hand'])} hand keys (at most {MAX_SCRIPT_KEYS})")
    try:
        checked = check_script(loaded, where)
    except core.InputError:
        raise
    except core.ContactsError as error:
        raise core.InputError(str(error)) from None
    last = checked["hand"][-1]["t"]
    if last > MAX_SCRIPT_DURATION_S:
        raise refuse(f"hand[{len(checked['hand']) - 1}].t = {last:g} s: the script lasts at most "
                     f"{MAX_SCRIPT_DURATION_S:g} s")
    for name, values in [("start.translate", checked["start"]["translate"]),
                         ("start.rotate_deg", checked["start"]["rotate_deg"])] + \
            [(f"hand[{i}].{field}", key[field]) for i, key in enumerate(checked["hand"])
             for field in ("translate", "rotate_deg")]:
        if any(abs(v) > MAX_SCRIPT_OFFSET for v in values):
            raise refuse(f"{name} = {values}: beyond {MAX_SCRIPT_OFFSET:g} (mm or degrees)")
    return checked


def make_scene(assembly, part, progress=None, **options):
    return haptics().TrialScene(assembly, part, progress=progress, **options)


DEVICES = ("sim", "spacemouse", "hid-ff", "replay")


def run(scene, script, realtime=False, record_every=10, device="sim", hid_file=None, record_hid=None,
        duration=None, **options):
    """The trial's result: a contactcore.haptics.TrialResult (documented
    read-only fields; to_dict() gives what `contacts trial --json` picks from,
    with its 'path').

    device: 'sim' (the scripted simulated hand), 'spacemouse' or 'hid-ff'
    (hardware, real time; `record_hid` a file for the raw reports), 'replay'
    (`hid_file`, a recording). Hardware that is not there raises
    haptics().DeviceUnavailable, whose `devices` lists the HID devices seen.
    A device other than 'sim' needs no hand keys: the script gives the start."""
    if device == "sim" or script is not None and script.get("hand"):
        script = check_script(script)
    else:
        script = {"start": check_script({"start": (script or {}).get("start", {}), "hand": [{"t": 0}]})["start"]}
    return haptics().run_trial(scene, script, realtime=realtime, record_every=record_every, device=device,
                               hid_file=hid_file, record_hid=record_hid, duration=duration, **options)


def describe_devices_seen(devices):
    """One line per HID device seen (contactcore.haptics.HidDeviceSeen) (for "no device" messages), or a line saying there were none."""
    if not devices:
        return "no HID devices seen"
    return "\n".join(f"{d.vendor:04x}:{d.product_id:04x} {d.manufacturer} {d.product} ({d.path})"
                     for d in devices)


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
