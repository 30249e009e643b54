"""Issue 21, headless: a contact keeps its object, name and number across
moves and recomputes (identity = body pair + partition pair); new contacts
get new numbers, never one given before; the undo history holds one entry
per action (no hidden "Delete" from a recompute), and undoing a recompute
also undoes the edit it followed; Find contacts on the same scope finds the
analysis to update."""
import pytest

import FreeCAD

from contactwb.core import extension  # noqa: F401  (FreeCAD set up, the extension found)
from contactwb.document.identify import is_contact, is_joint
from contactwb.make import analysis_of_scope, make_contact_analysis
from contactwb.objects.body_watcher import RECOMPUTE_TRANSACTION
from headless_helpers import three_boxes


@pytest.fixture
def boxes():
    """Base 10x10x10; Top 6x4x5 on it (PLF 24 mm2); Side 10x10x10 beside
    Base (PLF 100 mm2); undo on, as in the GUI."""
    yield from three_boxes("IdentityTest", undo=True, labels=True)


def state(group):
    """{(body A, body B): (object name, number, label)} of the group's contacts."""
    return {(c.BodyA, c.BodyB): (c.Name, c.Number, c.Label) for c in group.Group if is_contact(c)}


def find(doc, **options):
    doc.openTransaction("Find contacts")
    group = make_contact_analysis(doc, **options)
    doc.commitTransaction()
    return group


def test_identity_survives_a_move_and_new_contacts_get_new_numbers(boxes):
    group = find(boxes)
    before = state(group)
    assert sorted(n for _, n, _ in before.values()) == [1, 2]
    top = boxes.getObject("Top")
    boxes.openTransaction("Move Top")
    top.Placement.Base = FreeCAD.Vector(2, 3, 30)  # off the base: its contact vanishes
    boxes.commitTransaction()
    boxes.recompute()
    assert state(group) == {("Base", "Side"): before[("Base", "Side")]}
    boxes.openTransaction("Move Top")
    top.Placement.Base = FreeCAD.Vector(3, 3, 10)  # back on it, elsewhere: a new contact
    boxes.commitTransaction()
    boxes.recompute()
    after = state(group)
    assert after[("Base", "Side")] == before[("Base", "Side")]
    _, number, label = after[("Base", "Top")]
    assert number == 3 and label == "PLF 3: Base \u2013 Top"  # never a number given before
    boxes.openTransaction("Move Top")
    top.Placement.Base = FreeCAD.Vector(2, 3, 10)  # a move keeping the contact: the same object
    boxes.commitTransaction()
    boxes.recompute()
    after = state(group)
    assert after[("Base", "Top")][1:] == (3, "PLF 3: Base \u2013 Top")
    # a recompute with nothing changed keeps everything and records nothing
    undo = list(boxes.UndoNames)
    group.touch()
    boxes.recompute()
    assert state(group) == after and list(boxes.UndoNames) == undo


def test_two_analyses_never_share_numbers(boxes):
    first = find(boxes)
    second = find(boxes, objects=[boxes.getObject("Top"), boxes.getObject("Base")])
    before = state(first), state(second)
    assert sorted(n for _, n, _ in before[0].values()) == [1, 2]
    assert [n for _, n, _ in before[1].values()] == [3]
    boxes.getObject("Top").Placement.Base = FreeCAD.Vector(3, 3, 10)
    boxes.recompute()  # both find Base-Top again: the same objects and numbers
    assert (state(first), state(second)) == before


