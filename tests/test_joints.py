"""Joints and mobility through the Python API and the CLI: canonical cases
built with FreeCAD Part (DOF and axes derived by hand), the bundled motor,
body-order invariance, the liaison graph files, clearances and interferences."""
import json
import os
import random
import subprocess
import sys
from types import SimpleNamespace

import pytest

import FreeCAD
import Part
from contactwb import core, joints

from conftest import REPO

V = FreeCAD.Vector


def joint_between(found, a, b):
    matches = [j for j in found.joints if {j.a, j.b} == {a, b}]
    assert len(matches) == 1, f"no single joint {a} - {b}: {[(j.a, j.b) for j in found.joints]}"
    return matches[0]


def parallel(u, v, tol=1e-6):
    cross = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
    return sum(c * c for c in cross) ** 0.5 < tol


def test_pin_with_shoulder_is_revolute_with_one_sided_axial_stop():
    # Block 40 x 40 x 20 with a bore r 5 at (20, 20); the pin's shoulder (r 8) on
    # the top face. By hand: revolute about x = y = 20, one stop (+z), leaves along +z.
    block = Part.makeBox(40, 40, 20).cut(Part.makeCylinder(5, 40, V(20, 20, -10)))
    pin = Part.makeCylinder(5, 30, V(20, 20, -5)).fuse(Part.makeCylinder(8, 5, V(20, 20, 20)))
    _, found = joints.joints_in_shapes([("Block", block), ("Pin", pin)])
    j = joint_between(found, "Block", "Pin")
    assert (j.type, j.dof, j.one_sided) == ("revolute", 1, 1)
    assert len(j.rotations) == 1 and parallel(j.rotations[0]["direction"], (0, 0, 1))
    px, py, _ = j.rotations[0]["point"]
    assert abs(px - 20) < 1e-6 and abs(py - 20) < 1e-6
    assert len(j.free_directions) == 1 and j.free_directions[0] == pytest.approx([0, 0, 1], abs=1e-9)


def test_ball_in_socket_is_spherical_and_ball_in_bore_sphere_cylinder():
    centre = V(20, 20, 20)
    cup = Part.makeBox(40, 40, 20).cut(Part.makeSphere(10, centre))
    _, found = joints.joints_in_shapes([("Cup", cup), ("Ball", Part.makeSphere(10, centre))])
    j = joint_between(found, "Cup", "Ball")
    assert (j.type, j.dof) == ("spherical", 3)
    for r in j.rotations:
        assert r["point"] == pytest.approx([20, 20, 20], abs=1e-6)
    # A ball r 5 in a vertical bore r 5: rotations about its centre, slides along z.
    block = Part.makeBox(40, 40, 20).cut(Part.makeCylinder(5, 40, V(20, 20, -10)))
    _, found = joints.joints_in_shapes([("Block", block), ("Ball", Part.makeSphere(5, V(20, 20, 10)))])
    j = joint_between(found, "Block", "Ball")
    assert (j.type, j.dof) == ("sphere_cylinder", 4)
    assert len(j.translations) == 1 and parallel(j.translations[0]["direction"], (0, 0, 1))


# The motor with the Body grounded, derived by hand: the screws turn in the
# front cover (revolute: bore + head) and pass through body and back cover, so
# body, covers and screws are rigid (two parallel screw axes lock each plane
# fit); stator and back bearing turn in their seats (revolute, balanced
# about the axis): passive spins, in the ground's group. The shaft is
# cylindrical everywhere (2 DOF); rotor-front, rotor-back and the front
# bearing turn and slide together (cylindrical, 2); each magnet is planar on
# the rotor-back (3 each); the seal slides in the front cover (1). Passive
# spins: 4 screws, stator, back bearing, rotor-front, front bearing, seal = 9.
# DOF = 2 + 2 + 4 * 3 + 1 + 9 = 26.
MOTOR_GROUND_GROUP = {"Body", "Front-cover", "Back-cover", "Screw-1", "Screw-2", "Screw-3", "Screw-4",
                      "Stator", "Bearing-back"}


