#!/usr/bin/python3
"""The haptic loop in real time (issue 20: "loop rate and jitter over 10 s in
realtime mode, the CPU it ran on, and the figures under two busy processes").

Runs `contacts trial`'s realtime trial (contactwb.core.trial.run with
realtime=True: the 1 kHz loop on its own thread, absolute deadlines on
CLOCK_MONOTONIC, SCHED_FIFO 80 asked for as `contacts trial --realtime` does)
on the bundled motor with the simulated hand, for --seconds (10) per case:

- *Axis in contact*: the Axis seated, the hand pushing 0.2 mm into the seat
  and circling 0.3 mm sideways (held in its bores, on its seat);
- *Screw-1 seated*: the same hand on Screw-1 (in its holes, its head on the
  Front-cover).

Each case runs once on the machine as it is, then again beside two busy
processes (`yes`, stdout to /dev/null, started here and killed by their pids
when the case ends). The figures are the trial's own (TrialResult): rate_hz,
step_us and jitter_us p50/p99 (wall time), overruns (long steps and late
wake-ups), realtime_priority (SCHED_FIFO granted), memory_locked; the CPU is
/proc/cpuinfo's model name, the load average /proc/loadavg's 1-minute figure
at each case's start. The scene (STEP read, partitions, meshes) is built once
per part, before any timing.

  bench/bench_realtime_loop.py [--build-dir build] [--seconds 10] [--meshes-only] [--write docs/benchmarks.md]

`make bench` runs it through bench/run_benchmarks.py; --write replaces the
"realtime loop bench" section of the Markdown file."""
import argparse
import math
import os
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from markdown_sections import write_section  # noqa: E402

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MOTOR = os.path.join(REPO, "Resources", "samples", "motor.step")
CASES = (("Axis in contact", "Axis"), ("Screw-1 seated", "Screw-1"))
BUSY = 2
SECTION = "realtime loop bench"


def cpu_model():
    """The CPU's model name from /proc/cpuinfo (the first processor's)."""
    try:
        with open("/proc/cpuinfo") as stream:
            for line in stream:
                if line.lower().startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return "unknown (no model name in /proc/cpuinfo)"


def load_average():
    with open("/proc/loadavg") as stream:
        return float(stream.read().split()[0])


def pushing_hand(seconds):
    """The trial script: the part starts seated; the hand pushes 0.2 mm into
    the seat and circles 0.3 mm sideways (keys every 50 ms, piecewise linear)."""
    keys = []
    steps = int(round(seconds / 0.05))
    for i in range(steps + 1):
        t = i * 0.05
        keys.append({"t": t, "translate": [0.3 * math.sin(2 * t), 0.3 * math.cos(2 * t), -0.2],
                     "rotate_deg": [0, 0, 0]})
    return {"start": {"translate": [0, 0, 0], "rotate_deg": [0, 0, 0]}, "hand": keys}


def start_busy(count):
    """`count` CPU burners (`yes > /dev/null`), stopped by stop_busy."""
    return [subprocess.Popen(["yes"], stdout=subprocess.DEVNULL) for _ in range(count)]


def stop_busy(processes):
    for process in processes:
        process.kill()
        process.wait()


def run_case(trial, scene, seconds, busy):
    """One realtime trial of `seconds` with `busy` burners alongside: a dict of its figures."""
    burners = start_busy(busy)
    try:
        time.sleep(0.5 if busy else 0)  # the burners running before the loop starts
        load = load_average()
        result = trial.run(scene, pushing_hand(seconds), realtime=True, settle=0.0, realtime_priority=80)
    finally:
        stop_busy(burners)
    return {"load": load, "ticks": result.ticks, "rate_hz": result.rate_hz, "step_p50": result.step_us.p50,
            "step_p99": result.step_us.p99, "jitter_p50": result.jitter_us.p50, "jitter_p99": result.jitter_us.p99,
            "overruns": result.overruns, "long_steps": result.long_steps, "late_wakeups": result.late_wakeups,
            "realtime_priority": result.realtime_priority, "memory_locked": result.memory_locked,
            "mode": result.mode, "success": result.success, "max_penetration_mm": result.max_penetration_mm}


