"""Runs inside the FreeCAD GUI (freecad tests/gui/annotation_session.py under
Xvfb) for tests/gui/test_gui_annotations.py: the motor's contacts annotated
as Resources/samples/motor.annotations.json says, through
Contacts_AnnotateContact and its dialog (from the tree's selection, a
contact's context menu and the contact table's rows); the joints derived
again after each step; undone step by step; redone; saved, reopened and
recomputed. Writes what it saw to $CONTACTS_GUI_RESULT."""
import json
import os
import sys
import tempfile

import FreeCAD
import FreeCADGui
from PySide2 import QtCore, QtWidgets

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))  # the shared session helpers
import session_helpers  # noqa: E402

out_dir = os.environ["CONTACTS_GUI_OUT"]
report = {"errors": {}}
state = {}


step = session_helpers.stepper(report["errors"], settle_rounds=1)


contacts_of = session_helpers.contacts_of


def dof(group):
    """(DOF, rigid groups) from the analysis' Mobility lines."""
    lines = list(group.Mobility)
    degrees = next((int(line.split(":")[1].split("(")[0]) for line in lines
                    if line.startswith("Degrees of freedom")), None)
    return degrees, sum(1 for line in lines if line.startswith("Rigid group"))


def matching(group, entry):
    """The group's contacts an annotations-file entry covers."""
    return [c for c in contacts_of(group) if {c.BodyA, c.BodyB} == {entry["a"], entry["b"]}
            and (not entry.get("type") or c.ContactType == entry["type"])]


def fill_dialog(intent, fit, seen):
    """Fills the modal annotate dialog when it shows, then presses OK."""
    def fill():
        dialog = QtWidgets.QApplication.activeModalWidget()
        if dialog is None or dialog.objectName() != "ContactsAnnotateDialog":
            QtCore.QTimer.singleShot(100, fill)
            return
        dialog.findChild(QtWidgets.QComboBox, "intent").setCurrentText(intent)
        dialog.findChild(QtWidgets.QLineEdit, "fit").setText(fit)
        QtWidgets.QApplication.processEvents()
        seen["verdict"] = dialog.findChild(QtWidgets.QLabel, "verdict").text()
        seen["ok_enabled"] = dialog.ok_button.isEnabled()
        if "png" not in state:
            state["png"] = os.path.join(out_dir, "annotate_dialog.png")
            dialog.grab().save(state["png"])
        if seen["ok_enabled"]:
            dialog.accept()
        else:
            dialog.reject()
    QtCore.QTimer.singleShot(100, fill)


def annotate(contacts, intent, fit, how):
    """One annotate step through the command, from the tree's selection, a
    contact's context menu or the contact table's rows."""
    seen = {}
    FreeCADGui.Selection.clearSelection()
    fill_dialog(intent, fit, seen)
    if how == "context menu":  # the contact's own menu in the tree: selects it, runs the command
        menu = QtWidgets.QMenu()
        vobj = contacts[0].ViewObject
        vobj.Proxy.setupContextMenu(vobj, menu)
        (action,) = [a for a in menu.actions() if a.text().startswith("Annotate")]
        action.trigger()
    elif how == "table":
        from contactwb.gui.panels import contact_table
        FreeCADGui.runCommand("Contacts_ShowContactTable")
        widget = contact_table.dock().widget()
        widget.fill()
        widget.table.clearSelection()
        names = {c.Name for c in contacts}
        mode = QtCore.QItemSelectionModel.Select | QtCore.QItemSelectionModel.Rows
        for row in range(widget.table.rowCount()):
            contact = widget.contact_of_row(row)
            if contact is not None and contact.Name in names:
                widget.table.selectionModel().select(widget.table.model().index(row, 0), mode)
        FreeCADGui.updateGui()
        seen["table_selected"] = sorted(o.Name for o in FreeCADGui.Selection.getSelection())
        FreeCADGui.runCommand("Contacts_AnnotateContact")
    else:
        for contact in contacts:
            FreeCADGui.Selection.addSelection(contact)
        FreeCADGui.runCommand("Contacts_AnnotateContact")
    FreeCADGui.updateGui()
    return seen


def find_and_derive():
    FreeCADGui.getMainWindow().resize(1400, 1000)
    FreeCADGui.activateWorkbench("ContactsWorkbench")
    FreeCADGui.runCommand("Contacts_OpenSample")
    doc = FreeCAD.ActiveDocument
    from contactwb.gui import task_panel
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.runCommand("Contacts_FindContacts")
    task_panel.current.accept()
    from contactwb import export
    (group,) = export.analyses(doc)
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(group)
    FreeCADGui.runCommand("Contacts_DeriveJoints")
    FreeCADGui.Control.closeDialog()
    state.update(doc=doc, group=group)
    report["unannotated"] = {"contacts": len(contacts_of(group)), "dof": dof(group), "mobility": list(group.Mobility),
                             "intents": sorted({c.Intent for c in contacts_of(group)})}