def test_motor_joints_groups_and_mobility(sample):
    _, found = joints.joints_in_step(sample("motor.step"))
    m = found.mobility
    assert m.ground == "Body"  # the largest by volume
    assert (m.dof, m.passive) == (26, 9)
    assert set(m.groups[0]) == MOTOR_GROUND_GROUP
    assert sorted(map(sorted, m.groups[1:])) == sorted([
        ["Axis"], ["Bearing-front", "Rotor-back", "Rotor-front"], ["Magnet-1"], ["Magnet-2"], ["Magnet-3"],
        ["Magnet-4"], ["Seal"]])
    motions = {tuple(sorted(g["bodies"])): g for g in m.group_joints}
    assert motions[("Axis",)]["type"] == "cylindrical"
    assert motions[("Bearing-front", "Rotor-back", "Rotor-front")]["type"] == "cylindrical"
    assert motions[("Seal",)]["type"] == "prismatic"
    spinning = {s["body"] for g in m.group_joints for s in g["passive_spins"]}
    assert spinning == {"Screw-1", "Screw-2", "Screw-3", "Screw-4", "Stator", "Bearing-back", "Rotor-front",
                        "Bearing-front", "Seal"}
    for k in range(1, 5):
        j = joint_between(found, f"Screw-{k}", "Front-cover")
        assert (j.type, j.dof) == ("revolute", 1)
        assert parallel(j.rotations[0]["direction"], (0, 0, 1))
        # b relative to a: the screw leaves the cover towards its head (+z).
        sign = 1 if j.b == f"Screw-{k}" else -1
        assert len(j.free_directions) == 1
        assert [sign * x for x in j.free_directions[0]] == pytest.approx([0, 0, 1], abs=1e-9)
        assert joint_between(found, f"Magnet-{k}", "Rotor-back").type == "planar"
    for part in ("Rotor-front", "Rotor-back", "Bearing-front", "Bearing-back", "Seal"):
        assert joint_between(found, "Axis", part).type == "cylindrical"
    # Ways out with every neighbour held: a screw up its axis only (head first),
    # the stator off the body's shoulder towards the front (+z) only (nothing
    # else touches it), the rotor-front none (planes on both sides, the shaft across).
    assert found.free_directions_of("Screw-3") == [pytest.approx([0, 0, 1], abs=1e-9)]
    assert found.free_directions_of("Stator") == [pytest.approx([0, 0, 1], abs=1e-9)]
    assert found.free_directions_of("Rotor-front") == []


def test_motor_document_gives_the_same_mobility(sample):
    done = run_cli(sample("motor.FCStd"), "--joints", "--json")
    assert done.returncode == 0, done.stderr
    mobility = json.loads(done.stdout)["mobility"]
    assert (mobility["ground"], mobility["dof"], mobility["passive"]) == ("Body", 26, 9)
    assert set(mobility["groups"][0]) == MOTOR_GROUND_GROUP


def test_motor_answers_do_not_depend_on_body_order(sample):
    assembly = core.contactcore.read_step(sample("motor.step"))
    shapes = []
    for body in assembly.bodies:
        shape = Part.Shape()
        shape.importBrepFromString(body.brep)
        shapes.append((body.name, shape))
    _, reference = joints.joints_in_shapes(shapes, ground="Body")
    random.Random(7).shuffle(shapes)
    _, shuffled = joints.joints_in_shapes(shapes, ground="Body")
    types = lambda found: {(frozenset((j.a, j.b)), j.type, j.dof) for j in found.joints}
    assert types(shuffled) == types(reference)
    groups = lambda found: {frozenset(g) for g in found.mobility.groups}
    assert groups(shuffled) == groups(reference)
    assert (shuffled.mobility.dof, shuffled.mobility.passive) == (reference.mobility.dof, reference.mobility.passive)


def run_cli(*args):
    return subprocess.run([sys.executable, "-m", "contactwb.cli", *args], cwd=REPO, capture_output=True, text=True,
                          env=dict(os.environ, PYTHONPATH=REPO))


def test_cli_joints_json_fields(sample):
    done = run_cli(sample("motor.step"), "--joints", "--json")
    assert done.returncode == 0, done.stderr
    document = json.loads(done.stdout)
    assert len(document["joints"]) == 29  # one per body pair in contact
    for j in document["joints"]:
        assert set(j) == {"a", "b", "type", "dof", "rotations", "translations", "free_directions", "contacts",
                          "higher_pairs"}
        assert j["higher_pairs"] == []  # the motor has no point or line contact
        assert len(j["rotations"]) + len(j["translations"]) == j["dof"]
        for r in j["rotations"]:
            assert set(r) == {"point", "direction"}
        for index in j["contacts"]:
            contact = document["contacts"][index]
            assert {contact["a"], contact["b"]} == {j["a"], j["b"]}
    assert {"ground", "dof", "groups", "group_joints"} <= set(document["mobility"])
    assert document["mobility"]["ground"] == "Body" and document["mobility"]["dof"] == 26
    assert sum(len(j["contacts"]) for j in document["joints"]) == len(document["contacts"])


