"""`contacts trial FILE --part NAME --device sim --script SCRIPT.json` — a
haptic trial run headless: the part starts at the script's offset from its
assembled placement, the simulated hand follows the script's targets, and the
1 kHz loop holds the part to the joints its contacts allow, stops it at
collisions and reports where it ended.

Script: {"start": {"translate": [x, y, z], "rotate_deg": [rx, ry, rz]},
         "hand": [{"t": s, "translate": [...], "rotate_deg": [...]}, ...]}
(offsets from the assembled placement in mm; rotations in degrees about global
axes through the part's centre of mass, x then y then z; the hand's targets
are piecewise linear in time and held after the last.)

Devices: sim (the scripted simulated hand, no hardware); spacemouse and
hid-ff (a 3Dconnexion device, a HID force-feedback device: real time, for
--duration s or the script's length; --record-hid FILE keeps their raw
reports with arrival times); replay (--hid-file FILE: a recording played back
through the same parser, in lockstep). Hardware not plugged in: exit status 3
and the HID devices seen."""
import argparse
import json
import os
import sys

from contactwb.cli.process import escape_controls, finite_number, naming_the_file, run as run_command, unsafe_output
from contactwb.cli.process import out_of_memory_message, working_on
from contactwb.cli.process import EXIT_CANCELLED, EXIT_FAILED, EXIT_INPUT, EXIT_OK, EXIT_USAGE

_finite = finite_number


# The keys of `contacts trial --json`, in order: other tools read them. Each is
# the TrialResult field of that name (to_dict()), except joints_engaged, of
# which only "with" and "type" are written.
JSON_FIELDS = ("mode", "ticks", "sim_time_s", "rate_hz", "step_us", "jitter_us", "overruns", "realtime_priority",
               "success", "failure", "joints_engaged", "final", "max_penetration_mm", "start_penetration_mm",
               "final_penetration_mm", "max_force_n")


def trial_json(result):
    """What `contacts trial --json` prints of a TrialResult."""
    fields = result.to_dict()
    out = {key: fields[key] for key in JSON_FIELDS}
    out["joints_engaged"] = [{"with": j["with"], "type": j["type"]} for j in fields["joints_engaged"]]
    return out


def main(argv, own_process=False):
    return run_command("contacts trial", lambda: _trial(argv), own_process)


