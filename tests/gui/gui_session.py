"""Runs inside the FreeCAD GUI (freecad tests/gui/gui_session.py under Xvfb).

Drives the real workbench: lists and activates it, opens the bundled motor,
runs Contacts_FindContacts, inspects the contacts' drawing in the 3D view
(Coin nodes, screenshots with most bodies hidden), exports the contacts, saves
and re-opens the document, and writes what it saw to $CONTACTS_GUI_RESULT
(JSON) for tests/gui/test_gui.py to check."""
import json
import os
import sys
import tempfile
import traceback

import FreeCAD
import FreeCADGui
from PySide2 import QtWidgets
from pivy import coin
from contactwb.objects.contact_objects import is_contact_analysis

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))  # the shared session helpers
import session_helpers  # noqa: E402

out_dir = os.environ["CONTACTS_GUI_OUT"]
report = {"errors": []}


def find_toolbar(title):
    for bar in FreeCADGui.getMainWindow().findChildren(QtWidgets.QToolBar):
        if bar.windowTitle() == title:
            return bar
    return None


# Shown for the contacts screenshot: the shaft and the parts at both ends,
# whose contact faces (PLF on the covers, CLJ on the shaft and in the bores)
# face the camera. The blue stator and body are hidden: they would pass for CLJ.
SHOWN_BODIES = ("Axis", "Front-cover", "Back-cover", "Bearing-back")


def count_nodes(root, node_type):
    """The distinct nodes of a type under root, behind switches in any state
    too (a node shared by several branches is found once per path)."""
    search = coin.SoSearchAction()
    search.setType(node_type.getClassTypeId())
    search.setInterest(coin.SoSearchAction.ALL)
    search.setSearchingAll(True)
    search.apply(root)
    nodes = {}
    for path in search.getPaths():
        node = path.getTail()
        nodes[int(node.this)] = node
    return list(nodes.values())


