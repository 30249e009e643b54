"""The common regions the core computes for the paint (Contact.region_brep,
region_mesh; find_contacts(regions=...)): each region's area equals the
brute-force Boolean of its faces (FreeCAD's Part common of every face pair
of the contact, as tests/bruteforce_contacts.py measures them) and the
contact's area; its faces point out of body A; hand-made cases have exact
areas; only the contacts of the bodies asked for are computed."""
import glob
import math
import os

import pytest

import FreeCAD  # noqa: F401  (before Part)
import Part

from contactwb import core
from contactwb.core.kinds import CIRCLE_TYPES
from contactwb.document.shapes import assembly_from_shapes

from conftest import SAMPLES

cc = core.contactcore
CASES = sorted(os.path.basename(p) for p in glob.glob(os.path.join(SAMPLES, "cases", "*.step")))


def shape_of(text):
    shape = Part.Shape()
    shape.importBrepFromString(text)
    return shape


def boolean_area(body_a, body_b, contact):
    """The brute-force checker's measure: Part's common of every face pair."""
    area = 0.0
    for fa in contact.faces_a:
        for fb in contact.faces_b:
            common = body_a.Faces[fa - 1].common(body_b.Faces[fb - 1])
            area += sum(face.Area for face in common.Faces)
    return area


def outward_of_a(region, solid_a):
    """Whether every region face's normal (its orientation applied) points
    out of body A: a point a little along it lies outside A's solid."""
    step = 1e-3 * max(solid_a.BoundBox.DiagonalLength, 1.0)
    for face in region.Faces:
        u0, u1, v0, v1 = face.ParameterRange
        u, v = (u0 + u1) / 2, (v0 + v1) / 2
        point = face.valueAt(u, v)
        normal = face.normalAt(u, v)  # orientation applied
        if face.isInside(point, 1e-6, True) is False:
            continue  # the middle of the range may fall in a hole
        if solid_a.isInside(point + normal * step, 1e-9, False):
            return False
    return True


def check_regions(assembly, result):
    bodies = [shape_of(b.brep) for b in assembly.bodies]
    checked = 0
    for contact in result.contacts:
        if contact.type_name in CIRCLE_TYPES:
            assert not contact.has_region  # a circle: drawn as one
            continue
        assert contact.has_region and contact.region_faces > 0, contact
        region = shape_of(contact.region_brep)
        expected = boolean_area(bodies[contact.body_a], bodies[contact.body_b], contact)
        # as the area oracle (tests/test_area_oracle.py): a face taken whole
        # where it lies on the other within a band of tolerance width
        tolerance = max(1e-3 * expected, 1e-3)
        assert region.Area == pytest.approx(expected, abs=tolerance), contact
        assert contact.region_area == pytest.approx(region.Area, rel=1e-9)
        # the contact's area is the typed surface's (a B-spline face typed as a
        # cylinder: the fitted cylinder's, 0.27 % off in nurbs.step); the region
        # is the faces themselves
        assert contact.region_area == pytest.approx(contact.area, abs=max(5e-3 * contact.area, 1e-3))
        assert outward_of_a(region, bodies[contact.body_a]), contact
        points, triangles = contact.region_mesh(0.01 * math.sqrt(contact.area))
        assert points.shape[1] == 3 and triangles.shape[1] == 3 and len(triangles) > 0
        assert triangles.min() >= 0 and triangles.max() < len(points)
        checked += 1
    return checked


def test_motor_regions_are_the_boolean_common_of_their_faces(sample):
    assembly = cc.read_step(sample("motor.step"))
    result = cc.find_contacts(assembly, regions=True)
    assert len(result.contacts) == 35
    assert result.regions_computed == 35 + len(result.interferences)
    assert check_regions(assembly, result) == sum(1 for c in result.contacts if c.type_name not in CIRCLE_TYPES)


@pytest.mark.parametrize("name", CASES)
def test_case_regions_are_the_boolean_common_of_their_faces(sample, name):
    assembly = cc.read_step(sample(os.path.join("cases", name)))
    result = cc.find_contacts(assembly, regions=True)
    check_regions(assembly, result)
    for overlap in result.interferences:
        assert overlap.has_solid
        solid = shape_of(overlap.solid_brep)
        assert solid.Volume == pytest.approx(overlap.volume, rel=1e-6)


def test_cases_are_committed():
    assert len(CASES) >= 14


def hand_made():
    """A block on a plate (its whole bottom face, 10 x 10), a block half on
    the plate's edge (5 x 10 by a Boolean), a pin of radius 2 through a 5 mm
    plate's hole (2 pi 2 5) standing on a base."""
    plate = Part.makeBox(30, 20, 5)
    block = Part.makeBox(10, 10, 10, FreeCAD.Vector(2, 2, 5))
    overhang = Part.makeBox(10, 10, 10, FreeCAD.Vector(25, 5, 5))
    holed = Part.makeBox(20, 20, 5, FreeCAD.Vector(100, 0, 0)).cut(
        Part.makeCylinder(2, 5, FreeCAD.Vector(110, 10, 0)))
    pin = Part.makeCylinder(2, 30, FreeCAD.Vector(110, 10, -10))
    return [("Plate", plate), ("Block", block), ("Overhang", overhang), ("Holed", holed), ("Pin", pin)]


def test_hand_made_regions_have_exact_areas():
    named = hand_made()
    assembly = assembly_from_shapes(named)
    result = cc.find_contacts(assembly, regions=True)
    names = [n for n, _ in named]
    found = {(names[c.body_a], names[c.body_b], c.type_name): c for c in result.contacts}
    assert sorted(found) == [("Holed", "Pin", "CLJ"), ("Plate", "Block", "PLF"), ("Plate", "Overhang", "PLF")]
    exact = {("Plate", "Block", "PLF"): 100.0, ("Plate", "Overhang", "PLF"): 50.0,
             ("Holed", "Pin", "CLJ"): 2 * math.pi * 2 * 5}
    for key, area in exact.items():
        region = shape_of(found[key].region_brep)
        assert region.Area == pytest.approx(area, rel=1e-9), key
        assert found[key].region_area == pytest.approx(area, rel=1e-9), key
    # the block's whole bottom face, the overhang's half (a Boolean piece), the hole's face
    assert [found[k].region_faces for k in sorted(exact)] == [1, 1, 1]
    check_regions(assembly, result)


def test_regions_only_for_the_bodies_asked_for():
    """Moved or changed bodies only: the contacts touching them are computed,
    the others left null, and the count says so."""
    named = hand_made()
    assembly = assembly_from_shapes(named)
    result = cc.find_contacts(assembly, regions=[4])  # the pin
    assert result.regions_computed == 1
    assert [c.has_region for c in result.contacts if c.body_b == 4 or c.body_a == 4] == [True]
    assert not any(c.has_region for c in result.contacts if 4 not in (c.body_a, c.body_b))
    assert cc.find_common_regions(assembly, result, [0]) == 2  # the plate's two
    assert sum(c.has_region for c in result.contacts) == 3
    none = cc.find_contacts(assembly, regions=[])
    assert none.regions_computed == 0 and not any(c.has_region for c in none.contacts)
    with pytest.raises(core.ContactsError):
        cc.find_common_regions(assembly, result, [7])