def _trial(argv):
    from contactwb.core import output_files  # here: the signal handler is in place before the extension loads
    parser = argparse.ArgumentParser(prog="contacts trial", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("file", help="a STEP (.step/.stp) or FreeCAD (.FCStd) assembly")
    parser.add_argument("--part", required=True, help="the body to move (its name in the assembly)")
    parser.add_argument("--device", default="sim", choices=["sim", "spacemouse", "hid-ff", "replay"],
                        help="the device: sim, the simulated hand (no hardware); spacemouse; hid-ff (HID force "
                             "feedback); replay (a --record-hid recording, see --hid-file)")
    parser.add_argument("--script", help="the trial script (JSON); required with --device sim, otherwise only "
                                         "its start offset is used")
    parser.add_argument("--record-hid", metavar="FILE",
                        help="spacemouse, hid-ff: record the raw HID reports with their arrival times")
    parser.add_argument("--hid-file", metavar="FILE", help="replay: the recording to play back")
    parser.add_argument("--duration", type=_finite(low=0, low_open=True), metavar="S",
                        help="spacemouse, hid-ff, replay: seconds to run (default: the script's length, the "
                             "recording's, or 10 s)")
    parser.add_argument("--json", action="store_true", help="print the result as JSON")
    parser.add_argument("--record", metavar="PATH", help="save the path (time, placement, force): .csv or .json")
    parser.add_argument("--realtime", action="store_true",
                        help="run the loop on its own thread in real time (default: lockstep, deterministic)")
    parser.add_argument("--stiffness", type=_finite(low=0, low_open=True),
                        help="virtual coupling stiffness, N/mm (clamped to the device)")
    parser.add_argument("--friction", type=_finite(low=0), default=0.0, metavar="MU",
                        help="Coulomb friction coefficient at the part's contacts (default 0: none)")
    parser.add_argument("--capture-distance", type=_finite(low=0), default=0.5, help="engagement capture distance, mm")
    parser.add_argument("--capture-angle", type=_finite(low=0, high=90), default=2.0,
                        help="engagement capture angle, degrees")
    args = parser.parse_args(argv)
    if args.device == "sim" and not args.script:
        parser.error("--script is required with --device sim")
    if args.record_hid and args.device not in ("spacemouse", "hid-ff"):
        parser.error("--record-hid records a HID device: --device spacemouse or hid-ff")
    if args.device == "replay" and not args.hid_file:
        parser.error("--device replay needs --hid-file FILE (a --record-hid recording)")
    if args.hid_file and args.device != "replay":
        parser.error("--hid-file is for --device replay")
    file = os.fsdecode(args.file)
    working_on(file)
    script_path = os.fsdecode(args.script) if args.script else None
    if args.record and unsafe_output("contacts trial", "--record", args.record):
        return EXIT_USAGE

    from contactwb import core
    from contactwb.core import trial
    from contactwb.document.files import load_assembly
    try:
        script = trial.read_script(script_path) if script_path else None
    except core.ContactsError as error:  # the script is an input: unreadable or refused
        print(f"contacts trial: {error}", file=sys.stderr)
        return EXIT_INPUT
    try:
        assembly = load_assembly(file)
        scene = trial.make_scene(assembly, args.part, capture_distance=args.capture_distance,
                                 capture_angle_deg=args.capture_angle)
        options = {"stiffness": args.stiffness} if args.stiffness is not None else {}
        if args.friction > 0:
            options["friction"] = args.friction
        if args.realtime:
            options["realtime_priority"] = 80  # SCHED_FIFO when the system grants it
        result = trial.run(scene, script, realtime=args.realtime, device=args.device, hid_file=args.hid_file,
                           record_hid=args.record_hid, duration=args.duration, **options)
    except core.Cancelled:
        print("contacts trial: cancelled", file=sys.stderr)
        return EXIT_CANCELLED
    except core.ContactsError as error:
        if hasattr(error, "devices"):  # haptics.DeviceUnavailable: the hardware is not plugged in
            print(f"contacts trial: no {args.device} device: {error.reason}", file=sys.stderr)
            print("HID devices seen:" + ("" if error.devices else " none"), file=sys.stderr)
            if error.devices:
                print(trial.describe_devices_seen(error.devices), file=sys.stderr)
            return EXIT_INPUT
        print(f"contacts trial: {naming_the_file(str(error), file)}", file=sys.stderr)
        if isinstance(error, core.ArgumentError):
            return EXIT_USAGE
        return EXIT_INPUT if isinstance(error, core.InputError) else EXIT_FAILED
    except MemoryError as error:
        print(f"contacts trial: {out_of_memory_message(error, file)}", file=sys.stderr)
        return EXIT_FAILED
    path = [sample.to_dict() for sample in result.path]
    if args.record:
        try:
            with output_files.replaced(args.record) as temporary:
                trial.write_path(path, temporary)
        except OSError as error:
            print(f"contacts trial: cannot write '{args.record}': {error.strerror}", file=sys.stderr)
            return EXIT_FAILED
    if args.json:
        json.dump(trial_json(result), sys.stdout, indent=2)
        sys.stdout.write("\n")
    else:
        final = result.final
        if result.mode == "realtime":
            print(f"Trial of '{escape_controls(args.part)}' in {escape_controls(file)} (realtime): {result.ticks} ticks at "
                  f"{result.rate_hz:.0f} Hz, step p50 {result.step_us.p50:.1f} us, "
                  f"p99 {result.step_us.p99:.1f} us, jitter p99 {result.jitter_us.p99:.1f} us, "
                  f"{result.overruns} overruns")
        else:
            print(f"Trial of '{escape_controls(args.part)}' in {escape_controls(file)} (lockstep): {result.ticks} ticks, "
                  f"{result.sim_time_s:.3f} s simulated")
        for j in result.joints_engaged:
            print(f"  engaged {j.type} ({j.joint}) with {escape_controls(j.with_body)} "
                  f"at t = {j.t:.3f} s")
        print("  final offset: translate [" + ", ".join(f"{v:.4f}" for v in final.translate) + "] mm, rotate ["
              + ", ".join(f"{v:.4f}" for v in final.rotate_deg) + "] deg")
        print(f"  max penetration {result.max_penetration_mm:.4f} mm, max force {result.max_force_n:.2f} N")
        if args.record:
            print(f"  path ({len(path)} samples) saved to {args.record}")
        if args.device != "sim":
            print(f"  device: {result.device_message}")
        if args.record_hid:
            print(f"  raw HID reports saved to {args.record_hid}")
    if not result.success:  # the trial ran, but its path is not acceptable: the analysis failed
        print(f"contacts trial: failed: {result.failure} (file '{escape_controls(file)}')", file=sys.stderr)
        return EXIT_FAILED
    return EXIT_OK
