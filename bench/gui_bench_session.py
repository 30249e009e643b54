"""Runs inside the FreeCAD GUI under Xvfb (bench/bench_gui.py starts it):
issue 21's GUI targets, timed as the designer meets them.

1. Find contacts on the motor in the task panel, nothing selected (the
   toolbar command, OK), until the paint is drawn; then again (in place).
2. Recompute after moving one motor part (Back-cover 40 mm, then back, then
   again: three recomputes), until the paint is drawn; the number of common
   regions the core computed each time, and the bodies whose BRep text
   crossed into the core (the others' core bodies kept).
3. The haptic trial panel on the motor with its contact analysis present
   (issue 20 item 6): the simulated hand's Z slider moved back and forth for
   PANEL_SECONDS, the Axis following along its bores; the 3D view's renders
   counted by a SoCallback first in its scene graph (every SoGLRenderAction
   over the whole graph, not its passes over delayed paths),
   the panel's own updates, and what touched the contact results meanwhile:
   property changes of the workbench's objects (a document observer), calls
   of their view providers' updateData/onChanged, rebuilds of the paint.
   Before it, the same view rendered back to back with the panel closed
   (the renderer's rate for that scene), and before everything an empty
   document's view rendered so (the renderer's floor on this display).
4. Find contacts on two ball bearings (../shared/data's R06 STEP imported
   twice, the copy moved beside the first) in the panel.

"Drawn" is: the command returned, the deferred paint ran (Qt events
processed until the analysis' view provider has nothing scheduled), and the
3D view rendered once. Wall clock (time.perf_counter) in this FreeCAD
process, and its CPU time (time.process_time, all threads). With CONTACTS_BENCH_PROFILE=1 each step's cProfile top functions
are reported too. Writes JSON to $CONTACTS_GUI_RESULT."""
import cProfile
import io
import json
import os
import pstats
import sys
import time
import traceback

import FreeCAD
import FreeCADGui
from PySide2 import QtWidgets

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "tests", "gui"))
import session_helpers  # noqa: E402
from view_probes import RenderCounter, ResultTouches, forced_render_rate  # noqa: E402  (shared with the GUI test sessions)

report = {"errors": {}, "times": {}, "cpu": {}, "profiles": {}, "regions": {}}
PROFILE = os.environ.get("CONTACTS_BENCH_PROFILE") == "1"
SHARED_STEP = os.environ.get("CONTACTS_SHARED_STEP", "")
REPEAT = int(os.environ.get("CONTACTS_BENCH_REPEAT", "3"))
PANEL_SECONDS = float(os.environ.get("CONTACTS_BENCH_PANEL_SECONDS", "5"))
# The main window's size (WxH, logical pixels; unset: FreeCAD's own, about 1300 x 1000): a smaller
# 3D view for the render rates (bench_gui.py --window).
WINDOW = os.environ.get("CONTACTS_BENCH_WINDOW", "")


def size_the_window():
    if not WINDOW:
        return
    width, height = (int(v) for v in WINDOW.lower().split("x"))
    main = FreeCADGui.getMainWindow()
    main.showNormal()
    main.resize(width, height)
    QtWidgets.QApplication.processEvents()


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
    start, cpu_start = time.perf_counter(), time.process_time()
    if profiler:
        profiler.enable()
    action()
    drawn(doc)
    if profiler:
        profiler.disable()
    seconds = time.perf_counter() - start
    report["times"].setdefault(name, []).append(round(seconds, 3))
    # CPU time of this process, all its threads (Mesa's software rendering included): what the step
    # costs, less changed than the wall clock by the other processes sharing the cores
    report["cpu"].setdefault(name, []).append(round(time.process_time() - cpu_start, 3))
    if profiler:
        text = io.StringIO()
        stats = pstats.Stats(profiler, stream=text)
        stats.sort_stats("cumulative").print_stats(40)
        stats.sort_stats("tottime").print_stats(25)  # where the time itself goes (C++ calls included)
        report["profiles"].setdefault(name, []).append(text.getvalue()[-16000:])  # each repeat's
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
    doc = session_helpers.open_contacts_sample()
    report["motor_document"] = doc.Name
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
        core_bodies = getattr(regions.cache_of(group), "core_bodies", None)  # absent from older workbenches
        if core_bodies is not None:
            report.setdefault("crossed", []).append(list(core_bodies.crossed))
    doc.openTransaction("Move Back-cover")
    cover.Placement = home
    doc.commitTransaction()
    FreeCADGui.runCommand("Std_Refresh")
    drawn(doc)