def overlay_report(group):
    """What the group's view provider draws, counted in its Coin graph."""
    root = group.ViewObject.RootNode
    face_sets = count_nodes(root, coin.SoIndexedFaceSet)
    proxy = group.ViewObject.Proxy
    return {
        "face_sets": len(face_sets),
        "triangles": sum(f.coordIndex.getNum() // 4 for f in face_sets),
        "line_sets": len(count_nodes(root, coin.SoLineSet)),
        "layers": sorted(n.getName().getString() for n in count_nodes(root, coin.SoSeparator)
                         if n.getName().getString().startswith("Contacts_")),
        "proxy_triangles": proxy.overlay.triangles,
        "proxy_faces": proxy.overlay.faces,
        "common_contacts": proxy.overlay.common_contacts,
        "contacts_drawn": len(proxy.overlay.names),
        # counted from the document: the faces the drawing must hold
        "contact_faces": len({(root.Name, subname) for c in group.Group for links in (c.FacesA, c.FacesB)
                              for root, subnames in links for subname in subnames}),
        "provider": type(proxy).__name__,
        "child_providers": sorted({type(c.ViewObject.Proxy).__name__ for c in group.Group}),
    }


def contact_switch(group, contact):
    return group.ViewObject.Proxy.overlay.switches[contact.Name].whichChild.getValue()


def save_view(name):
    path = os.path.join(out_dir, name)
    FreeCADGui.updateGui()
    FreeCADGui.activeDocument().activeView().saveImage(path, 800, 600, "White")
    return path


def check_overlay(doc, group):
    """The drawing: nodes, visibility, highlight, screenshots."""
    from contactwb.gui import view_providers
    session_helpers.wait_for_drawing(group)  # the drawing is deferred until the search is over
    report["overlay"] = overlay_report(group)
    report["legend"] = dict(view_providers.TYPE_COLOURS)
    report["icons"] = {kind: view_providers.contact_icon_path(kind) for kind in view_providers.TYPE_COLOURS}

    # Children: hiding one contact hides its part of the drawing only.
    FreeCADGui.Selection.clearSelection()
    first, second = group.Group[0], group.Group[1]
    first.ViewObject.Visibility = False
    report["hidden_contact_switch"] = contact_switch(group, first)
    report["other_contact_switch"] = contact_switch(group, second)
    first.ViewObject.Visibility = True
    report["shown_again_switch"] = contact_switch(group, first)

    # Highlight: a contact selected in the tree, then by its faces (double-click).
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(second)
    report["highlight_tree"] = sorted(group.ViewObject.Proxy.overlay.highlighted)
    view_providers.select_contact_faces(first)
    report["highlight_faces"] = sorted(group.ViewObject.Proxy.overlay.highlighted)
    FreeCADGui.Selection.clearSelection()
    report["highlight_cleared"] = sorted(group.ViewObject.Proxy.overlay.highlighted)
    report["contact_names"] = [first.Name, second.Name]

    # Screenshots: most bodies hidden, contacts shown, then the group hidden.
    for obj in doc.Objects:
        if obj.TypeId == "Part::Feature":
            obj.ViewObject.Visibility = obj.Label in SHOWN_BODIES
    view = FreeCADGui.activeDocument().activeView()
    view.viewIsometric()
    view.fitAll()
    report["contacts_png"] = save_view("gui_contacts.png")
    group.ViewObject.Visibility = False
    report["group_hidden_switch"] = group.ViewObject.Proxy.switch.whichChild.getValue()
    report["no_contacts_png"] = save_view("gui_contacts_hidden.png")
    group.ViewObject.Visibility = True
    report["group_shown_switch"] = group.ViewObject.Proxy.switch.whichChild.getValue()
    report["sides_shown"] = sum(switch.whichChild.getValue() == coin.SO_SWITCH_ALL
                                for sides in group.ViewObject.Proxy.overlay.sides.values()
                                for switch, _ in sides)
    for obj in doc.Objects:
        if obj.TypeId == "Part::Feature":
            obj.ViewObject.Visibility = True
    report["sides_shown_all_bodies"] = sum(switch.whichChild.getValue() == coin.SO_SWITCH_ALL
                                           for sides in group.ViewObject.Proxy.overlay.sides.values()
                                           for switch, _ in sides)


def check_export(group):
    from contactwb import export
    from contactwb.gui import commands
    report["export_active"] = commands.Contacts_ExportContacts().IsActive()
    report["exports"] = {}
    for extension in ("json", "csv"):
        path = os.path.join(out_dir, f"motor_contacts.{extension}")
        report["exports"][extension] = [path, export.export_contacts(group, path)]


def check_reopen(doc, group):
    """Save, close, re-open: the view providers come back and draw again."""
    folder = tempfile.mkdtemp(prefix="contacts-gui-")
    path = os.path.join(folder, "motor_with_contacts.FCStd")
    name = group.Name
    doc.saveAs(path)
    FreeCAD.closeDocument(doc.Name)
    doc = FreeCAD.openDocument(path)
    session_helpers.wait_for_drawing(doc.getObject(name))  # the drawing is built once loading is over
    report["reopened"] = overlay_report(doc.getObject(name))
    return doc, doc.getObject(name)


# Exploded view: offsets along the motor axis, mm (as tools/render_motor.py).
EXPLODE_Z = {"Back-cover": -32, "Bearing-back": -14, "Axis": 42, "Rotor-back": 42, "Rotor-front": 48,
             "Magnet": 42, "Bearing-front": 66, "Front-cover": 80, "Seal": 98, "Screw": 112}


def overlay_z_range(group):
    """Lowest and highest z of the drawn contact faces."""
    zs = [p[2] for node in count_nodes(group.ViewObject.RootNode, coin.SoCoordinate3)
          for p in node.point.getValues()]
    return [min(zs), max(zs)]


def check_exploded(doc, group):
    """Moving the bodies redraws their contact faces where they now are; the
    picture (neutral bodies, contact colours) is the README's overview."""
    session_helpers.wait_for_drawing(group)  # reopened: drawn once the document has opened
    report["z_range_assembled"] = overlay_z_range(group)
    group.UpdateOnRecompute = False  # a snapshot: its paint follows the moved faces
    for obj in doc.Objects:
        if obj.TypeId != "Part::Feature":
            continue
        obj.ViewObject.ShapeColor = (0.72, 0.74, 0.77)
        key = obj.Label.split("-")[0] if obj.Label.startswith(("Magnet-", "Screw-")) else obj.Label
        base = obj.Placement.Base + FreeCAD.Vector(0, 0, EXPLODE_Z.get(key, 0))
        if key == "Magnet":  # out of the rotor, radially
            base += obj.Placement.Rotation.multVec(FreeCAD.Vector(12, 0, 0))
        obj.Placement = FreeCAD.Placement(base, obj.Placement.Rotation)
    doc.recompute()
    FreeCADGui.updateGui()  # the redraw waits for the moves to end
    report["z_range_exploded"] = overlay_z_range(group)
    # The motor axis across the picture, seen from the output side, above.
    view = FreeCADGui.activeDocument().activeView()
    toward_viewer = FreeCAD.Vector(0.35, -0.75, 0.55).normalize()
    right = (FreeCAD.Vector(0, 0, 1) - toward_viewer * toward_viewer.z).normalize()
    up = toward_viewer.cross(right)
    view.setCameraOrientation(FreeCAD.Rotation(right, up, toward_viewer, "ZXY").Q)
    view.fitAll()
    camera = view.getCameraNode()
    camera.height.setValue(camera.height.getValue() * 0.8)
    report["exploded_png"] = save_view("gui_contacts_exploded.png")


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
        # Every action the toolbar holds, in order (at 1280 px the last ones sit behind the toolbar's
        # overflow arrow: held, not shown as buttons)
        report["toolbar_actions"] = [a.text() for a in bar.actions() if not a.isSeparator() and a.isVisible()]
        report["toolbar_buttons_shown"] = [b.defaultAction().text() for b in buttons]
        if buttons:
            top_left = buttons[0].mapTo(main, buttons[0].rect().topLeft())
            report["first_button_rect"] = [top_left.x(), top_left.y(), buttons[0].width(), buttons[0].height()]

    doc = FreeCAD.openDocument(os.environ["CONTACTS_SAMPLE"])
    FreeCADGui.SendMsgToActiveView("ViewFit")
    FreeCADGui.activeDocument().activeView().viewIsometric()
    from contactwb.gui import commands
    report["export_active_before"] = commands.Contacts_ExportContacts().IsActive()
    FreeCADGui.runCommand("Contacts_FindContacts")  # the task panel, whole document
    FreeCADGui.updateGui()
    from contactwb.gui import task_panel
    report["panel_scope"] = task_panel.current.scope_value()
    task_panel.current.accept()
    FreeCADGui.updateGui()
    groups = [o for o in doc.Objects if is_contact_analysis(o)]
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
    if groups:
        check_overlay(doc, groups[0])
        check_export(groups[0])
        doc, group = check_reopen(doc, groups[0])
        check_exploded(doc, group)


try:
    run()
except Exception:  # the report carries it to the test, which fails on it
    report["errors"].append(traceback.format_exc())
with open(os.environ["CONTACTS_GUI_RESULT"], "w") as stream:
    json.dump(report, stream, indent=1)
os._exit(0)  # FreeCAD's own shutdown is slow and may prompt; the report is written
