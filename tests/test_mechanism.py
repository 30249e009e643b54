"""Issue 22 through the Python API and the CLI: prismatic joints keep their
direction, overlapping pairs keep their contacts, point and line contacts
(higher pairs) in the JSON, and the designer's annotations (the motor's
example file: two rigid groups, 1 DOF). Expected values derived by hand in
the comments (the same cases as cpp_module/tests/test_mechanism.cpp)."""
import json
import os
import subprocess
import sys

import pytest

import FreeCAD
import Part
from contactwb import core, joints
from contactwb.core import annotations

from conftest import REPO, SAMPLES

V = FreeCAD.Vector
MOTOR_NOTES = os.path.join(SAMPLES, "motor.annotations.json")


def run_cli(*args):
    return subprocess.run([sys.executable, "-m", "contactwb.cli", *args], cwd=REPO, capture_output=True, text=True,
                          env=dict(os.environ, PYTHONPATH=REPO))


def parallel(u, v, tol=1e-6):
    cross = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
    return sum(c * c for c in cross) ** 0.5 < tol


def test_block_in_an_l_shaped_corner_slides_along_the_corner():
    # Floor z <= 10 and wall x <= 10 (one body), the block on the floor against
    # the wall: prismatic along y, "slides along (0, 1, 0)" in the table.
    corner = Part.makeBox(40, 40, 10).fuse(Part.makeBox(10, 40, 30, V(0, 0, 10)))
    block = Part.makeBox(10, 20, 10, V(10, 10, 10))
    _, found = joints.joints_in_shapes([("Corner", corner), ("Block", block)])
    (j,) = found.joints
    assert (j.type, j.dof) == ("prismatic", 1)
    assert len(j.translations) == 1 and parallel(j.translations[0]["direction"], (0, 1, 0))
    assert len(j.free_directions) == 4
    assert "prismatic (1): slides along (0, 1, 0)" in found.table() or \
        "prismatic (1): slides along (0, -1, 0)" in found.table()


def test_overlapping_tongue_keeps_its_two_plane_contacts_and_reports_the_interference():
    # The tongue 12 x 8 x 2.5 sits 0.02 mm into each long wall of its slot
    # (11.96 x 20): 0.8 mm3 of overlap; the large faces 40 x 30 - 11.96 x 20 -
    # 0.32 = 960.48 mm2 and the tongue's end on the slot floor 11.96 x 8 =
    # 95.68 mm2 (hand-derived, docs/reliability.md).
    lower = Part.makeBox(40, 30, 10).cut(Part.makeBox(11.96, 20, 3.5, V(14.02, 5, 7.5)))
    upper = Part.makeBox(40, 30, 5, V(0, 0, 10)).fuse(Part.makeBox(12, 8, 2.5, V(14, 11, 7.5)))
    result, _ = joints.joints_in_shapes([("Slotted", lower), ("Tongued", upper)])
    document = result.to_json()
    assert sorted(round(c["area"], 6) for c in document["contacts"]) == [95.68, 960.48]
    assert {c["type"] for c in document["contacts"]} == {"PLF"}
    (interference,) = document["interferences"]
    assert set(interference) == {"a", "b", "volume"}
    assert interference["volume"] == pytest.approx(lower.common(upper).Volume, abs=1e-6)
    assert interference["volume"] == pytest.approx(0.8, abs=1e-6)


def test_ball_on_a_plane_is_a_sphere_plane_higher_pair():
    # A ball r 5 on a plate's top: the point (20, 20, 10), normal +z; no
    # surface contact; the joint sphere_plane, 5 DOF, free directions with +z.
    plate, ball = Part.makeBox(40, 40, 10), Part.makeSphere(5, V(20, 20, 15))
    result, found = joints.joints_in_shapes([("Plate", plate), ("Ball", ball)], ground="Plate")
    assert result.contacts == []
    (pair,) = result.to_json()["higher_pairs"]
    assert (pair["type"], pair["kind"], pair["a"], pair["b"]) == ("sphere_on_plane", "point", "Plate", "Ball")
    assert pair["point"] == pytest.approx([20, 20, 10], abs=1e-9)
    assert pair["normal"] == pytest.approx([0, 0, 1], abs=1e-9)
    (j,) = found.joints
    assert (j.type, j.dof, j.contacts, j.higher_pairs) == ("sphere_plane", 5, [], [0])
    assert any(d == pytest.approx([0, 0, 1], abs=1e-9) for d in j.free_directions)
    assert len(j.free_directions) == 5
    assert found.mobility.dof == 5
    assert "sphere_on_plane at (20, 20, 10)" in result.table()


