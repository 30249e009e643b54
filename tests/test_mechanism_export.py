"""Issue 22, item 5: the derived mechanism exported as URDF and MJCF
(contactwb.core.mechanism and mechanism_export, `contacts FILE --export-urdf DIR --export-mjcf
FILE.xml`). URDF files are checked by `check_urdf` (Debian liburdfdom-tools),
MJCF files loaded and stepped in MuJoCo 2.2 (Debian libmujoco-dev) through
cpp_module/tests/tools/mujoco_step_check.cpp. Where those are missing the
tests skip with a message, except on CI (the CI variable set), where they fail.

Expected values are derived by hand in the comments (a lever on a pin and a
slider in a channel), or from the motor's own solids and MuJoCo's
integrator (semi-implicit Euler: after N steps of h under a constant
acceleration a from rest, q = a h^2 N (N + 1) / 2)."""
import json
import math
import os
import shutil
import struct
import subprocess
import sys

import pytest

import FreeCAD
import Part
from contactwb import joints
from contactwb.core import mechanism_export, meshes

from conftest import REPO, SAMPLES

V = FreeCAD.Vector
MOTOR = os.path.join(SAMPLES, "motor.step")
MOTOR_NOTES = os.path.join(SAMPLES, "motor.annotations.json")
BUILD_DIR = os.environ.get("CONTACTS_BUILD_DIR", os.path.join(REPO, "build"))
ON_CI = bool(os.environ.get("CI"))


def missing(what):
    """Skips (fails on CI, which installs everything) for a missing tool."""
    if ON_CI:
        pytest.fail(f"{what} missing on CI")
    pytest.skip(f"{what} missing (make deps-test installs it)")


def check_urdf_tool():
    tool = shutil.which("check_urdf")
    if not tool:
        missing("check_urdf (Debian liburdfdom-tools)")
    return tool


def mujoco_tool():
    tool = os.path.join(BUILD_DIR, "cpp_module", "mujoco_step_check")
    if not os.path.isfile(tool):
        missing(f"{tool} (built by CMake when Debian's libmujoco-dev is installed)")
    return tool


def run_cli(*args):
    return subprocess.run([sys.executable, "-m", "contactwb.cli", *args], cwd=REPO, capture_output=True, text=True,
                          env=dict(os.environ, PYTHONPATH=REPO))


def step(tool, model, steps, **forces):
    done = subprocess.run([tool, model, str(steps), *(f"{k}={v!r}" for k, v in forces.items())],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout)


def euler_travel(acceleration, timestep, steps):
    return acceleration * timestep ** 2 * steps * (steps + 1) / 2


def quat_about_z(quat):
    """The angle of a unit quaternion (w, x, y, z) that turns about z only."""
    w, x, y, z = quat
    assert abs(x) < 1e-12 and abs(y) < 1e-12
    return 2 * math.atan2(z, w)


def read_stl(path):
    with open(path, "rb") as stream:
        data = stream.read()
    (count,) = struct.unpack_from("<I", data, 80)
    assert len(data) == 84 + 50 * count
    points = [struct.unpack_from("<3f", data, 84 + 50 * t + 12 + 12 * k) for t in range(count) for k in range(3)]
    return count, points


# ---------------------------------------------------------------- the motor with its example annotations

@pytest.fixture(scope="module")
def motor_export(tmp_path_factory):
    out = tmp_path_factory.mktemp("motor_export")
    urdf_dir, mjcf = out / "urdf", out / "mjcf" / "motor.xml"
    mjcf.parent.mkdir()
    done = run_cli(MOTOR, "--annotations", MOTOR_NOTES, "--export-urdf", str(urdf_dir), "--export-mjcf", str(mjcf),
                   "--json")
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout), urdf_dir, mjcf


def test_motor_exports_its_two_rigid_groups_as_two_links_and_a_continuous_joint(motor_export):
    document, urdf_dir, mjcf = motor_export
    export = document["export"]
    groups = document["mobility"]["groups"]
    assert [link["bodies"] for link in export["links"]] == groups  # ground group first
    assert [link["name"] for link in export["links"]] == ["Body", "Axis"]
    assert export["ground"] == "Body"
    (joint,) = export["joints"]
    assert (joint["type"], joint["parent"], joint["child"]) == ("revolute", "Body", "Axis")
    (element,) = joint["elements"]
    assert element["kind"] == "revolute" and abs(element["axis"][2]) == 1.0
    # The rotor's axis is the motor's z axis: the joint's origin on it.
    assert element["origin"][:2] == pytest.approx([0, 0], abs=1e-12)
    assert export["files"] == [str(urdf_dir / "motor.urdf"), str(mjcf)]
    assert export["notes"] == []


