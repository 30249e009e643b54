"""Runs inside the FreeCAD GUI (freecad tests/gui/paint_session.py under
Xvfb) for tests/gui/test_gui_paint.py: the paint from the core's common
regions (issue 21), the interferences as first-class results and the
contacts made visible (selection highlight through the parts, see-through
mode), on the motor with the GUI's own commands. Each step records what the
document and the view hold; screenshots go to $CONTACTS_GUI_OUT."""
import os
import sys

import FreeCAD
import FreeCADGui
import numpy
from PySide2 import QtGui

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))  # the shared session helpers
import session_helpers  # noqa: E402
from session_helpers import settle  # noqa: E402

out_dir = os.environ["CONTACTS_GUI_OUT"]
report = {"errors": {}}
state = {}


step = session_helpers.stepper(report["errors"])


def save_view(name, width=900, height=650):
    return session_helpers.save_view(out_dir, name, width, height)


def pixels(path):
    """(h, w, 3) RGB array of a saved picture."""
    image = QtGui.QImage(path).convertToFormat(QtGui.QImage.Format_RGB32)
    data = numpy.frombuffer(image.constBits(), dtype=numpy.uint8, count=image.byteCount())
    return data.reshape(image.height(), image.width(), 4)[:, :, 2::-1].astype(int)  # BGRA -> RGB


def near(rgb, colour, within=60):
    """Pixels within `within` (0-255, each channel) of a colour (0-1 floats)."""
    target = numpy.array([round(c * 255) for c in colour])
    return int((numpy.abs(rgb - target).max(axis=2) <= within).sum())


contacts_of = session_helpers.contacts_of


def paint_state(group):
    from contactwb.core.kinds import CIRCLE_TYPES
    from contactwb.objects import regions
    overlay = group.ViewObject.Proxy.overlay
    contacts = contacts_of(group)
    return {"contacts": len(contacts), "surface_contacts": sum(1 for c in contacts if c.ContactType not in CIRCLE_TYPES),
            "drawn": len(overlay.names), "common": overlay.common_contacts, "core": overlay.core_contacts,
            "computed": regions.cache_of(group).computed, "failures": list(overlay.failures),
            "undo": list(group.Document.UndoNames)}


def open_and_find():
    doc = session_helpers.open_contacts_sample()
    group = session_helpers.find_contacts_in_panel(doc)
    state["doc"], state["group"] = doc, group
    report["found"] = paint_state(group)


def screw_axis(group, name):
    """A point and the direction of the screw's axis (its CLJ contacts')."""
    clj = [c for c in contacts_of(group) if c.ContactType == "CLJ" and name in (c.BodyA, c.BodyB)]
    return FreeCAD.Vector(clj[0].Point), FreeCAD.Vector(clj[0].Direction)


def turn_one_part():
    """Screw-1 turned 30 degrees about its own axis: every contact stays,
    the screw's placement changed: the core computes its contacts' regions
    only."""
    doc, group = state["doc"], state["group"]
    screw = doc.getObjectsByLabel("Screw-1")[0]
    state["screw_home"] = FreeCAD.Placement(screw.Placement)
    point, axis = screw_axis(group, "Screw-1")
    before = {c.Name: c.Label for c in contacts_of(group)}
    turn = FreeCAD.Placement(FreeCAD.Vector(), FreeCAD.Rotation(axis, 30), point)  # about the axis
    doc.openTransaction("Turn Screw-1")
    screw.Placement = turn.multiply(screw.Placement)
    doc.commitTransaction()
    FreeCADGui.runCommand("Std_Refresh")
    settle()
    after = paint_state(group)
    after["same_contacts"] = {c.Name: c.Label for c in contacts_of(group)} == before
    after["screw_contacts"] = sum(1 for c in contacts_of(group) if "Screw-1" in (c.BodyA, c.BodyB))
    report["turned"] = after
    FreeCADGui.runCommand("Std_Undo")
    settle()
    report["turn_undone"] = paint_state(group)


