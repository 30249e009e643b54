"""The core's bodies kept between an analysis' recomputes (issue 21's
recompute target): contactcore.assembly_of_bodies gathers Body objects read
before into the Assembly bodies_from_brep gives for their compound, and
contactwb.document.shapes.CoreBodyCache passes only the moved and changed
bodies' BRep text (with every body sharing their geometry). Each recompute
is checked against a fresh analysis of the same document, read from nothing:
the same contacts with the same areas, points and directions to the last
bit, the same bodies' volumes and centres, the same interferences."""
import json
import os

import pytest

import FreeCAD
import Part

from contactwb import core
from contactwb.document.shapes import assembly_from_shapes
from contactwb.make import make_contact_analysis, update_contact_analysis
from contactwb.objects import regions
from contactwb.objects.contact_objects import is_contact
from contactwb.document.identify import is_interference, is_interference_group
from headless_helpers import motor_shapes, three_boxes

from conftest import SAMPLES

cc = core.contactcore


def raw_contacts(result):
    """Everything find_contacts says of each contact, exactly."""
    return [(c.type_name, c.body_a, c.body_b, tuple(c.faces_a), tuple(c.faces_b), c.area, c.radius, c.span,
             c.half_angle, c.partial, tuple(c.point), tuple(c.direction)) for c in result.contacts]


def test_assembly_of_bodies_is_the_compound_read():
    """Bodies from two reads (the first twelve of a whole read, the rest read
    on their own) gathered: the names, the shapes' BRep text and the contacts
    of the one read of the whole compound, to the last bit."""
    named = motor_shapes()
    whole = assembly_from_shapes(named)
    rest = assembly_from_shapes(named[12:])
    gathered = cc.assembly_of_bodies(list(whole.bodies[:12]) + list(rest.bodies), [n for n, _ in named])
    assert [b.name for b in gathered.bodies] == [b.name for b in whole.bodies] == [n for n, _ in named]
    assert [b.brep for b in gathered.bodies] == [b.brep for b in whole.bodies]
    assert gathered.units == "mm" and gathered.source_unit_in_mm == 1.0 and list(gathered.messages) == []
    expected, found = cc.find_contacts(whole), cc.find_contacts(gathered)
    assert len(expected.contacts) == 35
    assert raw_contacts(found) == raw_contacts(expected)
    assert [(i.body_a, i.body_b, i.volume) for i in found.interferences] == \
        [(i.body_a, i.body_b, i.volume) for i in expected.interferences]


def test_assembly_of_bodies_names_and_refusals():
    """Named in order and made unique as bodies_from_brep names them; a count
    that differs is an ArgumentError (a value inside the core, raised at the
    binding)."""
    box = Part.makeBox(1, 2, 3)
    read = assembly_from_shapes([("a", box)])
    twice = cc.assembly_of_bodies([read.bodies[0], read.bodies[0]], ["Plate", "Plate"])
    assert [b.name for b in twice.bodies] == ["Plate", "Plate.2"]
    assert [b.path for b in twice.bodies] == ["Plate", "Plate"]
    assert twice.bodies[1].volume == pytest.approx(6.0)
    with pytest.raises(core.ContactsError, match="2 bodies but 1 names"):
        cc.assembly_of_bodies([read.bodies[0], read.bodies[0]], ["Plate"])
    assert len(cc.assembly_of_bodies([], [])) == 0


def everything(result):
    """All of a find_contacts result a caller reads, exactly."""
    return {"contacts": raw_contacts(result),
            "regions": [(c.has_region, c.region_area if c.has_region else 0.0) for c in result.contacts],
            "higher": [(h.type, h.kind, h.body_a, h.body_b, h.partition_a, h.partition_b, tuple(h.faces_a),
                        tuple(h.faces_b), tuple(h.point), tuple(h.normal), tuple(h.start), tuple(h.end))
                       for h in result.higher_pairs],
            "interferences": [(i.body_a, i.body_b, i.volume, i.has_solid) for i in result.interferences],
            "pairs": list(result.body_pairs), "candidates": result.candidates, "messages": list(result.messages),
            "partitions": [[(p.id, tuple(p.faces)) for p in b.partitions] for b in result.partitions],
            "tolerances": (result.tolerances.linear, result.tolerances.angular),
            "invalid": [(b.body, tuple(b.faces), b.reason) for b in result.invalid_bodies],
            "regions_computed": result.regions_computed}


