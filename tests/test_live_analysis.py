"""The ContactAnalysis as a live document object (headless): scopes resolved
from selection paths, stable unique labels, update in place, recompute after
a move or a delete, the export's schema (the CLI's)."""
import json

import pytest

import FreeCAD

from contactwb import analysis, export, freecad_setup
from contactwb.make import make_contact_analysis, update_contact_analysis
from contactwb.objects.contact_objects import is_contact
from headless_helpers import three_boxes


@pytest.fixture
def boxes():
    """Base 10x10x10; Top 6x4x5 on it (PLF area 24); Side 10x10x10 beside
    Base (PLF area 100, x = 10)."""
    yield from three_boxes("LiveTest")


def pairs(group):
    return sorted((c.ContactType, c.BodyA, c.BodyB) for c in group.Group if is_contact(c))


def test_labels_name_their_own_bodies_and_stay_unique(boxes):
    first = make_contact_analysis(boxes)
    second = make_contact_analysis(boxes)
    labels = [c.Label for g in (first, second) for c in g.Group]
    assert len(set(labels)) == len(labels) == 4
    for group in (first, second):
        for contact in group.Group:
            assert contact.Label == f"{contact.ContactType} {contact.Number}: {contact.BodyA} \u2013 {contact.BodyB}"
    assert sorted(c.Number for c in first.Group) == [1, 2]
    assert sorted(c.Number for c in second.Group) == [3, 4]
    # the description column writes the area as the property editor does (the Standard schema)
    assert sorted(c.Label2 for c in first.Group) == ["1.00 cm^2", "24.00 mm^2"]
    assert sorted(c.Label2 for c in first.Group) == sorted(c.Area.UserString for c in first.Group)


def test_scopes(boxes):
    base = boxes.getObject("Base")
    selection = make_contact_analysis(boxes, [boxes.getObject("Top"), base])
    assert selection.Scope == "Selection"
    assert pairs(selection) == [("PLF", "Base", "Top")]
    against = make_contact_analysis(boxes, [boxes.getObject("Side")], scope="PartAgainstRest")
    assert pairs(against) == [("PLF", "Base", "Side")]
    # a selected face picks its body; a selected analysis or contact is ignored
    faces = make_contact_analysis(boxes, [(base, ["Face6"]), (boxes.getObject("Top"), ["Face5"]), selection,
                                          selection.Group[0]])
    assert pairs(faces) == [("PLF", "Base", "Top")]
    only_types = make_contact_analysis(boxes, types=["CLJ"])
    assert pairs(only_types) == []
    with pytest.raises(ValueError, match="unknown contact types"):
        make_contact_analysis(boxes, types=["XYZ"])


def test_update_in_place_keeps_the_objects(boxes):
    group = make_contact_analysis(boxes, [boxes.getObject("Top"), boxes.getObject("Base")])
    names = [c.Name for c in group.Group]
    again = make_contact_analysis(boxes, None, group=group)
    assert again is group
    assert [o for o in boxes.Objects if o.TypeId == "App::DocumentObjectGroupPython"] == [group]
    assert [c.Name for c in group.Group][:1] == names
    assert pairs(group) == [("PLF", "Base", "Side"), ("PLF", "Base", "Top")]
    assert group.Scope == "Document"


def test_moving_a_body_marks_the_analysis_and_recompute_redoes_it(boxes):
    group = make_contact_analysis(boxes)
    assert "Touched" not in group.State
    top = boxes.getObject("Top")
    top.Placement = FreeCAD.Placement(FreeCAD.Vector(2, 3, 12), FreeCAD.Rotation())
    assert "Touched" in group.State
    boxes.recompute()
    assert pairs(group) == [("PLF", "Base", "Side")]
    assert group.Summary == ["PLF: 1"]
    top.Placement = FreeCAD.Placement(FreeCAD.Vector(2, 3, 10), FreeCAD.Rotation())
    top.Length = 8  # a shape change: the area follows
    boxes.recompute()
    assert pairs(group) == [("PLF", "Base", "Side"), ("PLF", "Base", "Top")]
    assert sorted(c.Area.Value for c in group.Group) == pytest.approx([32.0, 100.0])


