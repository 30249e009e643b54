#!/usr/bin/python3
"""The cost of the Python bindings' conversions beside the core's work (docs/benchmarks.md, "Idle,
and end to end"): the motor read, its contacts, its meshes' vertex and triangle lists, and a trial's
path as dicts, each the best of 3 in process CPU time. Run it once per extension to compare two
builds (the bindings at -O0 and at -O1):

    CONTACTS_PYTHON_DIR=build/python PYTHONPATH=. /usr/bin/python3 bench/bind_speed.py
"""
import json
import os
import time

from contactwb.core import analysis, meshes, trial

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MOTOR = os.path.join(REPO, "Resources", "samples", "motor.step")
SCRIPT = os.path.join(REPO, "Resources", "trials", "motor_axis_insertion.json")


def best_cpu_seconds(work, repeats=3):
    times = []
    for _ in range(repeats):
        start = time.process_time()
        work()
        times.append(time.process_time() - start)
    return min(times)


def main():
    assembly = meshes.read_step_assembly(MOTOR)
    results = meshes.mesh_assembly(assembly, deflection=0.01)

    def mesh_lists():
        for result in results:
            mesh = result.mesh
            mesh.vertices, mesh.triangles

    trial_result = trial.run(trial.make_scene(assembly, "Axis"), trial.read_script(SCRIPT))
    figures = {
        "read_step": best_cpu_seconds(lambda: meshes.read_step_assembly(MOTOR)),
        "find_contacts": best_cpu_seconds(lambda: analysis.find_contacts_in_step(MOTOR)),
        "mesh_lists(defl 0.01)": best_cpu_seconds(mesh_lists),
        "path_to_dicts": best_cpu_seconds(lambda: [sample.to_dict() for sample in trial_result.path]),
    }
    vertices = sum(len(result.mesh.vertices) for result in results)
    print(json.dumps({name: round(seconds * 1000, 1) for name, seconds in figures.items()}),
          "ms; vertices", vertices, "samples", len(trial_result.path))


if __name__ == "__main__":
    main()
