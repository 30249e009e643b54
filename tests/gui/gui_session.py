"""Runs inside the FreeCAD GUI (freecad tests/gui/gui_session.py under Xvfb).

Drives the real workbench: lists and activates it, opens the bundled motor,
runs Contacts_FindContacts, takes screenshots, and writes what it saw to
$CONTACTS_GUI_RESULT (JSON) for tests/gui/test_gui.py to check."""
import json
import os
import traceback

import FreeCAD
import FreeCADGui
from PySide2 import QtWidgets

out_dir = os.environ["CONTACTS_GUI_OUT"]
report = {"errors": []}


def find_toolbar(title):
    for bar in FreeCADGui.getMainWindow().findChildren(QtWidgets.QToolBar):
        if bar.windowTitle() == title:
            return bar
    return None


def run():
    main = FreeCADGui.getMainWindow()
    main.resize(1280, 960)
    report["workbench_listed"] = "ContactsWorkbench" in FreeCADGui.listWorkbenches()
    FreeCADGui.activateWorkbench("ContactsWorkbench")
    FreeCADGui.updateGui()
    report["active_workbench"] = FreeCADGui.activeWorkbench().name()
    bar = find_toolbar("Contacts")
    report["toolbar_visible"] = bool(bar and bar.isVisible())
    if bar:
        buttons = [b for b in bar.findChildren(QtWidgets.QToolButton) if b.defaultAction()
                   and b.isVisible()]
        report["toolbar_actions"] = [b.defaultAction().text() for b in buttons]
        if buttons:
            top_left = buttons[0].mapTo(main, buttons[0].rect().topLeft())
            report["first_button_rect"] = [top_left.x(), top_left.y(), buttons[0].width(), buttons[0].height()]

    doc = FreeCAD.openDocument(os.environ["CONTACTS_SAMPLE"])
    FreeCADGui.SendMsgToActiveView("ViewFit")
    FreeCADGui.activeDocument().activeView().viewIsometric()
    FreeCADGui.runCommand("Contacts_FindContacts")
    FreeCADGui.updateGui()
    groups = [o for o in doc.Objects if getattr(o, "Proxy", None).__class__.__name__ == "ContactAnalysis"]
    report["analyses"] = len(groups)
    if groups:
        report["contacts"] = len(groups[0].Group)
        report["summary"] = list(groups[0].Summary)
        report["contact_types"] = sorted({c.ContactType for c in groups[0].Group})
        # Double-click behaviour: select one contact's faces and count them.
        from contactwb.gui import view_providers
        view_providers.select_contact_faces(groups[0].Group[0])
        report["selected_faces"] = sum(len(s.SubElementNames) for s in FreeCADGui.Selection.getSelectionEx("", 0))
    report["undo_names"] = list(doc.UndoNames)
    FreeCADGui.SendMsgToActiveView("ViewFit")
    FreeCADGui.updateGui()
    window_png = os.path.join(out_dir, "gui_main_window.png")
    main.grab().save(window_png)
    report["window_width"] = main.width()  # the grab may be scaled by the device pixel ratio
    view_png = os.path.join(out_dir, "gui_3d_view.png")
    FreeCADGui.activeDocument().activeView().saveImage(view_png, 800, 600, "White")
    report["screenshots"] = [window_png, view_png]


try:
    run()
except Exception:  # the report carries it to the test, which fails on it
    report["errors"].append(traceback.format_exc())
with open(os.environ["CONTACTS_GUI_RESULT"], "w") as stream:
    json.dump(report, stream, indent=1)
os._exit(0)  # FreeCAD's own shutdown is slow and may prompt; the report is written
