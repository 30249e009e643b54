"""Runs inside the FreeCAD GUI under Xvfb (bench/bench_gui.py starts it):
issue 21's GUI targets, timed as the designer meets them.

1. Find contacts on the motor in the task panel, nothing selected (the
   toolbar command, OK), until the paint is drawn; then again (in place).
2. Recompute after moving one motor part (Back-cover 40 mm, then back, then
   again: three recomputes), until the paint is drawn; the number of common
   regions the core computed each time.
3. Find contacts on two ball bearings (../shared/data's R06 STEP imported
   twice, the copy moved beside the first) in the panel.

"Drawn" is: the command returned, the deferred paint ran (Qt events
processed until the analysis' view provider has nothing scheduled), and the
3D view rendered once. Wall clock (time.perf_counter) in this FreeCAD
process. With CONTACTS_BENCH_PROFILE=1 each step's cProfile top functions
are reported too. Writes JSON to $CONTACTS_GUI_RESULT."""
import cProfile
import io
import json
import os
import pstats
import time
import traceback

import FreeCAD
import FreeCADGui
from PySide2 import QtWidgets

report = {"errors": {}, "times": {}, "profiles": {}, "regions": {}}
PROFILE = os.environ.get("CONTACTS_BENCH_PROFILE") == "1"
SHARED_STEP = os.environ.get("CONTACTS_SHARED_STEP", "")
REPEAT = int(os.environ.get("CONTACTS_BENCH_REPEAT", "3"))


def analyses(doc):
    from contactwb.document.identify import analyses as found
    return found(doc)


def drawn(doc):
    """Processes events until every analysis' paint is built, then renders once."""
    app = QtWidgets.QApplication.instance()
    deadline = time.perf_counter() + 120
    while time.perf_counter() < deadline:
        app.processEvents()
        pending = [g for g in analyses(doc)
                   if getattr(g.ViewObject.Proxy, "_scheduled", False) or getattr(g.ViewObject.Proxy, "_stale", False)]
        if not pending and not doc.Recomputing:
            break
        time.sleep(0.002)
    FreeCADGui.activeDocument().activeView().redraw()
    app.processEvents()


def timed(name, action, doc):
    """Seconds from the action to the paint drawn (profiled on request)."""
    profiler = cProfile.Profile() if PROFILE else None
    start = time.perf_counter()
    if profiler:
        profiler.enable()
    action()
    drawn(doc)
    if profiler:
        profiler.disable()
    seconds = time.perf_counter() - start
    report["times"].setdefault(name, []).append(round(seconds, 3))
    if profiler:
        text = io.StringIO()
        pstats.Stats(profiler, stream=text).sort_stats("cumulative").print_stats(25)
        report["profiles"].setdefault(name, text.getvalue()[-6000:])
    return seconds


def find_in_panel():
    from contactwb.gui.panels import task_panel
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.runCommand("Contacts_FindContacts")
    if not task_panel.current.accept():
        raise RuntimeError("the panel refused: " + str(getattr(task_panel.current, "message", "")))


def settle():
    for _ in range(3):
        FreeCADGui.updateGui()


def motor():
    FreeCADGui.getMainWindow().resize(1400, 1000)
    FreeCADGui.activateWorkbench("ContactsWorkbench")
    FreeCADGui.runCommand("Contacts_OpenSample")
    settle()
    doc = FreeCAD.ActiveDocument
    doc.UndoMode = 1
    for _ in range(REPEAT):
        timed("motor_find_contacts_panel", find_in_panel, doc)
    (group,) = analyses(doc)
    report["motor_contacts"] = sum(1 for c in group.Group if c.TypeId == "App::FeaturePython"
                                   and hasattr(c, "ContactType"))
    report["motor_drawn"] = len(group.ViewObject.Proxy.overlay.names)
    report["motor_core_painted"] = group.ViewObject.Proxy.overlay.core_contacts
    cover = doc.getObjectsByLabel("Back-cover")[0]
    report["motor_cover_contacts"] = sum(1 for c in group.Group if hasattr(c, "ContactType")
                                         and "Back-cover" in (c.BodyA, c.BodyB))
    home = FreeCAD.Placement(cover.Placement)
    from contactwb.objects import regions
    for k in range(REPEAT):
        offset = FreeCAD.Vector(0, 0, -40 if k % 2 == 0 else 0)
        doc.openTransaction("Move Back-cover")
        cover.Placement = FreeCAD.Placement(home.Base + offset, home.Rotation)
        doc.commitTransaction()
        settle()

        def recompute():
            FreeCADGui.runCommand("Std_Refresh")
        timed("motor_recompute_after_move", recompute, doc)
        report["regions"].setdefault("motor_recompute_after_move", []).append(regions.cache_of(group).computed)


def bearings():
    if not os.path.isfile(SHARED_STEP):
        report["bearings_skipped"] = f"shared data absent: {SHARED_STEP}"
        return
    import ImportGui
    doc = FreeCAD.newDocument("Bearings")
    doc.UndoMode = 1
    ImportGui.insert(SHARED_STEP, doc.Name)
    first = set(o.Name for o in doc.Objects)
    ImportGui.insert(SHARED_STEP, doc.Name)
    roots = [o for o in doc.Objects if o.Name not in first and not o.InList]
    for obj in roots:  # the copy beside the first, 50 mm along x
        if hasattr(obj, "Placement"):
            obj.Placement = FreeCAD.Placement(obj.Placement.Base + FreeCAD.Vector(50, 0, 0), obj.Placement.Rotation)
    doc.recompute()
    FreeCADGui.SendMsgToActiveView("ViewFit")
    settle()
    from contactwb.document import bodies as document_bodies
    report["bearing_bodies"] = len(document_bodies.document_bodies(doc, None, []))
    for _ in range(REPEAT):
        timed("bearings_find_contacts_panel", find_in_panel, doc)
    (group,) = analyses(doc)
    report["bearing_contacts"] = sum(1 for c in group.Group if hasattr(c, "ContactType"))


for step in (motor, bearings):
    try:
        step()
    except Exception:
        report["errors"][step.__name__] = traceback.format_exc()
with open(os.environ["CONTACTS_GUI_RESULT"], "w") as stream:
    json.dump(report, stream, indent=1)
os._exit(0)