def test_motor_links_weigh_the_density_times_the_solids_volumes(motor_export):
    # Independent: FreeCAD's own volumes of the STEP's solids, 7850 kg/m^3.
    document, _, _ = motor_export
    assembly = meshes.read_step_assembly(MOTOR)
    volume = {b.name: b.volume for b in assembly.bodies}
    for link in document["export"]["links"]:
        assert link["mass"] == pytest.approx(7850e-9 * sum(volume[b] for b in link["bodies"]), rel=1e-9)
    assert document["export"]["density"] == 7850


def test_motor_urdf_passes_check_urdf(motor_export):
    tool = check_urdf_tool()
    _, urdf_dir, _ = motor_export
    done = subprocess.run([tool, str(urdf_dir / "motor.urdf")], capture_output=True, text=True)
    assert done.returncode == 0, done.stdout + done.stderr
    assert "Successfully Parsed XML" in done.stdout
    tree = [line.strip() for line in done.stdout.splitlines() if "child(" in line or "root Link" in line]
    assert tree == ["root Link: world has 1 child(ren)", "child(1):  Body", "child(1):  Axis"]


def test_motor_meshes_are_the_contacts_mesh_tessellation_in_metres(motor_export):
    # Same tessellation as `contacts mesh` (its defaults): the same triangles per body; the STL
    # in metres in the link's frame: the Body's box is FreeCAD's bounding box / 1000.
    _, urdf_dir, _ = motor_export
    assembly = meshes.read_step_assembly(MOTOR)
    results = meshes.mesh_assembly(assembly)
    files = sorted(os.listdir(urdf_dir / "meshes"))
    assert files == sorted(f"{b.name}.stl" for b in assembly.bodies)
    for body, result in zip(assembly.bodies, results):
        count, _ = read_stl(urdf_dir / "meshes" / f"{body.name}.stl")
        assert count == result.quality.triangles, body.name
    _, points = read_stl(urdf_dir / "meshes" / "Body.stl")
    shape = Part.Shape()
    shape.importBrepFromString(next(b for b in assembly.bodies if b.name == "Body").brep)
    box = shape.BoundBox
    for axis, (low, high) in enumerate([(box.XMin, box.XMax), (box.YMin, box.YMax), (box.ZMin, box.ZMax)]):
        values = [p[axis] for p in points]
        assert min(values) == pytest.approx(low / 1000, abs=2e-7)
        assert max(values) == pytest.approx(high / 1000, abs=2e-7)


def test_motor_in_mujoco_only_the_rotor_group_turns(motor_export):
    # Gravity on (MuJoCo's -z, the motor's axis), a torque tau on the rotor's hinge for N steps:
    # one joint only (the rotor group's), the body group welded (its pose exactly as before), the
    # rotor's frame still on the axis, turned about z by tau h^2 N (N + 1) / (2 I), I the rotor
    # group's moment about the axis (its inertia about z plus m d^2, d its centre's distance).
    tool = mujoco_tool()
    document, _, mjcf = motor_export
    tau, steps = 1e-5, 500
    result = step(tool, str(mjcf), steps, Body__Axis=tau)
    assert result["gravity"] == pytest.approx([0, 0, -9.81])
    assert (result["nq"], result["njnt"]) == (1, 1)
    before = {b["name"]: b for b in result["before"]["bodies"]}
    after = {b["name"]: b for b in result["after"]["bodies"]}
    assert sorted(after) == ["Axis", "Body", "world"]
    assert after["Body"] == before["Body"]
    assert after["Axis"]["xpos"] == before["Axis"]["xpos"]
    rotor = document["export"]["links"][1]
    d2 = rotor["centre"][0] ** 2 + rotor["centre"][1] ** 2
    moment = rotor["inertia"][2][2] + rotor["mass"] * d2
    expected = euler_travel(tau / moment, result["timestep"], steps)
    (joint,) = result["after"]["joints"]
    assert abs(joint["qpos"][0]) == pytest.approx(expected, rel=1e-6)
    assert abs(quat_about_z(after["Axis"]["xquat"])) == pytest.approx(expected, rel=1e-6)
    assert 0.5 < expected < 3  # a visible turn, less than a half turn (the angle read back is unique)


