"""Runs inside the FreeCAD GUI (freecad tests/gui/day_session.py under Xvfb)
for tests/gui/test_gui_day.py: issue 21's designer's day replayed with the
GUI's own commands on the motor. Find contacts (twice, nothing selected);
delete Screw-4, recompute, undo, derive joints, save and reopen; move a part,
recompute, undo; ghost, isolate, show all. Each step records what the
document holds afterwards (objects, names, numbers, labels, undo names) and
its duration; screenshots go to $CONTACTS_GUI_OUT. Each step records its own
traceback, so one failure does not hide the others."""
import os
import re
import sys
import tempfile
import time

import FreeCAD
import FreeCADGui
from PySide2 import QtCore, QtWidgets
from pivy import coin

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))  # the shared session helpers
import session_helpers  # noqa: E402
from session_helpers import settle  # noqa: E402

out_dir = os.environ["CONTACTS_GUI_OUT"]
report = {"errors": {}, "times": {}}
state = {}
LABEL = re.compile(r"^(PLF|CLJ|CJU|SPF|LAF|SPT|TRF) (\d+): (.+) \u2013 (.+)$")


step = session_helpers.stepper(report["errors"])


class Timer:
    """Times one user action (wall clock, printed by the test)."""

    def __init__(self, name):
        self.name = name

    def __enter__(self):
        self.start = time.perf_counter()

    def __exit__(self, *exc):
        settle()
        report["times"][self.name] = round(time.perf_counter() - self.start, 3)


def save_view(name, width=900, height=650):
    return session_helpers.save_view(out_dir, name, width, height)


def show_in_tree(obj):
    """Selects `obj` (the tree expands to it and the property view shows it)."""
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(obj)
    settle()


def grab_window(name, undo_list=False):
    """The main window as shown (the 3D view's render pasted in); with
    undo_list, the Undo toolbar button's list of undo entries (FreeCAD's
    UndoDialog menu, filled as when it drops down) drawn under the button.
    Returns (path, whether the view was pasted, the list's entries or None)."""
    from PySide2 import QtGui
    settle()
    path, pasted = session_helpers.grab_window_with_view(out_dir, name)
    if not undo_list:
        return path, pasted, None
    main = FreeCADGui.getMainWindow()
    # the toolbar's Undo button: its action's menu is FreeCAD's UndoDialog
    buttons = [b for b in main.findChildren(QtWidgets.QToolButton) if b.isVisible() and b.defaultAction() is not None
               and b.defaultAction().menu() is not None
               and b.defaultAction().menu().metaObject().className() == "Gui::Dialog::UndoDialog"]
    if not buttons:
        return path, pasted, None
    button = buttons[0]
    menu = button.defaultAction().menu()
    menu.aboutToShow.emit()  # FreeCAD fills the list when it drops down
    menu.adjustSize()
    entries = [action.text() for action in menu.actions()]
    image = QtGui.QImage(path)
    painter = QtGui.QPainter(image)
    painter.drawPixmap(button.mapTo(main, QtCore.QPoint(0, button.height())), menu.grab())
    painter.end()
    image.save(path)
    return path, pasted, entries


report_view_text = session_helpers.report_view_text


def new_report_text():
    """What the Report view printed since the last call."""
    text = report_view_text()
    seen = state.get("report_seen", 0)
    state["report_seen"] = len(text)
    return text[seen:]


def answer_dialogs():
    """Accepts the question a command asks (Std_Delete's 'the analysis
    depends on it'), as the designer did."""
    for widget in QtWidgets.QApplication.topLevelWidgets():
        if isinstance(widget, QtWidgets.QMessageBox) and widget.isVisible():
            button = widget.button(QtWidgets.QMessageBox.Yes) or widget.button(QtWidgets.QMessageBox.Ok)
            if button is not None:
                button.click()


def run(command):
    """A GUI command, as from its menu or toolbar."""
    timer = QtCore.QTimer()
    timer.timeout.connect(answer_dialogs)
    timer.start(100)
    try:
        FreeCADGui.runCommand(command)
    finally:
        timer.stop()
    settle()


def analyses(doc):
    from contactwb.document.identify import analyses as found
    return found(doc)


contacts_of = session_helpers.contacts_of


def joints_of(group):
    from contactwb.document.identify import is_joint
    return [c for c in group.Group if is_joint(c)]


def snapshot(doc, group):
    """What the analysis holds: its contacts by name (number, label,
    bodies), whether every contact is in it, its paint, the undo names."""
    from contactwb.document.identify import is_contact
    contacts = contacts_of(group)
    labels_ok = all(LABEL.match(c.Label) and LABEL.match(c.Label).group(2) == str(c.Number)
                    and LABEL.match(c.Label).group(1) == c.ContactType
                    and LABEL.match(c.Label).groups()[2:] == (c.BodyA, c.BodyB) for c in contacts)
    proxy = group.ViewObject.Proxy
    return {"contacts": {c.Name: [c.Number, c.Label, c.BodyA, c.BodyB] for c in contacts},
            "count": len(contacts), "labels_ok": labels_ok,
            "all_in_group": sorted(o.Name for o in doc.Objects if is_contact(o)) == sorted(c.Name for c in contacts),
            "numbers_unique": len({c.Number for c in contacts}) == len(contacts),
            "analyses": len(analyses(doc)), "touched": "Touched" in group.State,
            "drawn": len(proxy.overlay.names),
            "paint_shown": proxy.switch.whichChild.getValue() == coin.SO_SWITCH_ALL,
            "undo": list(doc.UndoNames), "redo": list(doc.RedoNames)}


