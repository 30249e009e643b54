"""Runs inside the FreeCAD GUI (freecad tests/gui/table_session.py under Xvfb)
for tests/gui/test_gui_table.py: issue 21 item 7, the contact table at 500
contacts. A grid of 16 x 16 blocks (480 planar fits between neighbours), 20
of them holding a pin in a bore (20 cylindrical joints); Find contacts from
the toolbar; the table opened: its order, its summary pane, the room left to
the 3D view, the plane contacts' extent; Zoom to and Isolate from the table,
judged on the rendered view (the contact's box projected on the screen, the
paint's pixels). Screenshots go to $CONTACTS_GUI_OUT."""
import os
import sys
import time

import FreeCAD
import FreeCADGui
from PySide2 import QtGui, QtWidgets

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))  # the shared session helpers
import session_helpers  # noqa: E402
from session_helpers import settle  # noqa: E402

out_dir = os.environ["CONTACTS_GUI_OUT"]
report = {"errors": {}, "times": {}}
state = {}

GRID = 16            # blocks per side
BLOCK = (10.0, 10.0, 6.0)
PINS = 20            # the first blocks (row order) hold a pin
PIN_RADIUS = 2.0


step = session_helpers.stepper(report["errors"])


def grab_window(name):
    return session_helpers.grab_window(out_dir, name)


def colour_pixels(path, colour, tolerance=0.2):
    """How many pixels of the image are within `tolerance` (per channel, 0..1)
    of `colour` ("#rrggbb")."""
    image = QtGui.QImage(path)
    target = [int(colour[i:i + 2], 16) for i in (1, 3, 5)]
    limit = tolerance * 255
    count = 0
    for y in range(0, image.height(), 2):
        for x in range(0, image.width(), 2):
            pixel = QtGui.QColor(image.pixel(x, y))
            if all(abs(a - b) <= limit for a, b in zip((pixel.red(), pixel.green(), pixel.blue()), target)):
                count += 1
    return count * 4


def save_view(name, width=900, height=650):
    return session_helpers.save_view(out_dir, name, width, height)


def make_grid():
    """The grid: block i, j at (10 i, 10 j, 0); blocks 0..19 bored through
    (radius 2) at their centre, a pin of the same radius and height in it."""
    import Part
    doc = FreeCAD.newDocument("Grid")
    doc.UndoMode = 1
    dx, dy, dz = BLOCK
    for j in range(GRID):
        for i in range(GRID):
            index = j * GRID + i
            block = Part.makeBox(dx, dy, dz, FreeCAD.Vector(i * dx, j * dy, 0))
            centre = FreeCAD.Vector(i * dx + dx / 2, j * dy + dy / 2, 0)
            if index < PINS:
                block = block.cut(Part.makeCylinder(PIN_RADIUS, dz, centre))
                pin = doc.addObject("Part::Feature", f"Pin{index:03d}")
                pin.Shape = Part.makeCylinder(PIN_RADIUS, dz, centre)
                pin.Label = f"Pin-{index:03d}"
            obj = doc.addObject("Part::Feature", f"Block{index:03d}")
            obj.Shape = block
            obj.Label = f"Block-{i:02d}-{j:02d}"
    doc.recompute()
    return doc


def open_grid():
    main = FreeCADGui.getMainWindow()
    main.resize(1400, 1000)
    FreeCADGui.activateWorkbench("ContactsWorkbench")
    doc = make_grid()
    state["doc"] = doc
    view = FreeCADGui.activeDocument().activeView()
    view.viewIsometric()
    view.fitAll()
    settle()


def find_contacts():
    from contactwb.document.identify import analyses, is_contact
    from contactwb.gui.panels import task_panel
    doc = state["doc"]
    FreeCADGui.Selection.clearSelection()
    start = time.perf_counter()
    FreeCADGui.runCommand("Contacts_FindContacts")
    settle()
    accepted = task_panel.current.accept()
    settle()
    report["times"]["find_contacts_panel"] = round(time.perf_counter() - start, 3)
    (group,) = analyses(doc)
    state["group"] = group
    contacts = [c for c in group.Group if is_contact(c)]
    report["find"] = {"accepted": accepted, "count": len(contacts),
                      "types": sorted({c.ContactType for c in contacts}),
                      "by_type": {t: sum(c.ContactType == t for c in contacts) for t in ("PLF", "CLJ")}}


def table_at_500():
    from contactwb.gui.panels import contact_table
    doc = state["doc"]
    main = FreeCADGui.getMainWindow()
    start = time.perf_counter()
    FreeCADGui.runCommand("Contacts_ShowContactTable")
    settle()
    report["times"]["open_table"] = round(time.perf_counter() - start, 3)
    dock = contact_table.dock()
    widget = dock.widget()
    state["table"] = widget
    table = widget.table
    rows = [r for r in range(table.rowCount())]
    order = []
    for row in rows:
        contact = widget.contact_of_row(row)
        order.append([contact.ContactType, *sorted((contact.BodyA, contact.BodyB)), contact.Number])
    area = main.findChild(QtWidgets.QMdiArea)
    row_height = table.rowHeight(0) if table.rowCount() else 1
    result = {"rows": table.rowCount(), "order": order,
              "sort_column": table.horizontalHeader().sortIndicatorSection(),
              "main_width": main.width(), "view_width": area.width(), "view_height": area.height(),
              "dock_width": dock.width(), "dock_area": int(main.dockWidgetArea(dock)),
              "table_rows_shown": table.viewport().height() // max(row_height, 1),
              "summary_height": widget.summary_pane.height(), "widget_height": widget.height(),
              "summary": widget.summary.toPlainText()}
    # every plane contact's extent (a 10 x 6 face shared whole), the revolution ones' span and radius
    cells = {}
    for row in rows:
        kind = table.item(row, 1).text()
        cells.setdefault(kind, set()).add((table.item(row, 5).text(), table.item(row, 6).text(),
                                           table.item(row, 7).text()))
    result["cells"] = {kind: sorted(map(list, values)) for kind, values in cells.items()}
    result["headers"] = [table.horizontalHeaderItem(c).text() for c in range(table.columnCount())]
    # the summary folded: the table takes the room
    widget.summary_toggle.setChecked(False)
    settle()
    result["folded_rows_shown"] = table.viewport().height() // max(row_height, 1)
    result["folded_summary_height"] = widget.summary_pane.height()
    widget.summary_toggle.setChecked(True)
    settle()
    result["png"] = grab_window("gui_table_500.png")
    report["table"] = result


