"""What the session scripts (run inside FreeCAD's GUI, tests/gui/*_session.py)
share: settling and waiting with the event loop running, the step runner that
keeps each step's traceback, the 3D view saved as a picture, a window grab
with the 3D view's own render pasted in, the report written at the end. A session imports it after putting its own folder
on sys.path (FreeCAD runs a script with only its own folders there)."""
import os
import time
import traceback

import FreeCADGui
from PySide2 import QtWidgets


def wait(seconds):
    """Processes Qt events for `seconds` (the GUI keeps drawing and timers fire)."""
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        QtWidgets.QApplication.processEvents()
        time.sleep(0.005)


def settle(rounds=5):
    """Lets FreeCAD's GUI catch up `rounds` times: deferred work (view
    providers attached, drawings rebuilt) done before anything is looked at."""
    for _ in range(rounds):
        FreeCADGui.updateGui()


def wait_for_drawing(group, seconds=3.0):
    """Lets the event loop run until the analysis group's deferred drawing is done (its view
    provider retries every 50 ms while the document is still opening or recomputing), `seconds`
    at most: whether it is drawn and shown."""
    import time
    from pivy import coin
    proxy = group.ViewObject.Proxy
    deadline = time.monotonic() + seconds
    while True:
        FreeCADGui.updateGui()
        drawn = not proxy._stale and proxy.switch.whichChild.getValue() == coin.SO_SWITCH_ALL
        if drawn or time.monotonic() > deadline:
            return drawn
        time.sleep(0.05)


def stepper(errors, settle_rounds=5):
    """A session's `step(function)`: runs function, keeps its traceback in
    errors[function's name] (one failing step does not hide the others), then
    settles the GUI `settle_rounds` times."""
    def step(function):
        try:
            function()
        except Exception:
            errors[function.__name__] = traceback.format_exc()
        settle(settle_rounds)
    return step


def save_view(out_dir, name, width=900, height=650, background="White", settle_rounds=5):
    """The active 3D view rendered to out_dir/name (width x height pixels, on
    `background`: "White", "Current", ...) once the GUI has settled: its path."""
    settle(settle_rounds)
    path = os.path.join(out_dir, name)
    FreeCADGui.activeDocument().activeView().saveImage(path, width, height, background)
    return path


def contacts_of(group):
    """The contact objects of an analysis group."""
    from contactwb.document.identify import is_contact
    return [c for c in group.Group if is_contact(c)]


def active_view_area():
    """The active 3D view's OpenGL area (the widget Coin draws in) and its
    top-left corner in the main window, or (None, None) when no view shows."""
    from PySide2 import QtCore
    main = FreeCADGui.getMainWindow()
    # The active 3D view's widget: Quarter's (FreeCAD 0.20), an OpenGL viewport,
    # in the active window of the MDI area (other documents' views are hidden tabs).
    mdi = main.findChild(QtWidgets.QMdiArea)
    active = mdi.activeSubWindow() if mdi is not None else None
    viewers = [w for w in (active or main).findChildren(QtWidgets.QWidget)
               if w.metaObject().className() == "SIM::Coin3D::Quarter::QuarterWidget" and w.isVisible()]
    if not viewers:
        return None, None
    area = viewers[0].viewport() if hasattr(viewers[0], "viewport") else viewers[0]
    return area, area.mapTo(main, QtCore.QPoint(0, 0))


def grab_window_with_view(out_dir, name):
    """The main window as shown, saved as out_dir/name: its grab with the 3D
    view's own render pasted in place (grabbing a window leaves its OpenGL area
    blank). Returns (path, whether a view was pasted)."""
    from PySide2 import QtGui
    main = FreeCADGui.getMainWindow()
    QtWidgets.QApplication.processEvents()
    path = os.path.join(out_dir, name)
    pixmap = main.grab()
    area, corner = active_view_area()
    if area is not None:
        rendered = os.path.join(out_dir, "view_" + name)
        FreeCADGui.activeDocument().activeView().saveImage(rendered, area.width(), area.height(), "Current")
        painter = QtGui.QPainter(pixmap)
        painter.drawImage(corner, QtGui.QImage(rendered))
        painter.end()
    pixmap.save(path)
    return path, area is not None


