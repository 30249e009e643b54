"""What the session scripts (run inside FreeCAD's GUI, tests/gui/*_session.py)
share: waiting with the event loop running, and a window grab with the 3D
view's own render pasted in. A session imports it after putting its own folder
on sys.path (FreeCAD runs a script with only its own folders there)."""
import os
import time

import FreeCADGui
from PySide2 import QtWidgets


def wait(seconds):
    """Processes Qt events for `seconds` (the GUI keeps drawing and timers fire)."""
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        QtWidgets.QApplication.processEvents()
        time.sleep(0.005)


def grab_window_with_view(out_dir, name):
    """The main window as shown, saved as out_dir/name: its grab with the 3D
    view's own render pasted in place (grabbing a window leaves its OpenGL area
    blank). Returns (path, whether a view was pasted)."""
    from PySide2 import QtCore, QtGui
    main = FreeCADGui.getMainWindow()
    QtWidgets.QApplication.processEvents()
    path = os.path.join(out_dir, name)
    pixmap = main.grab()
    # The active 3D view's widget: Quarter's (FreeCAD 0.20), an OpenGL viewport,
    # in the active window of the MDI area (other documents' views are hidden tabs).
    mdi = main.findChild(QtWidgets.QMdiArea)
    active = mdi.activeSubWindow() if mdi is not None else None
    viewers = [w for w in (active or main).findChildren(QtWidgets.QWidget)
               if w.metaObject().className() == "SIM::Coin3D::Quarter::QuarterWidget" and w.isVisible()]
    if viewers:
        area = viewers[0].viewport() if hasattr(viewers[0], "viewport") else viewers[0]
        rendered = os.path.join(out_dir, "view_" + name)
        FreeCADGui.activeDocument().activeView().saveImage(rendered, area.width(), area.height(), "Current")
        painter = QtGui.QPainter(pixmap)
        painter.drawImage(area.mapTo(main, QtCore.QPoint(0, 0)), QtGui.QImage(rendered))
        painter.end()
    pixmap.save(path)
    return path, bool(viewers)


def open_sample_in_workbench():
    """The main window at 1280x960, the workbench active and $CONTACTS_SAMPLE open: its document."""
    import FreeCAD
    FreeCADGui.getMainWindow().resize(1280, 960)
    FreeCADGui.activateWorkbench("ContactsWorkbench")
    return FreeCAD.openDocument(os.environ["CONTACTS_SAMPLE"])


def run_and_report(run, report):
    """Runs the session, keeps its traceback in report["errors"], writes the report to
    $CONTACTS_GUI_RESULT and ends FreeCAD (os._exit: no dialog can hold it open)."""
    import json
    import traceback
    try:
        run()
    except Exception:
        report["errors"].append(traceback.format_exc())
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
