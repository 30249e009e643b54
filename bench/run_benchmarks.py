#!/usr/bin/python3
"""Benchmarks of the contacts pipeline, with ratios against baselines measured
in the same run (`make bench`):

1. contacts: per stage (read, partitions, broad phase, candidates, common
   area) and peak memory, from bench_contacts (C++, one child process per
   file), on the motor, the shared R08 press and bolted grids of N parts;
   side by side with the brute-force way a FreeCAD user can script today
   (tests/bruteforce_contacts.py: Boolean common of face pairs of touching
   bodies), timed from shapes in memory like ours.
2. partitions: bench_partitions (ours vs OCCT's ShapeUpgrade_UnifySameDomain).

The scripted baseline is the plain script of notes.md (Boolean common of
every same-type face pair of touching bodies).

Prints Markdown tables; --write FILE also saves them (docs/benchmarks.md)."""
import argparse
import json
import math
import os
import platform
import subprocess
import sys
import time

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(REPO, "tests"))  # the brute-force checker
SHARED = os.path.join(os.path.dirname(REPO), "shared", "data", "step")
GRID_SIZES = [10, 100, 1000, 10000]


def grid_file(data_dir, n):
    path = os.path.join(data_dir, f"bolted_grid_{n}.step")
    if not os.path.isfile(path):
        subprocess.run([sys.executable, os.path.join(REPO, "tools", "make_samples.py"), "--grid", str(n),
                        "--no-fcstd", "--out", data_dir], check=True, stdout=subprocess.DEVNULL)
    return path


def run_ours(build_dir, files, repeat):
    exe = os.path.join(build_dir, "bench", "bench_contacts")
    out = subprocess.run([exe, "--repeat", str(repeat), *files], check=True, capture_output=True, text=True)
    rows = [json.loads(line) for line in out.stdout.splitlines() if line.startswith("{")]
    return {row["file"]: row for row in rows}


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


def contacts_table(cases, ours, brute, scripted_times):
    lines = ["| case | bodies | faces | contacts | read ms | partitions ms | broad phase ms | candidates ms "
             "| area ms | total ms (in memory) | peak MB | scripted s | scripted / ours | checker s | checker / ours |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for name, path in cases:
        r = ours[path]
        b = brute.get(path)
        scripted = scripted_times.get(path)
        brute_cell = f"{b[0]:.2f}" if b else "not run"
        ratio_cell = f"{b[0] / r['total']:.0f}x" if b else "-"
        if b and b[1] != r["contacts"]:
            ratio_cell += f" (checker found {b[1]})"
        scripted_cell = f"{scripted:.2f}" if scripted else "not run"
        scripted_ratio = f"{scripted / r['total']:.0f}x" if scripted else "-"
        lines.append(
            f"| {name} | {r['bodies']} | {r['faces']} | {r['contacts']} | {r['read'] * 1e3:.1f} "
            f"| {r['partitions'] * 1e3:.2f} | {r['broad_phase'] * 1e3:.3f} | {r['candidates_time'] * 1e3:.3f} "
            f"| {r['area'] * 1e3:.2f} | {r['total'] * 1e3:.2f} | {r['peak_rss_mb']:.0f} | {scripted_cell} | {scripted_ratio} "
            f"| {brute_cell} | {ratio_cell} |")
    return "\n".join(lines)


def growth_table(grid_rows):
    lines = ["| N from | N to | time ratio | exponent (1 = linear; N log N gives about 1.1) |", "|---|---|---|---|"]
    for (n0, r0), (n1, r1) in zip(grid_rows, grid_rows[1:]):
        ratio = r1["total"] / r0["total"]
        lines.append(f"| {n0} | {n1} | {ratio:.1f} | {math.log(ratio) / math.log(n1 / n0):.2f} |")
    return "\n".join(lines)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build-dir", default=os.path.join(REPO, "build"))
    parser.add_argument("--repeat", type=int, default=5, help="runs of ours per file (best taken)")
    parser.add_argument("--brute-max", type=int, default=1000,
                        help="largest grid on which the brute force runs (10000 takes minutes)")
    parser.add_argument("--scripted-max", type=int, default=100,
                        help="largest grid on which the scripted baseline runs")
    parser.add_argument("--grids", type=int, nargs="*", default=GRID_SIZES)
    parser.add_argument("--write", help="also write the report to this Markdown file")
    args = parser.parse_args()
    build_dir = os.path.abspath(args.build_dir)
    data_dir = os.path.join(build_dir, "bench-data")
    os.makedirs(data_dir, exist_ok=True)

    cases = [("motor (bundled)", os.path.join(REPO, "Resources", "samples", "motor.step"))]
    r08 = os.path.join(SHARED, "R08_presse_asm.step")
    if os.path.isfile(r08):
        cases.append(("R08 press (shared)", r08))
    grid_cases = [(f"bolted grid N={n}", grid_file(data_dir, n)) for n in args.grids]
    cases += grid_cases

    ours = run_ours(build_dir, [path for _, path in cases], args.repeat)
    brute, scripted = {}, {}
    for name, path in cases:
        n = next((g for g in args.grids if path.endswith(f"_{g}.step")), 0)
        if n <= args.brute_max:
            brute[path] = run_brute_force(path)
        if n <= args.scripted_max:
            scripted[path] = run_scripted_baseline(path)

    report = [f"Measured {time.strftime('%Y-%m-%d')} on {os.cpu_count()} cores ({platform.processor() or platform.machine()}), "
              "Release build. Ours: best of "
              f"{args.repeat} runs from shapes in memory (read excluded from total). Baselines, one run each "
              "from shapes in memory: *scripted* is what a FreeCAD user can script today (body box filter, "
              "Boolean common of every same-type face pair whose boxes meet); *checker* is the tests' "
              "brute-force checker (tests/bruteforce_contacts.py), which compares surface parameters before "
              "its Boolean commons and so is a much stricter baseline.", "", "## Contacts", "", contacts_table(cases, ours, brute, scripted), "",
              "## Growth on the bolted grids", "",
              growth_table([(n, ours[path]) for n, (_, path) in zip(args.grids, grid_cases)])]
    exe = os.path.join(build_dir, "bench", "bench_partitions")
    if os.path.isfile(exe):
        out = subprocess.run([exe, "--benchmark_min_time=0.05"], capture_output=True, text=True)
        table = [line for line in out.stdout.splitlines() if line.startswith("|")]
        report += ["", "## Partitions (ours vs ShapeUpgrade_UnifySameDomain)", "", *(table or [out.stdout])]
    text = "\n".join(report)
    print(text)
    if args.write:
        with open(args.write, "w") as stream:
            stream.write("# Benchmarks\n\n`make bench` (bench/run_benchmarks.py) prints these tables.\n\n" + text + "\n")


if __name__ == "__main__":
    main()
