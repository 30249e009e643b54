#!/usr/bin/python3
"""Benchmarks of the contacts pipeline, with ratios against baselines measured
in the same run (`make bench`):

1. End to end against the floor: bench_contacts (C++) runs, per file and each
   in its own child process, a bare XDE read of the file (OCCT alone:
   STEPCAFControl_Reader, names on) and our whole pipeline from the file
   (read_step, then find_contacts on all cores): time and peak memory of
   each, best time of --repeat runs. Files: the motor, the shared R08 press,
   bolted grids of N parts, the same grids stacked along z, and 10,000
   instances of one part under one name. Growth exponents of what comes
   after the read, per family.
2. Brute force: the same files, from shapes in memory, against the way a
   FreeCAD user can script it today and the tests' checker (small files).
3. partitions: bench_partitions (ours vs OCCT's ShapeUpgrade_UnifySameDomain).
4. the haptic loop's collision budget: bench_haptic_query (Google Benchmark):
   contact query per pair in contact on the motor, servo tick in contact,
   the loop on its thread in real time; run idle and again beside two busy
   processes (`yes > /dev/null`), the CPU named (`lscpu`). --haptics-only runs
   just this part (its own section of docs/benchmarks.md).
5. interference and validity checks: bench/bench_interferences.py (the motor,
   R08, R01 and five B-spline solids against their bare reads, and the
   whole-solid Boolean pass they replaced).
6. the servo loop in realtime mode: bench/bench_realtime_loop.py (10 s
   realtime trials on the motor, Axis in contact and Screw-1 seated, with
   the simulated hand, idle and beside two busy processes; rate, step and
   jitter p50/p99, overruns, realtime priority, the CPU from /proc/cpuinfo).

Prints Markdown tables; --write FILE also saves them (docs/benchmarks.md)."""
import argparse
import json
import math
import os
import platform
import re
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from contacts_runs import best_runs  # noqa: E402
from markdown_sections import write_section  # noqa: E402

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(REPO, "tests"))  # the brute-force checker
sys.path.insert(0, os.path.join(REPO, "tools"))  # the sample families
sys.path.insert(0, REPO)  # contactwb, for FreeCAD as a library (stacked grids)
SHARED = os.path.join(os.path.dirname(REPO), "shared", "data", "step")
GRID_SIZES = [100, 1000, 10000]
ONE_NAME_COUNT = 10000


def grid_file(data_dir, n):
    path = os.path.join(data_dir, f"bolted_grid_{n}.step")
    if not os.path.isfile(path):
        subprocess.run([sys.executable, os.path.join(REPO, "tools", "make_samples.py"), "--grid", str(n),
                        "--no-fcstd", "--out", data_dir], check=True, stdout=subprocess.DEVNULL)
    return path


def _freecad():
    from contactwb import freecad_setup
    freecad_setup.import_freecad()
    import FreeCAD
    return FreeCAD


def stacked_grid_file(data_dir, n):
    """The bolted grid of n parts turned a quarter about y: its rows run
    along z, as a motor's parts do (a sweep on z alone would degrade)."""
    path = os.path.join(data_dir, f"stacked_grid_{n}.step")
    if not os.path.isfile(path):
        FreeCAD = _freecad()
        import samples_common as sc
        import samples_families as sf
        parts, _, _ = sf.bolted_grid(n)
        turn = FreeCAD.Placement(FreeCAD.Vector(), FreeCAD.Rotation(FreeCAD.Vector(0, 1, 0), -90))
        for part in parts:
            part.placement = turn.multiply(part.placement)
        sc.export_assembly(parts, data_dir, f"stacked_grid_{n}", write_fcstd=False, share_shapes=True)
    return path