def test_delete_recompute_undo_then_derive_joints(boxes):
    """The issue's sequence: Find contacts, delete a part, recompute, undo,
    derive joints."""
    group = find(boxes)
    before = state(group)
    boxes.openTransaction("Delete")
    boxes.removeObject("Side")
    boxes.commitTransaction()
    boxes.recompute()
    assert list(boxes.UndoNames) == [RECOMPUTE_TRANSACTION, "Delete", "Find contacts"]
    assert list(state(group)) == [("Base", "Top")]
    boxes.undo()  # one undo: the recompute and the deletion it followed
    assert list(boxes.UndoNames) == ["Find contacts"]
    assert boxes.getObject("Side") is not None
    assert state(group) == before
    assert all(any(p is group for p in c.InList) for c in boxes.Objects if is_contact(c))
    boxes.openTransaction("Derive joints")
    make_contact_analysis(boxes, group=group, derive_joints=True)
    boxes.commitTransaction()
    assert state(group) == before
    assert sorted((j.BodyA, j.BodyB) for j in group.Group if is_joint(j)) == [("Base", "Side"), ("Base", "Top")]
    assert list(boxes.UndoNames) == ["Derive joints", "Find contacts"]
    boxes.redo()  # nothing to redo after a new action
    assert list(boxes.UndoNames) == ["Derive joints", "Find contacts"]


def test_redo_replays_the_edit_and_its_recompute(boxes):
    group = find(boxes)
    boxes.openTransaction("Delete")
    boxes.removeObject("Side")
    boxes.commitTransaction()
    boxes.recompute()
    after = state(group)
    boxes.undo()
    assert list(boxes.RedoNames) == ["Delete", RECOMPUTE_TRANSACTION]
    boxes.redo()
    assert list(boxes.UndoNames) == [RECOMPUTE_TRANSACTION, "Delete", "Find contacts"]
    assert boxes.getObject("Side") is None and state(group) == after


def test_the_same_scope_finds_its_analysis(boxes):
    whole = find(boxes)
    top, base = boxes.getObject("Top"), boxes.getObject("Base")
    chosen = find(boxes, objects=[top, base])
    assert analysis_of_scope(boxes, "Document") is whole
    assert analysis_of_scope(boxes, "Selection", [base, top]) is chosen
    assert analysis_of_scope(boxes, "Selection", [(top, [""]), (base, ["Face6"])]) is None
    assert analysis_of_scope(boxes, "PartAgainstRest", [top]) is None


def test_a_recompute_leaves_no_transaction_open(boxes):
    """An unchanged recompute records nothing, and the next edit outside a
    transaction is not recorded under the recompute's name."""
    group = find(boxes)
    group.touch()
    boxes.recompute()
    assert FreeCAD.getActiveTransaction() is None
    boxes.getObject("Top").Label = "Top again"
    assert list(boxes.UndoNames) == ["Find contacts"]


def test_undo_and_redo_restore_whether_the_analysis_is_current(boxes):
    group = find(boxes)
    top = boxes.getObject("Top")
    boxes.openTransaction("Move Top")
    top.Placement.Base = FreeCAD.Vector(2, 3, 30)
    boxes.commitTransaction()
    assert "Touched" in group.State and group.OutOfDate
    boxes.recompute()
    assert "Touched" not in group.State and not group.OutOfDate
    boxes.undo()  # the recompute and the move: current again, not touched
    assert list(boxes.UndoNames) == ["Find contacts"]
    assert "Touched" not in group.State and not group.OutOfDate
    boxes.openTransaction("Move Top")
    top.Placement.Base = FreeCAD.Vector(2, 3, 30)
    boxes.commitTransaction()
    boxes.openTransaction("Rename")
    top.Label = "Top block"
    boxes.commitTransaction()
    boxes.undo()  # the rename only: the move is still not searched again
    assert "Touched" in group.State and group.OutOfDate


