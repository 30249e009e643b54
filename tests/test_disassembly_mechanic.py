"""Disassembly a mechanic would follow (issue 22, item 6): the annotated
motor comes apart in sub-assemblies (the rotor with its axis and magnets,
each cover with the bearing and seal pressed into it), the front cover right
after its screws; directions sampled inside the free-direction cones; each
step says what blocked it and why it is free now; every step judged by OCCT
Booleans along its path (no step cuts into a part still in place)."""
import json
import os

import pytest

import FreeCAD
import Part
from contactwb import cli, core
from contactwb.core import meshes
from contactwb.document import shapes as document_shapes

from conftest import SAMPLES

V = FreeCAD.Vector
MOTOR = os.path.join(SAMPLES, "motor.step")
MOTOR_NOTES = os.path.join(SAMPLES, "motor.annotations.json")
CUT = 1e-3  # mm3: more common volume than this is a cut (touching faces have none)


def cuts_along_paths(named_shapes, document, step_mm=0.5):
    """Every (step, moved part, part in place, distance, volume) where a step's
    parts, translated along its direction, share material with a part still in
    place: OCCT Booleans at every `step_mm` of the way out (until the moved
    parts' box is past every part in place), plus the first 0.05 mm."""
    shapes = dict(named_shapes)
    gone = set()
    cuts = []
    for number, step in enumerate(document["disassembly"], 1):
        d = V(*step["direction"])
        moving = [(name, shapes[name]) for name in step["parts"]]
        fixed = [(name, shape) for name, shape in shapes.items() if name not in gone and name not in step["parts"]]

        def extent(shape):
            box = shape.BoundBox
            corners = [V(x, y, z) for x in (box.XMin, box.XMax) for y in (box.YMin, box.YMax)
                       for z in (box.ZMin, box.ZMax)]
            values = [c.dot(d) for c in corners]
            return min(values), max(values)

        start = min(extent(s)[0] for _, s in moving)
        end = max([extent(s)[1] for _, s in fixed] + [start])
        travel = end - start + 1.0
        distances = [0.05] + [k * step_mm for k in range(1, int(travel / step_mm) + 2)]
        for name, shape in moving:
            for t in distances:
                moved = shape.copy()
                moved.translate(d * t)
                for other, still in fixed:
                    if not moved.BoundBox.intersect(still.BoundBox):
                        continue
                    volume = moved.common(still).Volume
                    if volume > CUT:
                        cuts.append((number, name, other, round(t, 3), volume))
        gone.update(step["parts"])
    return cuts


def motor_shapes(assembly):
    return [(body.name, document_shapes.shape_from_brep(body.brep)) for body in assembly.bodies]


@pytest.fixture(scope="module")
def annotated_motor():
    assembly = meshes.read_step_assembly(MOTOR)
    result = meshes.disassemble(assembly, annotations=MOTOR_NOTES)
    return assembly, meshes.disassembly_json(assembly, result)


def test_annotated_motor_comes_apart_as_a_mechanic_would(annotated_motor):
    # The screws are threaded into the back cover (threaded CLJ in the example
    # file): nothing can leave until one is undone, so each is released and
    # unscrewed up its axis (+z, head first); then the front cover with the
    # bearing and seal pressed into it (freed by the last screw); then the
    # rotor with its axis and magnets (freed by the front cover); the back
    # cover with its bearing down (-z); the body with the stator glued in it
    # stays.
    _, document = annotated_motor
    assert document["complete"] is True
    steps = [(sorted(s["parts"]), s["direction"]) for s in document["disassembly"]]
    assert steps == [
        (["Screw-1"], [0.0, 0.0, 1.0]), (["Screw-2"], [0.0, 0.0, 1.0]),
        (["Screw-3"], [0.0, 0.0, 1.0]), (["Screw-4"], [0.0, 0.0, 1.0]),
        (["Bearing-front", "Front-cover", "Seal"], [0.0, 0.0, 1.0]),
        (["Axis", "Magnet-1", "Magnet-2", "Magnet-3", "Magnet-4", "Rotor-back", "Rotor-front"], [0.0, 0.0, 1.0]),
        (["Back-cover", "Bearing-back"], [0.0, 0.0, -1.0])]
    assert sorted(document["base_parts"]) == ["Body", "Stator"] and document["base"] == "Body"