def one_name_file(data_dir, n=ONE_NAME_COUNT):
    """n instances of one cube, all named 'Screw', side by side on a square
    lattice (each touches its neighbours: 2 k (k - 1) PLF for k = sqrt n)."""
    path = os.path.join(data_dir, f"one_name_{n}.step")
    if not os.path.isfile(path):
        FreeCAD = _freecad()
        import Import
        import Part
        doc = FreeCAD.newDocument("one_name")
        prefs = FreeCAD.ParamGet("User parameter:BaseApp/Preferences/Document")
        old = prefs.GetBool("DuplicateLabels", False)
        prefs.SetBool("DuplicateLabels", True)  # every part keeps the label "Screw"
        try:
            cube, side = Part.makeBox(10, 10, 10), int(math.ceil(math.sqrt(n)))
            objects = []
            for i in range(n):
                obj = doc.addObject("Part::Feature", f"Part{i}")
                obj.Shape = cube
                obj.Placement = FreeCAD.Placement(FreeCAD.Vector(10 * (i % side), 10 * (i // side), 0),
                                                  FreeCAD.Rotation())
                obj.Label = "Screw"
                objects.append(obj)
            Import.export(objects, path)
        finally:
            prefs.SetBool("DuplicateLabels", old)
            FreeCAD.closeDocument(doc.Name)
    return path


def run_ours(build_dir, files, repeat):
    """{file: {"bare": best bare-read row, "ours": best pipeline row}}: one
    run of each file, then repeat - 1 more of those that took under 10 s
    (the largest files read for a minute)."""
    exe = os.path.join(build_dir, "bench", "bench_contacts")
    rows = {}
    best_runs(exe, files, 1, rows)
    quick = [f for f in files if rows[f]["ours"]["total"] < 10]
    if repeat > 1 and quick:
        best_runs(exe, quick, repeat - 1, rows)
    return rows


def scripted_baseline(solids):
    """The script a FreeCAD user can write today (notes.md): body box filter,
    then a Boolean common of every same-type face pair of touching bodies
    whose face boxes meet; a common with area is a contact. Returns the
    number of face pairs in contact."""
    boxes = [s.BoundBox for s in solids]
    found = 0
    for i in range(len(solids)):
        for j in range(i + 1, len(solids)):
            if not boxes[i].intersect(boxes[j]):
                continue
            for fa in solids[i].Faces:
                kind = type(fa.Surface).__name__
                for fb in solids[j].Faces:
                    if type(fb.Surface).__name__ != kind or not fa.BoundBox.intersect(fb.BoundBox):
                        continue
                    if fa.common(fb).Area > 1e-6:
                        found += 1
    return found


def run_scripted_baseline(path):
    import Part
    solids = Part.read(path).Solids
    start = time.perf_counter()
    scripted_baseline(solids)
    return time.perf_counter() - start


def run_brute_force(path):
    """Seconds of the brute-force search from shapes in memory, and its contact count."""
    import bruteforce_contacts as brute
    import Part
    # Names do not matter to the timing: solids in file order, numbered.
    shapes = {f"solid{i}": solid for i, solid in enumerate(Part.read(path).Solids)}
    start = time.perf_counter()
    contacts = brute.brute_force_contacts(shapes)
    seconds = time.perf_counter() - start
    return seconds, sum(sum(types.values()) for types in contacts.values())


def unique_names_table():
    """Unique names of 8,000 instances, all of one name and all distinct
    (through the Python binding, as the document path calls it)."""
    os.environ.setdefault("CONTACTS_PYTHON_DIR", os.path.join(REPO, "build", "python"))
    sys.path.insert(0, REPO)
    from contactwb import core
    lines = ["| 8,000 names | ms (best of 5) |", "|---|---|"]
    for label, names in (("all the same", ["Screw"] * 8000), ("all different", [f"Screw{i}" for i in range(8000)])):
        best = 1e9
        for _ in range(5):
            start = time.perf_counter()
            core.contactcore.unique_names(names)
            best = min(best, time.perf_counter() - start)
        lines.append(f"| {label} | {best * 1e3:.2f} |")
    return "\n".join(lines)


def cancel_cell(latency):
    return f"{latency * 1e3:.0f}" if latency >= 0 else "done first"


def end_to_end_table(cases, ours):
    lines = ["| case | bodies | faces | contacts | bare XDE read s | ours end to end s | ratio | "
             "of which read s | partitions ms | broad phase ms | candidates ms | area ms | after read ms | "
             "bare read peak MB | our peak MB | peak ratio | cancel latency ms |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for name, path in cases:
        bare, r = ours[path]["bare"], ours[path]["ours"]
        lines.append(
            f"| {name} | {r['bodies']} | {r['faces']} | {r['contacts']} | {bare['seconds']:.3f} | {r['total']:.3f} "
            f"| {r['total'] / bare['seconds']:.2f}x | {r['read']:.3f} | {r['partitions'] * 1e3:.1f} "
            f"| {r['broad_phase'] * 1e3:.2f} | {r['candidates_time'] * 1e3:.2f} | {r['area'] * 1e3:.1f} "
            f"| {r['after_read'] * 1e3:.1f} | {bare['peak_rss_mb']:.0f} | {r['peak_rss_mb']:.0f} "
            f"| {r['peak_rss_mb'] / bare['peak_rss_mb']:.2f}x | {cancel_cell(r['cancel_latency'])} |")
    return "\n".join(lines)


STAGES = (("read", "read"), ("partitions", "partitions"), ("contacts", None), ("interferences", "interferences"),
          ("validity", "validity"))


def stage_seconds(row):
    """Seconds of each stage of one pipeline row, and what is left (the
    tolerances, the clearances, freeing memory): they add up to the total."""
    seconds = {"read": row["read"], "partitions": row["partitions"],
               "contacts": row["broad_phase"] + row["candidates_time"] + row["area"],
               "interferences": row.get("interferences", 0.0), "validity": row.get("validity", 0.0)}
    seconds["other"] = max(0.0, row["total"] - sum(seconds.values()))
    return seconds


def shares_table(cases, ours):
    """Each stage's share of the end-to-end time, per case: the slowest stage
    at a glance."""
    names = [name for name, _ in STAGES] + ["other"]
    lines = ["| case | reader | end to end s | " + " | ".join(f"{n} %" for n in names) + " | slowest |",
             "|---|---|---|" + "---|" * len(names) + "---|"]
    for name, path in cases:
        r = ours[path]["ours"]
        seconds = stage_seconds(r)
        total = r["total"]
        slowest = max(names, key=lambda n: seconds[n])
        lines.append(f"| {name} | {r.get('reader', '?')} | {total:.3f} | "
                     + " | ".join(f"{100 * seconds[n] / total:.1f}" for n in names) + f" | {slowest} |")
    return "\n".join(lines)


def plot_read_scaling(series, path):
    """A PNG, log-log: seconds against parts, one line per series
    ([(label, colour, [(n, seconds)])]), drawn with PIL (python3-pil)."""
    from PIL import Image, ImageDraw
    width, height, left, right, top, bottom = 900, 600, 90, 30, 40, 70
    points = [p for _, _, pts in series for p in pts if p[1] > 0]
    if not points:
        return
    n0, n1 = min(p[0] for p in points), max(p[0] for p in points)
    t0, t1 = min(p[1] for p in points), max(p[1] for p in points)
    lx0, lx1 = math.floor(math.log10(n0)), math.ceil(math.log10(n1))
    ly0, ly1 = math.floor(math.log10(t0)), math.ceil(math.log10(t1))
    if lx1 == lx0:
        lx1 += 1
    if ly1 == ly0:
        ly1 += 1

    def xy(n, t):
        x = left + (math.log10(n) - lx0) / (lx1 - lx0) * (width - left - right)
        y = height - bottom - (math.log10(t) - ly0) / (ly1 - ly0) * (height - top - bottom)
        return x, y
    image = Image.new("RGB", (width, height), "white")
    draw = ImageDraw.Draw(image)
    for e in range(lx0, lx1 + 1):
        x, _ = xy(10 ** e, 10 ** ly0)
        draw.line([(x, top), (x, height - bottom)], fill=(220, 220, 220))
        draw.text((x - 15, height - bottom + 8), f"{10 ** e:,}", fill="black")
    for e in range(ly0, ly1 + 1):
        _, y = xy(10 ** lx0, 10 ** e)
        draw.line([(left, y), (width - right, y)], fill=(220, 220, 220))
        draw.text((10, y - 6), f"{10.0 ** e:g} s", fill="black")
    draw.rectangle([left, top, width - right, height - bottom], outline="black")
    draw.text((width // 2 - 40, height - 30), "parts (log)", fill="black")
    draw.text((left, 12), "seconds against parts, log-log (bench/run_benchmarks.py)", fill="black")
    for k, (label, colour, pts) in enumerate(series):
        pts = sorted(p for p in pts if p[1] > 0)
        xys = [xy(n, t) for n, t in pts]
        if len(xys) > 1:
            draw.line(xys, fill=colour, width=3)
        for x, y in xys:
            draw.ellipse([x - 4, y - 4, x + 4, y + 4], fill=colour)
        draw.line([(left + 20, top + 20 + 18 * k), (left + 50, top + 20 + 18 * k)], fill=colour, width=3)
        draw.text((left + 58, top + 14 + 18 * k), label, fill="black")
    image.save(path)


def growth_table(families):
    lines = ["| family | N from | N to | after the read: time ratio | exponent | bare read exponent "
             "| end to end exponent |", "|---|---|---|---|---|---|---|"]

    def exponent(t0, t1, n0, n1):
        return math.log(t1 / t0) / math.log(n1 / n0)
    for family, rows in families:
        for (n0, r0), (n1, r1) in zip(rows, rows[1:]):
            a0, a1 = r0["ours"]["after_read"], r1["ours"]["after_read"]
            lines.append(
                f"| {family} | {n0} | {n1} | {a1 / a0:.1f} | {exponent(a0, a1, n0, n1):.2f} "
                f"| {exponent(r0['bare']['seconds'], r1['bare']['seconds'], n0, n1):.2f} "
                f"| {exponent(r0['ours']['total'], r1['ours']['total'], n0, n1):.2f} |")
    return "\n".join(lines)


def brute_table(cases, ours, brute, scripted_times):
    lines = ["| case | contacts | ours after read ms | scripted s | scripted / ours | checker s | checker / ours |",
             "|---|---|---|---|---|---|---|"]
    for name, path in cases:
        if path not in brute and path not in scripted_times:
            continue
        r = ours[path]["ours"]
        b = brute.get(path)
        scripted = scripted_times.get(path)
        ratio_cell = f"{b[0] / r['after_read']:.0f}x" if b else "-"
        if b and b[1] != r["contacts"]:
            ratio_cell += f" (checker found {b[1]})"
        scripted_cell = f"{scripted:.2f}" if scripted else "not run"
        scripted_ratio = f"{scripted / r['after_read']:.0f}x" if scripted else "-"
        brute_cell = f"{b[0]:.2f}" if b else "not run"
        lines.append(f"| {name} | {r['contacts']} | {r['after_read'] * 1e3:.1f} | {scripted_cell} "
                     f"| {scripted_ratio} | {brute_cell} | {ratio_cell} |")
    return "\n".join(lines)


def cpu_model():
    try:
        out = subprocess.run(["lscpu"], capture_output=True, text=True).stdout
    except OSError:
        return platform.processor() or platform.machine()
    for line in out.splitlines():
        if line.startswith("Model name:"):
            return line.split(":", 1)[1].strip()
    return platform.processor() or platform.machine()


def run_haptic_query(exe, loop_seconds, busy):
    """bench_haptic_query's benchmarks (name -> counters), with `busy` CPU hogs
    (`yes`, started here and stopped by their own pids) running alongside."""
    hogs = [subprocess.Popen(["yes"], stdout=subprocess.DEVNULL) for _ in range(busy)]
    try:
        load = open("/proc/loadavg").read().split()[0]
        out = subprocess.run([exe, "--benchmark_format=json", "--loop_seconds", str(loop_seconds)],
                             capture_output=True, text=True)
    finally:
        for hog in hogs:
            hog.kill()
            hog.wait()
    if out.returncode != 0:
        raise RuntimeError(f"{exe} failed: {out.stderr[-2000:]}")
    data = json.loads(out.stdout)
    # Google Benchmark appends "/iterations:N" to a name given a fixed count, and the closed forms
    # and the meshes run different counts: the rows are matched on the name without it.
    return {re.sub(r"/iterations:\d+$", "", b["name"]): b for b in data["benchmarks"]}, load


def haptic_query_tables(runs):
    """Markdown tables of the query, tick and loop rows; `runs` is [(label, results, load)]."""
    def f(value, digits=1):
        return "-" if value is None else f"{value:.{digits}f}"

    def rows_under(prefix):
        """(machine label, load, the name after prefix, row, that run's results) of each row named prefix..."""
        for label, results, load in runs:
            for name, row in results.items():
                if name.startswith(prefix):
                    yield label, load, name[len(prefix):], row, results
    lines = ["| machine | load avg at start | pair (part / neighbour) | closed forms: query p50 us | p99 us | "
             "CPU p99 us | closed-form pairs / query | mesh fallbacks / query | meshes only: p50 us | p99 us | "
             "p99 ratio | meshes only on body trees: CPU p50 us | body trees / per-partition trees CPU p50 |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for label, load, pair, row, results in rows_under("contact_query/closed_form/"):
        mesh = results.get("contact_query/meshes_only/" + pair, {})
        ratio = mesh.get("p99_us", 0) / row["p99_us"] if row.get("p99_us") else None
        bodies = results.get("contact_query/meshes_only_body_trees/" + pair, {})
        trees = (bodies["cpu_p50_us"] / mesh["cpu_p50_us"]
                 if mesh.get("cpu_p50_us") and bodies.get("cpu_p50_us") else None)
        lines.append(f"| {label} | {load} | {pair} | {f(row['p50_us'])} | {f(row['p99_us'])} | "
                     f"{f(row['cpu_p99_us'])} | {f(row['closed_pairs'])} | {f(row['mesh_fallbacks'])} | "
                     f"{f(mesh.get('p50_us'))} | {f(mesh.get('p99_us'))} | {f(ratio)}x | "
                     f"{f(bodies.get('cpu_p50_us'))} | {f(trees, 2)}x |")
    lines += ["", "| machine | the machine's floor: a fixed 6,000 multiply-adds timed as a query, p50 us | p99 us | "
              "CPU p50 us | CPU p99 us |", "|---|---|---|---|---|"]
    for label, _, _, row, _ in rows_under("machine_floor/fixed_loop"):
        lines.append(f"| {label} | {f(row['p50_us'])} | {f(row['p99_us'])} | {f(row['cpu_p50_us'])} | "
                     f"{f(row['cpu_p99_us'])} |")
    lines += ["", "| machine | part | servo tick, closed forms: p50 us | p99 us | CPU p99 us | contacts / tick | "
              "meshes only: p50 us | p99 us |", "|---|---|---|---|---|---|---|---|"]
    for label, _, rest, row, results in rows_under("servo_tick/closed_form/"):
        part = rest.split("/")[-1]
        mesh = results.get("servo_tick/meshes_only/" + part, {})
        lines.append(f"| {label} | {part} | {f(row['p50_us'])} | {f(row['p99_us'])} | {f(row['cpu_p99_us'])} | "
                     f"{f(row['contacts'])} | {f(mesh.get('p50_us'))} | {f(mesh.get('p99_us'))} |")
    lines += ["", "| machine | part | priority | ticks | rate Hz | jitter p50 us | jitter p99 us | step p50 us | "
              "step p99 us | overruns | late wake-ups |", "|---|---|---|---|---|---|---|---|---|---|---|"]
    for label, _, rest, row, _ in rows_under("realtime_loop/"):
        priority, part = rest.split("/")[:2]
        granted = "SCHED_FIFO 80" if row.get("fifo") else ("normal" if priority == "normal" else
                                                            "SCHED_FIFO refused: normal")
        lines.append(f"| {label} | {part} | {granted} | {int(row['ticks'])} | {f(row['rate_hz'])} | "
                     f"{f(row['jitter_p50_us'])} | {f(row['jitter_p99_us'])} | {f(row['step_p50_us'])} | "
                     f"{f(row['step_p99_us'])} | {int(row['overruns'])} | {int(row['late_wakeups'])} |")
    return "\n".join(lines)


def haptic_query_report(build_dir, loop_seconds):
    exe = os.path.join(build_dir, "bench", "bench_haptic_query")
    if not os.path.isfile(exe):
        return None
    runs = []
    for label, busy in (("as found", 0), ("as found + 2 busy", 2)):
        results, load = run_haptic_query(exe, loop_seconds, busy)
        runs.append((label, results, load))
    return "\n".join([
        f"Measured {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())} by `bench/run_benchmarks.py` "
        f"(bench_haptic_query, Google Benchmark), Release build, CPU: {cpu_model()}, {os.cpu_count()} cores, "
        "*as found*: the machine as it was, idle or shared with other builds (the load average at the "
        "start of each run is in the tables); *as found + 2 busy*: the same run again with two "
        "`yes > /dev/null` processes started by the script. Query and tick rows are wall time on "
        "CLOCK_MONOTONIC (CPU: the thread's own time) in lockstep (a virtual clock: no sleeping between "
        "ticks); loop rows are realtime mode (the loop on its own thread, absolute deadlines, "
        f"{loop_seconds:g} s). *closed forms*: the contact query as the trial runs it (analytic partition "
        "pairs in closed form, the meshes for the rest); *meshes only*: the same query with the closed "
        "forms off (the collision stage's meshes alone, as before), in the same process. *The machine's "
        "floor*: a fixed computation of about a query's p50, timed the same way in the same process: what "
        "this machine adds to the p99 of any short computation.",
        "", haptic_query_tables(runs)])


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build-dir", default=os.path.join(REPO, "build"))
    parser.add_argument("--repeat", type=int, default=3, help="runs of each file (best taken)")
    parser.add_argument("--brute-max", type=int, default=100,
                        help="largest grid on which the brute-force checker runs (1000 takes 6 s)")
    parser.add_argument("--scripted-max", type=int, default=100,
                        help="largest grid on which the scripted baseline runs")
    parser.add_argument("--grids", type=int, nargs="*", default=GRID_SIZES)
    parser.add_argument("--write", help="also write the report to this Markdown file")
    parser.add_argument("--plot", help="also draw time against parts (bare XDE read, ours) into this PNG")
    parser.add_argument("--skip-meshes", action="store_true", help="leave out bench/bench_meshes.py")
    parser.add_argument("--haptics-only", action="store_true",
                        help="run only the haptic loop's collision benchmark (bench_haptic_query)")
    parser.add_argument("--loop-seconds", type=float, default=10, help="the realtime loop's duration")
    args = parser.parse_args()
    build_dir = os.path.abspath(args.build_dir)
    if args.haptics_only:
        text = haptic_query_report(build_dir, args.loop_seconds) or "bench_haptic_query not built"
        print(text)
        if args.write:
            write_section(args.write, "haptic query bench", text)
        return
    data_dir = os.path.join(build_dir, "bench-data")
    os.makedirs(data_dir, exist_ok=True)

    cases = [("motor (bundled)", os.path.join(REPO, "Resources", "samples", "motor.step"))]
    r08 = os.path.join(SHARED, "R08_presse_asm.step")
    if os.path.isfile(r08):
        cases.append(("R08 press (shared)", r08))
    grid_cases = [(n, f"bolted grid N={n}", grid_file(data_dir, n)) for n in args.grids]
    stacked_cases = [(n, f"stacked along z N={n}", stacked_grid_file(data_dir, n)) for n in args.grids]
    cases += [(name, path) for _, name, path in grid_cases + stacked_cases]
    cases.append((f"{ONE_NAME_COUNT} instances, one name", one_name_file(data_dir)))

    ours = run_ours(build_dir, [path for _, path in cases], args.repeat)
    brute, scripted = {}, {}
    for n, _, path in grid_cases:
        if n <= args.brute_max:
            brute[path] = run_brute_force(path)
        if n <= args.scripted_max:
            scripted[path] = run_scripted_baseline(path)
    for _, path in cases[:2]:  # motor, press
        brute[path] = run_brute_force(path)
        scripted[path] = run_scripted_baseline(path)

    families = [("bolted grid", [(n, ours[path]) for n, _, path in grid_cases]),
                ("stacked along z", [(n, ours[path]) for n, _, path in stacked_cases])]
    report = [f"Measured {time.strftime('%Y-%m-%d')} on {os.cpu_count()} cores "
              f"({platform.processor() or platform.machine()}), Release build, the machine shared with other "
              f"builds. Each run in its own process; best of {args.repeat}.",
              "",
              "*Bare XDE read*: OCCT alone bringing the file into an XDE document (STEPCAFControl_Reader, "
              "names on, colours/layers/properties off: what a STEP tool built on XDE waits for). *Ours end to "
              "end*: read_step (the read by products: each product transferred once, its instances placed; "
              "OCCT's XDE read where it falls back, see *reader* below) then find_contacts on all cores, from "
              "the same file. Peaks are each process's maximum resident memory. *Cancel latency*: "
              "a second run asked to stop halfway through find_contacts, time from the request to the return.",
              "", "## End to end, against a bare XDE read of the same file", "", end_to_end_table(cases, ours), "",
              "## Growth (N log N gives about 1.1)", "",
              "Exponents between successive sizes: log(time ratio) / log(N ratio). *After the read* is "
              "find_contacts alone: what we add to the read.", "", growth_table(families), "",
              "## Where the time goes", "",
              "Each stage's share of *ours end to end* (the rows above): *read* is read_step, *contacts* the "
              "broad phase, candidates and common areas, *interferences* and *validity* the passes after the "
              "contacts, *other* the rest (tolerances, clearances). *reader*: `products` when the fast "
              "product read served the file, `xde` when it fell back to OCCT's XDE read.", "",
              shares_table(cases, ours), "",
              "## Against brute force (shapes in memory)", "",
              "*scripted* is what a FreeCAD user can script today (body box filter, Boolean common of every "
              "same-type face pair whose boxes meet); *checker* is the tests' brute-force checker "
              "(tests/bruteforce_contacts.py). Ratios against our time after the read.", "",
              brute_table(cases, ours, brute, scripted), "",
              "## Unique names", "", unique_names_table()]
    exe = os.path.join(build_dir, "bench", "bench_partitions")
    if os.path.isfile(exe):
        out = subprocess.run([exe, "--benchmark_min_time=0.05"], capture_output=True, text=True)
        table = [line for line in out.stdout.splitlines() if line.startswith("|")]
        report += ["", "## Partitions (ours vs ShapeUpgrade_UnifySameDomain)", "", *(table or [out.stdout])]
    haptics = haptic_query_report(build_dir, args.loop_seconds)
    if haptics:
        report += ["", "## The haptic loop's collision budget", "", haptics]
    if args.plot:
        plot_read_scaling([("bare XDE read, bolted grid", (200, 40, 40),
                            [(n, ours[path]["bare"]["seconds"]) for n, _, path in grid_cases]),
                           ("ours end to end, bolted grid", (30, 90, 200),
                            [(n, ours[path]["ours"]["total"]) for n, _, path in grid_cases]),
                           ("ours: read alone, bolted grid", (40, 160, 60),
                            [(n, ours[path]["ours"]["read"]) for n, _, path in grid_cases])], args.plot)
        report += ["", f"Plot of these rows: {os.path.relpath(args.plot, REPO)}."]
    text = "\n".join(report)
    print(text)
    if args.write:
        write_section(args.write, "contacts bench", "`make bench` (bench/run_benchmarks.py) prints these tables.\n\n" + text)
    # Interference and validity checks against the read: their own program and section (issue 24).
    subprocess.run([sys.executable, os.path.join(REPO, "bench", "bench_interferences.py"), "--build-dir", build_dir,
                    "--repeat", str(args.repeat)] + (["--write", args.write] if args.write else []), check=True)
    # The servo loop in realtime mode: its own program and section (issue 20).
    subprocess.run([sys.executable, os.path.join(REPO, "bench", "bench_realtime_loop.py"), "--build-dir", build_dir,
                    "--seconds", str(args.loop_seconds)] + (["--write", args.write] if args.write else []), check=True)
    # Meshes, collision and disassembly: their own program and section (bench/bench_meshes.py).
    if args.skip_meshes:
        return
    subprocess.run([sys.executable, os.path.join(REPO, "bench", "bench_meshes.py"), "--build-dir", build_dir]
                   + (["--write", args.write] if args.write else []), check=True)


if __name__ == "__main__":
    main()