def projected_box(box):
    """The contact box's corners on the screen: (xmin, ymin, xmax, ymax) and the view's size."""
    view = FreeCADGui.activeDocument().activeView()
    points = [view.getPointOnScreen(FreeCAD.Vector(x, y, z))
              for x in (box.XMin, box.XMax) for y in (box.YMin, box.YMax) for z in (box.ZMin, box.ZMax)]
    xs, ys = [p[0] for p in points], [p[1] for p in points]
    return [min(xs), min(ys), max(xs), max(ys)], list(view.getSize())


def middle_contact(kind):
    """A contact of this type well inside the grid (blocks 7-8 of row 8)."""
    widget, group = state["table"], state["group"]
    if kind == "PLF":
        wanted = {"Block-07-08", "Block-08-08"}
        return next(c for c in group.Group if {getattr(c, "BodyA", ""), getattr(c, "BodyB", "")} == wanted)
    return next(c for c in group.Group if getattr(c, "ContactType", "") == kind)


def zoom_to():
    """Zoom to frames the contact's common region (a PLF in the grid's middle,
    then a pin's CLJ), from the whole grid in view."""
    from contactwb.gui.panels import contact_extent
    widget = state["table"]
    view = FreeCADGui.activeDocument().activeView()
    result = {}
    for kind in ("PLF", "CLJ"):
        view.viewIsometric()
        view.fitAll()
        settle()
        contact = middle_contact(kind)
        box = contact_extent.contact_box(contact)
        before, size = projected_box(box)
        widget.table.clearSelection()
        widget.table.selectRow(widget.row_of(contact.Name))
        widget.zoom()
        settle()
        after, size = projected_box(box)
        result[kind] = {"box": [box.XLength, box.YLength, box.ZLength], "before": before, "after": after,
                        "size": size, "undo": list(state["doc"].UndoNames)}
    result["png"] = save_view("gui_table_zoom_to.png")
    report["zoom"] = result


def isolate():
    """Isolate from the table: the two blocks ghosted, everything else
    ghosted fainter (never hidden), the contact's paint showing through
    them, no other contact's paint."""
    from contactwb.gui.overlay.colours import legend_colours
    doc, group, widget = state["doc"], state["group"], state["table"]
    contact = middle_contact("PLF")
    colour = legend_colours()["PLF"]
    view = FreeCADGui.activeDocument().activeView()
    widget.table.clearSelection()
    widget.table.selectRow(widget.row_of(contact.Name))
    widget.zoom()
    FreeCADGui.Selection.clearSelection()  # the selection colour must not cover the paint
    before_png = save_view("_table_before_isolate.png")
    result = {"before_pixels": colour_pixels(before_png, colour)}
    os.remove(before_png)
    undo = list(doc.UndoNames)
    widget.table.selectRow(widget.row_of(contact.Name))
    widget.isolate()
    FreeCADGui.Selection.clearSelection()
    settle()
    png = save_view("gui_table_isolate.png")
    result["after_pixels"] = colour_pixels(png, colour)
    result["image_pixels"] = 900 * 650
    parts = [o for o in doc.Objects if o.TypeId == "Part::Feature"]
    result["shown"] = sorted(o.Label for o in parts if o.ViewObject.Visibility)
    result["pair"] = sorted((contact.BodyA, contact.BodyB))
    result["transparency"] = sorted({o.ViewObject.Transparency for o in parts if o.Label in result["pair"]})
    result["others_transparency"] = sorted({o.ViewObject.Transparency for o in parts if o.Label not in result["pair"]})
    result["parts"] = len(parts)
    from contactwb.document.identify import is_contact
    result["contacts_shown"] = [c.Name for c in group.Group if is_contact(c) and c.ViewObject.Visibility]
    result["contact"] = contact.Name
    result["overlay_visible"] = group.ViewObject.Proxy.overlay.visible.get(contact.Name)
    result["undo_same"] = list(doc.UndoNames) == undo
    result["png"] = png
    widget.show_all()
    settle()
    result["after_show_all"] = {"hidden": sum(not o.ViewObject.Visibility for o in parts),
                                "transparency": sorted({o.ViewObject.Transparency for o in parts}),
                                "contacts_shown": sum(bool(c.ViewObject.Visibility) for c in group.Group
                                                      if is_contact(c))}
    report["isolate"] = result


for function in (open_grid, find_contacts, table_at_500, zoom_to, isolate):
    step(function)
session_helpers.write_report_and_exit(report)
