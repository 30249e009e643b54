"""Runs inside the FreeCAD GUI (freecad tests/gui/haptic_hand_session.py under Xvfb).

The motor with its contact analysis drawn: opens the haptic trial panel on
the Axis, drives the simulated hand with the panel's sliders (no hardware),
measures the panel's display rate and counts the contact overlay's redraws
while the part moves, reads the active-constraints readout, replays the
bundled trial script through the panel's Replay, commits with OK and checks
the document; writes what it saw to $CONTACTS_GUI_RESULT."""
import os
import sys
import time
import traceback

import FreeCAD
import FreeCADGui
from PySide2 import QtWidgets

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))  # the shared session helpers
import session_helpers  # noqa: E402
from session_helpers import wait  # noqa: E402
from view_probes import RenderCounter, ResultTouches, view_viewport  # noqa: E402

out_dir = os.environ["CONTACTS_GUI_OUT"]
report = {"errors": []}


def progress(label):
    """A line per stage with the time (to see where a session that timed out was)."""
    with open(os.path.join(out_dir, "haptic_hand_progress.txt"), "a") as stream:
        stream.write(f"{time.monotonic():.2f} {label}\n")


def grab_window_with_view(name):
    return session_helpers.grab_window_with_view(out_dir, name)[0]


def offset(obj, original):
    return list(obj.Placement.Base - original.Base)


def send_mouse(widget, kind, pos, buttons):
    """A Qt mouse event at `pos` (logical pixels of `widget`), sent as a user's would arrive."""
    from PySide2 import QtCore, QtGui
    button = QtCore.Qt.NoButton if kind == QtCore.QEvent.MouseMove else QtCore.Qt.LeftButton
    pos = QtCore.QPointF(pos)
    event = QtGui.QMouseEvent(kind, pos, QtCore.QPointF(widget.mapToGlobal(pos.toPoint())), button, buttons,
                              QtCore.Qt.NoModifier)
    QtWidgets.QApplication.sendEvent(widget, event)


def drag_the_handle(panel, axis, original, pixels_up=100, steps=20):
    """The designer grabs the hand's handle in the 3D view (front view) on its
    front face near its top, where no other body hides it (Coin picks the
    nearest surface), and drags it `pixels_up` straight up: Qt mouse events
    sent to the view's OpenGL widget, a press, moves with the button held, a
    release. The handle's front face moves in its plane (x, z): the hand
    follows to where the mouse went, the Axis out along its bores."""
    from PySide2 import QtCore
    view = FreeCADGui.activeDocument().activeView()
    viewport = view_viewport()
    ratio = viewport.devicePixelRatioF()  # Coin's pixels are the device's, Qt's events logical
    height = round(viewport.height() * ratio)
    centre, half = panel.scene.centre, panel.handle.half_size
    at = FreeCAD.Vector(*centre) + FreeCAD.Vector(*panel.handle.dragger.translation.getValue().getValue())
    grip = view.getPointOnScreen(at + FreeCAD.Vector(0, -half[1], half[2] - 3.0))
    report["drag_from_hand"] = list(panel.hand_slider_values()[0])
    press = QtCore.QPointF(grip[0] / ratio, (height - 1 - grip[1]) / ratio)
    release = press - QtCore.QPointF(0, pixels_up)

    def world(point):  # the point of the view's focal plane under a logical pixel (independent of the dragger)
        return view.getPoint(int(round(point.x() * ratio)), int(round(height - 1 - point.y() * ratio)))
    report["drag_expected_dz"] = world(release).z - world(press).z
    report["drag_mm_per_pixel"] = report["drag_expected_dz"] / (pixels_up * ratio)
    undo_before = list(axis.Document.UndoNames)
    send_mouse(viewport, QtCore.QEvent.MouseMove, press, QtCore.Qt.NoButton)
    wait(0.2)
    send_mouse(viewport, QtCore.QEvent.MouseButtonPress, press, QtCore.Qt.LeftButton)
    wait(0.2)
    report["handle_grabbed"] = panel.handle.dragging()
    for i in range(1, steps + 1):
        send_mouse(viewport, QtCore.QEvent.MouseMove, press - QtCore.QPointF(0, pixels_up * i / steps),
                   QtCore.Qt.LeftButton)
        wait(0.1)
    send_mouse(viewport, QtCore.QEvent.MouseButtonRelease, release, QtCore.Qt.NoButton)
    wait(0.3)
    report["handle_released"] = not panel.handle.dragging()
    translate, rotate = panel.hand_slider_values()
    report["dragged_sliders"] = translate + rotate
    report["dragged_hand"] = list(panel.handle.dragger.translation.getValue().getValue())
    # Real time on a loaded machine: wait until the Axis has come to the hand, 20 s at most.
    target = report["dragged_hand"][2]
    for _ in range(200):
        wait(0.1)
        if abs(panel.session.snapshot().translate[2] - target) < 0.01:
            break
    wait(0.3)
    report["dragged_snapshot"] = panel.session.snapshot().translate
    report["dragged_offset"] = offset(axis, original)
    report["dragged_constraints"] = panel.readouts["constraints"].text()
    report["undo_while_dragging"] = [n for n in axis.Document.UndoNames if n not in undo_before]
    report["dragged_png"] = grab_window_with_view("haptic_hand_dragged.png")