def table(rows):
    lines = ["| case | busy processes | load avg at start | ticks | rate_hz | step_us p50 | step_us p99 | "
             "jitter_us p50 | jitter_us p99 | overruns (long steps + late wake-ups) | realtime_priority | "
             "memory locked |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for name, busy, r in rows:
        lines.append(f"| {name} | {busy} | {r['load']:.2f} | {r['ticks']} | {r['rate_hz']:.1f} | "
                     f"{r['step_p50']:.1f} | {r['step_p99']:.1f} | {r['jitter_p50']:.1f} | {r['jitter_p99']:.1f} | "
                     f"{r['overruns']} ({r['long_steps']} + {r['late_wakeups']}) | "
                     f"{'true' if r['realtime_priority'] else 'false'} | {'yes' if r['memory_locked'] else 'no'} |")
    return "\n".join(lines)


def report(rows, seconds, cpu, note):
    return "\n".join([
        f"Issue 20: the servo loop in realtime mode, `bench/bench_realtime_loop.py` (`make bench` runs it through "
        f"`bench/run_benchmarks.py`). Measured {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, Release "
        f"build, CPU: {cpu} ({os.cpu_count()} cores). Each row is one realtime trial of {seconds:g} s on the "
        "motor with the simulated hand (`contacts trial --realtime`: the loop on its own thread, absolute "
        "deadlines on CLOCK_MONOTONIC, SCHED_FIFO 80 asked for); the hand pushes 0.2 mm into the seat and "
        "circles 0.3 mm sideways, the part starting seated. *busy processes*: `yes > /dev/null` processes "
        "started by the script for that row and killed after it. Figures are the trial's own (`--json`): "
        "rate_hz = ticks / wall time, step_us the tick's computation, jitter_us |period - 1 ms|, overruns "
        "= steps over 1 ms plus wake-ups more than 100 us late."
        + (f" {note}" if note else ""),
        "", table(rows)])


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build-dir", default=os.path.join(REPO, "build"))
    parser.add_argument("--seconds", type=float, default=10.0, help="each realtime trial's duration")
    parser.add_argument("--busy", type=int, default=BUSY, help="busy processes in the second run of each case")
    parser.add_argument("--note", default="", help="a sentence added to the report (how the machine was loaded)")
    parser.add_argument("--write", help="also replace this Markdown file's section 'realtime loop bench'")
    parser.add_argument("--meshes-only", action="store_true",
                        help="the contact query on the meshes alone (the closed forms between analytic "
                             "partitions off: the scene's closed_forms=False), for comparison")
    args = parser.parse_args()
    os.environ.setdefault("CONTACTS_PYTHON_DIR", os.path.join(os.path.abspath(args.build_dir), "python"))
    sys.path.insert(0, REPO)
    from contactwb.core import trial
    from contactwb.document.files import load_assembly

    assembly = load_assembly(MOTOR)
    rows = []
    for name, part in CASES:
        scene = trial.make_scene(assembly, part, closed_forms=not args.meshes_only)
        for busy in (0, args.busy):
            result = run_case(trial, scene, args.seconds, busy)
            if result["mode"] != "realtime":
                raise RuntimeError(f"{name}: the trial did not run in realtime mode ({result['mode']})")
            rows.append((name, busy, result))
            print(f"{name}, {busy} busy: {result['rate_hz']:.1f} Hz, jitter p99 {result['jitter_p99']:.1f} us, "
                  f"{result['overruns']} overruns", file=sys.stderr)
    query = ("The contact query on the meshes alone (`--meshes-only`)." if args.meshes_only else
             "The contact query with the closed forms between analytic partitions (the default).")
    text = report(rows, args.seconds, cpu_model(), f"{args.note} {query}".strip())
    print(text)
    if args.write:
        write_section(args.write, SECTION, text)


if __name__ == "__main__":
    main()
