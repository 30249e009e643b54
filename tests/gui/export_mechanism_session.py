"""Runs inside the FreeCAD GUI (freecad tests/gui/export_mechanism_session.py under Xvfb).

Opens the bundled motor (its sidecar motor.annotations.json beside it), finds
its contacts, runs Contacts_ExportMechanism twice through its dialog (filled
and accepted by a timer, as a user would): URDF into a folder, then MJCF into
an .xml file; saves the dialog and the window, and writes what it saw to
$CONTACTS_GUI_RESULT."""
import os
import sys
import traceback

import FreeCADGui
from PySide2 import QtCore, QtWidgets

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))  # the shared session helpers
import session_helpers  # noqa: E402

out_dir = os.environ["CONTACTS_GUI_OUT"]
report = {"errors": [], "dialogs": []}


wait = session_helpers.wait


def answer(fmt_index, path, screenshot):
    """Fills the modal dialog once it is up, saves its picture and presses OK."""
    def fill():
        dialog = QtWidgets.QApplication.activeModalWidget()
        if dialog is None or dialog.objectName() != "ContactsExportMechanism":
            QtCore.QTimer.singleShot(50, fill)
            return
        try:
            combos = dialog.findChildren(QtWidgets.QComboBox)
            edits = dialog.findChildren(QtWidgets.QLineEdit)
            fmt, ground = combos[0], combos[1]
            fmt.setCurrentIndex(fmt_index)
            seen = {"title": dialog.windowTitle(), "formats": [fmt.itemText(i) for i in range(fmt.count())],
                    "grounds": ground.count(), "annotations": edits[1].text(),
                    "density": dialog.findChildren(QtWidgets.QDoubleSpinBox)[0].value(),
                    "suggested": edits[0].text()}
            edits[0].setText(path)
            wait(0.2)
            dialog.grab().save(screenshot)
            seen["png"] = screenshot
            report["dialogs"].append(seen)
            box = dialog.findChildren(QtWidgets.QDialogButtonBox)[0]
            box.button(QtWidgets.QDialogButtonBox.Ok).click()
        except Exception:
            report["errors"].append(traceback.format_exc())
            dialog.reject()
    QtCore.QTimer.singleShot(50, fill)


def run():
    main = FreeCADGui.getMainWindow()
    doc = session_helpers.open_sample_in_workbench()
    report["command_listed"] = "Contacts_ExportMechanism" in FreeCADGui.listCommands()
    from contactwb.gui.commands.mechanism import Contacts_ExportMechanism
    report["active_before"] = Contacts_ExportMechanism().IsActive()
    from contactwb.make import make_contact_analysis
    group = make_contact_analysis(doc)
    doc.recompute()
    FreeCADGui.updateGui()
    report["active_after"] = Contacts_ExportMechanism().IsActive()
    undo_before = list(doc.UndoNames)
    urdf_dir = os.path.join(out_dir, "export_mechanism_urdf")
    mjcf = os.path.join(out_dir, "export_mechanism_mjcf", "motor.xml")
    os.makedirs(os.path.dirname(mjcf), exist_ok=True)
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(group)
    answer(0, urdf_dir, os.path.join(out_dir, "export_mechanism_dialog_urdf.png"))
    FreeCADGui.runCommand("Contacts_ExportMechanism")
    wait(0.5)
    answer(1, mjcf, os.path.join(out_dir, "export_mechanism_dialog_mjcf.png"))
    FreeCADGui.runCommand("Contacts_ExportMechanism")
    wait(0.5)
    report["urdf_dir"] = urdf_dir
    report["mjcf"] = mjcf
    report["urdf_files"] = sorted(os.listdir(urdf_dir)) if os.path.isdir(urdf_dir) else []
    report["mjcf_files"] = sorted(os.listdir(os.path.dirname(mjcf)))
    report["undo_unchanged"] = list(doc.UndoNames) == undo_before  # files only: the document is not changed
    toolbar = next((t for t in main.findChildren(QtWidgets.QToolBar) if t.windowTitle() == "Contacts"), None)
    report["toolbar_has_command"] = toolbar is not None and "Export mechanism..." in [a.text() for a in toolbar.actions()]
    FreeCADGui.activeDocument().activeView().viewIsometric()
    FreeCADGui.SendMsgToActiveView("ViewFit")
    wait(0.5)
    path = os.path.join(out_dir, "export_mechanism_window.png")
    main.grab().save(path)
    report["window_png"] = path


session_helpers.run_and_report(run, report)