def grab_behind_a_body(panel):
    """The designer presses on the handle's front face at the part's middle height, where the
    motor's Body lies in front of it (the Axis is inside it): what the view picks there with the
    handle hidden (a body) and shown (nothing but the handle is pickable), whether the press
    grabbed the handle, and the hand after the release (a press without a move moves nothing)."""
    from PySide2 import QtCore
    view = FreeCADGui.activeDocument().activeView()
    viewport = view_viewport()
    ratio = viewport.devicePixelRatioF()
    height = round(viewport.height() * ratio)
    centre, half = panel.scene.centre, panel.handle.half_size
    at = FreeCAD.Vector(*centre) + FreeCAD.Vector(*panel.handle.dragger.translation.getValue().getValue())
    pixel = view.getPointOnScreen(at + FreeCAD.Vector(0, -half[1], 0))
    pixel = (int(pixel[0]), int(pixel[1]))

    def picked():
        info = view.getObjectInfo(pixel)
        return info["Object"] if info else None
    panel.handle.show(False)
    FreeCADGui.updateGui()
    hidden = picked()
    report["behind_body"] = FreeCAD.ActiveDocument.getObject(hidden).Label if hidden else None
    panel.handle.show(True)
    FreeCADGui.updateGui()
    report["behind_picked_while_shown"] = picked()
    report["behind_pixel"] = list(pixel)
    hand_before = list(panel.handle.dragger.translation.getValue().getValue())
    press = QtCore.QPointF(pixel[0] / ratio, (height - 1 - pixel[1]) / ratio)
    send_mouse(viewport, QtCore.QEvent.MouseMove, press, QtCore.Qt.NoButton)
    wait(0.2)
    send_mouse(viewport, QtCore.QEvent.MouseButtonPress, press, QtCore.Qt.LeftButton)
    wait(0.2)
    report["behind_grabbed"] = panel.handle.dragging()
    report["behind_png"] = grab_window_with_view("haptic_hand_grabbed_behind_body.png")
    send_mouse(viewport, QtCore.QEvent.MouseButtonRelease, press, QtCore.Qt.NoButton)
    wait(0.3)
    report["behind_released"] = not panel.handle.dragging()
    report["behind_hand_moved"] = [b - a for a, b in zip(hand_before,
                                                         panel.handle.dragger.translation.getValue().getValue())]