def test_motor_without_annotations_exports_its_26_dof_as_a_tree(tmp_path):
    # Without the annotations: 26 DOF (docs/joints.md); the export still gives a valid tree
    # (check_urdf), one link per rigid group.
    done = run_cli(MOTOR, "--export-urdf", str(tmp_path), "--json")
    assert done.returncode == 0, done.stderr
    document = json.loads(done.stdout)
    assert document["mobility"]["dof"] == 26
    export = document["export"]
    assert len(export["links"]) == len(document["mobility"]["groups"])
    # Two loops through the axis (rotor group and seal), each named by its closing joint: both
    # cylindrical on the motor's axis, between links hanging from the body on that axis, so the
    # tree already allows them nothing more (no MJCF equality needed).
    closures = [(c["name"], c["type"], c["equality"], c["kept_by_tree"]) for c in export["closures"]]
    assert closures == [("Axis__Rotor-back", "cylindrical", None, True), ("Axis__Seal", "cylindrical", None, True)]
    assert [n.split(" (")[0] for n in export["notes"]] == ["loop closed by joint Axis__Rotor-back",
                                                          "loop closed by joint Axis__Seal"]
    assert "<!-- loop closed by joint Axis__Seal (cylindrical" in (tmp_path / "motor.urdf").read_text()
    tool = check_urdf_tool()
    checked = subprocess.run([tool, str(tmp_path / "motor.urdf")], capture_output=True, text=True)
    assert checked.returncode == 0, checked.stdout + checked.stderr


def test_named_ground_becomes_the_fixed_link(tmp_path):
    done = run_cli(MOTOR, "--annotations", MOTOR_NOTES, "--ground", "Axis", "--export-urdf", str(tmp_path), "--json")
    assert done.returncode == 0, done.stderr
    export = json.loads(done.stdout)["export"]
    assert export["ground"] == "Axis"
    (joint,) = export["joints"]
    assert (joint["parent"], joint["child"], joint["type"]) == ("Axis", "Body", "revolute")
    text = (tmp_path / "motor.urdf").read_text()
    assert '<joint name="world__Axis" type="fixed">' in text


def test_table_output_shows_the_exported_tree(tmp_path):
    done = run_cli(MOTOR, "--annotations", MOTOR_NOTES, "--export-mjcf", str(tmp_path / "m.xml"))
    assert done.returncode == 0, done.stderr
    assert "Mechanism exported (2 links, 1 joints, density 7850 kg/m^3):" in done.stdout
    assert "  Body [fixed to the world]" in done.stdout
    assert "    Axis [revolute: turns about (0, 0, 1)]" in done.stdout or \
        "    Axis [revolute: turns about (0, 0, -1)]" in done.stdout
    assert sorted(os.listdir(tmp_path / "m_meshes"))[:2] == ["Axis.stl", "Back-cover.stl"]


# ---------------------------------------------------------------- a hand-built lever and slider

def lever_and_slider():
    # Base 80 x 40 x 20 with a blind bore r 5 from z 10 to 20 at (20, 10) and a channel 10 wide,
    # 5 deep along x (y 25..35, z 15..20). The lever: a pin r 5, z 10..30 in the bore, under an
    # arm 50 x 10 x 5 (x 15..65, y 5..15, z 30..35): revolute about z through (20, 10). The
    # slider 20 x 10 x 10 at x 50..70 in the channel: prismatic along x.
    base = Part.makeBox(80, 40, 20).cut(Part.makeCylinder(5, 10, V(20, 10, 10))).cut(
        Part.makeBox(80, 10, 5, V(0, 25, 15)))
    lever = Part.makeCylinder(5, 20, V(20, 10, 10)).fuse(Part.makeBox(50, 10, 5, V(15, 5, 30))).removeSplitter()
    slider = Part.makeBox(20, 10, 10, V(50, 25, 15))
    return [("Base", base), ("Lever", lever), ("Slider", slider)]


RHO = 1000.0  # kg/m^3 in these tests: masses in grams per cm^3 of solid


def lever_by_hand():
    """(mass kg, centre m, inertia kg m^2 about the centre) of the lever: a cylinder r 5 h 20 centred
    at (20, 10, 20) and a box 50 x 10 x 5 centred at (40, 10, 32.5), in mm, at RHO."""
    kg = RHO * 1e-9
    pieces = []
    vc = math.pi * 25 * 20
    pieces.append((vc * kg, (20, 10, 20), (vc * (3 * 25 + 400) / 12, vc * (3 * 25 + 400) / 12, vc * 25 / 2)))
    vb = 50 * 10 * 5
    pieces.append((vb * kg, (40, 10, 32.5), (vb * (100 + 25) / 12, vb * (2500 + 25) / 12, vb * (2500 + 100) / 12)))
    mass = sum(m for m, _, _ in pieces)
    centre = [sum(m * c[k] for m, c, _ in pieces) / mass for k in range(3)]
    inertia = [[0.0] * 3 for _ in range(3)]
    for m, c, own in pieces:
        d = [c[k] - centre[k] for k in range(3)]
        for i in range(3):
            for j in range(3):
                inertia[i][j] += (own[i] * kg if i == j else 0.0) + m * ((sum(x * x for x in d) if i == j else 0.0)
                                                                         - d[i] * d[j])
    # mm -> m: centre / 1000, inertia (kg mm^2) / 1e6
    return mass, [c / 1000 for c in centre], [[v / 1e6 for v in row] for row in inertia]


