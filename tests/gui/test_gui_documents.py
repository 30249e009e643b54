"""GUI tests of documents with contacts and joints (issue 14): saved and
reopened in the real FreeCAD, opened in a FreeCAD without the workbench,
brought back; driven by tests/gui/document_gui_session.py under Xvfb."""
import os

import pytest

from freecad_session import OUT_DIR, REPO, run_session  # tests/gui is on sys.path

V1_FIXTURE = os.path.join(REPO, "tests", "data", "contacts_v1.FCStd")
V2_0_1_FIXTURE = os.path.join(REPO, "tests", "data", "contacts_v2_0_1.FCStd")
PROXIES = {"Contacts": "ContactAnalysis", "CLJ": "Contact", "PLF": "Contact", "Joint": "Joint", "Joint001": "Joint"}
VIEW_PROVIDERS = {"ContactAnalysis": "ViewProviderContactAnalysis", "Contact": "ViewProviderContact",
                  "Joint": "ViewProviderJoint"}
PARTS = {"Plate": 40 * 40 * 10 - 3.141592653589793 * 25 * 10, "Shaft": 3.141592653589793 * 25 * 30,
         "Block": 500.0}
SAVED = os.path.join(OUT_DIR, "documents_saved.FCStd")
WITHOUT = os.path.join(OUT_DIR, "documents_saved_without_workbench.FCStd")


def session(tmp_path_factory, step, install=True):
    report = run_session(tmp_path_factory, "document_gui_session.py", f"documents_{step}.json",
                         {"CONTACTS_DOC_STEP": step, "CONTACTS_DOC_SAVED": SAVED, "CONTACTS_DOC_WITHOUT": WITHOUT,
                          "CONTACTS_DOC_V1": V1_FIXTURE, "CONTACTS_DOC_V2_0_1": V2_0_1_FIXTURE}, install=install)
    assert not report["errors"], "\n".join(report["errors"])
    return report


@pytest.fixture(scope="module")
def reports(tmp_path_factory):
    """The three sessions, in order: each opens what the one before saved."""
    for path in (SAVED, WITHOUT):
        if os.path.exists(path):
            os.remove(path)
    made = session(tmp_path_factory, "make")
    without = session(tmp_path_factory, "without", install=False)
    back = session(tmp_path_factory, "back")
    return {"make": made, "without": without, "back": back}


def check_working(objects, contacts_drawn=2):
    """Every Contacts object has its proxy and view provider, the analysis
    draws its contacts and the joints their axes; the parts are intact."""
    for name, kind in PROXIES.items():
        assert objects[name]["proxy"] == kind, name
        assert objects[name]["view_provider"] == VIEW_PROVIDERS[kind], name
        assert objects[name]["version"] == 2, name
        assert "Touched" not in objects[name]["state"], name
    assert objects["Contacts"]["contacts_drawn"] == contacts_drawn
    assert objects["Contacts"]["triangles"] > 0
    assert (objects["Contacts"]["ContactCount"], objects["Contacts"]["JointCount"]) == (2, 2)
    assert objects["Joint"]["JointType"] == "cylindrical" and objects["Joint"]["glyph_axes"] == 1
    for name, volume in PARTS.items():
        assert objects[name]["volume"] == pytest.approx(volume)
    assert objects["Note"]["Text"] == "kept"


def no_errors(text):
    return [line for line in text.splitlines() if "Traceback" in line or "Error" in line or "error" in line]


def test_saved_document_reopens_with_its_view_providers(reports):
    made = reports["make"]
    assert made["workbench_importable"]
    check_working(made["made"])
    check_working(made["reopened"])
    assert {n: o["label"] for n, o in made["reopened"].items()} == {n: o["label"] for n, o in made["made"].items()}


def test_headless_version_1_document_gets_view_providers_and_is_migrated(reports):
    # made headless by the code before proxy versions: no view provider saved
    check_working(reports["make"]["version_1"])


def test_headless_2_0_1_document_gets_view_providers_and_draws(reports):
    # saved headless by the code before the Python layers: the motor's analysis and a collision model
    objects = reports["make"]["version_2_0_1"]
    group = objects["Contacts"]
    assert (group["proxy"], group["view_provider"]) == ("ContactAnalysis", "ViewProviderContactAnalysis")
    assert (group["ContactCount"], group["JointCount"]) == (35, 29)
    assert group["contacts_drawn"] == 35 and group["triangles"] > 0
    kinds = {}
    for name, entry in objects.items():
        assert "Invalid" not in entry["state"] and "Touched" not in entry["state"], name
        if entry["proxy"] in ("Contact", "Joint", "SimulationModel"):
            assert entry["view_provider"] == f"ViewProvider{entry['proxy']}", name
            kinds[entry["proxy"]] = kinds.get(entry["proxy"], 0) + 1
    assert kinds == {"Contact": 35, "Joint": 29, "SimulationModel": 1}


def test_no_errors_in_the_report_view_with_the_workbench(reports):
    for step in ("make", "back"):
        assert no_errors(reports[step]["report_view"]) == [], reports[step]["report_view"][-3000:]


def test_opens_without_the_workbench_with_nothing_lost(reports):
    without = reports["without"]
    assert without["workbench_importable"] is False
    objects = without["opened"]
    assert sorted(objects) == sorted(reports["make"]["reopened"])
    for name in PROXIES:  # kept with their properties, only their Python parts are missing
        assert objects[name]["proxy"] is None and objects[name]["view_provider"] is None, name
        assert objects[name]["version"] == 2
        assert objects[name]["label"] == reports["make"]["reopened"][name]["label"]
    assert (objects["Contacts"]["ContactCount"], objects["Contacts"]["JointCount"]) == (2, 2)
    for name, volume in PARTS.items():
        assert objects[name]["volume"] == pytest.approx(volume)
    assert objects["Note"]["Text"] == "kept"
    # FreeCAD says which module it could not import, and nothing else went wrong
    lines = no_errors(without["report_view"])
    assert lines and all("contactwb" in line for line in lines), without["report_view"][-3000:]


def test_saved_without_the_workbench_comes_back_working(reports):
    assert os.path.exists(WITHOUT)
    check_working(reports["back"]["opened"])


def test_screenshots_show_the_contacts(reports):
    from PIL import Image
    orange = (255, 140, 26)  # PLF
    for key, step, least in (("reopened_png", "make", 1000), ("without_png", "without", 0),
                             ("back_png", "back", 1000)):
        image = Image.open(reports[step][key]).convert("RGB")
        below_legend = image.crop((0, 80, image.width, image.height))  # the legend's text is orange too
        near = sum(1 for p in below_legend.getdata() if max(abs(a - b) for a, b in zip(p, orange)) < 50)
        if least:
            assert near >= least, f"no PLF paint in {reports[step][key]}"
        else:
            assert near == 0, f"PLF paint without the workbench in {reports[step][key]}"