def empty_view_rate():
    """The renderer's floor: an empty document's 3D view (FreeCAD's
    background gradient and navigation cube only) rendered back to back, at
    the size the motor's view has later."""
    doc = FreeCAD.newDocument("EmptyView")
    session_helpers.settle()
    rate, renders, size = forced_render_rate(3.0)
    report["times"].setdefault("empty_view_forced_rate_hz", []).append(round(rate, 1))
    report["empty_view"] = {"renders": renders, "view_pixels": size}
    FreeCAD.closeDocument(doc.Name)
    session_helpers.settle()


def haptic_panel_rate():
    """The haptic panel on the motor's Axis, its contact analysis present and
    drawn: the 3D view's render rate while the simulated hand moves the part
    (issue 20 item 6: >= 30 Hz, no contact repaint per tick)."""
    import math
    from contactwb.gui.panels import haptic_panel
    doc = FreeCAD.getDocument(report["motor_document"])
    size_the_window()  # again: opening the motor set FreeCAD's window to 1400 x 1000
    FreeCADGui.getDocument(doc.Name)  # its view active
    FreeCAD.setActiveDocument(doc.Name)
    FreeCADGui.activeDocument().activeView().viewIsometric()
    FreeCADGui.SendMsgToActiveView("ViewFit")
    drawn(doc)
    (group,) = analyses(doc)
    report["panel_contacts"] = sum(1 for c in group.Group if hasattr(c, "ContactType"))
    # What the renderer does for this scene alone (no panel, nothing moving): the ceiling of the panel's rate.
    rate, renders, size = forced_render_rate(3.0)
    report["times"].setdefault("motor_forced_rate_hz", []).append(round(rate, 1))
    report["motor_view"] = {"renders": renders, "view_pixels": size}
    axis = doc.getObjectsByLabel("Axis")[0]
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(axis)
    FreeCADGui.runCommand("Contacts_HapticTrial")
    settle()
    FreeCADGui.Selection.clearSelection()
    panel = haptic_panel.active_panel
    if panel is None:
        raise RuntimeError("the haptic panel did not open on the Axis")
    app = QtWidgets.QApplication.instance()
    wait_until = time.perf_counter() + 0.5
    while time.perf_counter() < wait_until:
        app.processEvents()
    touches = ResultTouches(doc)
    counter = RenderCounter(FreeCADGui.activeDocument().activeView())
    frames_before = len(panel.frame_times)
    start = time.perf_counter()
    end = start + PANEL_SECONDS
    moves = 0
    while True:
        now = time.perf_counter()
        if now >= end:
            break
        # the hand pulls the axis out 10 mm and back, every 2 s (a designer's slider drag)
        z = 5.0 * (1.0 - math.cos(math.pi * (now - start)))
        panel.hand_sliders["z"].setValue(int(round(z * haptic_panel.SLIDER_STEPS_PER_UNIT)))
        moves += 1
        app.processEvents()
        time.sleep(0.005)
    seconds = time.perf_counter() - start
    counter.remove()
    touches.stop()
    frames = len(panel.frame_times) - frames_before
    costs = panel.update_seconds[-frames:] if frames else [0.0]
    renders = [t for t in counter.times if t >= start]
    gaps = sorted(b - a for a, b in zip(renders, renders[1:])) or [0.0]
    report["times"].setdefault("motor_panel_view_rate_hz", []).append(round(len(renders) / seconds, 1))
    report["panel"] = {"seconds": round(seconds, 2), "renders": len(renders), "panel_updates": frames,
                       "panel_rate_hz": round(frames / seconds, 1), "slider_moves": moves,
                       "update_ms_mean": round(1000 * sum(costs) / len(costs), 3),
                       "render_gap_ms_p50": round(1000 * gaps[len(gaps) // 2], 1),
                       "render_gap_ms_max": round(1000 * gaps[-1], 1),
                       "result_changes": len(touches.changes), "changed": touches.changes[:10],
                       "provider_calls": len(touches.provider_calls), "paint_builds": touches.paint_builds,
                       "axis_moved_mm": round((axis.Placement.Base - panel.original.Base).Length, 3)}
    panel.reject()
    settle()


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


for step in (size_the_window, empty_view_rate, motor, haptic_panel_rate, bearings):
    try:
        step()
    except Exception:
        report["errors"][step.__name__] = traceback.format_exc()
with open(os.environ["CONTACTS_GUI_RESULT"], "w") as stream:
    json.dump(report, stream, indent=1)
os._exit(0)
