"""Issue 14, documents: a document with a contact analysis (contacts and
joints) saves and reopens intact; opens in a FreeCAD without the workbench
with nothing lost; comes back working once the workbench is installed again;
files of the previous version (tests/data/contacts_v1.FCStd, saved by the
code before proxy versions) are migrated."""
import json
import os
import subprocess
import sys
import zipfile

import pytest

import FreeCAD
from contactwb.objects import contact_objects
from contactwb.objects.contact_objects import PROXY_VERSION
from contacts_document import build_contacts_document  # tests/ is on sys.path
from document_session import proxy_name, snapshot

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
V1_FIXTURE = os.path.join(REPO, "tests", "data", "contacts_v1.FCStd")
BUILD_DIR = os.path.join(REPO, "build")
PROXIES = {"Contacts": "ContactAnalysis", "CLJ": "Contact", "PLF": "Contact", "Joint": "Joint", "Joint001": "Joint"}
LABELS = ["CLJ 1: Plate \u2013 Shaft", "J1 cylindrical: Plate \u2013 Shaft",
          "J2 planar: Plate \u2013 Block", "PLF 2: Plate \u2013 Block"]


def build_document(path):
    """The document of tests/contacts_document.py, saved at `path`."""
    doc = build_contacts_document()
    doc.saveAs(str(path))
    return doc


def document_snapshot(doc):
    return {obj.Name: snapshot(obj) for obj in doc.Objects}


def test_document_saves_and_reopens_intact(tmp_path):
    doc = build_document(tmp_path / "contacts.FCStd")
    before = document_snapshot(doc)
    FreeCAD.closeDocument(doc.Name)
    doc = FreeCAD.openDocument(str(tmp_path / "contacts.FCStd"))
    try:
        assert document_snapshot(doc) == before
        assert sorted(o.Label for o in doc.Contacts.Group) == LABELS
        for name, kind in PROXIES.items():
            obj = doc.getObject(name)
            assert proxy_name(obj) == f"contactwb.objects.contact_objects.{kind}"
            assert (obj.ProxyType, obj.ProxyVersion) == (kind, PROXY_VERSION)
            assert "Touched" not in obj.State
        assert (doc.Contacts.ContactCount, doc.Contacts.JointCount) == (2, 2)
        # still live: the block moved off the plate loses its contact and joint
        doc.Block.Placement.Base = FreeCAD.Vector(100, 100, 10)
        doc.recompute()
        assert sorted(o.Label for o in doc.Contacts.Group) == LABELS[:2]
        assert (doc.Contacts.ContactCount, doc.Contacts.JointCount) == (1, 1)
    finally:
        FreeCAD.closeDocument(doc.Name)


def test_fixture_is_a_version_1_file():
    with zipfile.ZipFile(V1_FIXTURE) as archive:
        xml = archive.read("Document.xml").decode()
    assert "contactwb.objects.contact_objects" in xml
    assert "ProxyVersion" not in xml and "ContactCount" not in xml


def test_version_1_document_is_migrated(tmp_path):
    doc = FreeCAD.openDocument(V1_FIXTURE)
    try:
        group = doc.Contacts
        assert sorted(o.Label for o in group.Group) == LABELS
        assert group.ProxyVersion == PROXY_VERSION
        # the counts added by version 2, from the saved children
        assert (group.ContactCount, group.JointCount) == (2, 2)
        assert group.Summary == ["CLJ: 1", "PLF: 1"]
        for name, kind in PROXIES.items():
            assert (doc.getObject(name).ProxyType, doc.getObject(name).ProxyVersion) == (kind, PROXY_VERSION)
        # the migrated properties are saved as such
        migrated = document_snapshot(doc)
        doc.saveAs(str(tmp_path / "migrated.FCStd"))
        FreeCAD.closeDocument(doc.Name)
        doc = FreeCAD.openDocument(str(tmp_path / "migrated.FCStd"))
        assert document_snapshot(doc) == migrated
    finally:
        FreeCAD.closeDocument(doc.Name)