def test_motor_with_its_example_annotations_is_two_groups_and_one_dof(sample):
    # docs/joints.md: 26 DOF (9 passive) without; with the file the axis,
    # rotor halves and magnets turn together about the axis (revolute) and
    # everything else is rigid with the body.
    _, plain = joints.joints_in_step(sample("motor.step"))
    assert (plain.mobility.dof, plain.mobility.passive, len(plain.mobility.groups)) == (26, 9, 8)
    result, found = joints.joints_in_step(sample("motor.step"), annotations=MOTOR_NOTES)
    m = found.mobility
    assert (m.dof, m.passive, len(m.groups)) == (1, 0, 2)
    assert set(m.groups[1]) == {"Axis", "Rotor-front", "Rotor-back", "Magnet-1", "Magnet-2", "Magnet-3", "Magnet-4"}
    assert m.group_joints[1]["type"] == "revolute"
    assert parallel(m.group_joints[1]["rotations"][0]["direction"], (0, 0, 1))
    pressed = [c for c in result.contacts if {c.a, c.b} == {"Axis", "Rotor-front"}]
    assert [(c.intent, c.fit) for c in pressed] == [("interference", "H7/p6")]
    assert len(result.contacts) == 35  # the annotations change no contact


def test_cli_annotations_json_and_errors(sample, tmp_path):
    done = run_cli(sample("motor.step"), "--annotations", MOTOR_NOTES, "--json")
    assert done.returncode == 0, done.stderr
    document = json.loads(done.stdout)
    assert document["mobility"]["dof"] == 1 and len(document["mobility"]["groups"]) == 2
    marked = [c for c in document["contacts"] if "intent" in c]
    assert len(marked) == 17  # one contact per entry of the file
    seal = [c for c in marked if {c["a"], c["b"]} == {"Seal", "Front-cover"}]
    assert [(c["intent"], c["fit"]) for c in seal] == [("interference", "H8/s7")]
    unmarked = [c for c in document["contacts"] if "intent" not in c]
    assert len(unmarked) == 35 - 17
    assert sum(1 for j in document["joints"] if j.get("annotated_rigid")) == 14
    table = run_cli(sample("motor.step"), "--annotations", MOTOR_NOTES)
    assert table.returncode == 0, table.stderr
    assert "Axis           <->  Rotor-front    rigid (0): held by annotated fits or bonds" in table.stdout
    assert "Mobility (ground Body): 1 DOF, of which 0 passive spins; 2 rigid groups" in table.stdout
    # Without the file: today's 26 DOF.
    plain = json.loads(run_cli(sample("motor.step"), "--joints", "--json").stdout)
    assert plain["mobility"]["dof"] == 26

    wrong = tmp_path / "wrong.json"
    wrong.write_text(json.dumps([{"a": "Axis", "b": "Body", "intent": "bonded"}]))
    bad = run_cli(sample("motor.step"), "--annotations", str(wrong))
    assert bad.returncode == 2
    assert "entry 1 ('Axis' - 'Body', bonded) matches no contact" in bad.stderr
    wrong.write_text(json.dumps([{"a": "Axis", "b": "Seal", "intent": "glued"}]))
    bad = run_cli(sample("motor.step"), "--annotations", str(wrong))
    assert bad.returncode == 2 and "entry 1: unknown intent 'glued'" in bad.stderr
    wrong.write_text(json.dumps([{"a": "Axis", "b": "Nobody", "intent": "ignored"}]))
    bad = run_cli(sample("motor.step"), "--annotations", str(wrong))
    assert bad.returncode == 2 and "no body named 'Nobody'" in bad.stderr


def test_annotation_entries_are_checked():
    with pytest.raises(core.ArgumentError, match="not an ISO 286 fit code"):
        annotations.parse([{"a": "A", "b": "B", "intent": "interference", "fit": "p6"}])
    with pytest.raises(core.ArgumentError, match="unknown field"):
        annotations.parse([{"a": "A", "b": "B", "intent": "bonded", "glue": "epoxy"}])
    with pytest.raises(core.ArgumentError, match="a threaded contact has no fit"):
        annotations.parse([{"a": "A", "b": "B", "intent": "threaded", "fit": "H7/g6"}])
    (screw,) = annotations.parse([{"a": "Screw", "b": "Cover", "type": "CLJ", "intent": "threaded"}])
    assert (screw.intent, screw.type) == ("threaded", "CLJ")
    (note,) = annotations.parse([{"a": "A", "b": "B", "intent": "transition", "fit": "H7/k6"}])
    assert (note.a, note.b, note.intent, note.fit, note.type) == ("A", "B", "transition", "H7/k6", None)


