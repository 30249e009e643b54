"""`contacts mesh` and `contacts FILE --disassembly`: the PLY files read back
with a parser of our own (shared vertices, every edge in two triangles, tags
equal to the partitions contactcore gives each face, volume of the closed
mesh against the body's), meshes.json, the removal sequence's JSON."""
import json
import os
from collections import Counter

import pytest

from contactwb import cli, core, meshes
from contactwb.document import shapes as document_shapes

from conftest import SAMPLES

MOTOR = os.path.join(SAMPLES, "motor.step")


def read_ply(path):
    """(vertices, [(i, j, k, face, partition)]) of an ASCII PLY written by write_ply."""
    with open(path) as stream:
        lines = stream.read().splitlines()
    end = lines.index("end_header")
    header = lines[:end]
    vertex_count = int(next(l for l in header if l.startswith("element vertex")).split()[2])
    face_count = int(next(l for l in header if l.startswith("element face")).split()[2])
    assert header[-3:] == ["property list uchar int vertex_indices", "property int face", "property int partition"]
    body = lines[end + 1:]
    vertices = [tuple(map(float, l.split())) for l in body[:vertex_count]]
    triangles = []
    for line in body[vertex_count:vertex_count + face_count]:
        n, i, j, k, face, partition = map(int, line.split())
        assert n == 3
        triangles.append((i, j, k, face, partition))
    assert len(body) == vertex_count + face_count
    return vertices, triangles


def signed_volume(vertices, triangles):
    total = 0.0
    for i, j, k, *_ in triangles:
        (ax, ay, az), (bx, by, bz), (cx, cy, cz) = vertices[i], vertices[j], vertices[k]
        total += (ax * (by * cz - bz * cy) - ay * (bx * cz - bz * cx) + az * (bx * cy - by * cx)) / 6
    return total


def test_mesh_command_writes_watertight_tagged_ply_per_body(tmp_path, capsys):
    out = tmp_path / "motor"
    assert cli.main(["mesh", MOTOR, "--out", str(out), "--deflection", "0.05", "--max-edge", "4"]) == 0
    printed = capsys.readouterr().out
    document = json.loads((out / "meshes.json").read_text())
    assembly = core.contactcore.read_step(MOTOR)
    assert [b["name"] for b in document["bodies"]] == [b.name for b in assembly.bodies]
    assert len(document["bodies"]) == 18
    for entry, body in zip(document["bodies"], assembly.bodies):
        vertices, triangles = read_ply(out / entry["file"])
        assert entry["triangles"] == len(triangles)
        edges = Counter()
        for i, j, k, *_ in triangles:
            for a, b in ((i, j), (j, k), (k, i)):
                edges[(min(a, b), max(a, b))] += 1
        assert set(edges.values()) == {2}, body.name  # watertight, read from the file
        assert entry["watertight"] is True
        # Every triangle carries its face and that face's partition.
        partitions = core.contactcore.partition_brep(body.brep)
        face_partition = {f: p.id for p in partitions.partitions for f in p.faces}
        assert {t[3] for t in triangles} == set(face_partition), body.name  # every face meshed
        assert all(face_partition[face] == partition for *_, face, partition in triangles), body.name
        assert entry["partitions"] == len(partitions.partitions)
        # Closed and outward: the mesh holds the body's volume (chords cut a little off curved faces).
        assert signed_volume(vertices, triangles) == pytest.approx(body.volume, rel=0.01), body.name
        longest = max(
            sum((p - q) ** 2 for p, q in zip(vertices[a], vertices[b])) ** 0.5 for a, b in edges)
        assert longest <= 4.0 + 1e-9
        assert entry["max_edge_length"] == pytest.approx(longest)
        assert 1.0 <= entry["aspect_ratio"]["p50"] <= entry["aspect_ratio"]["p99"] <= entry["aspect_ratio"]["max"]
        assert 0 < entry["min_angle"] <= 60
        assert f"{body.name}: {len(triangles)} triangles, watertight" in printed


def _hole_partitions(body, radius):
    """Ids of the body's concave cylinder partitions of the given radius (its holes)."""
    partitions = core.contactcore.partition_brep(body.brep)
    return {p.id for p in partitions.partitions
            if p.params.kind.name == "Cylinder" and p.side.name == "Concave" and abs(p.params.radius - radius) < 1e-9}