def test_newer_version_is_kept_not_downgraded(tmp_path):
    doc = build_document(tmp_path / "newer.FCStd")
    for name in PROXIES:
        doc.getObject(name).ProxyVersion = PROXY_VERSION + 1
    doc.save()
    FreeCAD.closeDocument(doc.Name)
    doc = FreeCAD.openDocument(str(tmp_path / "newer.FCStd"))
    try:
        assert {doc.getObject(n).ProxyVersion for n in PROXIES} == {PROXY_VERSION + 1}
    finally:
        FreeCAD.closeDocument(doc.Name)


def run_session(home, source, target, *extra):
    """tests/document_session.py in its own FreeCAD with HOME=home: nothing of
    this checkout on its path, so the workbench is there only if installed in home."""
    report = os.path.join(os.path.dirname(target), os.path.basename(target) + ".json")
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "CONTACTS_PYTHON_DIR")}
    env["HOME"] = str(home)
    done = subprocess.run([sys.executable, os.path.join(REPO, "tests", "document_session.py"),
                           source, target, report, *extra],
                          env=env, capture_output=True, text=True, timeout=300, cwd=str(home))
    assert done.returncode == 0, done.stderr[-3000:]
    with open(report) as stream:
        return json.load(stream)


@pytest.fixture(scope="module")
def homes(tmp_path_factory):
    """(a HOME without the workbench, a HOME with it installed)."""
    bare = tmp_path_factory.mktemp("home_without")
    installed = tmp_path_factory.mktemp("home_with")
    subprocess.run([sys.executable, os.path.join(REPO, "tools", "install_workbench.py"), "--build-dir", BUILD_DIR,
                    "--mod-dir", str(installed / ".local/share/FreeCAD/Mod/Contacts"),
                    "--bin-dir", str(installed / "bin")], check=True, capture_output=True)
    return bare, installed


def check_round_trip(homes, tmp_path, source, expected, expected_back=None):
    """Opens `source` without the workbench, saves it there, reopens it with
    the workbench: `expected` (name -> properties) is what must come back
    (`expected_back` once the workbench migrated it, if it differs)."""
    bare, installed = homes
    without = run_session(bare, source, str(tmp_path / "without.FCStd"))
    assert without["workbench_importable"] is False
    objects = without["objects"]
    # every object there, every property kept; Contacts objects only lose their proxy
    assert sorted(objects) == sorted(expected)
    for name, properties in expected.items():
        kept = {k: v for k, v in objects[name]["properties"].items() if k in properties}
        assert kept == properties, name
    # FreeCAD 0.20 keeps the properties but cannot make the proxies
    assert all(objects[name]["proxy"] is None for name in PROXIES)
    assert objects["Plate"]["volume"] == pytest.approx(40 * 40 * 10 - 3.141592653589793 * 25 * 10)
    assert objects["Note"]["properties"]["Text"] == "kept"

    back = run_session(installed, str(tmp_path / "without.FCStd"), str(tmp_path / "back.FCStd"))
    assert back["workbench_importable"] is True
    for name, kind in PROXIES.items():
        assert back["objects"][name]["proxy"] == f"contactwb.objects.contact_objects.{kind}"
        assert back["objects"][name]["properties"]["ProxyVersion"] == PROXY_VERSION
        assert "Touched" not in back["objects"][name]["state"]
    for name, properties in (expected_back or expected).items():
        restored = {k: v for k, v in back["objects"][name]["properties"].items() if k in properties}
        assert restored == properties, name
    # and the analysis works: moving the block away loses its contact and joint
    moved = run_session(installed, str(tmp_path / "back.FCStd"), str(tmp_path / "unused.FCStd"), "--move-block")
    assert moved["after_move"] == {"labels": LABELS[:2], "ContactCount": 1, "invalid": []}
    return back


def test_document_survives_a_freecad_without_the_workbench(homes, tmp_path):
    doc = build_document(tmp_path / "contacts.FCStd")
    expected = document_snapshot(doc)
    FreeCAD.closeDocument(doc.Name)
    back = check_round_trip(homes, tmp_path, str(tmp_path / "contacts.FCStd"), expected)
    assert {name: back["objects"][name]["properties"] for name in expected} == expected