def test_interferences_are_objects_with_their_solid_and_exported(boxes, tmp_path):
    """Issue 21 item 5, headless: a box pushed 2 mm into another gives an
    Interferences group under the analysis holding one Interference (pair,
    volume 6 x 4 x 2 = 48 mm3, the common solid as its Shape, label I1),
    counted, exported; moved out again, it goes and the group with it."""
    import json
    from contactwb.document import export
    from contactwb.document.identify import interferences_of, is_interference, is_interference_group
    group = find(boxes)
    top = boxes.getObject("Top")
    top.Placement.Base = FreeCAD.Vector(2, 3, 8)  # 2 mm into Base
    boxes.recompute()
    (holder,) = [o for o in group.Group if is_interference_group(o)]
    assert not [o for o in group.Group if is_interference(o)]  # in the group, not beside the contacts
    (found,) = holder.Group
    assert is_interference(found) and interferences_of(group) == [found]
    assert (found.BodyA, found.BodyB) == ("Base", "Top")
    assert found.Volume.Value == pytest.approx(48.0, rel=1e-6)
    assert found.Shape.Volume == pytest.approx(48.0, rel=1e-6)  # the overlapping solid itself
    assert found.Label == "I1: Base \u2013 Top" and found.Label2 == "48.00 mm^3" and found.Number == 1
    assert holder.Label == "Interferences" and holder.Count == 1 and holder.TotalVolume.Value == pytest.approx(48.0)
    assert group.InterferenceCount == 1 and group.Interferences == ["Base \u2013 Top: 48.00 mm^3"]
    path = tmp_path / "boxes.json"
    export.export_contacts(group, str(path))
    written = json.loads(path.read_text())["interferences"]
    assert [(i["a"], i["b"]) for i in written] == [("Base", "Top")]
    assert written[0]["volume"] == pytest.approx(48.0, rel=1e-6)
    # the interference is no body of the next search, and a recompute keeps its object
    name = found.Name
    group.touch()
    boxes.recompute()
    assert [o.Name for o in interferences_of(group)] == [name]
    assert group.BodyCount == 3
    top.Placement.Base = FreeCAD.Vector(2, 3, 7)  # deeper: same object and number, the new volume
    boxes.recompute()
    assert [(o.Name, o.Number) for o in interferences_of(group)] == [(name, 1)]
    assert interferences_of(group)[0].Volume.Value == pytest.approx(72.0, rel=1e-6)
    top.Placement.Base = FreeCAD.Vector(2, 3, 10)
    boxes.recompute()
    assert not [o for o in boxes.Objects if is_interference(o) or is_interference_group(o)]
    assert group.InterferenceCount == 0 and not [o for o in group.Group if is_interference_group(o)]
    # found again after it vanished: a new number, never one given before
    top.Placement.Base = FreeCAD.Vector(2, 3, 9)
    boxes.recompute()
    (again,) = interferences_of(group)
    assert again.Number == 2 and again.Label == "I2: Base \u2013 Top"
    assert again.Volume.Value == pytest.approx(24.0, rel=1e-6)


def test_interferences_saved_and_reopened_and_old_files_migrated(boxes, tmp_path):
    """The Interferences group and its interference survive a save and a
    re-open (proxies, numbers, the solid); an interference held directly by
    the analysis (files saved before the group) moves into the group at the
    next recompute and gets a number."""
    from contactwb.document.identify import interferences_of, is_interference, is_interference_group
    from contactwb.objects.interferences import Interference
    group = find(boxes)
    boxes.getObject("Top").Placement.Base = FreeCAD.Vector(2, 3, 8)
    boxes.recompute()
    path = str(tmp_path / "boxes.FCStd")
    boxes.saveAs(path)
    FreeCAD.closeDocument(boxes.Name)
    doc = FreeCAD.openDocument(path)
    try:
        group = doc.getObject("Contacts")
        (holder,) = [o for o in group.Group if is_interference_group(o)]
        (found,) = holder.Group
        assert is_interference(found) and found.Label == "I1: Base \u2013 Top" and found.Number == 1
        assert found.Shape.Volume == pytest.approx(48.0, rel=1e-6)
        # an old file's layout: the interference beside the contacts, without a number
        old = doc.addObject("Part::FeaturePython", "Interference")
        Interference(old)
        old.BodyA, old.BodyB, old.Volume = "Base", "Top", 48.0
        group.Group = [o for o in group.Group if not is_interference_group(o)] + [old]
        for obj in list(holder.Group) + [holder]:
            holder.Group = []
            doc.removeObject(obj.Name)
        assert not interferences_of(group)[0].Number
        group.touch()
        doc.recompute()
        (holder,) = [o for o in group.Group if is_interference_group(o)]
        assert holder.Group == [old] and old.Number == 2 and old.Label == "I2: Base \u2013 Top"
        assert old.Shape.Volume == pytest.approx(48.0, rel=1e-6)
    finally:
        FreeCAD.closeDocument(doc.Name)