def interferences():
    """Screw-1 pushed 0.6 mm sideways into its holes: three interferences in
    the tree, the table, the legend, the panel's message and the export,
    their volumes checked against OCCT Booleans of the parts."""
    from contactwb.document import export
    from contactwb.document.identify import interferences_of, is_interference
    from contactwb.gui.panels import contact_table, task_panel
    doc, group = state["doc"], state["group"]
    screw = doc.getObjectsByLabel("Screw-1")[0]
    home = screw.Placement
    doc.openTransaction("Move Screw-1")
    screw.Placement = FreeCAD.Placement(home.Base + FreeCAD.Vector(0.6, 0, 0), home.Rotation)
    doc.commitTransaction()
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(group)
    FreeCADGui.runCommand("Contacts_FindContacts")  # the same analysis, found again in place
    panel, texts = task_panel.current, []
    shown = panel.status.setText
    panel.status.setText = lambda text: (texts.append(text), shown(text))  # the panel closes on OK
    panel.accept()
    message = texts[-1] if texts else ""
    settle()
    found = interferences_of(group)  # under the analysis' Interferences group
    booleans = {}
    for obj in found:
        a, b = (doc.getObjectsByLabel(n)[0] for n in (obj.BodyA, obj.BodyB))
        booleans[f"{obj.BodyA}|{obj.BodyB}"] = a.Shape.common(b.Shape).Volume
    table = contact_table.show()
    table.fill(doc)
    rows = []
    for row in range(table.table.rowCount()):
        if table.table.item(row, 1).text() == "Interference":
            rows.append([table.table.item(row, c).text() for c in range(4)] +
                        [table.table.item(row, 4).data(contact_table.QtCore.Qt.UserRole + 1)])
    overlay = group.ViewObject.Proxy.overlay
    report["interferences"] = {
        "objects": sorted([o.BodyA, o.BodyB, o.Volume.Value, o.Shape.Volume, o.Label, o.Label2,
                           list(o.ViewObject.ShapeColor[:3])] for o in found),
        "booleans": booleans, "rows": rows, "legend": overlay.interferences, "message": message,
        "count": group.InterferenceCount, "export": export.to_json(group)["interferences"],
        "undo": list(doc.UndoNames[:2])}
    FreeCADGui.Selection.clearSelection()
    view = FreeCADGui.activeDocument().activeView()
    view.viewIsometric()
    view.fitAll()
    FreeCADGui.runCommand("Contacts_GhostBodies")
    report["interferences"]["png"] = save_view("paint_interferences.png")
    FreeCADGui.runCommand("Contacts_GhostBodies")
    for _ in range(2):  # the search, then the move
        FreeCADGui.runCommand("Std_Undo")
        settle()
    report["interferences"]["after_undo"] = sorted(o.Name for o in doc.Objects if is_interference(o))
    report["interferences"]["screw_back"] = screw.Placement.multiply(home.inverse()).isIdentity()


def highlight_and_see_through():
    """Selecting a contact (the tree, or the table) highlights its common
    region in 3D, also where the parts hide it; Ghost parts shows the
    contacts inside the assembly; neither enters the undo stack."""
    from contactwb.gui.overlay.colours import legend_colours, selection_colour, type_colour  # noqa: F401
    from pivy import coin
    doc, group = state["doc"], state["group"]
    proxy = group.ViewObject.Proxy
    result = {"touched_before": "Touched" in group.State}
    if result["touched_before"]:
        doc.recompute()
        settle()
    result["paint_shown"] = proxy.switch.whichChild.getValue() == coin.SO_SWITCH_ALL
    result["drawn"] = len(proxy.overlay.names)
    undo = list(doc.UndoNames)
    view = FreeCADGui.activeDocument().activeView()
    view.viewIsometric()
    view.fitAll()
    FreeCADGui.Selection.clearSelection()
    plain = pixels(save_view("paint_unselected.png"))
    # the screw's bore in the body: hidden inside the body and the covers
    bore = next(c for c in contacts_of(group) if c.ContactType == "CLJ" and
                {c.BodyA, c.BodyB} == {"Body", "Screw-1"})
    FreeCADGui.Selection.addSelection(bore)
    settle()
    overlay = group.ViewObject.Proxy.overlay
    selected_png = save_view("paint_selected_contact.png")
    selected = pixels(selected_png)
    green = selection_colour()
    result.update({"highlighted": sorted(overlay.highlighted), "bore": bore.Name,
                   "selection": [s.ObjectName for s in FreeCADGui.Selection.getSelectionEx(doc.Name, 0)],
                   "selection_pixels_before": near(plain, green), "selection_pixels": near(selected, green),
                   "png_selected": selected_png})
    FreeCADGui.Selection.clearSelection()
    colours = legend_colours()
    solid = pixels(save_view("paint_assembled.png"))
    FreeCADGui.runCommand("Contacts_GhostBodies")
    ghost_png = save_view("paint_see_through.png")
    ghosted = pixels(ghost_png)
    result["ghosted_transparency"] = doc.getObjectsByLabel("Body")[0].ViewObject.Transparency
    # the paint as lit in the view: CLJ near its blue; PLF's orange by hue
    # (its lit shades are far from the legend's flat colour)
    colour = type_colour("CLJ", False, colours)
    result["CLJ_pixels_solid"] = near(solid, colour, 40)
    result["CLJ_pixels_see_through"] = near(ghosted, colour, 40)
    for name, rgb in (("solid", solid), ("see_through", ghosted)):
        r, g, b = rgb[:, :, 0], rgb[:, :, 1], rgb[:, :, 2]
        result[f"PLF_pixels_{name}"] = int(((r > g + 50) & (g > b + 30)).sum())
    FreeCADGui.runCommand("Contacts_GhostBodies")
    result["restored_transparency"] = doc.getObjectsByLabel("Body")[0].ViewObject.Transparency
    result["png_see_through"] = ghost_png
    result["undo_before"], result["undo_after"] = undo, list(doc.UndoNames)
    report["visible"] = result


for function in (open_and_find, turn_one_part, interferences, highlight_and_see_through):
    step(function)
session_helpers.write_report_and_exit(report)