def test_version_1_document_survives_a_freecad_without_the_workbench(homes, tmp_path):
    doc = FreeCAD.openDocument(V1_FIXTURE)
    # what the version 1 file holds (read here with the workbench, less the version-2 additions)
    added = {"ProxyType", "ProxyVersion", "ContactCount", "JointCount", "LastNumber", "OutOfDate",
             "InterferenceCount", "Interferences", "LastInterferenceNumber", "Annotations", "Intent", "Fit",
             "FitClass"}
    added |= {"LinearToleranceValue", "AngularToleranceValue"}
    expected = {name: {k: v for k, v in props.items() if k not in added}
                for name, props in document_snapshot(doc).items()}
    # the tolerances became text (issue 21): the file holds them as quantities, their values, until the
    # workbench migrates them
    expected_back = json.loads(json.dumps(expected))
    group = doc.getObject("Contacts")
    expected["Contacts"].update(LinearToleranceSetting=0.0, AngularToleranceSetting=0.0,
                                LinearTolerance=round(group.LinearToleranceValue.Value, 9),
                                AngularTolerance=round(group.AngularToleranceValue.Value, 9))
    FreeCAD.closeDocument(doc.Name)
    back = check_round_trip(homes, tmp_path, V1_FIXTURE, expected, expected_back)
    # recognised by its properties alone (no ProxyType in a version 1 file), then migrated
    assert back["objects"]["Contacts"]["properties"]["ContactCount"] == 2
    assert back["objects"]["Contacts"]["properties"]["JointCount"] == 2


def test_recovery_recognises_only_contacts_objects():
    doc = FreeCAD.newDocument("Recognise")
    try:
        other = doc.addObject("App::FeaturePython", "Other")
        other.addProperty("App::PropertyString", "ContactType", "X", "")  # one signature property is not enough
        from contactwb.objects import recovery
        assert recovery.proxy_type(other) is None
        assert recovery.restore_proxies(doc) == []
        assert contact_objects.is_contact(other) is False
    finally:
        FreeCAD.closeDocument(doc.Name)



# Issue 23: the modules moved into layers (contactwb/core, document, objects, make, gui, cli); saved
# files name the proxies' modules, which stay importable. Files of earlier releases open, recompute
# and find their contacts again.
V2_0_1_FIXTURE = os.path.join(REPO, "tests", "data", "contacts_v2_0_1.FCStd")


def _recomputed(doc, names):
    """Recomputes the named objects as a body change would (touched, then the document)."""
    for name in names:
        doc.getObject(name).touch()
    doc.recompute()
    return [o.Name for o in doc.Objects if "Invalid" in o.State or "Touched" in o.State]


def test_version_1_document_opens_recomputes_and_finds_its_contacts():
    doc = FreeCAD.openDocument(V1_FIXTURE)
    try:
        for name, kind in PROXIES.items():
            assert proxy_name(doc.getObject(name)) == f"contactwb.objects.contact_objects.{kind}"
        assert _recomputed(doc, ["Contacts"]) == []
        group = doc.Contacts
        assert sorted(o.Label for o in group.Group) == LABELS
        assert (group.ContactCount, group.JointCount) == (2, 2)
        assert group.Summary == ["CLJ: 1", "PLF: 1"]
        assert sorted(o.JointType for o in group.Group if contact_objects.is_joint(o)) == ["cylindrical", "planar"]
    finally:
        FreeCAD.closeDocument(doc.Name)


def test_fixture_2_0_1_names_the_proxies_before_the_layers():
    with zipfile.ZipFile(V2_0_1_FIXTURE) as archive:
        xml = archive.read("Document.xml").decode()
    assert 'module="contactwb.objects.contact_objects" class="ContactAnalysis"' in xml
    assert 'module="contactwb.objects.simulation_model" class="SimulationModel"' in xml