def still_readouts(panel, seconds=3.0):
    """The part and the hand still: how often the panel updated and how often
    the loop-rate and jitter readouts (which change every tick) were shown
    (each label repaint composes the whole window with the 3D view)."""
    # Under load the loop may still be ending the last move: the window starts once the part's
    # placement has not changed for a readout period (3 s at most). A move inside the window
    # shows the numbers with it: counted, so the test can allow for it.
    settle_start, last_change, shown = time.monotonic(), time.monotonic(), panel.shown_matrix
    while time.monotonic() - settle_start < 3.0 and time.monotonic() - last_change < 0.5:
        QtWidgets.QApplication.processEvents()
        if panel.shown_matrix != shown:
            shown, last_change = panel.shown_matrix, time.monotonic()
        time.sleep(0.002)
    texts = {key: [panel.readouts[key].text()] for key in ("rate", "jitter")}
    frames_before, start, moves = len(panel.frame_times), time.monotonic(), 0
    while time.monotonic() - start < seconds:
        QtWidgets.QApplication.processEvents()
        for key, seen in texts.items():
            if panel.readouts[key].text() != seen[-1]:
                seen.append(panel.readouts[key].text())
        if panel.shown_matrix != shown:
            shown, moves = panel.shown_matrix, moves + 1
        time.sleep(0.002)
    report["still_seconds"] = time.monotonic() - start
    report["still_moves"] = moves
    from contactwb.gui.panels import haptic_panel
    report["readout_period_s"] = haptic_panel.READOUT_PERIOD_S
    report["still_panel_updates"] = len(panel.frame_times) - frames_before
    report["still_readout_changes"] = {key: len(seen) - 1 for key, seen in texts.items()}


