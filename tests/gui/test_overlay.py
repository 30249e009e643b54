"""The contacts' Coin drawing (view_providers.ContactOverlay), built headless
from the bundled cases: circle contacts, partial contacts, per-body and
per-contact switches. (The GUI session checks it on screen.)"""
import pytest

import FreeCAD
import Part

from contactwb.make import make_contact_analysis

coin = pytest.importorskip("pivy.coin")
view_providers = pytest.importorskip("contactwb.gui.view_providers")


def nodes(root, node_type):
    """Distinct nodes of a type under root, whatever the switches show."""
    search = coin.SoSearchAction()
    search.setType(node_type.getClassTypeId())
    search.setInterest(coin.SoSearchAction.ALL)
    search.setSearchingAll(True)
    search.apply(root)
    found = {}
    for path in search.getPaths():
        found[int(path.getTail().this)] = path.getTail()
    return list(found.values())


def layer(overlay, name):
    (node,) = [n for n in nodes(overlay.root, coin.SoSeparator) if n.getName().getString() == name]
    return node


@pytest.fixture
def drawn(sample):
    """(document, group, overlay) of a bundled case."""
    opened = []

    def draw(name):
        doc = FreeCAD.openDocument(sample(f"cases/{name}.FCStd"))
        opened.append(doc.Name)
        group = make_contact_analysis(doc)
        overlay = view_providers.ContactOverlay(doc.Name)
        overlay.build(group.Group)
        return doc, group, overlay
    yield draw
    for name in opened:
        FreeCAD.closeDocument(name)


def test_ball_in_bore_gets_its_contact_circle(drawn):
    _, group, overlay = drawn("ball_in_bore")
    (contact,) = group.Group
    assert contact.ContactType == "LAF"
    assert overlay.circles == 1
    assert [n.getName().getString() for n in nodes(overlay.root, coin.SoSeparator)
            if n.getName().getString().startswith("Contacts_")] == ["Contacts_LAF"]
    (lines,) = nodes(overlay.root, coin.SoLineSet)
    assert lines.numVertices.getValues() == [view_providers.CIRCLE_SEGMENTS + 1]
    circle = [c for c in nodes(overlay.root, coin.SoCoordinate3) if c.point.getNum() == 97]
    centre, axis, radius = contact.Point, contact.Direction, contact.Radius.Value
    for x, y, z in circle[0].point.getValues():
        offset = FreeCAD.Vector(x, y, z) - centre
        assert offset.Length == pytest.approx(radius, rel=1e-5)
        assert abs(offset.dot(axis)) < 1e-4 * radius  # in the plane across the bore
    # the ball and the bore are drawn too, see-through behind the circle
    assert overlay.triangles > 0
    material = layer(overlay, "Contacts_LAF").getChild(0)
    assert material.transparency.getValues()[0] == pytest.approx(view_providers.CIRCLE_FACE_TRANSPARENCY)


def test_bearing_balls_get_one_circle_per_groove_contact(drawn):
    _, group, overlay = drawn("ball_bearing")
    assert overlay.circles == sum(c.ContactType == "SPT" for c in group.Group) == 16
    assert len(nodes(overlay.root, coin.SoLineSet)) == 16


def test_partial_contact_is_lighter_and_striped(drawn):
    _, group, overlay = drawn("cradle_120")
    (contact,) = group.Group
    assert contact.Partial
    partial = layer(overlay, "Contacts_CLJ_partial")
    material = partial.getChild(0)
    full, light = view_providers.rgb(view_providers.TYPE_COLOURS["CLJ"]), view_providers.type_colour("CLJ", True)
    assert all(b >= a for a, b in zip(full, light)) and sum(light) > sum(full) + 0.5  # towards white
    emissive = material.emissiveColor.getValues()[0].getValue()
    assert emissive == pytest.approx([0.6 * c for c in light], abs=1e-6)
    assert len(nodes(partial, coin.SoTexture2)) == 1
    (stripes,) = nodes(partial, coin.SoTextureCoordinatePlane)
    period = 1.0 / stripes.directionS.getValue().length()
    assert 0 < period < group.Group[0].Radius.Value * 4  # many stripes across the contact


def test_full_contacts_have_the_legend_colour_and_no_stripes(drawn):
    _, _, overlay = drawn("pin_block")
    for node in nodes(overlay.root, coin.SoSeparator):
        name = node.getName().getString()
        if name.startswith("Contacts_"):
            kind = name.split("_")[1]
            emissive = node.getChild(0).emissiveColor.getValues()[0].getValue()
            assert emissive == pytest.approx([0.6 * c for c in view_providers.rgb(view_providers.TYPE_COLOURS[kind])],
                                             abs=1e-6)
            assert not nodes(node, coin.SoTexture2)


def test_switches_follow_contacts_bodies_and_selection(drawn):
    _, group, overlay = drawn("pin_block")
    contact = group.Group[0]
    switch = overlay.switches[contact.Name]
    assert switch.whichChild.getValue() == 0
    overlay.highlight({contact.Name}, set())
    assert switch.whichChild.getValue() == 1
    faces = overlay.face_keys[contact.Name]
    overlay.highlight(set(), set(list(faces)[:1]) if len(faces) > 1 else set())
    assert switch.whichChild.getValue() == 0  # some faces selected: not the contact
    overlay.highlight(set(), set(faces))
    assert switch.whichChild.getValue() == 1  # all of its faces: the contact
    overlay.set_visible(contact.Name, False)
    assert switch.whichChild.getValue() == coin.SO_SWITCH_NONE
    overlay.set_visible(contact.Name, True)
    # hiding body A hides side A only
    side_a, side_b = overlay.sides[contact.Name][:2]
    (root_a, _), = [(r, s) for r, s in contact.FacesA]
    root_a.Visibility = False
    overlay.update_bodies()
    assert side_a[0].whichChild.getValue() == coin.SO_SWITCH_NONE
    assert side_b[0].whichChild.getValue() == coin.SO_SWITCH_ALL
    root_a.Visibility = True
    overlay.update_bodies()
    assert side_a[0].whichChild.getValue() == coin.SO_SWITCH_ALL


def test_faces_are_pushed_out_of_their_body(drawn):
    _, group, _ = drawn("pin_block")
    source = view_providers.FaceSource()
    for contact in group.Group:
        for root, subnames in contact.FacesA:
            for subname in subnames:
                points, _, _ = source.mesh(root, subname)
                solid = root.Shape
                for x, y, z in points[:: max(1, len(points) // 20)]:
                    # outside the body, by about the tessellation's deflection
                    assert not solid.isInside(FreeCAD.Vector(x, y, z), 1e-9, True)
                    assert solid.distToShape(Part.Vertex(x, y, z))[0] < 0.005 * solid.BoundBox.DiagonalLength