def test_deleting_a_body_drops_its_contacts(boxes, tmp_path):
    group = make_contact_analysis(boxes)
    boxes.removeObject("Side")
    assert "Touched" in group.State
    # before the recompute the export already leaves the dead contact out
    assert [(c["a"], c["b"]) for c in export.to_json(group)["contacts"]] == [("Base", "Top")]
    boxes.recompute()
    assert pairs(group) == [("PLF", "Base", "Top")]
    assert len(boxes.Objects) == 4  # Base, Top, the group and one contact


def test_snapshot_analysis_is_not_redone(boxes):
    group = make_contact_analysis(boxes)
    group.UpdateOnRecompute = False
    top = boxes.getObject("Top")
    top.Placement = FreeCAD.Placement(FreeCAD.Vector(2, 3, 12), FreeCAD.Rotation())
    boxes.recompute()
    assert len(group.Group) == 2


def test_export_is_the_cli_schema_with_bodies_and_half_angle(sample):
    """Bug 6: the GUI export held neither the bodies nor the CJU half-angle."""
    doc = freecad_setup.open_document(sample("cases/taper_pin.FCStd"))
    try:
        group = make_contact_analysis(doc)
        data = export.to_json(group)
        cli, _ = analysis.find_contacts_in_document(doc, [o for o in doc.Objects if o.TypeId == "Part::Feature"])
        expected = cli.to_json()
        assert set(data) == set(expected)
        assert [b["name"] for b in data["bodies"]] == [b["name"] for b in expected["bodies"]]
        assert data["bodies"][0]["volume"] == pytest.approx(expected["bodies"][0]["volume"])
        cones = [c for c in data["contacts"] if c["type"] == "CJU"]
        assert cones and [c["half_angle"] for c in cones] == pytest.approx(
            [c["half_angle"] for c in expected["contacts"] if c["type"] == "CJU"])
        assert cones[0]["half_angle"] > 0
        assert [c.HalfAngle.Value for c in group.Group if c.ContactType == "CJU"] == pytest.approx(
            [c["half_angle"] for c in cones])
        json.dumps(data)
    finally:
        FreeCAD.closeDocument(doc.Name)


def test_asm4_selection_paths_resolve_to_the_linked_bodies(shared_fcstd):
    """Bug 2: picking in the 3D view gives the top-level part and a path
    through the links down to a PartDesign feature's face."""
    doc = freecad_setup.open_document(shared_fcstd("Asm4_Tutorial2/asm_tuto2.FCStd"))
    try:
        model = doc.getObject("Model")
        picked = [(model, ["base001.Body.Pad.Face4", "disk001.Body001.Face2"])]
        group = make_contact_analysis(doc, picked)
        assert pairs(group) == [("PLF", "base001", "disk001")]
        # tree selection of the PartDesign bodies: named after their links
        group = make_contact_analysis(doc, [doc.getObject("Body"), doc.getObject("Body001")])
        assert pairs(group) == [("PLF", "base001", "disk001")]
        # one part against the rest, the part given inside its App::Part (bug 5: global links)
        group = make_contact_analysis(doc, [(model, ["arm001."])], scope="PartAgainstRest")
        assert pairs(group) == [("CLJ", "base001", "arm001"), ("PLF", "base001", "arm001"),
                                ("PLF", "disk001", "arm001")]
        assert group.getTypeIdOfProperty("Sources") == "App::PropertyXLinkSubList"
        assert [(o.Name, s) for o, s in group.Sources] == [("Model", ("arm001.",))]
    finally:
        FreeCAD.closeDocument(doc.Name)