def test_2_0_1_document_opens_recomputes_and_finds_its_contacts():
    """The motor with its contact analysis (contacts and joints) and the Seal's collision model, saved
    headless by the code before the layers (main at 650c151)."""
    doc = FreeCAD.openDocument(V2_0_1_FIXTURE)
    try:
        group = doc.getObject("Contacts")
        model = next(o for o in doc.Objects if o.TypeId == "App::FeaturePython"
                     and getattr(o, "ProxyType", "") == "SimulationModel")
        assert proxy_name(group) == "contactwb.objects.contact_objects.ContactAnalysis"
        assert proxy_name(model) == "contactwb.objects.simulation_model.SimulationModel"
        saved = {"labels": sorted(o.Label for o in group.Group), "summary": list(group.Summary),
                 "pairs": list(group.PairSummary), "mobility": list(group.Mobility),
                 "counts": (group.ContactCount, group.JointCount), "bodies": group.BodyCount}
        saved_model = (model.Triangles, model.Partitions, list(model.SwitchedOff), model.Watertight)
        assert saved["counts"] == (35, 29) and saved["summary"] == ["CLJ: 21", "PLF: 14"]
        # Issue 22 names a 4-DOF motion of two rotations and two translations in a plane (a line
        # contact's space, each magnet's relative to the body) cylinder_plane; the fixture says general.
        assert sum("(general, 4 DOF)" in line for line in saved["mobility"]) == 4
        saved["mobility"] = [line.replace("(general, 4 DOF)", "(cylinder_plane, 4 DOF)") for line in saved["mobility"]]
        assert _recomputed(doc, [group.Name, model.Name]) == []
        # issue 21 explains each mobility line after what the fixture says (which bodies, which motions)
        mobility = list(group.Mobility)
        assert len(mobility) == len(saved["mobility"])
        assert all(line.startswith(old_line) for line, old_line in zip(mobility, saved.pop("mobility")))
        assert {"labels": sorted(o.Label for o in group.Group), "summary": list(group.Summary),
                "pairs": list(group.PairSummary),
                "counts": (group.ContactCount, group.JointCount), "bodies": group.BodyCount} == saved
        assert (model.Triangles, model.Partitions, list(model.SwitchedOff), model.Watertight) == saved_model
        # still live: the seal moved away loses its contacts, and its model follows it
        seal = doc.getObject(model.Body[0].Name)
        before = len([o for o in group.Group if contact_objects.is_contact(o)])
        seal.Placement.Base = FreeCAD.Vector(500, 0, 0)
        doc.recompute()
        after = [o for o in group.Group if contact_objects.is_contact(o)]
        assert len(after) < before and all("Seal" not in (c.BodyA, c.BodyB) for c in after)
        assert min(p.x for p in model.MeshPoints) > 400
    finally:
        FreeCAD.closeDocument(doc.Name)


# Issue 21 item 11: the tolerances became text properties (the property editor shows them as the panel
# writes them, "0.0009751 mm", "0.00573 °", never FreeCAD's "975.10 nm" or "0.01 °"), their exact values
# hidden quantity properties. contacts_quantity_tolerances.FCStd was saved by main at 30bba7e, when they
# were App::PropertyLength and App::PropertyAngle: tests/contacts_document.py's document plus a second
# analysis "Tight" (Plate and Shaft, settings 0.002 mm and 0.01 deg).
QUANTITY_TOLERANCES_FIXTURE = os.path.join(REPO, "tests", "data", "contacts_quantity_tolerances.FCStd")
# what that code computed: the model's linear tolerance, the core's angular default (1e-4 rad), as the file
# writes them (16 digits)
SAVED_LINEAR, SAVED_ANGULAR = 0.0005744562677872, 0.0057295779513082


def _tolerance_properties(group):
    return {name: (group.getTypeIdOfProperty(name), getattr(group, name)) for name in
            ("LinearToleranceSetting", "AngularToleranceSetting", "LinearTolerance", "AngularTolerance")}