def view_area_colours(path, colour=None, within=40):
    """What the 3D view's area of a saved window picture shows: {"colours":
    distinct colours, "background": the share of its most common colour (a
    blank OpenGL area is one colour), "near": the share within `within`
    (0-255, each channel) of `colour` (0-1 floats)}; None when no view shows.
    Every other row and column is read: enough to tell."""
    from PySide2 import QtGui
    area, corner = active_view_area()
    if area is None:
        return None
    image = QtGui.QImage(path).copy(corner.x(), corner.y(), area.width(), area.height())
    image = image.convertToFormat(QtGui.QImage.Format_RGB32)
    target = [round(c * 255) for c in colour] if colour else None
    counts, near = {}, 0
    for y in range(0, image.height(), 2):
        for x in range(0, image.width(), 2):
            rgb = image.pixel(x, y) & 0xFFFFFF
            counts[rgb] = counts.get(rgb, 0) + 1
            if target and max(abs((rgb >> 16) - target[0]), abs(((rgb >> 8) & 0xFF) - target[1]),
                              abs((rgb & 0xFF) - target[2])) <= within:
                near += 1
    total = sum(counts.values()) or 1
    return {"colours": len(counts), "background": max(counts.values(), default=0) / total, "near": near / total}


def grab_window(out_dir, name):
    """grab_window_with_view once the GUI has settled: the picture's path."""
    settle()
    return grab_window_with_view(out_dir, name)[0]


def report_view_text():
    """All the text of FreeCAD's Report view (messages, warnings, tracebacks)."""
    texts = []
    for dock in FreeCADGui.getMainWindow().findChildren(QtWidgets.QDockWidget):
        if dock.objectName() == "Report view":
            texts += [edit.toPlainText() for edit in dock.findChildren(QtWidgets.QTextEdit)]
    return "\n".join(texts)


def with_modal_dialog(command, handle, first_ms=300, period_ms=200):
    """Runs FreeCAD command `command`, which opens a modal dialog (and returns
    when it closes), and calls handle(dialog) once the dialog is up (looked
    for after first_ms, then every period_ms); handle closes it."""
    from PySide2 import QtCore

    def poll():
        dialog = QtWidgets.QApplication.activeModalWidget()
        if dialog is None:
            QtCore.QTimer.singleShot(period_ms, poll)
            return
        handle(dialog)

    QtCore.QTimer.singleShot(first_ms, poll)
    FreeCADGui.runCommand(command)


def save_and_reopen(doc, path):
    """Saves doc as path, closes it, opens the file again: the reopened document."""
    import FreeCAD
    doc.saveAs(path)
    FreeCAD.closeDocument(doc.Name)
    doc = FreeCAD.openDocument(path)
    FreeCADGui.updateGui()
    return doc


def open_sample_in_workbench():
    """The main window at 1280x960, the workbench active and $CONTACTS_SAMPLE open: its document."""
    import FreeCAD
    FreeCADGui.getMainWindow().resize(1280, 960)
    FreeCADGui.activateWorkbench("ContactsWorkbench")
    return FreeCAD.openDocument(os.environ["CONTACTS_SAMPLE"])


def open_contacts_sample():
    """The main window at 1400x1000, the workbench active, its bundled motor opened by
    Contacts_OpenSample with undo on: its document."""
    import FreeCAD
    FreeCADGui.getMainWindow().resize(1400, 1000)
    FreeCADGui.activateWorkbench("ContactsWorkbench")
    FreeCADGui.runCommand("Contacts_OpenSample")
    settle()
    doc = FreeCAD.ActiveDocument
    doc.UndoMode = 1
    return doc


def find_contacts_in_panel(doc):
    """Find contacts on the whole document (nothing selected), the task panel accepted: its one analysis."""
    from contactwb.document.identify import analyses
    from contactwb.gui.panels import task_panel
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.runCommand("Contacts_FindContacts")
    task_panel.current.accept()
    settle()
    (analysis,) = analyses(doc)
    return analysis


def run_and_report(run, report):
    """Runs the session, keeps its traceback in report["errors"], writes the report to
    $CONTACTS_GUI_RESULT and ends FreeCAD (os._exit: no dialog can hold it open)."""
    try:
        run()
    except Exception:
        report["errors"].append(traceback.format_exc())
    write_report_and_exit(report)


def write_report_and_exit(report):
    """Writes the report (JSON) to $CONTACTS_GUI_RESULT and ends FreeCAD
    (os._exit: no dialog can hold it open)."""
    import json
    with open(os.environ["CONTACTS_GUI_RESULT"], "w") as stream:
        json.dump(report, stream, indent=1)
    os._exit(0)


def open_haptic_panel(part):
    """Selects `part`, runs Contacts_HapticTrial, clears the selection: the panel it opened (None: none)."""
    from contactwb.gui.panels import haptic_panel
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(part)
    FreeCADGui.runCommand("Contacts_HapticTrial")
    wait(0.5)
    FreeCADGui.Selection.clearSelection()
    return haptic_panel.active_panel