def test_mesh_command_simplifies_the_front_cover_within_its_envelope(tmp_path, capsys):
    # Fig. 4b: the front cover's four small through holes (diameter 2.4) leave its collision model, its
    # four screw holes (diameter 3) stay. The holes go through the 8 mm cover: their filled walls lie at
    # most 4 mm (half the thickness) from its faces: the Hausdorff distance, hand-derived.
    out = tmp_path / "motor"
    assert cli.main(["mesh", MOTOR, "--out", str(out), "--simplify", "2.5", "--envelope", "5"]) == 0
    printed = capsys.readouterr().out
    document = json.loads((out / "meshes.json").read_text())
    assert (document["simplify"], document["envelope"]) == (2.5, 5.0)
    assembly = core.contactcore.read_step(MOTOR)
    (index, cover), = [(i, b) for i, b in enumerate(assembly.bodies) if b.name == "Front-cover"]
    entry = document["bodies"][index]
    small, screw = _hole_partitions(cover, 1.2), _hole_partitions(cover, 1.5)
    assert (len(small), len(screw)) == (4, 4)
    collision = entry["collision"]
    assert collision["simplified"] is True and collision["message"] == ""
    assert collision["hausdorff"] == pytest.approx(4.0, abs=1e-6)
    partitions = core.contactcore.partition_brep(cover.brep)
    small_faces = sorted(f for p in partitions.partitions if p.id in small for f in p.faces)
    assert collision["removed_faces"] == [f"Face{f}" for f in small_faces]
    assert "12 faces of small features removed, Hausdorff 4.000 mm <= 5" in printed
    # Read back: closed, the small holes' partitions gone, the screw holes' kept; the view model has both.
    vertices, triangles = read_ply(out / collision["file"])
    edges = Counter()
    for i, j, k, *_ in triangles:
        for a, b in ((i, j), (j, k), (k, i)):
            edges[(min(a, b), max(a, b))] += 1
    assert set(edges.values()) == {2} and collision["watertight"] is True
    present = {t[4] for t in triangles}
    assert not present & small and screw <= present
    # Every surviving face kept its partition: the tags are the original's (a subset of them).
    assert present <= {p.id for p in partitions.partitions}
    # Filled holes add material: 4 holes of radius 1.2 through 8 mm (chords take a little off).
    hole_volume = 4 * 3.141592653589793 * 1.2 ** 2 * 8
    assert signed_volume(vertices, triangles) == pytest.approx(cover.volume + hole_volume, rel=0.01)
    _, view_triangles = read_ply(out / entry["file"])
    assert small | screw <= {t[4] for t in view_triangles}
    assert 0 < entry["hausdorff"] <= document["deflection"]  # the view model: its chordal deviation
    # Coarser: the collision model has fewer triangles than the view model.
    assert collision["triangles"] < entry["triangles"]


def test_simplification_beyond_the_envelope_keeps_the_original(tmp_path):
    assembly = core.contactcore.read_step(MOTOR)
    index = [b.name for b in assembly.bodies].index("Front-cover")
    (models,) = meshes.simulation_models(assembly, simplify=2.5, envelope=3.0, bodies=[index])
    assert not models.simplified
    assert "4.000000 mm > 3.000000 mm" in models.message
    assert models.removed_faces == []
    cover = assembly.bodies[index]
    assert _hole_partitions(cover, 1.2) <= set(models.collision.mesh.triangle_partition)
    assert models.collision.quality.watertight
    assert 0 < models.collision_hausdorff <= 0.2  # its tessellation's deviation (deflection 2 x 0.1)
    with pytest.raises(core.ContactsError):
        meshes.simulation_models(assembly, simplify=2.5, envelope=0.0, bodies=[index])


def test_mesh_command_refuses_bad_input(tmp_path, capsys):
    assert cli.main(["mesh", str(tmp_path / "missing.step"), "--out", str(tmp_path / "o")]) == cli.EXIT_INPUT
    assert "missing.step" in capsys.readouterr().err
    with pytest.raises(SystemExit):
        cli.main(["mesh", MOTOR, "--out", str(tmp_path / "o"), "--deflection", "0"])
    with pytest.raises(SystemExit):
        cli.main(["mesh", MOTOR, "--out", str(tmp_path / "o"), "--simplify", "2.5"])  # no envelope
    with pytest.raises(SystemExit):
        cli.main(["mesh", MOTOR, "--out", str(tmp_path / "o"), "--envelope", "2"])  # no --simplify


def test_disassembly_json_of_the_taper_pin(capsys):
    # The pin sits in a conical hole narrowing downwards: it can only leave upwards, along its axis;
    # the block stays.
    path = os.path.join(SAMPLES, "cases", "taper_pin.step")
    assert cli.main([path, "--disassembly", "--json"]) == 0
    document = json.loads(capsys.readouterr().out)
    assert document["disassembly"] == [{"parts": ["Taper-pin"], "direction": [0.0, 0.0, 1.0], "blocked_before": [],
                                        "why_free": "nothing blocked it along (0, 0, 1) from the start"}]
    assert document["base"] == "Block" and document["base_parts"] == ["Block"]
    assert document["complete"] is True


def test_disassembly_of_a_ball_bearing_reports_the_interlock(capsys):
    # Balls held between the rings' grooves: nothing can leave without deforming a part.
    path = os.path.join(SAMPLES, "cases", "ball_bearing.step")
    assert cli.main([path, "--disassembly"]) == cli.EXIT_FAILED  # the analysis found no sequence (not a usage error)
    text = capsys.readouterr().out
    assert "Stopped: no part or group of the remaining parts" in text
    assert "Inner-ring" in text and "Outer-ring" in text