@pytest.fixture(scope="module")
def hand_export(tmp_path_factory):
    out = tmp_path_factory.mktemp("hand")
    _, found = joints.joints_in_shapes(lever_and_slider())
    model, written = mechanism_export.export_mechanism(found.assembly, found, urdf_dir=str(out), mjcf_path=str(out / "hand.xml"),
                                                density=RHO, name="hand")
    return model, out


def test_hand_built_links_mass_centre_and_inertia_match_the_hand_values(hand_export):
    model, _ = hand_export
    assert [link.name for link in model.links] == ["Base", "Lever", "Slider"]
    assert model.ground == "Base"
    lever, slider = model.link("Lever"), model.link("Slider")
    mass, centre, inertia = lever_by_hand()
    assert lever.mass == pytest.approx(mass, rel=1e-9)  # 4.0708 g
    assert list(lever.centre) == pytest.approx(centre, abs=1e-12)
    for row, expected in zip(lever.inertia, inertia):
        assert row == pytest.approx(expected, rel=1e-7, abs=1e-15)
    assert inertia[0][2] < 0  # the arm up and out: a negative product of inertia
    # The slider: 2000 mm^3 -> 2 g at (60, 30, 20) mm; m/12 (b^2 + c^2): 200, 500, 500 mm^2.
    assert slider.mass == pytest.approx(0.002, rel=1e-12)
    assert list(slider.centre) == pytest.approx([0.06, 0.03, 0.02], abs=1e-12)
    expected = [[0.002 / 12 * 200e-6, 0, 0], [0, 0.002 / 12 * 500e-6, 0], [0, 0, 0.002 / 12 * 500e-6]]
    for row, want in zip(slider.inertia, expected):
        assert row == pytest.approx(want, rel=1e-9, abs=1e-16)


def test_hand_built_joints_axes_origins_and_travel(hand_export):
    model, _ = hand_export
    revolute, prismatic = model.joints
    assert (revolute.type, revolute.parent, revolute.child) == ("revolute", "Base", "Lever")
    (turn,) = revolute.elements
    assert turn.kind == "revolute" and [abs(v) for v in turn.axis] == [0, 0, 1]
    assert list(turn.origin[:2]) == pytest.approx([0.020, 0.010], abs=1e-12)  # on the pin's axis
    assert model.link("Lever").origin == turn.origin
    assert (prismatic.type, prismatic.child) == ("prismatic", "Slider")
    (slide,) = prismatic.elements
    assert [abs(v) for v in slide.axis] == [1, 0, 0]
    assert list(slide.origin) == pytest.approx([0.06, 0.03, 0.02], abs=1e-12)  # at the slider's centre
    # The channel runs through the base: free both ways, the slider's length (20 mm) each side.
    assert (slide.lower, slide.upper) == pytest.approx((-0.02, 0.02), abs=1e-12)


def test_hand_built_urdf_text_and_check_urdf(hand_export):
    _, out = hand_export
    text = (out / "hand.urdf").read_text()
    assert '<joint name="Base__Lever" type="continuous">' in text
    assert '<joint name="Base__Slider" type="prismatic">' in text
    # The lever's frame on the pin's axis at the bore's floor (z 10 mm), the slider's at its centre.
    assert '<origin xyz="0.02 0.01 0.01" rpy="0 0 0"/>\n    <axis xyz="0 0 -1"/>' in text
    assert '<origin xyz="0.06 0.03 0.02" rpy="0 0 0"/>\n    <axis xyz="-1 0 0"/>' in text
    assert '<limit lower="-0.02" upper="0.02" effort="1000" velocity="1"/>' in text
    assert '<mass value="0.002"/>' in text
    tool = check_urdf_tool()
    done = subprocess.run([tool, str(out / "hand.urdf")], capture_output=True, text=True)
    assert done.returncode == 0, done.stdout + done.stderr
    assert "root Link: world has 1 child(ren)" in done.stdout and "child(2):  Slider" in done.stdout


def test_hand_built_mjcf_moves_by_the_hand_derived_inertia_and_mass(hand_export):
    # A torque tau on the lever's hinge: theta = tau / I h^2 N (N + 1) / 2 with I the lever's
    # moment about the pin's axis (Izz about its centre + m d^2, d = 12.28 mm); a force F on the
    # slider: x = F / m h^2 N (N + 1) / 2. Gravity (-z) is along the pin and across the slide.
    tool = mujoco_tool()
    _, out = hand_export
    mass, centre, inertia = lever_by_hand()
    moment = inertia[2][2] + mass * ((centre[0] - 0.020) ** 2 + (centre[1] - 0.010) ** 2)
    tau, force, steps = 1e-6, 1e-4, 200
    result = step(tool, str(out / "hand.xml"), steps, Base__Lever=tau, Base__Slider=force)
    joints_after = {j["name"]: j["qpos"][0] for j in result["after"]["joints"]}
    assert sorted(joints_after) == ["Base__Lever", "Base__Slider"]
    h = result["timestep"]
    assert abs(joints_after["Base__Lever"]) == pytest.approx(euler_travel(tau / moment, h, steps), rel=1e-6)
    assert abs(joints_after["Base__Slider"]) == pytest.approx(euler_travel(force / 0.002, h, steps), rel=1e-6)
    before = {b["name"]: b for b in result["before"]["bodies"]}
    after = {b["name"]: b for b in result["after"]["bodies"]}
    assert after["Base"] == before["Base"]
    assert after["Slider"]["xquat"] == before["Slider"]["xquat"]
    moved = [a - b for a, b in zip(after["Slider"]["xpos"], before["Slider"]["xpos"])]
    assert abs(moved[0]) == pytest.approx(euler_travel(force / 0.002, h, steps), rel=1e-6)
    assert moved[1:] == [0, 0]


