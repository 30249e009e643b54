"""`contacts trial FILE --part NAME --device sim --script SCRIPT.json` — a
haptic trial run headless: the part starts at the script's offset from its
assembled placement, the simulated hand follows the script's targets, and the
1 kHz loop holds the part to the joints its contacts allow, stops it at
collisions and reports where it ended.

Script: {"start": {"translate": [x, y, z], "rotate_deg": [rx, ry, rz]},
         "hand": [{"t": s, "translate": [...], "rotate_deg": [...]}, ...]}
(offsets from the assembled placement in mm; rotations in degrees about global
axes through the part's centre of mass, x then y then z; the hand's targets
are piecewise linear in time and held after the last.)"""
import argparse
import json
import sys


def main(argv):
    parser = argparse.ArgumentParser(prog="contacts trial", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("file", help="a STEP (.step/.stp) or FreeCAD (.FCStd) assembly")
    parser.add_argument("--part", required=True, help="the body to move (its name in the assembly)")
    parser.add_argument("--device", default="sim", choices=["sim"],
                        help="the device: sim, the simulated hand (headless trials need no hardware)")
    parser.add_argument("--script", required=True, help="the trial script (JSON)")
    parser.add_argument("--json", action="store_true", help="print the result as JSON")
    parser.add_argument("--record", metavar="PATH", help="save the path (time, placement, force): .csv or .json")
    parser.add_argument("--realtime", action="store_true",
                        help="run the loop on its own thread in real time (default: lockstep, deterministic)")
    parser.add_argument("--stiffness", type=float, help="virtual coupling stiffness, N/mm (clamped to the device)")
    parser.add_argument("--capture-distance", type=float, default=0.5, help="engagement capture distance, mm")
    parser.add_argument("--capture-angle", type=float, default=2.0, help="engagement capture angle, degrees")
    args = parser.parse_args(argv)

    from contactwb import core
    from contactwb.core import trial
    from contactwb.document.files import load_assembly
    try:
        script = trial.read_script(args.script)
        assembly = load_assembly(args.file)
        scene = trial.make_scene(assembly, args.part, capture_distance=args.capture_distance,
                                 capture_angle_deg=args.capture_angle)
        options = {"stiffness": args.stiffness} if args.stiffness is not None else {}
        if args.realtime:
            options["realtime_priority"] = 80  # SCHED_FIFO when the system grants it
        result = trial.run(scene, script, realtime=args.realtime, **options)
    except core.Cancelled:
        print("contacts trial: cancelled", file=sys.stderr)
        return 130
    except core.ContactsError as error:
        print(f"contacts trial: {error} (file '{args.file}')", file=sys.stderr)
        return 1
    path = result.pop("path")
    if args.record:
        try:
            trial.write_path(path, args.record)
        except OSError as error:
            print(f"contacts trial: cannot write '{args.record}': {error.strerror}", file=sys.stderr)
            return 1
    if args.json:
        out = {k: result[k] for k in ("mode", "ticks", "sim_time_s", "rate_hz", "step_us", "jitter_us",
                                      "overruns", "realtime_priority", "success", "failure")}
        out["joints_engaged"] = [{"with": j["with"], "type": j["type"]} for j in result["joints_engaged"]]
        out["final"] = result["final"]
        for key in ("max_penetration_mm", "start_penetration_mm", "final_penetration_mm", "max_force_n"):
            out[key] = result[key]
        json.dump(out, sys.stdout, indent=2)
        sys.stdout.write("\n")
    else:
        final = result["final"]
        if result["mode"] == "realtime":
            print(f"Trial of '{args.part}' in {args.file} (realtime): {result['ticks']} ticks at "
                  f"{result['rate_hz']:.0f} Hz, step p50 {result['step_us']['p50']:.1f} us, "
                  f"p99 {result['step_us']['p99']:.1f} us, jitter p99 {result['jitter_us']['p99']:.1f} us, "
                  f"{result['overruns']} overruns")
        else:
            print(f"Trial of '{args.part}' in {args.file} (lockstep): {result['ticks']} ticks, "
                  f"{result['sim_time_s']:.3f} s simulated")
        for j in result["joints_engaged"]:
            print(f"  engaged {j['type']} ({j['joint']}) with {j['with']} at t = {j['t']:.3f} s")
        print("  final offset: translate [" + ", ".join(f"{v:.4f}" for v in final["translate"]) + "] mm, rotate ["
              + ", ".join(f"{v:.4f}" for v in final["rotate_deg"]) + "] deg")
        print(f"  max penetration {result['max_penetration_mm']:.4f} mm, max force {result['max_force_n']:.2f} N")
        if args.record:
            print(f"  path ({len(path)} samples) saved to {args.record}")
    if not result["success"]:
        print(f"contacts trial: failed: {result['failure']} (file '{args.file}')", file=sys.stderr)
        return 2
    return 0