def test_compound_import_gets_the_product_names(sample, tmp_path):
    """Bug 8: FreeCAD's compound import gives one object named after the file
    (as Part.read does); its bodies take the STEP's product names, found
    through FreeCAD's recent files."""
    import shutil
    import Part
    from contactwb import bodies, core
    step = str(tmp_path / "motor.step")
    shutil.copy(sample("motor.step"), step)
    params = FreeCAD.ParamGet(bodies.RECENT_FILES)
    saved = {k: params.GetString(f"MRU{k}", "") for k in range(12)}
    for k in saved:  # no recent file of the user's may name the solids
        params.SetString(f"MRU{k}", "")
    doc = FreeCAD.newDocument("CompoundTest")
    try:
        feature = doc.addObject("Part::Feature", "motor001")
        feature.Shape = Part.read(step)
        assert len(feature.Shape.Solids) == 18
        unnamed = [b.name for b in bodies.document_bodies(doc)]
        assert unnamed[:2] == ["motor001", "motor001.2"]
        params.SetString("MRU0", step)  # as File > Import records it
        names = [b.name for b in bodies.document_bodies(doc)]
        expected = [b.name for b in core.contactcore.read_step(step).bodies]
        assert sorted(names) == sorted(expected) and len(set(names)) == 18
        group = make_contact_analysis(doc)
        assert len(group.Group) == 35
        assert {c.BodyA for c in group.Group} <= set(expected)
        # a face of one solid picks that body only
        axis = next(b for b in bodies.document_bodies(doc) if b.name == "Axis")
        picked = bodies.bodies_of_selection(bodies.document_bodies(doc), [(feature, [f"Face{axis.face_map[0]}"])])
        assert [b.name for b in picked] == ["Axis"]
    finally:
        for k, path in saved.items():
            params.SetString(f"MRU{k}", path)
        FreeCAD.closeDocument(doc.Name)


def test_derived_joints_follow_the_contacts(boxes):
    """Two boxes on a base, each on one face: planar joints (3 DOF: two
    translations in the plane, the rotation about its normal)."""
    from contactwb.objects.contact_objects import is_joint
    group = make_contact_analysis(boxes, derive_joints=True)
    joints = [o for o in group.Group if is_joint(o)]
    assert sorted((j.JointType, j.DOF, j.BodyA, j.BodyB) for j in joints) == [
        ("planar", 3, "Base", "Side"), ("planar", 3, "Base", "Top")]
    top = next(j for j in joints if j.BodyB == "Top")
    assert [abs(d.z) for d in top.AxisDirections] == pytest.approx([1.0])  # about the contact's normal
    assert len(top.Translations) == 2 and all(abs(d.z) < 1e-9 for d in top.Translations)
    assert [c.BodyB for c in top.Contacts] == ["Top"]
    assert top.Label.startswith("J") and top.Label.endswith("planar: Base \u2013 Top")
    assert group.Mobility[0].startswith("Ground: ") and "digraph" in group.LiaisonGraph or "graph" in group.LiaisonGraph
    # the joints follow a move: Top lifted off, its joint goes at the recompute
    boxes.getObject("Top").Placement = FreeCAD.Placement(FreeCAD.Vector(2, 3, 12), FreeCAD.Rotation())
    boxes.recompute()
    assert [(j.BodyA, j.BodyB) for j in group.Group if is_joint(j)] == [("Base", "Side")]
    group.DeriveJoints = False
    boxes.recompute()
    assert not [o for o in group.Group if is_joint(o)] and group.Mobility == []
    assert not [o for o in boxes.Objects if is_joint(o)]