def test_quantity_tolerances_of_an_earlier_file_become_text_and_recompute_the_same():
    with zipfile.ZipFile(QUANTITY_TOLERANCES_FIXTURE) as archive:
        xml = archive.read("Document.xml").decode()
    assert '<Property name="LinearToleranceSetting" type="App::PropertyLength"' in xml
    assert '<Property name="AngularTolerance" type="App::PropertyAngle"' in xml
    doc = FreeCAD.openDocument(QUANTITY_TOLERANCES_FIXTURE)
    try:
        group, tight = doc.getObject("Contacts"), doc.getObject("Tight")
        string = "App::PropertyString"
        assert _tolerance_properties(group) == {
            "LinearToleranceSetting": (string, "scaled to the model"), "AngularToleranceSetting": (string, "default"),
            "LinearTolerance": (string, "0.0005745 mm"), "AngularTolerance": (string, "0.00573 \u00b0")}
        assert _tolerance_properties(tight) == {
            "LinearToleranceSetting": (string, "0.002 mm"), "AngularToleranceSetting": (string, "0.01 \u00b0"),
            "LinearTolerance": (string, "0.002 mm"), "AngularTolerance": (string, "0.01 \u00b0")}
        # the exact values kept, hidden from the property editor
        assert group.LinearToleranceValue.Value == SAVED_LINEAR
        assert group.AngularToleranceValue.Value == SAVED_ANGULAR
        assert (tight.LinearToleranceValue.Value, tight.AngularToleranceValue.Value) == (0.002, 0.01)
        assert group.getEditorMode("LinearToleranceValue") == ["Hidden"]
        assert group.getEditorMode("LinearTolerance") == ["ReadOnly"]
        assert group.getEditorMode("LinearToleranceSetting") == []
        before = {g.Name: sorted(o.Label for o in g.Group) for g in (group, tight)}
        assert before == {"Contacts": LABELS, "Tight": ["CLJ 3: Plate \u2013 Shaft"]}
        # recomputed: the same contacts, with the same tolerances
        assert _recomputed(doc, ["Contacts", "Tight"]) == []
        assert {g.Name: sorted(o.Label for o in g.Group) for g in (group, tight)} == before
        assert group.LinearToleranceValue.Value == pytest.approx(SAVED_LINEAR, rel=1e-15)
        assert group.AngularToleranceValue.Value == pytest.approx(SAVED_ANGULAR, rel=1e-15)
        assert (tight.LinearToleranceValue.Value, tight.AngularToleranceValue.Value) == (0.002, 0.01)
        assert tight.LinearTolerance == "0.002 mm" and group.LinearTolerance == "0.0005745 mm"
    finally:
        FreeCAD.closeDocument(doc.Name)


def test_tolerance_settings_typed_in_any_unit_read_as_the_panel_writes_them(tmp_path):
    doc = build_document(tmp_path / "contacts.FCStd")
    try:
        group = doc.Contacts
        # typed in the property editor: rewritten as the panel writes them, used by the recompute
        group.LinearToleranceSetting = "0.5 um"
        group.AngularToleranceSetting = "2e-4 rad"
        assert (group.LinearToleranceSetting, group.AngularToleranceSetting) == ("0.0005 mm", "0.0114591559026 \u00b0")
        doc.recompute()
        assert group.LinearToleranceValue.Value == pytest.approx(0.0005, abs=1e-15)
        assert group.AngularToleranceValue.Value == pytest.approx(0.0114591559026, abs=1e-13)
        assert (group.LinearTolerance, group.AngularTolerance) == ("0.0005 mm", "0.01146 \u00b0")
        assert contact_objects.tolerance_settings(group) == (pytest.approx(0.0005), pytest.approx(2e-4, rel=1e-6))
        # empty or zero: the default's words again
        group.LinearToleranceSetting = ""
        group.AngularToleranceSetting = "0"
        assert (group.LinearToleranceSetting, group.AngularToleranceSetting) == ("scaled to the model", "default")
        # not a tolerance: kept as typed, the recompute names the analysis and the text
        group.LinearToleranceSetting = "2 mm^2"
        assert group.LinearToleranceSetting == "2 mm^2"
        with pytest.raises(contact_objects.core.ContactsError,
                           match="analysis 'Contacts': LinearToleranceSetting: tolerance setting '2 mm\\^2' "
                                 "is not a positive length"):
            contact_objects.update_contact_analysis(group)
        # saved and reopened: the text as it was, nothing to migrate or recompute
        group.LinearToleranceSetting = "0.001"
        assert group.LinearToleranceSetting == "0.001 mm"
        doc.recompute()
        doc.save()
        name = doc.FileName
        FreeCAD.closeDocument(doc.Name)
        doc = FreeCAD.openDocument(name)
        assert (doc.Contacts.LinearToleranceSetting, doc.Contacts.LinearTolerance) == ("0.001 mm", "0.001 mm")
        assert doc.Contacts.LinearToleranceValue.Value == 0.001
        assert not [o.Name for o in doc.Objects if "Touched" in o.State]
    finally:
        FreeCAD.closeDocument(doc.Name)
