"""Meshes tagged by partition, collision queries and the removal sequence,
headless and without FreeCAD (the paper's mixed representation, stage 5).
FreeCAD documents as input: contactwb.document.files.load_assembly.

    from contactwb.core import meshes
    assembly = meshes.read_step_assembly("Resources/samples/motor.step")
    for body, result in zip(assembly.bodies, meshes.mesh_assembly(assembly, deflection=0.1)):
        print(body.name, result.quality.watertight)
    print(meshes.disassembly_json(assembly))
"""
import json
import math
import os

from contactwb import core
from contactwb.core import output_files

DEFAULT_MAX_TRIANGLES = 10_000_000  # refused before meshing beyond this estimate (MeshOptions.max_triangles)


def read_step_assembly(path, max_bodies=None):
    """The bodies of a STEP file, read in C++. An assembly expanding to more than `max_bodies`
    instances (default one million) is refused before it is expanded."""
    if not os.path.isfile(path):
        raise core.InputError(f"no such file: '{path}'")
    limit = {} if max_bodies is None else {"max_bodies": int(max_bodies)}
    return core.contactcore.read_step(os.fsencode(os.path.abspath(path)), **limit)  # bytes: non-UTF-8 names work


def mesh_assembly(assembly, deflection=0.1, angle=0.5, max_edge=0.0, linear=None, angular=None,
                  max_triangles=None):
    """One contactcore.MeshResult (mesh, quality, failed_faces, invalid_reason) per body, in order.
    Refused (InputError) before meshing when the sizes asked need more than `max_triangles`
    (estimated; default DEFAULT_MAX_TRIANGLES)."""
    options = core.contactcore.MeshOptions(deflection, angle, max_edge, _max_triangles(max_triangles))
    return core.contactcore.mesh_assembly(assembly, options, linear, angular)


def _max_triangles(value):
    return float(DEFAULT_MAX_TRIANGLES if value is None else value)


def _finite(value):
    """A number for meshes.json: JSON has no NaN or infinity (null instead)."""
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


def quality_report(quality, mesh):
    """Triangles, closure and shape of one model's mesh (meshes.json)."""
    return {
        "triangles": quality.triangles,
        "watertight": quality.watertight,
        "min_angle": _finite(quality.min_angle_deg),
        "aspect_ratio": {"p50": _finite(quality.aspect_p50), "p90": _finite(quality.aspect_p90),
                         "p99": _finite(quality.aspect_p99), "max": _finite(quality.aspect_max)},
        "max_edge_length": _finite(quality.max_edge_length),
        "partitions": mesh.partition_count,
    }


def body_report(name, result):
    """The per-body entry of meshes.json; "invalid" ({"reason", "faces"}) when the body is not a
    valid solid (meshed all the same), "failed_faces" ([{"face", "message"}]) for faces OCCT could
    not tessellate (left out: the mesh is then not watertight)."""
    entry = {"name": name, **quality_report(result.quality, result.mesh)}
    if getattr(result, "invalid_reason", ""):
        entry["invalid"] = {"reason": result.invalid_reason, "faces": list(result.invalid_faces)}
    failed = getattr(result, "failed_faces", [])
    if failed:
        entry["failed_faces"] = [{"face": face, "message": message} for face, message in failed]
    return entry


def collision_options(deflection, angle):
    """The collision model's tessellation: twice as coarse as the view model's, no edge bound
    (a BVH does not need well-shaped triangles)."""
    return core.contactcore.MeshOptions(2 * deflection, min(2 * angle, 1.0), 0.0)


def simulation_models(assembly, deflection=0.1, angle=0.5, max_edge=0.0, simplify=0.0, envelope=0.0,
                      linear=None, angular=None, bodies=None, max_triangles=None):
    """contactcore.SimulationModels of the bodies (all, or the given numbers): the view model (the
    original B-rep with the user's tessellation) and the collision model (without the features
    below `simplify` mm unless that leaves the `envelope`, tessellated coarser)."""
    view = core.contactcore.MeshOptions(deflection, angle, max_edge, _max_triangles(max_triangles))
    return core.contactcore.simulation_models(assembly, view, collision_options(deflection, angle), simplify,
                                              envelope, linear, angular, bodies)


def ply_name(name):
    """A file name for a body: path separators and odd characters replaced."""
    safe = "".join(c if c.isalnum() or c in "-_." else "_" for c in name)
    return (safe or "body") + ".ply"


def _unique_file(name, used, suffix=".ply"):
    file_name = ply_name(name)[:-4] + suffix
    stem, number = file_name[:-len(suffix)], 2
    while file_name in used:
        file_name = f"{stem}.{number}{suffix}"
        number += 1
    used.add(file_name)
    return file_name


