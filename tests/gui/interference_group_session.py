"""Runs inside the FreeCAD GUI (freecad tests/gui/interference_group_session.py
under Xvfb) for tests/gui/test_gui_interference_group.py: the Interferences
group of an analysis (issue 21). Replays a designer's steps on the motor:
Find contacts; Screw-1 moved 0.6 mm sideways into its holes; Find contacts
again (in place); the group under the analysis holds the three interferences;
Screw-1 moved back; recompute: the group is gone; one Ctrl+Z: the move back
and its recompute undone, the group back; save; close; reopen. Each step
records the document's state; screenshots go to $CONTACTS_GUI_OUT."""
import os
import sys
import traceback

import FreeCAD
import FreeCADGui

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import session_helpers  # noqa: E402
from session_helpers import grab_window_with_view, run_and_report  # noqa: E402

out_dir = os.environ["CONTACTS_GUI_OUT"]
report = {"errors": []}


def settle():
    for _ in range(5):
        FreeCADGui.updateGui()


def group_state(doc, analysis):
    """The analysis' Interferences groups and their children, as the tree holds them."""
    from contactwb.document.identify import is_interference, is_interference_group
    holders = [o for o in analysis.Group if is_interference_group(o)]
    found = []
    for holder in holders:
        for obj in holder.Group:
            a, b = (doc.getObjectsByLabel(n)[0] for n in (obj.BodyA, obj.BodyB))
            found.append({"name": obj.Name, "label": obj.Label, "label2": obj.Label2, "a": obj.BodyA,
                          "b": obj.BodyB, "number": obj.Number, "volume": obj.Volume.Value,
                          "solid": obj.Shape.Volume, "is_interference": is_interference(obj),
                          # OCCT's Boolean common of the two parts as they are now: the independent figure
                          "boolean": a.Shape.common(b.Shape).Volume,
                          "colour": list(obj.ViewObject.ShapeColor[:3]), "shown": obj.ViewObject.Visibility,
                          "provider": type(obj.ViewObject.Proxy).__name__})
    tree_children = [o.Name for o in analysis.ViewObject.claimChildren()]
    return {"groups": [{"name": h.Name, "label": h.Label, "label2": h.Label2, "count": h.Count,
                        "provider": type(h.ViewObject.Proxy).__name__,
                        "tree_children": [o.Name for o in h.ViewObject.claimChildren()],
                        "in_analysis_tree": h.Name in tree_children} for h in holders],
            "interferences": found,
            "direct": [o.Name for o in analysis.Group if is_interference(o)],
            "all_in_document": sorted(o.Name for o in doc.Objects if is_interference(o) or is_interference_group(o)),
            "count": analysis.InterferenceCount, "lines": list(analysis.Interferences),
            "touched": "Touched" in analysis.State, "undo": list(doc.UndoNames[:3]),
            "touched_results": sorted(o.Name for o in analysis.Group + [i for h in holders for i in h.Group]
                                      if "Touched" in o.State)}


def expand_tree(analysis):
    """The tree expanded and scrolled to the Interferences group (for the screenshot)."""
    from PySide2 import QtCore, QtWidgets
    for tree in FreeCADGui.getMainWindow().findChildren(QtWidgets.QTreeWidget):
        tree.expandAll()
        settle()
        items = tree.findItems("I1:", QtCore.Qt.MatchRecursive | QtCore.Qt.MatchStartsWith, 0)
        if items:
            tree.scrollToItem(items[0], QtWidgets.QAbstractItemView.PositionAtCenter)


def move(doc, screw, placement, name):
    doc.openTransaction(name)
    screw.Placement = placement
    doc.commitTransaction()


def run():
    from contactwb.document import export
    from contactwb.document.identify import analyses
    from contactwb.gui.panels import task_panel
    doc = session_helpers.open_contacts_sample()
    analysis = session_helpers.find_contacts_in_panel(doc)
    report["clean"] = group_state(doc, analysis)
    screw = doc.getObjectsByLabel("Screw-1")[0]
    home = FreeCAD.Placement(screw.Placement)
    pushed = FreeCAD.Placement(home.Base + FreeCAD.Vector(0.6, 0, 0), home.Rotation)
    move(doc, screw, pushed, "Move Screw-1")
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(analysis)
    FreeCADGui.runCommand("Contacts_FindContacts")  # the same analysis, found again in place
    task_panel.current.accept()
    settle()
    report["pushed"] = group_state(doc, analysis)
    report["pushed"]["export"] = export.to_json(analysis)["interferences"]
    FreeCADGui.Selection.clearSelection()
    expand_tree(analysis)
    view = FreeCADGui.activeDocument().activeView()
    view.viewIsometric()
    view.fitAll()
    FreeCADGui.runCommand("Contacts_GhostBodies")  # the red solids inside the see-through parts
    settle()
    report["pushed"]["png"] = grab_window_with_view(out_dir, "gui_interference_group.png")[0]
    FreeCADGui.runCommand("Contacts_GhostBodies")
    # moved back: the recompute (one entry, "Recompute contacts") removes them and their group
    move(doc, screw, home, "Move Screw-1 back")
    report["moved_back_touched"] = "Touched" in analysis.State
    doc.recompute()
    settle()
    report["back"] = group_state(doc, analysis)
    # one Ctrl+Z: the recompute and the move back it followed
    FreeCADGui.runCommand("Std_Undo")
    settle()
    report["undone"] = group_state(doc, analysis)
    report["undone"]["screw_pushed"] = (screw.Placement.Base - pushed.Base).Length < 1e-9 and \
        screw.Placement.Rotation.multiply(pushed.Rotation.inverted()).Angle < 1e-9
    report["undone"]["export"] = export.to_json(analysis)["interferences"]
    path = os.path.join(out_dir, "interference_group.FCStd")
    if os.path.exists(path):
        os.remove(path)
    doc.saveAs(path)
    FreeCAD.closeDocument(doc.Name)
    settle()
    doc = FreeCAD.openDocument(path)
    settle()
    (analysis,) = analyses(doc)
    session_helpers.wait_for_drawing(analysis)  # the paint is drawn once the document is loaded
    report["reopened"] = group_state(doc, analysis)
    report["reopened"]["export"] = export.to_json(analysis)["interferences"]
    report["reopened"]["legend"] = analysis.ViewObject.Proxy.overlay.interferences
    expand_tree(analysis)
    view = FreeCADGui.activeDocument().activeView()
    view.viewIsometric()
    view.fitAll()
    FreeCADGui.runCommand("Contacts_GhostBodies")
    settle()
    report["reopened"]["png"] = grab_window_with_view(out_dir, "gui_interference_group_reopened.png")[0]


try:
    run_and_report(run, report)
except Exception:
    report["errors"].append(traceback.format_exc())
    run_and_report(lambda: None, report)