def test_cli_table_ground_and_graph_files(sample, tmp_path):
    svg, png, dot = tmp_path / "g.svg", tmp_path / "g.png", tmp_path / "g.dot"
    done = run_cli(sample("motor.step"), "--joints", "--ground", "Front-cover", "--graph", str(svg))
    assert done.returncode == 0, done.stderr
    assert "Mobility (ground Front-cover): 26 DOF, of which 9 passive spins; 8 rigid groups" in done.stdout
    assert "<svg" in svg.read_text()
    assert run_cli(sample("motor.step"), "--graph", str(png)).returncode == 0
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert run_cli(sample("motor.step"), "--graph", str(dot)).returncode == 0
    text = dot.read_text()
    assert text.startswith("graph liaison {") and text.count(" -- ") == 29
    assert '"Front-cover" -- "Screw-1" [label="revolute (1)"' in text
    bad = run_cli(sample("motor.step"), "--joints", "--ground", "Nothing")
    assert bad.returncode == 2 and "no body named 'Nothing'" in bad.stderr  # a usage error


def test_wrench_and_nut_clearance_not_contact(shared_step):
    # R10: the wrench's jaws 0.436 mm from the nut's flats, on both sides.
    done = run_cli(shared_step("R10_wrenchnut.stp"), "--joints", "--json", "--clearance-gap", "0.5")
    assert done.returncode == 0, done.stderr
    document = json.loads(done.stdout)
    assert document["contacts"] == [] and document["joints"] == []
    assert [c["kind"] for c in document["clearances"]] == ["Plane", "Plane"]
    for c in document["clearances"]:
        assert c["gap"] == pytest.approx(0.436, abs=5e-4)
    narrow = json.loads(run_cli(shared_step("R10_wrenchnut.stp"), "--joints", "--json",
                                "--clearance-gap", "0.4").stdout)
    assert narrow["clearances"] == []


def test_interferences_are_printed_when_present():
    raw = SimpleNamespace(interferences=[SimpleNamespace(body_a=0, body_b=2, volume=12.5)])
    listed = joints.interferences_of(raw, ["Column", "Plate", "Base"])
    assert listed == [{"a": "Column", "b": "Base", "volume": 12.5}]
    found = joints.Joints(source="hand-made", joints=[], dot="",
                          mobility=joints.Mobility("Base", 0, 0, [["Base"]], [
                              {"group": 0, "bodies": ["Base"], "type": "rigid", "dof": 0, "rotations": [],
                               "translations": [], "passive_spins": []}]),
                          interferences=listed)
    table = found.table()
    assert "Interferences (overlapping material, not contacts): 1" in table
    assert "Column" in table and "12.5 mm3" in table
    assert joints.interferences_of(SimpleNamespace(), ["A"]) == []


def test_press_interferences_listed_once_beside_the_joints(shared_step):
    path = shared_step("R08_presse_asm.step")
    result, found = joints.joints_in_step(path)
    pairs = sorted((i["a"], i["b"]) for i in found.interferences)
    assert pairs == [("CAPTEUR_FORCE", "SOLID.5"), ("CORPS_AMMOVIBLE", "PRT0001"), ("CORPS_AMMOVIBLE", "SOLID.6")]
    assert len(result.interferences) == 3
    done = run_cli(path, "--joints")
    assert done.returncode == 0, done.stderr
    assert done.stdout.count("Interferences (overlapping material, not contacts): 3") == 1


def test_shaft_in_a_120_degree_cradle_lifts_out_within_30_degrees_of_vertical(sample):
    # The cradle (below) holds the shaft (axis x) over 120 deg centred on -z. By
    # hand: as a joint, cylindrical about the axis; one-sided, its normals at the
    # span's ends are (0, -/+sin 60, cos 60), so the shaft leaves along the axis
    # (both ways) or upwards within 90 - 60 = 30 deg of +z: generators
    # (0, -/+sin 30, cos 30).
    _, found = joints.joints_in_step(sample("cases/cradle_120.step"))
    j = joint_between(found, "Cradle", "Shaft")
    assert (j.type, j.dof, j.one_sided) == ("cylindrical", 2, 2)
    assert parallel(j.rotations[0]["direction"], (1, 0, 0)) and parallel(j.translations[0]["direction"], (1, 0, 0))
    generators = sorted(tuple(round(x, 9) + 0.0 for x in d) for d in j.free_directions)
    assert generators == [(-1.0, 0.0, 0.0), (0.0, -0.5, round(3 ** 0.5 / 2, 9)), (0.0, 0.5, round(3 ** 0.5 / 2, 9)),
                          (1.0, 0.0, 0.0)]