def test_cylindrical_and_spherical_groups_become_documented_chains(tmp_path):
    # A shaft r 5 through a plate's bore (cylindrical) and a ball r 5 in a spherical socket
    # (spherical): URDF chains through massless links; MJCF slide + hinge and a ball joint.
    # Each carries an arm off its axis or centre: balanced, it would only spin (a passive spin, no
    # group of its own, docs/joints.md).
    plate = Part.makeBox(40, 40, 10).cut(Part.makeCylinder(5, 10, V(10, 10, 0)))
    shaft = Part.makeCylinder(5, 40, V(10, 10, -10)).fuse(Part.makeBox(30, 10, 5, V(5, 5, 30))).removeSplitter()
    socket = Part.makeBox(20, 20, 10, V(30, 0, 10)).cut(Part.makeSphere(5, V(40, 10, 20)))
    ball = Part.makeSphere(5, V(40, 10, 20)).fuse(Part.makeBox(20, 4, 4, V(40, 8, 22))).removeSplitter()
    _, found = joints.joints_in_shapes([("Plate", plate.fuse(socket).removeSplitter()), ("Shaft", shaft),
                                        ("Ball", ball)])
    kinds = {g["type"] for g in found.mobility.group_joints}
    assert kinds == {"rigid", "cylindrical", "spherical"}
    model, _ = mechanism_export.export_mechanism(found.assembly, found, urdf_dir=str(tmp_path),
                                          mjcf_path=str(tmp_path / "m.xml"), name="chains")
    by_child = {j.child: j for j in model.joints}
    assert [e.kind for e in by_child["Shaft"].elements] == ["prismatic", "revolute"]
    assert [e.kind for e in by_child["Ball"].elements] == ["revolute"] * 3
    assert [e.axis for e in by_child["Ball"].elements] == [(1, 0, 0), (0, 1, 0), (0, 0, 1)]
    # The shaft's travel: its length along the axis (40 mm and the arm's 5), both ways.
    assert (by_child["Shaft"].elements[0].lower, by_child["Shaft"].elements[0].upper) == \
        pytest.approx((-0.045, 0.045), abs=1e-12)
    assert all(list(e.origin) == pytest.approx([0.04, 0.01, 0.02], abs=1e-9) for e in by_child["Ball"].elements)
    text = (tmp_path / "chains.urdf").read_text()
    assert '<link name="Plate__Shaft__1"/>' in text and '<link name="Plate__Ball__2"/>' in text
    mjcf = (tmp_path / "m.xml").read_text()
    assert 'type="ball"' in mjcf and 'type="slide"' in mjcf and 'type="hinge"' in mjcf
    done = subprocess.run([check_urdf_tool(), str(tmp_path / "chains.urdf")], capture_output=True, text=True)
    assert done.returncode == 0, done.stdout
    result = step(mujoco_tool(), str(tmp_path / "m.xml"), 10)
    assert (result["nq"], result["nv"]) == (2 + 4, 2 + 3)  # slide + hinge, a ball (quaternion)


# ---------------------------------------------------------------- the exit-code contract and safe output

@pytest.mark.parametrize("args, message", [
    (["--export-mjcf", "out.txt"], "name an .xml file"),
    (["--density", "2700"], "--density goes with --export-urdf or --export-mjcf"),
    (["--export-urdf", "D", "--density", "0"], "must be above 0"),
    (["--export-urdf", "D", "--density", "nan"], "must be a finite number"),
    (["--export-urdf", "D", "--disassembly"], "--disassembly cannot be combined"),
    (["--export-urdf", "/proc/urdf"], "system folder"),
])
def test_bad_export_options_are_usage_errors(tmp_path, args, message):
    args = [str(tmp_path / a) if a in ("out.txt", "D") else a for a in args]
    done = run_cli(MOTOR, *args)
    assert done.returncode == 2, done.stderr
    assert message in done.stderr