def test_memo_reuses_the_unchanged_bodies_search_and_finds_what_a_fresh_search_finds():
    """find_contacts(memo=...) on the motor with Back-cover moved 40 mm off
    (its Body read again, the 17 others the same Body objects): the 17
    bodies' partitions and solid checks, the candidate tests and the point
    and line contacts of every body pair without Back-cover are the last run's, and the result
    is a fresh search's on the whole compound read anew, to the last bit.
    Nothing changed: every body's and pair's reused. Other tolerances:
    nothing reused. Two bodies that trade places: neither reused."""
    named = motor_shapes()
    names = [n for n, _ in named]
    cover = names.index("Back-cover")
    whole = assembly_from_shapes(named)
    memo = cc.ContactsMemo()
    assert memo.bodies == 0
    first = cc.find_contacts(whole, regions=True, memo=memo)
    assert everything(first) == everything(cc.find_contacts(whole, regions=True))
    assert (memo.bodies, memo.reused_bodies, memo.reused_tested_pairs, memo.reused_higher_pairs) == (18, 0, 0, 0)

    moved_shape = named[cover][1].copy()
    moved_shape.translate(FreeCAD.Vector(0, 0, -40))
    moved_named = [(n, moved_shape if i == cover else s) for i, (n, s) in enumerate(named)]
    moved_read = assembly_from_shapes([moved_named[cover]])
    gathered = cc.assembly_of_bodies(
        [moved_read.bodies[0] if i == cover else b for i, b in enumerate(whole.bodies)], names)
    second = cc.find_contacts(gathered, regions=[cover], memo=memo)
    fresh = cc.find_contacts(assembly_from_shapes(moved_named), regions=[cover])
    assert everything(second) == everything(fresh)
    assert len(second.contacts) == 28 and len(first.contacts) == 35
    unchanged_pairs = [p for p in second.body_pairs if cover not in p]
    assert memo.reused_bodies == memo.reused_solid_checks == 17
    assert memo.reused_tested_pairs == memo.reused_higher_pairs == len(unchanged_pairs) == 44

    third = cc.find_contacts(gathered, memo=memo)  # nothing changed
    assert everything(third) == everything(cc.find_contacts(gathered))
    assert (memo.reused_bodies, memo.reused_tested_pairs, memo.reused_higher_pairs) == \
        (18, len(second.body_pairs), len(second.body_pairs))

    coarser = cc.find_contacts(gathered, linear=0.05, memo=memo)  # other tolerances: nothing reused
    assert everything(coarser) == everything(cc.find_contacts(gathered, linear=0.05))
    assert (memo.reused_bodies, memo.reused_tested_pairs, memo.reused_higher_pairs) == (0, 0, 0)

    cc.find_contacts(gathered, memo=memo)
    swapped = list(gathered.bodies)  # two bodies trade places: neither is the same body at its index
    swapped[0], swapped[1] = swapped[1], swapped[0]
    reordered = cc.assembly_of_bodies(swapped, [names[1], names[0]] + names[2:])
    assert everything(cc.find_contacts(reordered, memo=memo)) == everything(cc.find_contacts(reordered))
    assert memo.reused_bodies == 16


def snapshot(group):
    """What an analysis holds, apart from its numbering: every contact's
    figures exactly, the bodies' table, the summaries, the interferences."""
    contacts = sorted((c.ContactType, c.BodyA, c.BodyB, tuple(s for _, subs in c.FacesA for s in subs),
                       tuple(s for _, subs in c.FacesB for s in subs), c.Area.Value, c.Radius.Value, c.Span.Value,
                       c.HalfAngle.Value, c.Partial, tuple(c.Point), tuple(c.Direction))
                      for c in group.Group if is_contact(c))
    overlaps = sorted((o.BodyA, o.BodyB, o.Volume.Value, o.Shape.Volume) for g in group.Group
                      if is_interference_group(g) for o in g.Group if is_interference(o))
    return {"contacts": contacts, "bodies": json.loads(group.BodyTable), "summary": list(group.Summary),
            "pairs": list(group.PairSummary), "messages": list(group.Messages), "interferences": overlaps}


def fresh_snapshot(doc):
    """The snapshot of a new analysis of the whole document (its own caches,
    empty: every body read from BRep text), removed afterwards."""
    other = make_contact_analysis(doc)
    assert regions.cache_of(other).core_bodies.crossed == [b["name"] for b in json.loads(other.BodyTable)]
    taken = snapshot(other)
    regions.forget(other)
    for child in list(other.Group):
        for grandchild in list(getattr(child, "Group", [])):
            doc.removeObject(grandchild.Name)
        doc.removeObject(child.Name)
    doc.removeObject(other.Name)
    return taken


@pytest.fixture
def motor_doc():
    doc = FreeCAD.openDocument(os.path.join(SAMPLES, "motor.FCStd"))
    doc.UndoMode = 1
    yield doc
    FreeCAD.closeDocument(doc.Name)