def test_committed_line_contact_case_has_its_higher_pairs_and_no_contact(sample):
    # Resources/samples/cases/line_contact (tools/samples_families.py): a roller
    # r 5 along x (axis z = 5, y = -10, x -20..20) and a ball r 5 (centre 0, 15,
    # 5) on a plate's top z = 0. By hand: no surface contact (the expected
    # file's count is unchanged), a line y = -10, z = 0 from x = -20 to 20
    # (40 mm) and a point (0, 15, 0), both normal +z; the roller cylinder_plane
    # (4 DOF), the ball sphere_plane (5): 9 DOF with the plate grounded.
    path = os.path.join(SAMPLES, "cases", "line_contact.step")
    result, found = joints.joints_in_step(path, ground="Plate")
    assert result.contacts == []
    with open(os.path.join(SAMPLES, "cases", "line_contact.expected.json")) as stream:
        assert json.load(stream)["contacts"] == []
    pairs = {h["b"]: h for h in result.to_json()["higher_pairs"]}
    assert set(pairs) == {"Roller", "Ball"}
    line, point = pairs["Roller"], pairs["Ball"]
    assert (line["type"], line["kind"], point["type"], point["kind"]) == (
        "cylinder_on_plane", "line", "sphere_on_plane", "point")
    assert line["length"] == pytest.approx(40, abs=1e-6)
    assert sorted([line["start"][0], line["end"][0]]) == pytest.approx([-20, 20], abs=1e-6)
    assert line["start"][1:] == pytest.approx([-10, 0], abs=1e-6)
    assert point["point"] == pytest.approx([0, 15, 0], abs=1e-9)
    assert line["normal"] == pytest.approx([0, 0, 1], abs=1e-9)
    types = {(j.a, j.b): (j.type, j.dof) for j in found.joints}
    assert types == {("Plate", "Roller"): ("cylinder_plane", 4), ("Plate", "Ball"): ("sphere_plane", 5)}
    assert found.mobility.dof == 9


def test_d03_pin_in_the_arms_slot_is_two_line_contacts(shared_step):
    # D03 (Assembly4's disc and arm): the disc's pin (Body001) runs in the
    # straight slot of the arm (Body002), touching both of the slot's flat
    # walls. By hand: two cylinder_on_plane lines along the pin (15 mm each,
    # z 10..25) with opposite normals across the slot; the surface contacts
    # stay 3 PLF + 1 CLJ (tests/test_contacts.py). With the pin's face on the
    # arm (PLF), the pair turns about the pin and slides along the slot: 2 DOF,
    # the translation across both normals.
    result, found = joints.joints_in_step(shared_step("D03_asm4_tuto2_disk_arm.step"))
    assert len(result.contacts) == 4
    pairs = result.to_json()["higher_pairs"]
    assert [(h["type"], h["a"], h["b"]) for h in pairs] == [("cylinder_on_plane", "Body001", "Body002")] * 2
    for h in pairs:
        assert h["length"] == pytest.approx(15, abs=1e-6)
        assert sorted([h["start"][2], h["end"][2]]) == pytest.approx([10, 25], abs=1e-6)
    n0, n1 = pairs[0]["normal"], pairs[1]["normal"]
    assert sum(a * b for a, b in zip(n0, n1)) == pytest.approx(-1, abs=1e-9)
    (j,) = [j for j in found.joints if (j.a, j.b) == ("Body001", "Body002")]
    assert (j.dof, len(j.rotations), len(j.translations), j.higher_pairs) == (2, 1, 1, [0, 1])
    assert parallel(j.rotations[0]["direction"], (0, 0, 1))
    slide = j.translations[0]["direction"]
    assert abs(sum(a * b for a, b in zip(slide, n0))) < 1e-9 and abs(slide[2]) < 1e-9