def test_analysis_saved_by_the_first_version_reopens_live(boxes, tmp_path):
    """A 0.1 file: Sources a local link list, none of the new properties."""
    from contactwb.objects.contact_objects import ContactAnalysis
    group = make_contact_analysis(boxes, [boxes.getObject("Top"), boxes.getObject("Base")])
    for name in ("Scope", "LinearToleranceSetting", "AngularToleranceSetting", "ContactTypes", "ClearanceGap",
                 "UpdateOnRecompute", "Bodies", "BodyTable", "NumberBase", "PairSummary", "Clearances",
                 "DeriveJoints", "Ground", "Mobility", "LiaisonGraph"):
        group.removeProperty(name)
    group.removeProperty("Sources")
    group.addProperty("App::PropertyLinkList", "Sources", "Contacts", "")
    group.Sources = [boxes.getObject("Top"), boxes.getObject("Base")]
    for contact in group.Group:
        contact.removeProperty("HalfAngle")
        contact.removeProperty("Number")
    path = str(tmp_path / "old.FCStd")
    boxes.saveAs(path)
    name = group.Name
    FreeCAD.closeDocument(boxes.Name)
    doc = FreeCAD.openDocument(path)
    try:
        group = doc.getObject(name)
        assert isinstance(group.Proxy, ContactAnalysis)
        assert group.getTypeIdOfProperty("Sources") == "App::PropertyXLinkSubList"
        assert sorted(o.Name for o, _ in group.Sources) == ["Base", "Top"]
        assert group.Scope == "Selection" and group.UpdateOnRecompute
        group.touch()
        doc.recompute()
        assert pairs(group) == [("PLF", "Base", "Top")]
        assert [c.HalfAngle.Value for c in group.Group] == [0.0]
    finally:
        FreeCAD.closeDocument(doc.Name)


def test_a_recompute_keeps_the_unchanged_bodies_masses_and_gives_the_same_figures(boxes):
    """The volumes and centres of the bodies that did not change are kept from
    the last recompute (contactwb.objects.regions.reuse_masses); a changed
    body without instances is computed alone, a body sharing its geometry
    with another (an instance) makes every body computed at once as before.
    Each time the BodyTable is the one a fresh analysis computes from
    nothing, to the last bit."""
    from contactwb.objects import regions
    # Copy: a Part::Feature holding Base's own geometry (an instance: the same OCCT shape), further along x
    copy = boxes.addObject("Part::Feature", "Copy")
    copy.Shape = boxes.getObject("Base").Shape
    copy.Placement = FreeCAD.Placement(FreeCAD.Vector(40, 0, 0), FreeCAD.Rotation())
    boxes.recompute()
    assert copy.Shape.isPartner(boxes.getObject("Base").Shape)
    group = make_contact_analysis(boxes)
    cache = regions.cache_of(group)

    def fresh_table():
        """The BodyTable of a new analysis of the same bodies (its own cache, empty)."""
        other = make_contact_analysis(boxes)
        table = json.loads(other.BodyTable)
        regions.forget(other)
        for child in other.Group:
            boxes.removeObject(child.Name)
        boxes.removeObject(other.Name)
        return table

    top, side = boxes.getObject("Top"), boxes.getObject("Side")
    assert cache.masses[0] == ["Base", "Top", "Side", "Copy"] and cache.masses[2] == [False, True, True, False]
    # Top moved (no instance): Top alone computed again, the others' figures kept (the same objects)
    before = cache.masses[3]
    top.Placement = FreeCAD.Placement(FreeCAD.Vector(1, 2, 10), FreeCAD.Rotation(FreeCAD.Vector(0, 0, 1), 30))
    boxes.recompute()
    after = cache.masses[3]
    assert [a is b for a, b in zip(before, after)] == [True, False, True, True]
    assert json.loads(group.BodyTable) == fresh_table()
    # Side's shape changed (no instance): Side alone
    before = after
    side.Length = 12
    boxes.recompute()
    after = cache.masses[3]
    assert [a is b for a, b in zip(before, after)] == [True, True, False, True]
    assert json.loads(group.BodyTable) == fresh_table()
    assert json.loads(group.BodyTable)[2]["volume"] == pytest.approx(1200.0)
    # Copy (an instance of Base) moved: every body computed at once, as a fresh analysis does
    before = after
    copy.Placement = FreeCAD.Placement(FreeCAD.Vector(40, 5, 0), FreeCAD.Rotation(FreeCAD.Vector(1, 0, 0), 90))
    boxes.recompute()
    after = cache.masses[3]
    assert not any(a is b for a, b in zip(before, after))
    table = json.loads(group.BodyTable)
    assert table == fresh_table()
    assert table[3]["center"] == pytest.approx([45.0, 0.0, 5.0])
    # nothing changed (Find contacts again in place): every figure kept
    before = after
    update_contact_analysis(group)
    assert all(a is b for a, b in zip(before, cache.masses[3]))