def _stale_outputs(out_dir):
    """The PLY files an earlier run listed in out_dir/meshes.json (plain names
    inside out_dir only)."""
    try:
        with open(os.path.join(out_dir, "meshes.json"), encoding="utf-8") as stream:
            earlier = json.load(stream)
    except (OSError, ValueError):
        return set()
    names = set()
    for body in earlier.get("bodies", []) if isinstance(earlier, dict) else []:
        for entry in (body, body.get("collision") or {}) if isinstance(body, dict) else ():
            name = entry.get("file") if isinstance(entry, dict) else None
            if isinstance(name, str) and name.endswith(".ply") and name == os.path.basename(name) \
                    and name not in (".", ".."):
                names.add(name)
    return names


def _write_ply(mesh, out_dir, file_name):
    with output_files.replaced(os.path.join(out_dir, file_name)) as temporary:
        mesh.write_ply(temporary)


def write_meshes(assembly, out_dir, deflection=0.1, angle=0.5, max_edge=0.0, linear=None, angular=None,
                 simplify=0.0, envelope=0.0, max_triangles=None):
    """One PLY per body and out_dir/meshes.json; returns the JSON document. With `simplify` (mm),
    also each body's collision model (NAME.collision.ply, the "collision" entry), without the
    features below that size unless that leaves the `envelope` (mm): then from the original B-rep,
    with a "message" saying so. Each model's "hausdorff" is its distance to the original B-rep
    (two-sided for a simplified model; for a plain tessellation its farthest point).

    Every file is written to a temporary name and renamed into place (output_files): never
    through a symbolic link already there, never outside out_dir; meshes.json comes last, and the
    PLY files an earlier run listed there that this run does not write again are removed."""
    os.makedirs(out_dir, exist_ok=True)
    bodies = []
    used = set()
    if simplify > 0:
        results = simulation_models(assembly, deflection, angle, max_edge, simplify, envelope, linear, angular,
                                    max_triangles=max_triangles)
        views = [r.view for r in results]
        # Invalid solids and faces left out are checked by mesh_assembly's pass only.
    else:
        results = None
        views = mesh_assembly(assembly, deflection, angle, max_edge, linear, angular, max_triangles)
    stale = _stale_outputs(out_dir)
    for index, (body, view) in enumerate(zip(assembly.bodies, views)):
        file_name = _unique_file(body.name, used)
        _write_ply(view.mesh, out_dir, file_name)
        entry = body_report(body.name, view)
        entry["file"] = file_name
        if results is not None:
            models = results[index]
            entry["hausdorff"] = _finite(models.view_deviation)
            collision_file = _unique_file(body.name, used, ".collision.ply")
            _write_ply(models.collision.mesh, out_dir, collision_file)
            entry["collision"] = {
                **quality_report(models.collision.quality, models.collision.mesh),
                "file": collision_file,
                "simplified": models.simplified,
                "hausdorff": _finite(models.collision_hausdorff),
                "removed_faces": [f"Face{f}" for f in models.removed_faces],
                "features_kept": models.features_kept,
                "message": models.message,
            }
        bodies.append(entry)
    document = {"deflection": deflection, "angle": angle, "max_edge": max_edge, "bodies": bodies}
    if simplify > 0:
        options = collision_options(deflection, angle)
        document.update({"simplify": simplify, "envelope": envelope,
                         "collision_deflection": options.deflection, "collision_angle": options.angle})
    with output_files.output_file(os.path.join(out_dir, "meshes.json"), encoding="utf-8") as stream:
        json.dump(document, stream, indent=2, allow_nan=False)
    for name in stale - used:
        try:
            os.unlink(os.path.join(out_dir, name))
        except FileNotFoundError:
            pass
    return document


def disassemble(assembly, deflection=0.1, angle=0.5, tolerance=0.0, linear=None, angular=None, max_triangles=None,
                annotations=None, sample_free_cones=True):
    """contactcore.DisassemblyResult: the removal sequence, blocking graphs, or the reason none exists.
    `tolerance` (mm; 0: twice the deflection): how deep a swept part must cut into another to be
    blocked (two tessellations of one surface cross by up to their deflection); refused
    (ArgumentError) unless below half the thinnest part's thickness. `annotations` (a JSON file's
    path, a list of dicts or of contactwb.core.annotations.Annotation): parts joined by fits and
    bonds (and threads) come out as one sub-assembly; a threaded cylindrical contact (a screw in
    its thread) is released (unscrewed) when nothing else can leave, a bonded one never. The result keeps the contacts used as `.contacts`
    (a DisassemblyResult attribute set here)."""
    options = core.contactcore.MeshOptions(deflection, angle, 0.0, _max_triangles(max_triangles))
    notes = _annotations(annotations)
    raw = core.contactcore.find_contacts(assembly, linear=linear, angular=angular)
    intents = []
    if notes is not None:
        from contactwb.core import annotations as annotation_api
        marks, _ = annotation_api.resolve(notes, [b.name for b in assembly.bodies], raw.contacts, raw.higher_pairs)
        intents = [mark[0] for mark in marks]
    result = core.contactcore.disassemble(assembly, options, tolerance, linear, angular, contacts=raw,
                                          contact_intents=intents, sample_free_cones=sample_free_cones)
    return _WithContacts(result, raw, intents)


