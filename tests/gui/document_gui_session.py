"""Runs inside the FreeCAD GUI under Xvfb for tests/gui/test_gui_documents.py:
documents with contacts and joints saved, reopened, opened without the
workbench and brought back. $CONTACTS_DOC_STEP says which part:

- "make": builds a plate, a shaft in its bore and a block on it, finds their
  contacts and joints (tests/contacts_document.py, as tests/test_documents.py
  does headless), saves to $CONTACTS_DOC_SAVED,
  closes and reopens it; then opens the version 1 fixture made headless
  ($CONTACTS_DOC_V1: no view providers saved, old properties), and the
  motor saved headless by the code before the Python layers
  ($CONTACTS_DOC_V2_0_1). (Not recomputed here: a document saved headless
  opens in the GUI with its parts hidden; tests/test_documents.py recomputes it.)
- "without" (no workbench installed): opens $CONTACTS_DOC_SAVED, saves it as
  $CONTACTS_DOC_WITHOUT.
- "back": opens $CONTACTS_DOC_WITHOUT with the workbench installed again.

Each step reports the proxies, view providers, what is drawn and the Report
view's text to $CONTACTS_GUI_RESULT (JSON). Nothing of contactwb is imported
at module level: in the "without" step it must not be importable."""
import importlib.util
import json
import os
import sys
import traceback

import FreeCAD
import FreeCADGui

# tests/, for the document builder shared with tests/test_documents.py (FreeCAD runs this file with
# only its own and the workbenches' folders on sys.path)
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))  # the shared session helpers
import session_helpers  # noqa: E402
from session_helpers import settle  # noqa: E402

out_dir = os.environ["CONTACTS_GUI_OUT"]
step = os.environ["CONTACTS_DOC_STEP"]
report = {"errors": [], "step": step, "workbench_importable": importlib.util.find_spec("contactwb") is not None}


def class_name(proxy):
    # FreeCAD 0.20 puts an int in a Python view provider that has no proxy
    return None if proxy is None or isinstance(proxy, int) else type(proxy).__name__


def describe(doc):
    """Every object's type, proxy, view provider and what its view provider draws."""
    objects = {}
    for obj in doc.Objects:
        vobj = obj.ViewObject
        entry = {"type": obj.TypeId, "label": obj.Label, "proxy": class_name(getattr(obj, "Proxy", None)),
                 "view_provider": class_name(getattr(vobj, "Proxy", None)) if vobj else None,
                 "version": getattr(obj, "ProxyVersion", None), "state": list(obj.State)}
        if hasattr(obj, "Shape"):
            entry["volume"] = round(obj.Shape.Volume, 6)
        for name in ("ContactCount", "JointCount", "Text", "JointType", "ContactType"):
            if hasattr(obj, name):
                entry[name] = getattr(obj, name)
        proxy = getattr(vobj, "Proxy", None) if vobj else None
        if hasattr(proxy, "overlay"):
            entry["contacts_drawn"] = len(proxy.overlay.names)
            entry["triangles"] = proxy.overlay.triangles
        if hasattr(proxy, "axes"):
            entry["glyph_axes"] = proxy.axes
        objects[obj.Name] = entry
    return objects


report_view = session_helpers.report_view_text


def screenshot(name):
    """The plate alone: its sides of the contacts face the camera."""
    doc = FreeCAD.ActiveDocument
    for part in ("Block", "Shaft"):
        doc.getObject(part).ViewObject.Visibility = False
    view = FreeCADGui.activeDocument().activeView()
    view.viewIsometric()
    view.fitAll()
    FreeCADGui.updateGui()
    path = os.path.join(out_dir, name)
    view.saveImage(path, 800, 600, "White")
    return path


def make():
    from contacts_document import build_contacts_document
    doc = build_contacts_document()
    settle()
    report["made"] = describe(doc)
    path = os.environ["CONTACTS_DOC_SAVED"]
    doc.saveAs(path)
    FreeCAD.closeDocument(doc.Name)
    doc = FreeCAD.openDocument(path)
    settle()
    report["reopened"] = describe(doc)
    report["reopened_png"] = screenshot("documents_reopened.png")
    FreeCAD.closeDocument(doc.Name)
    doc = FreeCAD.openDocument(os.environ["CONTACTS_DOC_V1"])
    settle()
    report["version_1"] = describe(doc)
    FreeCAD.closeDocument(doc.Name)
    doc = FreeCAD.openDocument(os.environ["CONTACTS_DOC_V2_0_1"])
    settle()
    report["version_2_0_1"] = describe(doc)
    FreeCAD.closeDocument(doc.Name)


def without():
    doc = FreeCAD.openDocument(os.environ["CONTACTS_DOC_SAVED"])
    settle()
    report["opened"] = describe(doc)
    report["without_png"] = screenshot("documents_without_workbench.png")
    doc.saveAs(os.environ["CONTACTS_DOC_WITHOUT"])
    FreeCAD.closeDocument(doc.Name)


def back():
    doc = FreeCAD.openDocument(os.environ["CONTACTS_DOC_WITHOUT"])
    settle()
    report["opened"] = describe(doc)
    report["back_png"] = screenshot("documents_back.png")
    FreeCAD.closeDocument(doc.Name)


try:
    {"make": make, "without": without, "back": back}[step]()
except Exception:  # the report carries it to the test, which fails on it
    report["errors"].append(traceback.format_exc())
report["report_view"] = report_view()
with open(os.environ["CONTACTS_GUI_RESULT"], "w") as stream:
    json.dump(report, stream, indent=1)
os._exit(0)  # FreeCAD's own shutdown is slow and may prompt; the report is written
