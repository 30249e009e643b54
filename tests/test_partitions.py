"""Tests of the partitions binding (contactcore.partition_brep) on FreeCAD shapes.

Run with the extension of a build folder:
    CONTACTS_PYTHON_DIR=<build>/python /usr/bin/python3 -m pytest tests/test_partitions.py
"""
import math
import os
import re
import sys

import pytest

sys.path.append("/usr/lib/freecad-python3/lib")
try:
    import FreeCAD  # noqa: F401  (must come before Part)
    import Part
except ImportError:  # pragma: no cover - depends on the machine
    pytest.skip("FreeCAD's Python modules are not available", allow_module_level=True)

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.environ.get("CONTACTS_PYTHON_DIR", os.path.join(REPO, "build", "python")))
import contactcore as cc  # noqa: E402

SHARED_STEP = os.path.join(REPO, "..", "shared", "data", "step")

# FreeCAD surface classes and the kinds they must be typed as.
FREECAD_KINDS = {
    "Plane": cc.SurfaceKind.Plane,
    "Cylinder": cc.SurfaceKind.Cylinder,
    "Cone": cc.SurfaceKind.Cone,
    "Sphere": cc.SurfaceKind.Sphere,
    "Toroid": cc.SurfaceKind.Torus,
}


def split_shaft(radius=10.0, height=30.0):
    """A shaft whose faces are split the way Booleans leave them: the halves
    x < 0 and x > 0 of a cylinder fused back without refining. FreeCAD's
    cylinder has its seam at +X, so the half x > 0 is itself in two faces:
    the lateral surface comes in 3 faces, the end discs in 2 each."""
    shaft = Part.makeCylinder(radius, height)
    big = 4 * radius
    left = shaft.common(Part.makeBox(big, 2 * big, 2 * height, FreeCAD.Vector(-big, -big, -height)))
    right = shaft.common(Part.makeBox(big, 2 * big, 2 * height, FreeCAD.Vector(0, -big, -height)))
    fused = left.fuse(right)
    assert len(fused.Solids) == 1
    return fused


def kinked_block(angle):
    """A block whose top is two planar faces meeting at `angle` radians."""
    rise = 10 * math.tan(angle)
    profile = Part.makePolygon([FreeCAD.Vector(*p) for p in
                                [(0, 0, 0), (20, 0, 0), (20, 0, 10 + rise), (10, 0, 10), (0, 0, 10), (0, 0, 0)]])
    return Part.Face(profile).extrude(FreeCAD.Vector(0, 15, 0))


def test_split_shaft_gives_one_cylinder_partition_like_remove_splitter():
    shape = split_shaft()
    assert len(shape.Faces) == 7
    result = cc.partition_brep(shape.exportBrepToString())
    assert result.ok, result.status
    assert len(result.faces) == 7
    # FreeCAD's removeSplitter (OCCT UnifySameDomain) merges the same faces.
    assert len(result.partitions) == len(shape.removeSplitter().Faces) == 3
    cylinders = [p for p in result.partitions if p.params.kind == cc.SurfaceKind.Cylinder]
    assert len(cylinders) == 1
    cylinder = cylinders[0]
    assert len(cylinder.faces) == 3
    assert cylinder.side == cc.MaterialSide.Convex
    assert cylinder.params.radius == pytest.approx(10, abs=1e-9)
    assert cylinder.area == pytest.approx(2 * math.pi * 10 * 30, rel=1e-9)
    assert cylinder.extent.angular_span == pytest.approx(2 * math.pi)
    assert cylinder.extent.angular == [(0.0, pytest.approx(2 * math.pi))]
    assert cylinder.extent.axial_max - cylinder.extent.axial_min == pytest.approx(30)
    assert cylinder.face_names == ["Face%d" % i for i in cylinder.faces]
    # Every face in exactly one partition.
    covered = sorted(i for p in result.partitions for i in p.faces)
    assert covered == list(range(1, 8))
    # The end discs: two half-disc loops each, counter-clockwise (positive area).
    for plane in (p for p in result.partitions if p.params.kind == cc.SurfaceKind.Plane):
        assert len(plane.extent.outline) == 2
        area = 0.0
        for loop in plane.extent.outline:
            area += 0.5 * sum(x0 * y1 - x1 * y0 for (x0, y0), (x1, y1) in zip(loop, loop[1:] + loop[:1]))
        assert area == pytest.approx(math.pi * 100, rel=1e-4)


def test_face_numbers_follow_freecad_shape_faces():
    # Every surface kind, through Booleans, so faces come in a non-trivial order.
    body = Part.makeBox(40, 40, 20, FreeCAD.Vector(-20, -20, 0))
    body = body.cut(Part.makeCylinder(5, 30, FreeCAD.Vector(10, 10, -5)))
    body = body.fuse(Part.makeCone(10, 4, 10, FreeCAD.Vector(0, 0, 20)))
    body = body.fuse(Part.makeSphere(6, FreeCAD.Vector(-12, -12, 20)))
    body = body.cut(Part.makeTorus(12, 2, FreeCAD.Vector(0, 0, 0)))
    result = cc.partition_brep(body.exportBrepToString())
    assert result.ok
    assert len(result.faces) == len(body.Faces)
    kinds = set()
    for info, face in zip(result.faces, body.Faces):
        assert info.name == "Face%d" % info.index
        assert info.area == pytest.approx(face.Area, rel=1e-6), info.name
        assert body.getElement(info.name).isSame(face)
        expected = FREECAD_KINDS.get(type(face.Surface).__name__, cc.SurfaceKind.Other)
        assert info.params.kind == expected, info.name
        kinds.add(info.params.kind)
    assert kinds == set(FREECAD_KINDS.values())