class _WithContacts:
    """A DisassemblyResult with the contacts and intents it was planned with."""

    def __init__(self, result, contacts, intents):
        self._result, self.contacts, self.intents = result, contacts, intents

    def __getattr__(self, name):
        return getattr(self._result, name)


def _annotations(annotations):
    if annotations is None:
        return None
    from contactwb.core import annotations as annotation_api
    if isinstance(annotations, (str, os.PathLike)):
        return annotation_api.load(annotations)
    if annotations and isinstance(annotations[0], dict):
        return annotation_api.parse(annotations)
    return list(annotations)


def _vector(values):
    return [round(v, 12) + 0.0 for v in values]


def disassembly_json(assembly, result=None):
    """{"disassembly": [{"parts": [names], "direction": [x, y, z], "blocked_before": [{"part",
    "removed_in_step"}], "why_free": text, "released": [{"a", "b", "type", "intent"}] (when a bond
    was undone)}, ...], "base", "base_parts", "complete", "reason"}."""
    result = disassemble(assembly) if result is None else result
    names = [body.name for body in assembly.bodies]
    removed_in = {}
    steps = []
    contacts = getattr(result, "contacts", None)
    for number, step in enumerate(result.steps, 1):
        direction = _vector(step.direction)
        blocked = [{"part": names[j], "removed_in_step": removed_in.get(j)} for j in step.blocked_before]
        entry = {"parts": [names[i] for i in step.parts], "direction": direction, "blocked_before": blocked}
        released = []
        for k in step.released:
            c = contacts.contacts[k] if contacts is not None else None
            if c is not None:
                released.append({"a": names[c.body_a], "b": names[c.body_b], "type": c.type_name,
                                 "intent": result.intents[k] if result.intents else "threaded"})
        if released:
            entry["released"] = released
        entry["why_free"] = _why_free(entry, direction)
        steps.append(entry)
        for i in step.parts:
            removed_in[i] = number
    return {
        "disassembly": steps,
        "base": names[result.base] if result.base >= 0 else None,
        "base_parts": [names[i] for i in result.base_parts],
        "complete": result.complete,
        "reason": result.reason,
        **({"messages": list(result.messages)} if getattr(result, "messages", None) else {}),
    }


def _why_free(entry, direction):
    """Why a step's parts can leave now: what blocked them along their way out was removed (which
    steps), a bond was undone, or nothing ever blocked them."""
    way = "(" + ", ".join(f"{v:g}" for v in direction) + ")"
    reasons = []
    for bond in entry.get("released", []):
        other = bond["b"] if bond["a"] in entry["parts"] else bond["a"]
        reasons.append(f"its {bond['intent']} {bond['type']} with {other} undone (unscrewed)")
    if entry["blocked_before"]:
        by_step = ", ".join(f"{b['part']} (step {b['removed_in_step']})" for b in entry["blocked_before"])
        reasons.append(f"what blocked it along {way} was removed: {by_step}")
    else:
        reasons.append(f"nothing blocked it along {way} from the start")
    return "; ".join(reasons)


def disassembly_table(document):
    """The removal sequence as text, one step a line."""
    lines = ["Disassembly sequence:"]
    for number, step in enumerate(document["disassembly"], 1):
        x, y, z = step["direction"]
        lines.append(f"{number:3d}. {', '.join(step['parts'])} along ({x:g}, {y:g}, {z:g})")
        if "why_free" in step:
            lines.append(f"       free: {step['why_free']}")
    if document["complete"]:
        base = document.get("base_parts") or [document["base"]]
        lines.append(f"     {', '.join(base)} {'stays' if len(base) == 1 else 'stay'} (the base)")
    else:
        lines.append(f"Stopped: {document['reason']}")
    for message in document.get("messages", []):
        lines.append(f"  note: {message}")
    return "\n".join(lines)
