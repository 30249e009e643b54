#!/usr/bin/python3
"""Tessellation of the motor: ours (contactcore.mesh_assembly: BRepMesh, then
vertices shared by topology, tags, quality) against FreeCAD's Shape.tessellate
at the same deflection, best of 5 on fresh copies; then bench_collision's
query latencies and disassembly times. Prints a Markdown table."""
import argparse
import json
import os
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from markdown_sections import write_section  # noqa: E402

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, REPO)


def best_of(function, repeat=5):
    best = float("inf")
    for _ in range(repeat):
        start = time.perf_counter()
        function()
        best = min(best, time.perf_counter() - start)
    return best


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--build-dir", default=os.path.join(REPO, "build"))
    parser.add_argument("--deflection", type=float, default=0.1)
    parser.add_argument("--grid", type=int, default=10, help="cubes per side of the disassembly grid")
    parser.add_argument("--write", help="also write the table into this Markdown file (its own section)")
    args = parser.parse_args()
    os.environ.setdefault("CONTACTS_PYTHON_DIR", os.path.join(args.build_dir, "python"))
    from contactwb import freecad_setup
    freecad_setup.import_freecad()
    import Part
    from contactwb import core, meshes
    motor = os.path.join(REPO, "Resources", "samples", "motor.step")
    solids = Part.read(motor).Solids
    assembly = core.contactcore.read_step(motor)

    def freecad():
        for solid in solids:
            solid.copy().tessellate(args.deflection)

    # FreeCAD's tessellate(tolerance) meshes with an angular deflection of 0.1 rad: the same here, so
    # both make the same triangles (the counts below are equal).
    def ours():
        meshes.mesh_assembly(assembly, deflection=args.deflection, angle=0.1)

    t_freecad, t_ours = best_of(freecad), best_of(ours)
    triangles = sum(len(s.copy().tessellate(args.deflection)[1]) for s in solids)
    ours_triangles = sum(r.quality.triangles for r in meshes.mesh_assembly(assembly, deflection=args.deflection,
                                                                               angle=0.1))
    bench = subprocess.run([os.path.join(args.build_dir, "bench", "bench_collision"), motor, str(args.grid)],
                           check=True, capture_output=True, text=True)
    data = json.loads(bench.stdout)
    c = data["collision"]
    lines = [f"Measured {time.strftime('%Y-%m-%d %H:%M')} UTC on {os.cpu_count()} cores, Release build, "
             f"load average {os.getloadavg()[0]:.1f} (the machine shared with other builds: wall-clock tails "
             "include waits for a core; the thread CPU time columns do not).", "",
             "| measure | value |", "|---|---|",
             f"| motor tessellation, deflection {args.deflection} mm, angle 0.1 rad: FreeCAD Shape.tessellate (best of 5) | "
             f"{t_freecad * 1000:.1f} ms ({triangles} triangles) |",
             f"| motor tessellation: ours (partitions included), tagged, watertight (best of 5) | "
             f"{t_ours * 1000:.1f} ms ({ours_triangles} triangles), ratio {t_ours / t_freecad:.2f} |"]
    header = ["| query | p50 us | p99 us | max us | queries/s | thread CPU p50 us | thread CPU p99 us "
              "| BV tests mean | BV tests p99 | triangle tests mean |",
              "|---|---|---|---|---|---|---|---|---|---|"]

    def row(label, k):
        return (f"| {label} | {k['p50_us']:.1f} | {k['p99_us']:.1f} | {k['max_us']:.0f} | {k['per_second']:.0f} "
                f"| {k['cpu_p50_us']:.1f} | {k['cpu_p99_us']:.1f} | {k['bv_tests']:.0f} | {k['bv_tests_p99']:.0f} "
                f"| {k['triangle_tests']:.1f} |")

    lines += ["", f"Cold queries (no warm start: each query on its own, as a first contact or a jump) between two "
              f"geodesic spheres of radius 20 mm, {c['triangles']} triangles each "
              f"(watertight: {str(c['watertight']).lower()}), {c['queries']} random placements with the surfaces "
              "between 0.05 mm inside and 0.2 mm apart (one third crossing); the target is p99 under 50 us.", ""]
    lines += header
    for kind, label in (("distance", "distance (all placements)"), ("distance_apart", "distance (apart only)"),
                        ("intersect", "intersect"), ("intersect_apart", "intersect (apart only)"),
                        ("penetration", "penetration")):
        lines.append(row(label, c[kind]))
    t = data["trajectory"]
    lines += ["", f"Haptic-loop trajectory: {t['ticks']} ticks at {t['rate_hz']} Hz, B sliding around A while the gap "
              f"swings between -0.05 and 0.2 mm ({t['crossing_ticks']} ticks crossing), at most {t['max_step_mm']} mm "
              f"and {t['max_turn_rad']} rad per tick; the pair keeps its warm start from tick to tick (the cold rows: "
              "the same path with the warm start off).", ""]
    lines += header
    for kind, label in (("intersect", "intersect, warm with front tracking (what the servo loop asks; motion-bounded pruning)"),
                        ("intersect_no_front", "intersect, warm start without front tracking"),
                        ("intersect_cold", "intersect, cold"),
                        ("distance", "distance, warm with front tracking"),
                        ("distance_no_front", "distance, warm start without front tracking"),
                        ("distance_cold", "distance, cold"),
                        ("penetration", "penetration, warm")):
        lines.append(row(label, t[kind]))
    m, g = data["motor_disassembly"], data["grid_disassembly"]
    lines += ["", "| disassembly (contacts, joints, meshes, blocking, sequence) | time | steps | complete |",
              "|---|---|---|---|",
              f"| motor (18 parts) | {m['seconds']:.2f} s | {m['steps']} | {m['complete']} |",
              f"| {g['parts']}-cube grid | {g['seconds']:.2f} s | {g['steps']} | {g['complete']} |"]
    text = "\n".join(lines)
    print(text)
    if args.write:
        write_section(args.write, "meshes bench", text)


if __name__ == "__main__":
    main()