def test_motor_move_undo_redo_reads_only_the_moved_part(motor_doc):
    """Back-cover moved 40 mm off, the move undone, redone: each recompute
    reads Back-cover alone from BRep text, the other 17 bodies are the core
    bodies of the last recompute, and the analysis is the one a fresh
    analysis finds, exactly (35 contacts in place, 28 when moved off)."""
    doc = motor_doc
    group = make_contact_analysis(doc)
    cache = regions.cache_of(group).core_bodies
    assert len(cache.crossed) == 18
    home = snapshot(group)
    assert len(home["contacts"]) == 35 and home == fresh_snapshot(doc)
    cover = doc.getObjectsByLabel("Back-cover")[0]
    home_z = cover.Placement.Base.z
    doc.openTransaction("Move Back-cover")
    cover.Placement = FreeCAD.Placement(cover.Placement.Base + FreeCAD.Vector(0, 0, -40), cover.Placement.Rotation)
    doc.commitTransaction()
    doc.recompute()
    assert group.OutOfDate is False and cache.crossed == ["Back-cover"]
    moved = snapshot(group)
    assert len(moved["contacts"]) == 28
    # (the fresh analyses come after the undo and redo: their objects stay out of the undo stack's way)
    doc.undo()
    assert cover.Placement.Base.z == pytest.approx(home_z)
    doc.recompute()
    assert cache.crossed == ["Back-cover"]
    assert snapshot(group) == home
    doc.redo()
    assert cover.Placement.Base.z == pytest.approx(home_z - 40)
    doc.recompute()
    assert cache.crossed == ["Back-cover"]
    assert snapshot(group) == moved == fresh_snapshot(doc)
    update_contact_analysis(group)  # nothing changed: nothing crosses
    assert cache.crossed == [] and snapshot(group) == moved


@pytest.fixture
def boxes():
    yield from three_boxes("BodyCache", labels=True)


def test_boxes_shape_edits_instances_and_deletes(boxes):
    """A shape edited (not moved) crosses alone; a body sharing its geometry
    with another (an instance) crosses with it, and with its former
    partners when its shape changes; a body deleted makes every body cross.
    Each time the analysis is a fresh one's, exactly."""
    doc = boxes
    copy = doc.addObject("Part::Feature", "Copy")
    copy.Label = "Copy"
    copy.Shape = doc.getObject("Base").Shape
    copy.Placement = FreeCAD.Placement(FreeCAD.Vector(0, 10, 0), FreeCAD.Rotation())  # against Base: PLF 100
    doc.recompute()
    group = make_contact_analysis(doc)
    cache = regions.cache_of(group).core_bodies
    assert cache.crossed == ["Base", "Top", "Side", "Copy"]
    assert snapshot(group) == fresh_snapshot(doc)
    # Side's shape edited: its BRep alone, its PLF with Base grows to 10 x 10 still, its volume 1200
    doc.getObject("Side").Length = 12
    doc.recompute()
    assert cache.crossed == ["Side"]
    taken = snapshot(group)
    assert taken == fresh_snapshot(doc)
    assert taken["bodies"][2]["volume"] == pytest.approx(1200.0)
    # Top moved over Base's edge: on Base 4 x 4, on Side 2 x 4
    top = doc.getObject("Top")
    top.Placement = FreeCAD.Placement(FreeCAD.Vector(6, 3, 10), FreeCAD.Rotation())
    doc.recompute()
    assert cache.crossed == ["Top"]
    taken = snapshot(group)
    assert taken == fresh_snapshot(doc)
    assert [(c[1], c[2], c[5]) for c in taken["contacts"] if "Top" in (c[1], c[2])] == \
        [("Base", "Top", pytest.approx(16.0)), ("Top", "Side", pytest.approx(8.0))]
    # Copy (Base's geometry) moved: Copy and Base cross together (one OCCT shape in the core too)
    copy.Placement = FreeCAD.Placement(FreeCAD.Vector(0, -10, 0), FreeCAD.Rotation())
    doc.recompute()
    assert cache.crossed == ["Base", "Copy"]
    assert snapshot(group) == fresh_snapshot(doc)
    # Base's shape edited: it no longer shares Copy's, both cross (Copy its
    # former partner); 0.5 mm higher, it overlaps Top (an interference, 8 mm3)
    doc.getObject("Base").Height = 10.5
    doc.recompute()
    assert not copy.Shape.isPartner(doc.getObject("Base").Shape)
    assert cache.crossed == ["Base", "Copy"]
    taken = snapshot(group)
    assert taken == fresh_snapshot(doc)
    assert [(a, b, v) for a, b, v, _ in taken["interferences"]] == [("Base", "Top", pytest.approx(8.0))]
    # Side deleted: the bodies are not the same list, every body crosses
    doc.removeObject("Side")
    doc.recompute()
    assert cache.crossed == ["Base", "Top", "Copy"]
    taken = snapshot(group)
    assert taken == fresh_snapshot(doc) and len(taken["bodies"]) == 3
