"""Contact annotations in a FreeCAD document, headless
(contactwb.make.annotate_contacts): the Intent and Fit properties, one undo
step named "Annotate contact", the joints derived again, kept when the
contact is found again (also after being lost), saved with the document.
The GUI's way in: tests/gui/test_gui_annotations.py."""
import pytest

import FreeCAD
from contactwb import core
from contactwb.make import annotate_contacts
from contactwb.objects.contact_objects import is_contact, is_joint

from contacts_document import build_contacts_document


@pytest.fixture
def doc():
    # A plate bored r 5 with a shaft through it (one CLJ, a cylindrical
    # joint) and a block on the plate (one PLF, planar).
    doc = build_contacts_document("AnnotatedDoc")
    doc.UndoMode = 1
    name = doc.Name
    yield doc
    if name in FreeCAD.listDocuments():
        FreeCAD.closeDocument(name)


def parts(doc):
    group = doc.getObject("Contacts")
    (clj,) = [c for c in group.Group if is_contact(c) and c.ContactType == "CLJ"]
    (plf,) = [c for c in group.Group if is_contact(c) and c.ContactType == "PLF"]
    joints = {(j.BodyA, j.BodyB): j.JointType for j in group.Group if is_joint(j)}
    return group, clj, plf, joints


def test_annotating_makes_the_pair_rigid_in_one_undo_step(doc):
    group, clj, plf, joints = parts(doc)
    assert joints == {("Plate", "Shaft"): "cylindrical", ("Plate", "Block"): "planar"}
    assert (clj.Intent, clj.Fit, clj.FitClass) == ("none", "", "")
    undo_before = len(doc.UndoNames)
    # Ø10 H7/p6 (6-10 mm): hole 0/+15, shaft +15/+24: clearance -24..0, interference.
    annotate_contacts([clj], "interference", "H7/p6")
    assert doc.UndoNames[0] == "Annotate contact" and len(doc.UndoNames) == undo_before + 1
    group, clj, plf, joints = parts(doc)
    assert (clj.Intent, clj.Fit) == ("interference", "H7/p6")
    assert clj.FitClass == "interference at diameter 10 mm: clearance -24 to 0 \u00b5m"
    assert joints == {("Plate", "Shaft"): "rigid", ("Plate", "Block"): "planar"}
    assert group.Mobility[1].startswith("Degrees of freedom: 3 (0 passive spins):")
    doc.undo()
    group, clj, plf, joints = parts(doc)
    assert (clj.Intent, clj.Fit) == ("none", "")
    assert joints == {("Plate", "Shaft"): "cylindrical", ("Plate", "Block"): "planar"}
    doc.redo()
    assert parts(doc)[3][("Plate", "Shaft")] == "rigid"


def test_ignored_contact_leaves_the_joints(doc):
    group, clj, plf, joints = parts(doc)
    annotate_contacts([plf], "ignored")
    group, clj, plf, joints = parts(doc)
    assert plf.Intent == "ignored" and ("Plate", "Block") not in joints


def test_refused_annotations_change_nothing(doc):
    group, clj, plf, joints = parts(doc)
    undo_before = len(doc.UndoNames)
    with pytest.raises(core.ArgumentError, match=r"contact 'CLJ \d+: Plate \u2013 Shaft': fit H7/g6 at diameter "
                                                 r"10 mm is a clearance fit"):
        annotate_contacts([clj], "interference", "H7/g6")
    with pytest.raises(core.ArgumentError, match="needs a cylindrical contact"):
        annotate_contacts([plf], "clearance", "H7/g6")
    with pytest.raises(core.ArgumentError, match="unknown intent 'glued'"):
        annotate_contacts([clj], "glued")
    with pytest.raises(core.ArgumentError, match="shaft letter 'x' is not covered"):
        annotate_contacts([clj], "interference", "H7/x6")
    with pytest.raises(core.ArgumentError, match="needs an intent other than ignored"):
        annotate_contacts([clj], "ignored", "H7/g6")
    assert len(doc.UndoNames) == undo_before
    assert (clj.Intent, clj.Fit) == ("none", "")


def test_kept_after_a_recompute_when_lost_and_found_again_and_saved(doc, tmp_path):
    group, clj, plf, joints = parts(doc)
    annotate_contacts([clj], "bonded")
    annotate_contacts([plf], "clearance")
    # a plain recompute finds the contacts again: same objects, same annotations
    group.touch()
    doc.recompute()
    group, clj, plf, joints = parts(doc)
    assert (clj.Intent, plf.Intent) == ("bonded", "clearance") and joints[("Plate", "Shaft")] == "rigid"
    # the shaft moved away: its contact is gone; moved back: found again as a new object, annotated
    shaft = doc.getObject("Shaft")
    placement = shaft.Placement
    shaft.Placement = FreeCAD.Placement(FreeCAD.Vector(200, 0, 0), placement.Rotation)
    doc.recompute()
    assert [c.ContactType for c in group.Group if is_contact(c)] == ["PLF"]
    shaft.Placement = placement
    doc.recompute()
    group, clj, plf, joints = parts(doc)
    assert clj.Intent == "bonded" and joints[("Plate", "Shaft")] == "rigid"
    path = str(tmp_path / "annotated.FCStd")
    doc.saveAs(path)
    FreeCAD.closeDocument(doc.Name)
    reopened = FreeCAD.openDocument(path)
    try:
        group, clj, plf, joints = parts(reopened)
        assert (clj.Intent, plf.Intent) == ("bonded", "clearance")
        group.touch()
        reopened.recompute()
        group, clj, plf, joints = parts(reopened)
        assert (clj.Intent, plf.Intent) == ("bonded", "clearance") and joints[("Plate", "Shaft")] == "rigid"
    finally:
        FreeCAD.closeDocument(reopened.Name)


def test_threaded_intent_is_rigid_takes_no_fit_and_older_documents_get_the_choice(doc):
    # "threaded" (a screw in its thread): rigid in the joints like a bond; no ISO 286 fit.
    group, clj, plf, _ = parts(doc)
    annotate_contacts([clj], "threaded")
    _, clj, plf, joints = parts(doc)
    assert clj.Intent == "threaded" and joints[("Plate", "Shaft")] == "rigid"
    with pytest.raises(core.ArgumentError, match="a threaded contact has no fit"):
        annotate_contacts([clj], "threaded", "H7/g6")
    # A contact saved before "threaded" existed: its choices lack it; restoring adds it, the
    # contact's own intent kept.
    from contactwb.objects import contact_objects
    clj.Intent = "bonded"
    clj.Intent = ["none", "clearance", "transition", "interference", "bonded", "ignored"]
    clj.Intent = "bonded"
    contact_objects._annotation_properties(clj)
    assert list(clj.getEnumerationsOfProperty("Intent")) == contact_objects.INTENT_CHOICES
    assert clj.Intent == "bonded"