def test_export_into_a_file_or_through_a_link_is_refused(tmp_path):
    existing = tmp_path / "file"
    existing.write_text("keep")
    done = run_cli(MOTOR, "--export-urdf", str(existing))
    assert done.returncode == 2 and "is not a folder" in done.stderr
    assert existing.read_text() == "keep"
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    (tmp_path / "link").symlink_to(elsewhere)
    done = run_cli(MOTOR, "--export-urdf", str(tmp_path / "link"))
    assert done.returncode == 2 and "symbolic link" in done.stderr
    assert os.listdir(elsewhere) == []


def test_links_inside_the_output_are_replaced_never_written_through(tmp_path):
    outside = tmp_path / "outside.stl"
    outside.write_bytes(b"untouched")
    out = tmp_path / "urdf"
    (out / "meshes").mkdir(parents=True)
    (out / "meshes" / "Body.stl").symlink_to(outside)
    (out / "motor.urdf").symlink_to(outside)
    done = run_cli(MOTOR, "--annotations", MOTOR_NOTES, "--export-urdf", str(out))
    assert done.returncode == 0, done.stderr
    assert outside.read_bytes() == b"untouched"
    assert not os.path.islink(out / "meshes" / "Body.stl") and not os.path.islink(out / "motor.urdf")
    assert [n for n in os.listdir(out) if n.startswith(".")] == []  # no temporary left


def test_unreadable_input_and_unknown_ground(tmp_path):
    done = run_cli(str(tmp_path / "missing.step"), "--export-urdf", str(tmp_path / "u"))
    assert done.returncode == 3 and "no such file" in done.stderr
    done = run_cli(MOTOR, "--ground", "Nobody", "--export-urdf", str(tmp_path / "u"))
    assert done.returncode == 2 and "Nobody" in done.stderr
    assert not os.path.exists(tmp_path / "u" / "motor.urdf")


def test_document_analysis_exports_the_same_mechanism_as_the_step_file(tmp_path, motor_export):
    # The FreeCAD command's path (contactwb.document.mechanism): the motor's document, its sidecar
    # annotations found beside it; the same links (bodies, masses) and joint as the STEP file's.
    from contactwb.document import freecad_setup
    from contactwb.document import mechanism as document_mechanism
    from contactwb.make import make_contact_analysis
    doc = freecad_setup.open_document(os.path.join(SAMPLES, "motor.FCStd"))
    try:
        group = make_contact_analysis(doc)
        notes = document_mechanism.sidecar_annotations(doc)
        assert notes == MOTOR_NOTES
        model, paths = document_mechanism.export_analysis(group, "mjcf", str(tmp_path / "doc.xml"), annotations=notes)
        with pytest.raises(Exception, match="an MJCF file is an .xml file"):
            document_mechanism.export_analysis(group, "mjcf", str(tmp_path / "doc.txt"))
    finally:
        FreeCAD.closeDocument(doc.Name)
    assert paths == [str(tmp_path / "doc.xml")]
    step_links = motor_export[0]["export"]["links"]
    assert [sorted(l.bodies) for l in model.links] == [sorted(l["bodies"]) for l in step_links]
    for link, expected in zip(model.links, step_links):
        assert link.mass == pytest.approx(expected["mass"], rel=1e-7)  # the document stores its own B-rep
        assert list(link.centre) == pytest.approx(expected["centre"], abs=1e-8)
    assert [(j.type, j.parent, j.child) for j in model.joints] == [("revolute", "Body", "Axis")]


def test_a_part_touching_nothing_is_a_floating_link_that_falls_freely(tmp_path):
    # A block 20 x 20 x 10 on a plate and a cube 10 mm a side 20 mm away from both: the cube is
    # its own group with no joint to anything: URDF "floating", MJCF a freejoint; in MuJoCo it
    # falls freely (visual meshes do not collide): z drops by g h^2 N (N + 1) / 2.
    plate = Part.makeBox(60, 60, 10)
    block = Part.makeBox(20, 20, 10, V(0, 0, 10))
    cube = Part.makeBox(10, 10, 10, V(40, 40, 40))
    _, found = joints.joints_in_shapes([("Plate", plate), ("Block", block), ("Cube", cube)], ground="Plate")
    model, _ = mechanism_export.export_mechanism(found.assembly, found, urdf_dir=str(tmp_path),
                                          mjcf_path=str(tmp_path / "f.xml"), name="floating")
    by_child = {j.child: j for j in model.joints}
    assert (by_child["Cube"].type, by_child["Cube"].parent) == ("floating", "world")
    assert model.link("Cube").origin == pytest.approx((0.045, 0.045, 0.045), abs=1e-12)
    assert model.notes == ["Cube touches no other group: exported as a free (floating) body"]
    text = (tmp_path / "floating.urdf").read_text()
    assert '<joint name="world__Cube" type="floating">' in text
    done = subprocess.run([check_urdf_tool(), str(tmp_path / "floating.urdf")], capture_output=True, text=True)
    assert done.returncode == 0, done.stdout
    assert "root Link: world has 2 child(ren)" in done.stdout
    steps = 100
    result = step(mujoco_tool(), str(tmp_path / "f.xml"), steps)
    before = {b["name"]: b for b in result["before"]["bodies"]}
    after = {b["name"]: b for b in result["after"]["bodies"]}
    drop = before["Cube"]["xpos"][2] - after["Cube"]["xpos"][2]
    assert drop == pytest.approx(euler_travel(9.81, result["timestep"], steps), rel=1e-9)
    assert after["Cube"]["xpos"][:2] == pytest.approx(before["Cube"]["xpos"][:2], abs=1e-12)
    assert after["Plate"] == before["Plate"]