def test_ball_in_a_v_groove_is_two_point_contacts_and_four_dof():
    # A 90-degree V-groove along y (walls z = 10 + |x - 20|, cut by a square prism turned 45 degrees)
    # and a ball r 5 resting on both walls: its centre on x = 20 at z = 10 + 5 sqrt 2. By hand: two
    # sphere_on_plane points at (20 -+ 5/sqrt 2, 20, 10 + 5/sqrt 2), each with its wall's normal
    # (+-1, 0, 1)/sqrt 2; no surface contact. Two one-sided points take 2 of 6 DOF: the ball rolls
    # (3 turns) and runs along the groove (y): 4 DOF; it leaves along +-y or up either wall's normal
    # (the lift-out +z is in that cone).
    import math
    s = math.sqrt(2)
    prism = Part.makeBox(10 * s, 40, 10 * s, V(-5 * s, 0, -5 * s))
    prism.rotate(V(0, 0, 0), V(0, 1, 0), 45)
    prism.translate(V(20, 0, 20))
    block = Part.makeBox(40, 40, 20).cut(prism)
    ball = Part.makeSphere(5, V(20, 20, 10 + 5 * s))
    result, found = joints.joints_in_shapes([("Block", block), ("Ball", ball)], ground="Block")
    assert result.contacts == []
    pairs = sorted(result.to_json()["higher_pairs"], key=lambda h: h["point"][0])
    assert [(h["type"], h["a"], h["b"]) for h in pairs] == [("sphere_on_plane", "Block", "Ball")] * 2
    assert pairs[0]["point"] == pytest.approx([20 - 5 / s, 20, 10 + 5 / s], abs=1e-9)
    assert pairs[1]["point"] == pytest.approx([20 + 5 / s, 20, 10 + 5 / s], abs=1e-9)
    assert pairs[0]["normal"] == pytest.approx([1 / s, 0, 1 / s], abs=1e-9)
    assert pairs[1]["normal"] == pytest.approx([-1 / s, 0, 1 / s], abs=1e-9)
    (j,) = found.joints
    assert (j.dof, len(j.rotations), len(j.translations), j.higher_pairs) == (4, 3, 1, [0, 1])
    assert parallel(j.translations[0]["direction"], (0, 1, 0))
    expected = [(0, 1, 0), (0, -1, 0), (1 / s, 0, 1 / s), (-1 / s, 0, 1 / s)]
    assert sorted(tuple(round(v, 9) + 0.0 for v in d) for d in j.free_directions) == \
        sorted(tuple(round(v, 9) + 0.0 for v in d) for d in expected)
    assert found.mobility.dof == 4


def cone_and_ring_on_a_block():
    """A block 80 x 40 x 20 with a bore r 5 through it at (20, 20); a pointed
    cone (apex (20, 20, 15), axis +z, half angle 45 deg, r 10 at z 25)
    seated on the bore's sharp rim; an O-ring (torus R 10, r 2, axis z)
    lying flat on the block's top at (60, 20)."""
    block = Part.makeBox(80, 40, 20).cut(Part.makeCylinder(5, 40, V(20, 20, -10)))
    cone = Part.makeCone(0, 10, 10, V(20, 20, 15), V(0, 0, 1))
    ring = Part.makeTorus(10, 2, V(60, 20, 22), V(0, 0, 1))
    return [("Block", block), ("Cone", cone), ("Ring", ring)]