def annotate_as_the_file():
    """The file's entries grouped by (intent, fit): one command each."""
    import contactwb
    doc, group = state["doc"], state["group"]
    with open(os.path.join(contactwb.SAMPLES_DIR, "motor.annotations.json")) as stream:
        entries = json.load(stream)
    steps = {}
    for entry in entries:
        steps.setdefault((entry["intent"], entry.get("fit", "")), []).extend(matching(group, entry))
    # each way in: the tree's selection, the contact table's rows, a contact's context menu (one contact)
    ways = ["tree", "tree", "table", "context menu", "tree", "table"]
    done = []
    for index, ((intent, fit), contacts) in enumerate(steps.items()):
        how = ways[index] if index < len(ways) else "tree"
        seen = annotate(contacts, intent, fit, how)
        done.append({"intent": intent, "fit": fit, "contacts": len(contacts), "how": how, "seen": seen,
                     "set": sorted({(c.Intent, c.Fit) for c in contacts}), "dof": dof(group),
                     "undo": doc.UndoNames[0] if doc.UndoNames else None})
    report["annotated"] = {"steps": done, "dof": dof(group), "mobility": list(group.Mobility),
                           "marked": sum(1 for c in contacts_of(group) if c.Intent != "none"),
                           "fit_classes": sorted({c.FitClass for c in contacts_of(group) if c.FitClass}),
                           "contacts": len(contacts_of(group)),
                           "undo_names": list(doc.UndoNames)[:len(done) + 1]}
    state["steps"] = len(done)
    # the picture: the rotor group, its joints, a pressed contact selected (its properties shown)
    pressed = next(c for c in contacts_of(group) if {c.BodyA, c.BodyB} == {"Axis", "Rotor-front"})
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(pressed)
    view = FreeCADGui.activeDocument().activeView()
    view.viewIsometric()
    view.fitAll()
    FreeCADGui.updateGui()
    # the window with the 3D view's own render pasted in (a plain grab leaves the OpenGL area blank)
    path, pasted = session_helpers.grab_window_with_view(out_dir, "annotated_motor.png")
    report["annotated"]["png"] = path
    report["annotated"]["view_pasted"] = pasted
    from contactwb.gui.overlay.colours import selection_colour
    report["annotated"]["view_area"] = session_helpers.view_area_colours(path, selection_colour())
    report["annotated"]["dialog_png"] = state.get("png")


def a_contradicting_fit_is_refused():
    """H7/g6 asked as an interference: the dialog says why and OK is off; nothing changes."""
    doc, group = state["doc"], state["group"]
    contact = next(c for c in contacts_of(group) if {c.BodyA, c.BodyB} == {"Axis", "Bearing-front"}
                   and c.ContactType == "CLJ")
    before = (len(doc.UndoNames), contact.Intent, contact.Fit)
    seen = annotate([contact], "interference", "H7/g6", "tree")
    report["refused"] = {"seen": seen, "unchanged": before == (len(doc.UndoNames), contact.Intent, contact.Fit)}


def undo_and_redo():
    doc, group = state["doc"], state["group"]
    for _ in range(state["steps"]):
        doc.undo()
    FreeCADGui.updateGui()
    report["undone"] = {"dof": dof(group), "mobility": list(group.Mobility),
                        "intents": sorted({c.Intent for c in contacts_of(group)}),
                        "fits": sorted({c.Fit for c in contacts_of(group)})}
    for _ in range(state["steps"]):
        doc.redo()
    FreeCADGui.updateGui()
    report["redone"] = {"dof": dof(group), "marked": sum(1 for c in contacts_of(group) if c.Intent != "none")}


def identity(contact):
    """Body pair and faces (a contact found again after being lost is a new object, numbered anew)."""
    from contactwb.objects.contact_objects import key_of_contact
    return repr(key_of_contact(contact))


def save_reopen_recompute():
    doc, group = state["doc"], state["group"]
    marks = {identity(c): (c.Intent, c.Fit) for c in contacts_of(group) if c.Intent != "none"}
    path = os.path.join(tempfile.mkdtemp(prefix="contacts-annotations-"), "motor_annotated.FCStd")
    name = group.Name
    doc = session_helpers.save_and_reopen(doc, path)
    group = doc.getObject(name)
    reopened = {identity(c): (c.Intent, c.Fit) for c in contacts_of(group) if c.Intent != "none"}
    # move the axis away and back: the contacts are found again (same objects by identity)
    axis = doc.getObjectsByLabel("Axis")[0]
    placement = axis.Placement
    axis.Placement = FreeCAD.Placement(placement.Base + FreeCAD.Vector(0, 0, 300), placement.Rotation)
    doc.recompute()
    moved = dof(group)
    axis.Placement = placement
    doc.recompute()
    recomputed = {identity(c): (c.Intent, c.Fit) for c in contacts_of(group) if c.Intent != "none"}
    report["reopened"] = {"marks": len(marks), "kept_on_open": reopened == marks,
                          "kept_on_recompute": recomputed == marks, "dof_moved_away": moved,
                          "dof": dof(group), "mobility": list(group.Mobility),
                          "touched": "Touched" in group.State or "Error" in group.State}
    FreeCAD.closeDocument(doc.Name)


def report_view():
    report["report_view"] = session_helpers.report_view_text()


for function in (find_and_derive, annotate_as_the_file, a_contradicting_fit_is_refused, undo_and_redo,
                 save_reopen_recompute, report_view):
    step(function)
session_helpers.write_report_and_exit(report)
