"""Bodies: shapes cross into C++ as BRep and come back unchanged; STEP files
read in C++ with names; FreeCAD documents walked through parts and links."""
import os

import pytest

import FreeCAD
import Part
from contactwb import bodies, core, freecad_setup
from contactwb.document import shapes as document_shapes


# The shared STEP files (../shared/data/README.md), named here so that the
# tests exist, and skip one by one, when the folder is absent.
STEP_FILES = ["R01_as1-oc-214.stp", "R05_SKF_6004.stp", "R06_bearing_20x37x9_freecad.stp",
              "R08_presse_asm.step", "R09_chrono_assembly.stp", "R10_wrenchnut.stp",
              "D03_asm4_tuto2_disk_arm.step"]


@pytest.mark.parametrize("name", STEP_FILES)
def test_round_trip_through_cpp_keeps_every_solid(shared_step, name):
    path = shared_step(name)
    solids = Part.read(path).Solids
    assert solids, path
    assembly = document_shapes.assembly_from_shapes((f"s{i}", s) for i, s in enumerate(solids))
    assert len(assembly.bodies) == len(solids)
    back = document_shapes.shape_from_brep(assembly.to_brep()).Solids
    assert len(back) == len(solids)
    for original, returned, body in zip(solids, back, assembly.bodies):
        assert returned.Volume == pytest.approx(original.Volume, rel=1e-9)
        assert returned.Area == pytest.approx(original.Area, rel=1e-9)
        assert len(returned.Faces) == len(original.Faces)
        assert returned.BoundBox.Center.isEqual(original.BoundBox.Center, 1e-9)
        assert body.volume == pytest.approx(original.Volume, rel=1e-6)


def test_placement_travels_with_the_shape():
    box = Part.makeBox(1, 2, 3)
    box.Placement = FreeCAD.Placement(FreeCAD.Vector(10, 0, 0), FreeCAD.Rotation(FreeCAD.Vector(0, 0, 1), 90))
    (body,) = document_shapes.assembly_from_shapes([("box", box)]).bodies
    assert body.center == pytest.approx(tuple(box.CenterOfMass), abs=1e-9)


def test_bad_brep_raises_a_clear_error():
    with pytest.raises(core.ContactsError, match="BRep"):
        core.contactcore.bodies_from_brep("garbage", ["x"])


def test_read_step_names_bodies_and_skips_no_duplicates(shared_step):
    assembly = core.contactcore.read_step(shared_step("R09_chrono_assembly.stp"))
    assert len(assembly.bodies) == 2  # Part.read returns 4 here
    assert assembly.units == "m"
    assert len({b.name for b in assembly.bodies}) == 2


def test_missing_step_names_the_file():
    with pytest.raises(core.ContactsError, match="nowhere.step"):
        core.contactcore.read_step("/nowhere.step")


def test_document_bodies_through_parts_and_links(shared_fcstd):
    doc = freecad_setup.open_document(shared_fcstd("Asm4_Tutorial2/asm_tuto2.FCStd"))
    try:
        found = bodies.document_bodies(doc)
        assert sorted(b.name for b in found) == ["arm001", "base001", "disk001"]
        for body in found:
            assert body.subname.endswith(body.obj.Name + ".")
            # The link placement is applied: the global shape differs from the body's own.
            assert body.shape.Volume == pytest.approx(body.obj.Shape.Volume, rel=1e-9)
    finally:
        FreeCAD.closeDocument(doc.Name)


def test_multi_solid_feature_gives_one_body_per_solid_with_face_map():
    doc = FreeCAD.newDocument("multi")
    try:
        compound = Part.makeCompound([Part.makeBox(1, 1, 1), Part.makeBox(1, 1, 1, FreeCAD.Vector(1, 0, 0))])
        feature = doc.addObject("Part::Feature", "Pair")
        feature.Shape = compound
        found = bodies.document_bodies(doc)
        assert [b.name for b in found] == ["Pair", "Pair.2"]
        assert found[1].face_map == list(range(7, 13))
        assert found[1].object_face_name(1) == "Face7"
    finally:
        FreeCAD.closeDocument(doc.Name)