def test_each_step_says_what_blocked_it_and_why_it_is_free(annotated_motor):
    _, document = annotated_motor
    steps = document["disassembly"]
    for number, screw in enumerate(("Screw-1", "Screw-2", "Screw-3", "Screw-4"), 1):
        step = steps[number - 1]
        assert step["released"] == [{"a": "Back-cover", "b": screw, "type": "CLJ", "intent": "threaded"}]
        assert step["blocked_before"] == []
        assert step["why_free"] == ("its threaded CLJ with Back-cover undone (unscrewed); nothing blocked it along "
                                    "(0, 0, 1) from the start")
    front = steps[4]
    assert "released" not in front
    # The screws' heads held the front cover's sub-assembly along +z.
    assert front["blocked_before"] == [{"part": f"Screw-{k}", "removed_in_step": k} for k in (1, 2, 3, 4)]
    assert front["why_free"].startswith("what blocked it along (0, 0, 1) was removed: Screw-1 (step 1)")
    rotor = steps[5]
    assert {b["part"] for b in rotor["blocked_before"]} <= {"Bearing-front", "Front-cover", "Seal"}
    assert rotor["blocked_before"] and all(b["removed_in_step"] == 5 for b in rotor["blocked_before"])
    back = steps[6]
    assert {b["part"] for b in back["blocked_before"]} >= {"Screw-1", "Screw-2", "Screw-3", "Screw-4"}


def test_no_step_of_the_annotated_motor_cuts_into_a_part_in_place(annotated_motor):
    assembly, document = annotated_motor
    assert cuts_along_paths(motor_shapes(assembly), document) == []


def test_cli_disassembly_with_annotations(capsys):
    assert cli.main([MOTOR, "--disassembly", "--annotations", MOTOR_NOTES]) == 0
    text = capsys.readouterr().out
    assert "  5. Bearing-front, Seal, Front-cover along (0, 0, 1)" in text  # the parts in the file's order
    assert "free: its threaded CLJ with Back-cover undone (unscrewed)" in text
    assert "     Stator, Body stay (the base)" in text
    bad = os.path.join(os.path.dirname(MOTOR), "cases", "taper_pin.step")
    assert cli.main([bad, "--disassembly", "--annotations", MOTOR_NOTES]) == cli.EXIT_USAGE
    assert "no body named" in capsys.readouterr().err


def corner_with_posts():
    """A 10 mm block in the corner of a frame (floor z <= 0, walls x <= 0 and
    y <= 0, a roof 5 mm above it) with two posts 5 mm beside it (x 15..20 at
    y 0..4, y 15..20 at x 0..4): +x, +y and +z are blocked, the walls and floor
    close -x, -y, -z; the block leaves only between the posts, along the
    diagonal (1, 1, 0) of its free-direction cone (generators +x, +y, +z)."""
    frame = Part.makeBox(45, 45, 5, V(-5, -5, -5))
    for box in (Part.makeBox(5, 45, 15, V(-5, -5, 0)), Part.makeBox(45, 5, 15, V(-5, -5, 0)),
                Part.makeBox(45, 45, 2, V(-5, -5, 15)), Part.makeBox(5, 4, 15, V(15, 0, 0)),
                Part.makeBox(4, 5, 15, V(0, 15, 0))):
        frame = frame.fuse(box)
    frame = frame.removeSplitter()
    return [("Frame", frame), ("Block", Part.makeBox(10, 10, 10))]


def test_directions_sampled_inside_the_free_cone(tmp_path):
    named = corner_with_posts()
    path = str(tmp_path / "corner.step")
    Part.makeCompound([s for _, s in named]).exportStep(path)
    assembly = meshes.read_step_assembly(path)
    names = [b.name for b in assembly.bodies]
    # STEP names of a plain compound's solids are not ours: map by volume
    block_name = min(names, key=lambda n: abs(document_shapes.shape_from_brep(
        assembly.bodies[names.index(n)].brep).Volume - 1000))
    only_axes = meshes.disassembly_json(assembly, meshes.disassemble(assembly, sample_free_cones=False))
    assert only_axes["complete"] is False and "interlock" in only_axes["reason"]
    sampled = meshes.disassembly_json(assembly, meshes.disassemble(assembly))
    assert sampled["complete"] is True
    (step,) = sampled["disassembly"]
    assert step["parts"] == [block_name]
    assert step["direction"] == pytest.approx([2 ** -0.5, 2 ** -0.5, 0], abs=1e-9)
    shapes = [(body.name, document_shapes.shape_from_brep(body.brep)) for body in assembly.bodies]
    assert cuts_along_paths(shapes, sampled) == []
    # and the judge sees a cut where there is one: the block pushed along +x hits the post
    pushed = {"disassembly": [{"parts": [block_name], "direction": [1.0, 0.0, 0.0]}]}
    assert [c[2] for c in cuts_along_paths(shapes, pushed)][:1] == [n for n in names if n != block_name]