def run_panel():
    """Find contacts from the toolbar with nothing selected; OK."""
    from contactwb.gui.panels import task_panel
    FreeCADGui.Selection.clearSelection()
    run("Contacts_FindContacts")
    return task_panel.current.accept()


def open_sample():
    FreeCADGui.getMainWindow().resize(1400, 1000)
    FreeCADGui.activateWorkbench("ContactsWorkbench")
    run("Contacts_OpenSample")
    doc = FreeCAD.ActiveDocument
    doc.UndoMode = 1
    state["doc"] = doc
    new_report_text()


def find_contacts_twice():
    """Item 3: a second Find contacts on the same scope updates the analysis."""
    doc = state["doc"]
    with Timer("find_contacts_panel"):
        accepted = run_panel()
    (group,) = analyses(doc)
    state["group"] = group
    first = snapshot(doc, group)
    from view_probes import ResultTouches
    touches = ResultTouches(doc)  # counts the paint's rebuilds
    with Timer("find_contacts_again_panel"):
        again = run_panel()
    touches.stop()
    report["find_twice"] = {"accepted": [accepted, again], "first": first, "second": snapshot(doc, group),
                            "paint_builds_again": touches.paint_builds,
                            "labels": sorted(o.Label for o in doc.Objects if o.TypeId == "App::DocumentObjectGroupPython")}
    # the picture (item 5): one analysis in the tree, selected (its 35 contacts in the property view)
    show_in_tree(group)
    report["find_twice"]["png"] = grab_window("gui_day_find_twice.png")[:2]


def delete_recompute_undo_derive():
    """Item 1: Find contacts, delete Screw-4, Recompute, Undo, Derive joints."""
    doc, group = state["doc"], state["group"]
    before = snapshot(doc, group)
    screw = doc.getObjectsByLabel("Screw-4")[0]
    screw_name = screw.Name
    result = {"before": before, "screw_contacts": sum("Screw-4" in (c.BodyA, c.BodyB) for c in contacts_of(group))}
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(screw)
    with Timer("delete_screw"):
        run("Std_Delete")  # FreeCAD's Delete recomputes: the contacts go in its one entry
    result["deleted"] = doc.getObject(screw_name) is None
    result["after_delete"] = snapshot(doc, group)
    with Timer("recompute_after_delete"):
        run("Std_Refresh")
    result["after_recompute"] = snapshot(doc, group)
    result["png_deleted"] = save_view("day_screw4_deleted.png")
    with Timer("undo_delete"):
        run("Std_Undo")
    result["screw_back"] = doc.getObject(screw_name) is not None
    result["after_undo"] = snapshot(doc, group)
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(group)
    with Timer("derive_joints"):
        run("Contacts_DeriveJoints")
    FreeCADGui.Control.closeDialog()
    result["after_derive"] = snapshot(doc, group)
    result["joints"] = len(joints_of(group))
    result["joint_labels_ok"] = all(re.match(r"^J\d+ \w+: .+ \u2013 .+$", j.Label) for j in joints_of(group))
    result["report"] = new_report_text()
    view = FreeCADGui.activeDocument().activeView()
    view.viewIsometric()
    view.fitAll()
    result["png"] = save_view("day_undo_then_joints.png")
    # save, reopen: no warnings, the same contacts and joints, drawn
    path = os.path.join(tempfile.mkdtemp(prefix="contacts-day-"), "motor_day.FCStd")
    names = sorted(before["contacts"])
    doc.saveAs(path)
    FreeCAD.closeDocument(doc.Name)
    settle()
    new_report_text()
    with Timer("reopen"):
        doc = FreeCAD.openDocument(path)
        settle()
        QtCore.QThread.msleep(200)
        settle()
    group = analyses(doc)[0]
    session_helpers.wait_for_drawing(group)  # its drawing is deferred until the document has opened
    result["reopened"] = snapshot(doc, group)
    result["reopened_names_same"] = sorted(snapshot(doc, group)["contacts"]) == names
    result["reopened_joints"] = len(joints_of(group))
    result["reopen_report"] = new_report_text()
    state["doc"], state["group"] = doc, group
    report["delete_undo"] = result