def test_hidden_objects_are_not_bodies():
    doc = FreeCAD.newDocument("hidden")
    try:
        doc.addObject("Part::Box", "Shown")
        hidden = doc.addObject("Part::Box", "Hidden")
        hidden.Visibility = False
        doc.recompute()
        assert [b.name for b in bodies.document_bodies(doc)] == ["Shown"]
    finally:
        FreeCAD.closeDocument(doc.Name)


@pytest.mark.parametrize("name", ["motor.step", "families/bolted_grid_100.step", "cases/inch.step"])
def test_fast_step_read_gives_what_the_xde_read_gives(sample, name):
    """The read by products (the default) against OCCT's XDE read, through the
    binding: same names, paths, units, volumes and centres, in the same order."""
    fast = core.contactcore.read_step(sample(name))
    xde = core.contactcore.read_step(sample(name), reader="xde")
    assert (fast.reader, xde.reader) == ("products", "xde")
    assert fast.units == xde.units
    assert [(b.name, b.path) for b in fast.bodies] == [(b.name, b.path) for b in xde.bodies]
    for a, b in zip(fast.bodies, xde.bodies):
        assert a.volume == pytest.approx(b.volume, rel=1e-9)
        assert a.center == pytest.approx(b.center, abs=1e-9)


def test_fast_step_read_falls_back_in_the_json_messages(sample, tmp_path):
    """pin_block.step with a placement (CONTEXT_DEPENDENT_SHAPE_REPRESENTATION)
    of a product rather than of an occurrence: the XDE read serves it, and
    `contacts --json --progress` says so."""
    import json
    import subprocess
    import sys
    with open(sample("cases/pin_block.step")) as f:
        text = f.read()
    end = text.rindex("ENDSEC;")
    path = tmp_path / "pin_block_fallback.step"
    path.write_text(text[:end] + "#99990 = CONTEXT_DEPENDENT_SHAPE_REPRESENTATION(#461,#34);\n" + text[end:])
    repo = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    out = subprocess.run([sys.executable, "-m", "contactwb.cli", str(path), "--json", "--progress"], capture_output=True,
                         text=True, env=dict(os.environ, PYTHONPATH=repo), cwd=repo, timeout=300)
    assert out.returncode == 0, out.stderr
    messages = json.loads(out.stdout)["messages"]
    assert ("STEP read: the fast product read cannot serve this file (a placement of no assembly occurrence "
            "(#99990)): read through OCCT's XDE reader") in messages
    assert "read (XDE fallback)" in out.stderr


def test_fast_step_read_serves_hybrid_and_mapped_products(shared_step):
    """R08's products made of a solid beside a surface model and R09's products
    placed by MAPPED_ITEMs: the read by products gives XDE's sub-assemblies
    (names, paths, volumes, centres, skipped shells), with no fallback."""
    for name in ("R08_presse_asm.step", "R09_chrono_assembly.stp"):
        fast = core.contactcore.read_step(shared_step(name))
        xde = core.contactcore.read_step(shared_step(name), reader="xde")
        assert (fast.reader, xde.reader) == ("products", "xde")
        assert [(b.name, b.path) for b in fast.bodies] == [(b.name, b.path) for b in xde.bodies]
        for a, b in zip(fast.bodies, xde.bodies):
            assert a.volume == pytest.approx(b.volume, rel=1e-9)
            assert a.center == pytest.approx(b.center, abs=1e-9)
        skipped = [m for m in xde.messages if m.startswith("skipped")]
        assert [m for m in fast.messages if m.startswith("skipped")] == skipped
        assert not any("cannot serve" in m for m in fast.messages)
    r09 = core.contactcore.read_step(shared_step("R09_chrono_assembly.stp"))
    assert [(b.name, b.path) for b in r09.bodies] == [("body1", "Assem1/body1"), ("body2", "Assem1/body2")]


def test_step_reader_must_be_known(sample):
    with pytest.raises(ValueError, match="products' or 'xde'"):
        core.contactcore.read_step(sample("motor.step"), reader="fast")