# ---------------------------------------------------------------- bonds are never undone, threads are

def pinned_cover():
    """A base 40 x 40 x 20 with a blind bore r 3 at (20, 20) from z 8 up; a cover 40 x 40 x 5 on it
    (z 20..25) with a through bore there; a pin r 3 from the bore's floor (z 8) through both, its
    head r 5 on the cover (z 25..27). Drawn at nominal size: the pin slides in both bores."""
    base = Part.makeBox(40, 40, 20).cut(Part.makeCylinder(3, 12, V(20, 20, 8)))
    cover = Part.makeBox(40, 40, 5, V(0, 0, 20)).cut(Part.makeCylinder(3, 5, V(20, 20, 20)))
    pin = Part.makeCylinder(3, 17, V(20, 20, 8)).fuse(Part.makeCylinder(5, 2, V(20, 20, 25))).removeSplitter()
    return [("Base", base), ("Cover", cover), ("Pin", pin)]


@pytest.fixture(scope="module")
def pinned_assembly():
    named = pinned_cover()
    return named, document_shapes.assembly_from_shapes(named)


def pinned_disassembly(pinned_assembly, annotations):
    named, assembly = pinned_assembly
    document = meshes.disassembly_json(assembly, meshes.disassemble(assembly, annotations=annotations))
    if document["complete"]:
        assert cuts_along_paths(named, document) == []
    return document


def test_a_threaded_pin_is_unscrewed_then_the_cover_lifts(pinned_assembly):
    # Threaded into the base: nothing can leave (the head holds the cover, the thread the pin)
    # until the thread is undone: the pin up its axis, then the cover.
    document = pinned_disassembly(pinned_assembly, [{"a": "Pin", "b": "Base", "type": "CLJ", "intent": "threaded"}])
    assert document["complete"] is True
    assert [(s["parts"], s["direction"]) for s in document["disassembly"]] == [
        (["Pin"], [0.0, 0.0, 1.0]), (["Cover"], [0.0, 0.0, 1.0])]
    assert document["disassembly"][0]["released"] == [{"a": "Base", "b": "Pin", "type": "CLJ", "intent": "threaded"}]
    assert document["base_parts"] == ["Base"]


def test_a_pin_bonded_into_the_base_is_never_pulled_so_the_cover_is_trapped(pinned_assembly):
    # Glued into the base, the pin is part of the base's sub-assembly: it is never released
    # (the rule before treated every bonded cylinder as a thread and unscrewed it), so the cover
    # under its head cannot leave: no sequence (interlocked), nothing released.
    document = pinned_disassembly(pinned_assembly, [{"a": "Pin", "b": "Base", "type": "CLJ", "intent": "bonded"}])
    assert document["complete"] is False
    assert document["disassembly"] == []
    assert "interlock" in document["reason"] and "Cover" in document["reason"]


def test_a_pin_bonded_into_the_cover_comes_out_with_it_as_one_sub_assembly(pinned_assembly):
    # Item 6: annotated rigid groups come out as one sub-assembly: the cover with the pin glued in it.
    document = pinned_disassembly(pinned_assembly, [{"a": "Pin", "b": "Cover", "intent": "bonded"}])
    assert document["complete"] is True
    (step,) = document["disassembly"]
    assert (step["parts"], step["direction"]) == (["Cover", "Pin"], [0.0, 0.0, 1.0])
    assert "released" not in step
    assert document["base_parts"] == ["Base"]


def test_bonded_motor_screws_stay_in_the_back_cover(tmp_path):
    # The motor's example with its screws glued (bonded) instead of threaded: the screws are never
    # unscrewed; they join the back cover's sub-assembly, whose heads trap the front cover:
    # no sequence; the CLI exits with the analysis-failed code (4), not the usage code (2).
    entries = json.load(open(MOTOR_NOTES))
    for entry in entries:
        if entry["a"].startswith("Screw-"):
            entry["intent"] = "bonded"
    notes = tmp_path / "glued.json"
    notes.write_text(json.dumps(entries))
    assembly = meshes.read_step_assembly(MOTOR)
    document = meshes.disassembly_json(assembly, meshes.disassemble(assembly, annotations=str(notes)))
    assert document["complete"] is False and "interlock" in document["reason"]
    assert all("released" not in step for step in document["disassembly"])
    assert not any(p.startswith("Screw-") for step in document["disassembly"] for p in step["parts"])
    assert cli.main([MOTOR, "--disassembly", "--annotations", str(notes)]) == cli.EXIT_FAILED