# ---------------------------------------------------------------- a closed loop: a hand-built four-bar

FOUR_BAR_PINS = {"P1": (0, 0), "P2": (-10, -40), "P3": (65, -45), "P4": (60, 0)}  # (x, z) mm; axes along y


def four_bar_bar(p, q, y0, bores, pins, thickness=5.0, width=10.0, pin_radius=3.0, head_radius=4.5):
    """A bar `width` wide with rounded ends from p to q ((x, z), mm) in y0..y0 + thickness, bores
    (radius 3) at `bores`, pins (radius 3, 5 long) going +y with a head (radius 4.5, 2 thick) at `pins`."""
    dx, dz = q[0] - p[0], q[1] - p[1]
    length = math.hypot(dx, dz)
    shape = Part.makeBox(length, thickness, width, V(0, y0, -width / 2))
    for x in (0, length):
        shape = shape.fuse(Part.makeCylinder(width / 2, thickness, V(x, y0, 0), V(0, 1, 0)))
    shape.rotate(V(0, 0, 0), V(0, 1, 0), math.degrees(math.atan2(-dz, dx)))
    shape.translate(V(p[0], 0, p[1]))
    for b in bores:
        shape = shape.cut(Part.makeCylinder(pin_radius, thickness, V(b[0], y0, b[1]), V(0, 1, 0)))
    for c in pins:
        shape = shape.fuse(Part.makeCylinder(pin_radius, 5, V(c[0], y0 + thickness, c[1]), V(0, 1, 0)))
        shape = shape.fuse(Part.makeCylinder(head_radius, 2, V(c[0], y0 + thickness + 5, c[1]), V(0, 1, 0)))
    return shape.removeSplitter()


def four_bar():
    """A four-bar hanging in the x-z plane (gravity -z in MuJoCo) off a ground plate (y <= 0): the
    ground's headed pins at P1 and P4 through the crank's and the rocker's bores (both in y 0..5,
    on the plate), the crank's and the rocker's headed pins at P2 and P3 through the coupler's
    bores (y 5..10, on them). Each pin is held axially by the face under its part and its head:
    four revolute pair joints about y, one loop, DOF 1; it starts off its equilibrium and swings."""
    pins = FOUR_BAR_PINS
    ground = Part.makeBox(100, 10, 30, V(-20, -10, -15))
    for c in (pins["P1"], pins["P4"]):
        ground = ground.fuse(Part.makeCylinder(3, 5, V(c[0], 0, c[1]), V(0, 1, 0)))
        ground = ground.fuse(Part.makeCylinder(4.5, 2, V(c[0], 5, c[1]), V(0, 1, 0)))
    return [("Ground", ground.removeSplitter()),
            ("Crank", four_bar_bar(pins["P1"], pins["P2"], 0, [pins["P1"]], [pins["P2"]])),
            ("Rocker", four_bar_bar(pins["P4"], pins["P3"], 0, [pins["P4"]], [pins["P3"]])),
            ("Coupler", four_bar_bar(pins["P2"], pins["P3"], 5, [pins["P2"], pins["P3"]], []))]


def rotate_by_quaternion(quat, v):
    w, x, y, z = quat
    t = (2 * (y * v[2] - z * v[1]), 2 * (z * v[0] - x * v[2]), 2 * (x * v[1] - y * v[0]))
    return (v[0] + w * t[0] + y * t[2] - z * t[1], v[1] + w * t[1] + z * t[0] - x * t[2],
            v[2] + w * t[2] + x * t[1] - y * t[0])


def closure_gap(result, model, closure):
    """Distance (m) after stepping between the closure's anchor carried by each of its two links."""
    after = {b["name"]: b for b in result["after"]["bodies"]}
    points = []
    for name in (closure.link_a, closure.link_b):
        local = tuple(a - o for a, o in zip(closure.anchor, model.link(name).origin))
        turned = rotate_by_quaternion(after[name]["xquat"], local)
        points.append(tuple(p + q for p, q in zip(after[name]["xpos"], turned)))
    return math.dist(*points)