@pytest.mark.skipif(not os.path.isdir(SHARED_STEP), reason="shared test data (../shared/data) not found")
def test_face_numbers_match_on_a_real_assembly():
    shape = Part.read(os.path.join(SHARED_STEP, "R08_presse_asm.step"))
    solid = max(shape.Solids, key=lambda s: len(s.Faces))
    result = cc.partition_brep(solid.exportBrepToString())
    assert [round(f.area, 6) for f in result.faces] == [round(f.Area, 6) for f in solid.Faces]


def test_reprs_are_readable():
    result = cc.partition_brep(split_shaft().exportBrepToString())
    cylinder = next(p for p in result.partitions if p.params.kind == cc.SurfaceKind.Cylinder)
    assert re.fullmatch(r"<Partition \d+ Cylinder r=10 convex faces=\[Face\d+, Face\d+, Face\d+\] area=1885>",
                        repr(cylinder))
    assert re.fullmatch(r"<BodyPartitions faces=7 partitions=3 ok>", repr(result))
    half = next(result.faces[i - 1] for i in cylinder.faces if result.faces[i - 1].extent.angular_span > 3)
    assert re.fullmatch(r"<FaceInfo Face\d+ Cylinder r=10 convex area=942\.5>", repr(half))
    assert repr(half.extent) == "<Extent axial=[0, 30] span=180deg>"
    assert repr(cylinder.params).startswith("<SurfaceParams Cylinder r=10 location=(")
    plane = next(f for f in result.faces if f.params.kind == cc.SurfaceKind.Plane)
    assert re.fullmatch(r"<FaceInfo Face\d+ Plane n=\(0, 0, -?1\) area=157\.1>", repr(plane))
    assert re.fullmatch(r"<Extent outline loops=1 points=\d+>", repr(plane.extent))
    assert repr(cc.Tolerances(linear=0.01, angular=0.002)) == "<Tolerances linear=0.01 angular=0.002>"


def test_values_cross_as_python_types():
    result = cc.partition_brep(Part.makeSphere(7, FreeCAD.Vector(1, 2, 3)).exportBrepToString())
    sphere = result.partitions[0]
    assert sphere.params.kind == cc.SurfaceKind.Sphere
    assert sphere.params.location == pytest.approx((1, 2, 3))
    assert isinstance(sphere.params.axis, tuple) and len(sphere.params.axis) == 3
    assert sphere.area == pytest.approx(4 * math.pi * 49, rel=1e-9)
    # The box holds the ball, with a margin of a few micrometres at most.
    exact = (-6, -5, -4, 8, 9, 10)
    assert all(b <= e for b, e in zip(sphere.box[:3], exact[:3]))
    assert all(b >= e for b, e in zip(sphere.box[3:], exact[3:]))
    assert sphere.box == pytest.approx(exact, abs=0.01)
    assert sphere.extent.outline == []
    assert all(isinstance(interval, tuple) and len(interval) == 2 for interval in sphere.extent.angular)
    box_face = cc.partition_brep(Part.makeBox(1, 2, 3).exportBrepToString()).faces[0]
    loop = box_face.extent.outline[0]
    assert isinstance(loop, list) and all(isinstance(p, tuple) and len(p) == 2 for p in loop)
    assert box_face.recognised is False and box_face.max_deviation == 0


def test_tolerance_arguments_control_merging():
    block = kinked_block(5e-4)  # two top faces 5e-4 rad apart
    brep = block.exportBrepToString()
    default = cc.partition_brep(brep)
    loose = cc.partition_brep(brep, linear=0.01, angular=1e-3)
    angular_only = cc.partition_brep(brep, angular=1e-3)  # the linear default still keeps them apart
    assert len(default.partitions) == len(block.Faces)
    assert len(loose.partitions) == len(block.Faces) - 1
    assert len(angular_only.partitions) == len(block.Faces)


def test_tolerances_class_and_defaults():
    tol = cc.Tolerances(linear=0.02, angular=0.001)
    assert (tol.linear, tol.angular) == (0.02, 0.001)
    tol.linear = 0.5
    assert tol.linear == 0.5
    assert cc.Tolerances().angular == pytest.approx(1e-4)
    default = cc.default_tolerances(0, 0, 0, 300, 400, 0)  # diagonal 500
    assert default.linear == pytest.approx(5e-3)
    assert default.angular == pytest.approx(1e-4)
    assert cc.default_tolerances(0, 0, 0, 1e7, 0, 0).linear == pytest.approx(100)  # no ceiling
    assert cc.default_tolerances(0, 0, 0, 1e-3, 0, 0).linear == pytest.approx(1e-8)  # no floor


def test_bad_brep_string_raises_contacts_error():
    with pytest.raises(cc.ContactsError, match="unreadable BRep"):
        cc.partition_brep("this is not a BRep")
    with pytest.raises(RuntimeError):  # ContactsError is a RuntimeError
        cc.partition_brep("")


def test_shape_without_faces_reports_status():
    edge = Part.makeLine(FreeCAD.Vector(0, 0, 0), FreeCAD.Vector(1, 0, 0))
    result = cc.partition_brep(edge.exportBrepToString())
    assert not result.ok
    assert "no faces" in result.status
    assert result.faces == [] and result.partitions == []
