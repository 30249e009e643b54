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

    def ours():
        meshes.mesh_assembly(assembly, deflection=args.deflection)

    t_freecad, t_ours = best_of(freecad), best_of(ours)
    triangles = sum(len(s.copy().tessellate(args.deflection)[1]) for s in solids)
    ours_triangles = sum(r.quality.triangles for r in meshes.mesh_assembly(assembly, deflection=args.deflection))
    bench = subprocess.run([os.path.join(args.build_dir, "bench", "bench_collision"), motor, str(args.grid)],
                           check=True, capture_output=True, text=True)
    data = json.loads(bench.stdout)
    c = data["collision"]
    print("| measure | value |\n|---|---|")
    print(f"| motor tessellation, deflection {args.deflection} mm: FreeCAD Shape.tessellate | "
          f"{t_freecad * 1000:.1f} ms ({triangles} triangles) |")
    print(f"| motor tessellation: ours (partitions included), tagged, watertight | {t_ours * 1000:.1f} ms "
          f"({ours_triangles} triangles), ratio {t_ours / t_freecad:.2f} |")
    for kind in ("distance", "intersect", "penetration"):
        k = c[kind]
        print(f"| {kind} query, two {c['triangles']}-triangle spheres near contact | p50 {k['p50_us']:.1f} us, "
              f"p99 {k['p99_us']:.1f} us, max {k['max_us']:.0f} us, {k['per_second']:.0f} queries/s |")
    m, g = data["motor_disassembly"], data["grid_disassembly"]
    print(f"| motor disassembly (contacts, joints, meshes, blocking, sequence) | {m['seconds']:.2f} s, "
          f"{m['steps']} steps, complete: {m['complete']} |")
    print(f"| {g['parts']}-cube grid disassembly | {g['seconds']:.2f} s, {g['steps']} steps, "
          f"complete: {g['complete']} |")


if __name__ == "__main__":
    main()