def test_collision_query_from_python_matches_hand_values():
    assembly = core.contactcore.read_step(os.path.join(SAMPLES, "cases", "taper_pin.step"))
    results = meshes.mesh_assembly(assembly, deflection=0.05)
    block = core.contactcore.build_collision_model(results[0].mesh)
    pin = core.contactcore.build_collision_model(results[1].mesh)
    pair = core.contactcore.CollisionPair(block, pin)
    identity = ((1, 0, 0, 0, 1, 0, 0, 0, 1), (0, 0, 0))
    # In place the cone faces coincide: the meshes cross. Lifted, the gap is FreeCAD's exact B-rep
    # distance (distToShape), within the two meshes' chordal deviations.
    assert pair.query(None, identity, "intersect").intersecting
    shapes = [document_shapes.shape_from_brep(body.brep) for body in assembly.bodies]
    import FreeCAD
    for lift in (3.0, 40.0, 500.0):
        moved = shapes[1].copy()
        moved.translate(FreeCAD.Vector(0, 0, lift))
        exact = shapes[0].distToShape(moved)[0]
        result = pair.query(None, ((1, 0, 0, 0, 1, 0, 0, 0, 1), (0, 0, lift)), "distance")
        assert not result.intersecting
        assert result.distance == pytest.approx(exact, abs=0.1)
        gap = sum((a - b) ** 2 for a, b in zip(result.point_a, result.point_b)) ** 0.5
        assert gap == pytest.approx(result.distance, abs=1e-9)
    with pytest.raises(ValueError):
        pair.query(None, None, "sideways")
    # Warm start (the default) and cold give the same answers along a lift; the counts say work was done.
    cold = core.contactcore.CollisionPair(block, pin)
    cold.set_warm_start(False)
    for step in range(20):
        place = ((1, 0, 0, 0, 1, 0, 0, 0, 1), (0.01 * step, 0, 3.0 - 0.1 * step))
        warm_result, cold_result = pair.query(None, place, "distance"), cold.query(None, place, "distance")
        assert warm_result.distance == pytest.approx(cold_result.distance, abs=1e-12)
        assert warm_result.intersecting == cold_result.intersecting
    assert all(count > 0 for count in pair.counts())


def test_collision_margin_from_python():
    # Issue 25 item 7: a security margin on the pair. The taper pin lifted 1 mm out of its seat: the
    # plain query says apart at the meshes' distance d (within both deflections of FreeCAD's exact
    # distance); with a margin just above d the pair is intersecting (intersect and penetration), with
    # one just below it is not. Lifted 3 mm, apart with a margin of 0.1. Bad margins are ArgumentError.
    assembly = core.contactcore.read_step(os.path.join(SAMPLES, "cases", "taper_pin.step"))
    results = meshes.mesh_assembly(assembly, deflection=0.05)
    block = core.contactcore.build_collision_model(results[0].mesh)
    pin = core.contactcore.build_collision_model(results[1].mesh)
    plain = core.contactcore.CollisionPair(block, pin)
    assert plain.margin is None
    shapes = [document_shapes.shape_from_brep(body.brep) for body in assembly.bodies]
    import FreeCAD
    lift = ((1, 0, 0, 0, 1, 0, 0, 0, 1), (0, 0, 1.0))
    moved = shapes[1].copy()
    moved.translate(FreeCAD.Vector(0, 0, 1.0))
    exact = shapes[0].distToShape(moved)[0]
    d = plain.query(None, lift, "distance").distance
    assert not plain.query(None, lift, "intersect").intersecting
    assert d > 0 and d == pytest.approx(exact, abs=0.1)
    above = core.contactcore.CollisionPair(block, pin, margin=d * 1.01)
    assert above.margin == pytest.approx(d * 1.01)
    assert above.query(None, lift, "intersect").intersecting
    assert above.query(None, lift, "penetration").intersecting
    below = core.contactcore.CollisionPair(block, pin, margin=d * 0.99)
    assert not below.query(None, lift, "intersect").intersecting
    assert not below.query(None, lift, "penetration").intersecting
    far = ((1, 0, 0, 0, 1, 0, 0, 0, 1), (0, 0, 3.0))
    above.set_margin(0.1)
    assert plain.query(None, far, "distance").distance > 0.1
    assert not above.query(None, far, "intersect").intersecting
    above.clear_margin()
    assert above.margin is None
    for bad in (-1.0, float("nan"), float("inf")):
        with pytest.raises(core.ArgumentError):
            plain.set_margin(bad)
        with pytest.raises(core.ArgumentError):
            core.contactcore.CollisionPair(block, pin, margin=bad)