@pytest.fixture(scope="module")
def four_bar_export(tmp_path_factory):
    out = tmp_path_factory.mktemp("four_bar")
    _, found = joints.joints_in_shapes(four_bar(), ground="Ground")
    model, _ = mechanism_export.export_mechanism(found.assembly, found, urdf_dir=str(out),
                                                 mjcf_path=str(out / "four_bar.xml"), name="four_bar")
    return found, model, out


def test_four_bar_loop_closure_is_named_and_left_out_of_the_urdf_tree(four_bar_export):
    # Four single-body groups, four revolute pair joints about y, DOF 1 (Gruebler in the plane:
    # 3 (4 - 1) - 2 * 4 = 1). The tree: Ground -> Crank, Ground -> Rocker (their motions about P1,
    # P4), Crank -> Coupler (the pin at P2); the pin at P3 (Rocker - Coupler) closes the loop.
    found, model, out = four_bar_export
    assert found.mobility.dof == 1
    assert sorted(g["type"] for g in found.mobility.group_joints) == ["revolute"] * 3 + ["rigid"]
    assert [(j.parent, j.child, j.type) for j in model.joints] == [
        ("Ground", "Crank", "revolute"), ("Ground", "Rocker", "revolute"), ("Crank", "Coupler", "revolute")]
    (closure,) = model.closures
    assert (closure.name, closure.link_a, closure.link_b, closure.type, closure.equality) == \
        ("Rocker__Coupler", "Rocker", "Coupler", "revolute", "connect")
    assert closure.bodies == ("Rocker", "Coupler")
    assert [abs(v) for v in closure.axis] == [0, 1, 0]
    assert (closure.anchor[0], closure.anchor[2]) == pytest.approx((0.065, -0.045), abs=1e-12)  # P3
    (note,) = model.notes
    assert note.startswith("loop closed by joint Rocker__Coupler (revolute about (0, ")
    assert "left out of the URDF (a tree); MJCF closes it with an <equality> connect" in note
    text = (out / "four_bar.urdf").read_text()
    assert "<!-- loop closed by joint Rocker__Coupler (revolute" in text
    assert 'name="Rocker__Coupler"' not in text
    done = subprocess.run([check_urdf_tool(), str(out / "four_bar.urdf")], capture_output=True, text=True)
    assert done.returncode == 0, done.stdout + done.stderr
    tree = [line.strip() for line in done.stdout.splitlines() if "child(" in line or "root Link" in line]
    assert tree == ["root Link: world has 1 child(ren)", "child(1):  Ground", "child(1):  Crank",
                    "child(1):  Coupler", "child(2):  Rocker"]
    # The command line's messages name it too (the export's table, and "closures" in --json).
    from contactwb.cli.export_mechanism import export_table
    summary = dict(model.to_json(), files=[])
    assert f"  note: {note}" in export_table(summary).splitlines()
    assert summary["closures"] == [{"name": "Rocker__Coupler", "type": "revolute", "links": ["Rocker", "Coupler"],
                                    "bodies": ["Rocker", "Coupler"], "anchor": list(closure.anchor),
                                    "axis": list(closure.axis), "equality": "connect", "kept_by_tree": False}]


def test_four_bar_mjcf_equality_keeps_the_loop_closed_in_mujoco(four_bar_export):
    # Gravity on, no force: the four-bar swings from its start. The point P3 carried by the rocker
    # and by the coupler stays one point (the connect constraint, made stiff: MuJoCo's are soft)
    # to 1e-6 m after N steps, while the linkage has turned; the same model with its <equality>
    # removed falls apart (the coupler swings on the crank alone): the constraint is what holds it.
    _, model, out = four_bar_export
    (closure,) = model.closures
    text = (out / "four_bar.xml").read_text()
    assert ('<connect name="Rocker__Coupler" body1="Rocker" body2="Coupler" solref="0.004 1" '
            'solimp="0.9999 0.9999 0.001" anchor="0.005 0.0025 -0.045"/>') in text  # P3 - P4: the rocker's frame on P4
    tool = mujoco_tool()
    for steps in (100, 500, 1000):
        result = step(tool, str(out / "four_bar.xml"), steps)
        assert (result["nq"], result["njnt"]) == (3, 3)
        assert closure_gap(result, model, closure) <= 1e-6, steps
    swung = {j["name"]: j["qpos"][0] for j in step(tool, str(out / "four_bar.xml"), 100)["after"]["joints"]}
    assert abs(swung["Ground__Crank"]) > 0.05 and abs(swung["Ground__Rocker"]) > 0.05
    import re
    (out / "open.xml").write_text(re.sub(r"  <equality>.*?</equality>\n", "", text, flags=re.S))
    opened = step(tool, str(out / "open.xml"), 100)
    assert closure_gap(opened, model, closure) > 1e-2