def move_recompute_undo():
    """Item 2: move a part, recompute, one Ctrl+Z; identity kept (item 4)."""
    doc, group = state["doc"], state["group"]
    doc.UndoMode = 1
    before = snapshot(doc, group)
    cover = doc.getObjectsByLabel("Back-cover")[0]
    placement = FreeCAD.Placement(cover.Placement)
    doc.openTransaction("Move Back-cover")  # as the Placement dialog records it
    cover.Placement = FreeCAD.Placement(placement.Base + FreeCAD.Vector(0, 0, -40), placement.Rotation)
    doc.commitTransaction()
    settle()
    result = {"before": before, "touched_after_move": "Touched" in group.State}
    with Timer("recompute_after_move"):
        run("Std_Refresh")
    result["after_recompute"] = snapshot(doc, group)
    result["png_moved"] = save_view("day_cover_moved.png")
    # the picture (items 4 and 6): the tree's contacts keep their numbers (the cover's are gone), the
    # undo list holds the move and one "Recompute contacts"; the contact shown is the last one
    last = max(contacts_of(group), key=lambda c: c.Number)
    show_in_tree(last)
    path, pasted, entries = grab_window("gui_day_move_recomputed.png", undo_list=True)
    result["png_window"] = [path, pasted]
    result["undo_list_shown"] = entries
    result["shown_contact"] = [last.Name, last.Label]
    FreeCADGui.Selection.clearSelection()
    with Timer("undo_move"):
        run("Std_Undo")
    result["placement_restored"] = cover.Placement.multiply(placement.inverse()).isIdentity()
    result["after_undo"] = snapshot(doc, group)
    # after one Ctrl+Z: the cover back with its contacts, in their group, under the same numbers
    show_in_tree(last)
    result["png_undone"] = grab_window("gui_day_move_undone.png")[:2]
    FreeCADGui.Selection.clearSelection()
    with Timer("recompute_after_undo"):
        doc.recompute()
    result["after_undo_recompute"] = snapshot(doc, group)
    report["move_undo"] = result


def interferences():
    """Item 5: Screw-1 pushed 0.6 mm sideways into its holes: the CLI's three
    interferences as objects with their solids (red), in the export and the
    panel's message; one Ctrl+Z removes them with the move."""
    from contactwb.document import export
    from contactwb.document.identify import interferences_of, is_interference
    doc, group = state["doc"], state["group"]
    screw = doc.getObjectsByLabel("Screw-1")[0]
    placement = FreeCAD.Placement(screw.Placement)
    doc.openTransaction("Move Screw-1")
    screw.Placement = FreeCAD.Placement(placement.Base + FreeCAD.Vector(0.6, 0, 0), placement.Rotation)
    doc.commitTransaction()
    with Timer("recompute_with_interferences"):
        run("Std_Refresh")
    found = interferences_of(group)  # under the analysis' Interferences group
    result = {"objects": sorted([o.BodyA, o.BodyB, o.Volume.Value, o.Shape.Volume, o.Label, o.Label2,
                                 list(o.ViewObject.ShapeColor[:3]), o.ViewObject.Visibility] for o in found),
              "count": group.InterferenceCount, "lines": list(group.Interferences),
              "export": export.to_json(group)["interferences"],
              "undo": list(doc.UndoNames[:2])}
    # the picture: the overlaps in red on the see-through screw, the rest hidden
    shown = {o.Name: o.ViewObject.Visibility for o in doc.Objects if o.TypeId == "Part::Feature"}
    for obj in doc.Objects:
        if obj.TypeId == "Part::Feature":
            obj.ViewObject.Visibility = obj is screw
    screw.ViewObject.Transparency = 75
    for joint in joints_of(group):
        joint.ViewObject.Visibility = False
    switch = group.ViewObject.Proxy.switch
    switch.whichChild.setValue(coin.SO_SWITCH_NONE)
    view = FreeCADGui.activeDocument().activeView()
    view.viewIsometric()
    view.fitAll()
    result["png"] = save_view("day_interferences.png")
    result["display_modes"] = [o.ViewObject.DisplayMode for o in found]
    for name, visible in shown.items():
        doc.getObject(name).ViewObject.Visibility = visible
    screw.ViewObject.Transparency = 0
    for joint in joints_of(group):
        joint.ViewObject.Visibility = True
    switch.whichChild.setValue(coin.SO_SWITCH_ALL)
    run("Std_Undo")
    result["after_undo"] = {"interferences": [o.Name for o in doc.Objects if is_interference(o)],
                            "snapshot": snapshot(doc, group)}
    report["interferences"] = result


def view_only_actions():
    """Item 2: ghost, isolate, show all never enter the undo stack."""
    doc, group = state["doc"], state["group"]
    undo = list(doc.UndoNames)
    run("Contacts_GhostBodies")
    ghosted_undo = list(doc.UndoNames)
    contact = contacts_of(group)[0]
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(contact)
    run("Contacts_IsolateContact")
    isolated_undo = list(doc.UndoNames)
    run("Contacts_ShowAll")
    report["view_only"] = {"before": undo, "ghost": ghosted_undo, "isolate": isolated_undo,
                           "show_all": list(doc.UndoNames)}


def report_view():
    report["report_view"] = report_view_text()


for function in (open_sample, find_contacts_twice, delete_recompute_undo_derive, move_recompute_undo,
                 interferences, view_only_actions, report_view):
    step(function)
session_helpers.write_report_and_exit(report)