def test_cone_on_a_rim_and_a_flat_ring_are_circle_contacts_in_the_cli_json(tmp_path):
    # By hand (cpp_module/tests/test_mechanism.cpp has the same cases): the cone's radius at the
    # bore's mouth (z = 20) is 5 tan 45 = 5: cone_on_cylinder along the circle r 5 about
    # (20, 20, 20), the block's normal (-radial + z)/sqrt 2; the joint revolute about the bore's
    # axis, 1 DOF, free within 45 deg of +z. The ring's tube centres at z = 22 are its minor radius
    # above the top: torus_on_plane along the circle r 10 about (60, 20, 20), normal +z; the joint
    # planar, 3 DOF, free along the plane and up. The block grounded: 1 + 3 = 4 DOF. No surface
    # contact; the JSON keeps the point/line fields and adds "axis" and "radius" for a circle.
    import math
    named = cone_and_ring_on_a_block()
    path = str(tmp_path / "cone_ring.step")
    Part.makeCompound([s for _, s in named]).exportStep(path)
    done = run_cli(path, "--joints", "--json")
    assert done.returncode == 0, done.stderr
    document = json.loads(done.stdout)
    assert document["contacts"] == []
    pairs = {h["type"]: h for h in document["higher_pairs"]}
    assert sorted(pairs) == ["cone_on_cylinder", "torus_on_plane"]
    rim, flat = pairs["cone_on_cylinder"], pairs["torus_on_plane"]
    for h in (rim, flat):
        assert h["kind"] == "circle"
        assert set(h) == {"type", "kind", "a", "b", "faces_a", "faces_b", "point", "normal", "start", "end",
                          "length", "axis", "radius"}
        assert parallel(h["axis"], (0, 0, 1))
    assert rim["point"] == pytest.approx([20, 20, 20], abs=1e-9)
    assert rim["radius"] == pytest.approx(5, abs=1e-9)
    assert rim["length"] == pytest.approx(10 * math.pi, abs=1e-9)
    start = rim["start"]
    assert math.dist(start, [20, 20, 20]) == pytest.approx(5, abs=1e-9) and start[2] == pytest.approx(20, abs=1e-9)
    # The block (the file's first solid) is side a: the normal out of its material.
    assert rim["a"] == flat["a"] and rim["b"] != flat["b"]
    inwards = [(20 - start[0]) / 5, (20 - start[1]) / 5, 1]
    assert rim["normal"] == pytest.approx([v / math.sqrt(2) for v in inwards], abs=1e-9)
    assert flat["normal"] == pytest.approx([0, 0, 1], abs=1e-9)
    assert flat["point"] == pytest.approx([60, 20, 20], abs=1e-9)
    assert flat["radius"] == pytest.approx(10, abs=1e-9)
    joints_by_index = {tuple(j["higher_pairs"]): j for j in document["joints"]}
    index = {h["type"]: k for k, h in enumerate(document["higher_pairs"])}
    seated = joints_by_index[(index["cone_on_cylinder"],)]
    lying = joints_by_index[(index["torus_on_plane"],)]
    assert (seated["type"], seated["dof"], lying["type"], lying["dof"]) == ("revolute", 1, "planar", 3)
    assert parallel(seated["rotations"][0]["direction"], (0, 0, 1))
    for d in seated["free_directions"]:
        assert math.degrees(math.acos(abs(d[2]))) == pytest.approx(45, abs=1e-6) and d[2] > 0
    assert any(d == pytest.approx([0, 0, 1], abs=1e-9) for d in lying["free_directions"])
    assert document["mobility"]["dof"] == 4


def test_cone_and_ring_higher_pairs_in_the_table_and_the_disassembly(tmp_path):
    # The table prints each circle; the cone is free only within 45 deg of +z (12 generators
    # exactly on that cone). The disassembly keeps the block as its base and takes the cone and
    # the ring out by directions their joints leave free, never through the block.
    import math
    from contactwb.core import meshes
    from contactwb.document import shapes as document_shapes
    named = cone_and_ring_on_a_block()
    result, found = joints.joints_in_shapes(named, ground="Block")
    table = result.table()
    assert "cone_on_cylinder along a circle r 5 about (20, 20, 20)" in table
    assert "torus_on_plane along a circle r 10 about (60, 20, 20)" in table
    assert found.mobility.dof == 4
    cone_free = found.free_directions_of("Cone")
    assert len(cone_free) == 12
    assert all(math.degrees(math.acos(d[2])) == pytest.approx(45, abs=1e-6) for d in cone_free)
    path = str(tmp_path / "cone_ring.step")
    Part.makeCompound([s for _, s in named]).exportStep(path)
    assembly = meshes.read_step_assembly(path)
    volumes = {b.name: document_shapes.shape_from_brep(b.brep).Volume for b in assembly.bodies}
    by_volume = {name: min(volumes, key=lambda n: abs(volumes[n] - shape.Volume)) for name, shape in named}
    plan = meshes.disassembly_json(assembly, meshes.disassemble(assembly))
    assert plan["complete"] is True
    moved = {tuple(step["parts"]): step["direction"] for step in plan["disassembly"]}
    assert set(moved) == {(by_volume["Cone"],), (by_volume["Ring"],)}
    assert plan["base"] == by_volume["Block"]
    # Each by a direction its joint leaves free: the cone within 45 deg of +z, the ring up or
    # along the plane (it slides off the top), never into the block (OCCT Booleans on the way out).
    cone_way, ring_way = moved[(by_volume["Cone"],)], moved[(by_volume["Ring"],)]
    assert math.degrees(math.acos(cone_way[2] / math.sqrt(sum(v * v for v in cone_way)))) <= 45 + 1e-6
    assert ring_way == pytest.approx([1, 0, 0], abs=1e-9)  # slid off along the top, +x
    assert cone_way == pytest.approx([0, 0, 1], abs=1e-9)
    from test_disassembly_mechanic import cuts_along_paths
    shapes = [(body.name, document_shapes.shape_from_brep(body.brep)) for body in assembly.bodies]
    assert cuts_along_paths(shapes, plan) == []