def run():
    main = FreeCADGui.getMainWindow()
    doc = session_helpers.open_sample_in_workbench()
    from contactwb.gui.panels import haptic_panel
    axis = next(o for o in doc.Objects if o.Label == "Axis")
    view = FreeCADGui.activeDocument().activeView()
    view.viewFront()
    view.fitAll()
    # Baseline: the panel's display rate without a contact analysis (same drag, 1.5 s).
    panel = session_helpers.open_haptic_panel(axis)
    frames_before, start = len(panel.frame_times), time.monotonic()
    for i in range(31):
        panel.hand_sliders["z"].setValue(int(round(5.0 * i / 30 * haptic_panel.SLIDER_STEPS_PER_UNIT)))
        wait(0.05)
    report["baseline_rate_hz"] = (len(panel.frame_times) - frames_before) / (time.monotonic() - start)
    costs = panel.update_seconds[-(len(panel.frame_times) - frames_before):] or [0.0]
    report["baseline_update_ms"] = 1000 * sum(costs) / len(costs)
    panel.reject()
    wait(0.3)
    progress("baseline done")
    from contactwb.make import make_contact_analysis
    group = make_contact_analysis(doc)
    doc.recompute()
    wait(1.0)
    provider = group.ViewObject.Proxy
    report["contacts"] = len([c for c in group.Group if c.TypeId != "App::DocumentObjectGroup"])
    builds = []
    original_build = provider.overlay.build

    def counting_build(*args, **kwargs):
        builds.append(time.monotonic())
        return original_build(*args, **kwargs)
    provider.overlay.build = counting_build

    axis = next(o for o in doc.Objects if o.Label == "Axis")
    for o in doc.Objects:  # the shaft and what it goes through, cut open by hiding the rest
        if o.Label in ("Body", "Stator", "Front-cover", "Back-cover") or o.Label.startswith(("Screw", "Magnet")):
            o.ViewObject.Visibility = False
    view = FreeCADGui.activeDocument().activeView()
    view.viewFront()
    view.fitAll()
    wait(0.3)
    original = FreeCAD.Placement(axis.Placement)
    panel = session_helpers.open_haptic_panel(axis)
    progress("panel open with the analysis")
    report["panel_open"] = panel is not None
    if panel is None:
        return
    dock = next((d for d in main.findChildren(QtWidgets.QDockWidget) if d.windowTitle() == "Combo View"), None)
    if dock is not None:
        from PySide2 import QtCore
        main.resizeDocks([dock], [430], QtCore.Qt.Horizontal)
    report["hand_enabled"] = panel.hand_box.isEnabled()
    report["sliders"] = sorted(panel.hand_sliders)
    builds_before = len(builds)

    # The user drags the Z slider up 15 mm over 3 s: the hand pulls the axis out along its bores.
    touches = ResultTouches(doc)
    counter = RenderCounter(FreeCADGui.activeDocument().activeView())
    start = time.perf_counter()  # the counter's clock
    frames_before = len(panel.frame_times)
    for i in range(61):
        panel.hand_sliders["z"].setValue(int(round(15.0 * i / 60 * haptic_panel.SLIDER_STEPS_PER_UNIT)))
        wait(0.05)
    wait(1.0)
    elapsed = time.perf_counter() - start
    report["view_rate_hz"], report["view_renders"] = counter.rate(start)
    counter.remove()
    report["frames"] = len(panel.frame_times) - frames_before
    report["seconds"] = elapsed
    report["update_rate_hz"] = report["frames"] / elapsed
    costs = panel.update_seconds[-report["frames"]:] or [0.0]
    report["update_ms"] = 1000 * sum(costs) / len(costs)
    report["panel_rate_hz"] = panel.update_rate_hz(3.0)
    report["redraws_while_moving"] = len(builds) - builds_before
    touches.stop()
    report["result_changes_while_moving"] = touches.changes[:20]
    report["provider_calls_while_moving"] = touches.provider_calls[:20]
    report["slider_label"] = panel.hand_values["z"].text()
    report["pulled_offset"] = offset(axis, original)
    report["pulled_snapshot"] = panel.session.snapshot().translate
    report["constraints_pulled"] = panel.readouts["constraints"].text()
    report["sliders_png"] = grab_window_with_view("haptic_hand_sliders.png")

    progress("sliders done")

    # Replay of the bundled trial script (a script, not a recorded path).
    try:
        panel.replay_file(os.environ["CONTACTS_TRIAL_SCRIPT"])
        report["replay_error"] = None
    except Exception:
        report["replay_error"] = traceback.format_exc()
    frames_before, start = len(panel.frame_times), time.monotonic()
    while not panel.script_done() and time.monotonic() - start < 15:
        wait(0.05)
    wait(2.0)
    progress("replay done")
    report["replay_rate_hz"] = (len(panel.frame_times) - frames_before) / (time.monotonic() - start)
    report["redraws_while_replaying"] = len(builds) - builds_before - report["redraws_while_moving"]
    report["replayed_snapshot"] = panel.session.snapshot().translate
    report["replayed_offset"] = offset(axis, original)
    report["sliders_after_replay"] = list(panel.hand_slider_values()[0]) + list(panel.hand_slider_values()[1])
    report["constraints_seated"] = panel.readouts["constraints"].text()
    report["readouts"] = {k: v.text() for k, v in panel.readouts.items()}
    report["replay_png"] = grab_window_with_view("haptic_hand_replayed.png")

    # The hand's handle in the 3D view, dragged with the mouse (no sliders).
    report["handle_in_view"] = panel.handle is not None
    drag_the_handle(panel, axis, original)
    progress("handle dragged")
    still_readouts(panel)
    grab_behind_a_body(panel)
    progress("handle grabbed behind the Body")

    builds_at_ok = len(builds)
    undo_before = list(doc.UndoNames)
    panel.accept()
    FreeCADGui.updateGui()
    wait(0.5)
    report["panel_closed"] = haptic_panel.active_panel is None
    report["redraws_after_ok"] = len(builds) - builds_at_ok
    report["final_offset"] = offset(axis, original)
    report["undo_added"] = [n for n in doc.UndoNames if n not in undo_before] or list(doc.UndoNames)[:1]
    report["ok_png"] = grab_window_with_view("haptic_hand_ok.png")
    from pivy import coin
    from contactwb.gui.panels import hand_handle
    search = coin.SoSearchAction()
    search.setName(hand_handle.NODE_NAME)
    search.apply(FreeCADGui.activeDocument().activeView().getSceneGraph())
    report["handle_left_in_view"] = search.getPath() is not None
    # The panel closed: the bodies can be picked again where the handle was grabbed behind the Body.
    info = FreeCADGui.activeDocument().activeView().getObjectInfo(tuple(report["behind_pixel"]))
    report["behind_picked_after_ok"] = doc.getObject(info["Object"]).Label if info else None


session_helpers.run_and_report(run, report)
