"""Runs inside the FreeCAD GUI (freecad tests/gui/workflow_session.py under
Xvfb): a designer's day with the workbench. Opens the motor with
Contacts_OpenSample, runs the task panel with each scope, re-runs in place,
drives the contact table (sort, filter, selection both ways, isolate),
moves and deletes parts (stale marking, recompute), ghosts, shows the
partitions, picks in an Assembly4 document, saves and re-opens; takes the
README screenshots; writes what it saw to $CONTACTS_GUI_RESULT for
tests/gui/test_gui_workflow.py. Each step records its own traceback, so one
failure does not hide the others."""
import json
import os
import sys
import tempfile

import FreeCAD
import FreeCADGui
from PySide2 import QtCore, QtWidgets
from pivy import coin

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))  # the shared session helpers
import session_helpers  # noqa: E402

out_dir = os.environ["CONTACTS_GUI_OUT"]
report = {"errors": {}}
state = {}


step = session_helpers.stepper(report["errors"], settle_rounds=1)


def grab_window(name):
    """The main window, with the 3D view rendered into it (a grab of the
    window leaves the OpenGL view blank under Xvfb)."""
    from PySide2 import QtGui
    FreeCADGui.updateGui()
    main = FreeCADGui.getMainWindow()
    path = os.path.join(out_dir, name)
    picture = main.grab()
    area = main.findChild(QtWidgets.QMdiArea)
    window = area.activeSubWindow() if area else None
    if window is not None:
        widget = area.viewport()  # what shows of the (maximised) view
        corner = widget.mapTo(main, QtCore.QPoint(0, 0))
        scale = picture.width() / main.width()
        width, height = round(widget.width() * scale), round(widget.height() * scale)
        view_png = os.path.join(out_dir, "_view_for_" + name)
        FreeCADGui.activeDocument().activeView().saveImage(view_png, width, height, "Current")
        painter = QtGui.QPainter(picture)  # logical coordinates (the grab may be scaled)
        painter.drawImage(QtCore.QRectF(corner.x(), corner.y(), widget.width(), widget.height()),
                          QtGui.QImage(view_png))
        painter.end()
        os.remove(view_png)
    picture.save(path)
    return path


def widen_combo_view(width=430):
    main = FreeCADGui.getMainWindow()
    for dock in main.findChildren(QtWidgets.QDockWidget):
        if dock.objectName() == "Combo View":
            main.resizeDocks([dock], [width], QtCore.Qt.Horizontal)
    FreeCADGui.updateGui()


def save_view(name, width=800, height=600):
    return session_helpers.save_view(out_dir, name, width, height, settle_rounds=1)


def analyses(doc):
    from contactwb import export
    return export.analyses(doc)


def run_panel(select=None, group_selected=None):
    """Runs Contacts_FindContacts with a selection; returns the panel."""
    from contactwb.gui import task_panel
    doc = FreeCAD.ActiveDocument
    FreeCADGui.Selection.clearSelection()
    for entry in select or []:
        if isinstance(entry, tuple):
            FreeCADGui.Selection.addSelection(doc.Name, *entry)
        else:
            FreeCADGui.Selection.addSelection(entry)
    FreeCADGui.runCommand("Contacts_FindContacts")
    FreeCADGui.updateGui()
    return task_panel.current


def by_label(doc, label):
    (obj,) = doc.getObjectsByLabel(label)
    return obj


def contact_keys(group):
    return sorted((c.ContactType, c.BodyA, c.BodyB) for c in group.Group)


def open_sample():
    main = FreeCADGui.getMainWindow()
    main.resize(1400, 1000)
    FreeCADGui.activateWorkbench("ContactsWorkbench")
    FreeCADGui.runCommand("Contacts_OpenSample")
    FreeCADGui.updateGui()
    doc = FreeCAD.ActiveDocument
    state["doc"] = doc
    report["sample"] = {"label": doc.Label, "parts": sum(o.TypeId == "Part::Feature" for o in doc.Objects)}


def panel_whole_document():
    doc = state["doc"]
    panel = run_panel()
    report["panel_default_scope"] = panel.scope_value()
    report["panel_defaults"] = {"linear": panel.linear.value(),
                                "model_linear": panel.model_linear,
                                "text": panel.linear.text()}
    widen_combo_view()
    view = FreeCADGui.activeDocument().activeView()
    view.viewIsometric()
    view.fitAll()
    report["task_panel_png"] = grab_window("gui_task_panel.png")
    report["panel_accepted"] = panel.accept()
    (group,) = analyses(doc)
    state["group"] = group
    report["document_scope"] = {"contacts": len(group.Group), "summary": list(group.Summary),
                                "labels": [c.Label for c in group.Group],
                                "label2": [c.Label2 for c in group.Group],
                                "area_editor": [c.Area.UserString for c in group.Group],  # the property editor's
                                "bodies": [[c.BodyA, c.BodyB] for c in group.Group],
                                "numbers": [c.Number for c in group.Group],
                                "undo": list(doc.UndoNames), "touched": "Touched" in group.State}


def update_in_place():
    """Bug 4 and update in place: with the analysis or a contact selected,
    the panel finds that analysis's contacts again."""
    doc, group = state["doc"], state["group"]
    names = [c.Name for c in group.Group]
    panel = run_panel([group])
    panel_group = panel.group.Name if panel.group else None
    report["rerun_group_selected"] = {"panel_group": panel_group, "accepted": panel.accept()}
    panel = run_panel([group.Group[3]])
    panel_group = panel.group.Name if panel.group else None
    accepted = panel.accept()
    report["rerun_contact_selected"] = {"panel_group": panel_group, "accepted": accepted,
                                        "status": "" if accepted else panel.status.text()}
    report["in_place"] = {"analyses": len(analyses(doc)), "same_names": [c.Name for c in group.Group] == names,
                          "contacts": len(group.Group)}


def other_scopes():
    """One part against the rest; the selection only; then both removed."""
    doc, group = state["doc"], state["group"]
    axis = by_label(doc, "Axis")
    panel = run_panel([axis])
    report["single_part_scope"] = panel.scope_value()
    panel.accept()
    against = panel.result
    expected = sorted((c.ContactType, c.BodyA, c.BodyB) for c in group.Group if "Axis" in (c.BodyA, c.BodyB))
    report["part_against_rest"] = {"found": contact_keys(against), "expected": expected}
    rotor = by_label(doc, "Rotor-front")
    panel = run_panel([axis, (rotor.Name, "Face3")])  # a part and a face of another
    report["selection_scope"] = panel.scope_value()
    panel.accept()
    selection = panel.result
    expected = sorted((c.ContactType, c.BodyA, c.BodyB) for c in group.Group
                      if {c.BodyA, c.BodyB} == {"Axis", "Rotor-front"})
    report["selection"] = {"found": contact_keys(selection), "expected": expected}
    # bug 1: every label of every analysis names its own bodies, all unique
    labels = [c.Label for g in analyses(doc) for c in g.Group]
    report["labels_all"] = {"unique": len(set(labels)) == len(labels),
                            "own_bodies": all(c.Label.endswith(f": {c.BodyA} \u2013 {c.BodyB}")
                                              for g in analyses(doc) for c in g.Group)}
    for extra in (against, selection):
        for child in list(extra.Group):
            doc.removeObject(child.Name)
        doc.removeObject(extra.Name)
    FreeCADGui.Selection.clearSelection()


def table():
    from contactwb.gui import contact_table
    doc, group = state["doc"], state["group"]
    FreeCADGui.runCommand("Contacts_ShowContactTable")
    FreeCADGui.updateGui()
    widget = contact_table.dock().widget()
    state["table"] = widget
    result = {"rows": widget.table.rowCount(), "summary": widget.summary.toPlainText()}
    widget.table.sortItems(4, QtCore.Qt.DescendingOrder)
    areas = [widget.table.item(r, 4).data(QtCore.Qt.UserRole + 1) for r in range(widget.table.rowCount())]
    result["sorted_desc"] = areas == sorted(areas, reverse=True)
    result["largest_area"] = areas[0]
    widget.filter_type.setCurrentIndex(widget.filter_type.findData("CLJ"))
    result["clj_rows"] = len(widget.visible_rows())
    widget.filter_type.setCurrentIndex(0)
    widget.filter_text.setText("screw")
    result["screw_rows"] = len(widget.visible_rows())
    result["screw_expected"] = sum("screw" in (c.BodyA + c.BodyB).lower() for c in group.Group)
    widget.filter_text.setText("")
    widget.min_area.setValue(100.0)
    result["area_100_rows"] = len(widget.visible_rows())
    widget.min_area.setValue(0.0)
    # table -> document: a row selects its contact (and the overlay highlights it)
    widget.table.selectRow(0)
    FreeCADGui.updateGui()
    selected = [o.Name for o in FreeCADGui.Selection.getSelection(doc.Name)]
    first = widget.contact_of_row(0)
    result["row_selects"] = selected == [first.Name]
    result["row_highlight"] = sorted(group.ViewObject.Proxy.overlay.highlighted) == [first.Name]
    # document -> table: a part selects its contacts' rows; a painted face its contacts
    screw = by_label(doc, "Screw-1") if doc.getObjectsByLabel("Screw-1") else by_label(doc, "Axis")
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(screw)
    FreeCADGui.updateGui()
    rows = {widget.contact_of_row(i.row()).Name for i in widget.table.selectionModel().selectedRows()}
    result["part_rows"] = sorted(rows)
    result["part_expected"] = sorted(c.Name for c in group.Group if screw.Label in (c.BodyA, c.BodyB))
    contact = next(c for c in group.Group if c.ContactType == "PLF")
    (root, (face,)) = contact.FacesA[0][0], contact.FacesA[0][1][:1]
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(doc.Name, root.Name, face)
    FreeCADGui.updateGui()
    rows = {widget.contact_of_row(i.row()).Name for i in widget.table.selectionModel().selectedRows()}
    result["face_rows"] = sorted(rows)
    result["face_expected"] = sorted(c.Name for c in group.Group for r, subs in c.FacesA + c.FacesB
                                     if r is root and face in subs)
    result["tree_contact_rows"] = None
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(group.Group[5])
    FreeCADGui.updateGui()
    result["tree_contact_rows"] = sorted(widget.contact_of_row(i.row()).Name
                                         for i in widget.table.selectionModel().selectedRows())
    result["tree_contact"] = group.Group[5].Name
    FreeCADGui.Selection.clearSelection()
    view = FreeCADGui.activeDocument().activeView()
    view.viewIsometric()
    view.fitAll()
    FreeCADGui.Selection.addSelection(screw)  # its rows selected in the table
    report["table_png"] = grab_window("gui_contact_table.png")
    FreeCADGui.Selection.clearSelection()
    report["table"] = result


def isolation_state(doc, contact):
    """What Isolate left: the parts shown, the transparencies of the contact's
    two parts and of the others, the contacts shown."""
    from contactwb.document.identify import is_contact
    parts = [o for o in doc.Objects if o.TypeId == "Part::Feature"]
    pair = {contact.BodyA, contact.BodyB}
    return {"hidden": sorted(o.Label for o in parts if not o.ViewObject.Visibility),
            "pair_transparency": sorted({o.ViewObject.Transparency for o in parts if o.Label in pair}),
            "others_transparency": sorted({o.ViewObject.Transparency for o in parts if o.Label not in pair}),
            "contacts_shown": [c.Name for c in doc.Objects if is_contact(c) and c.ViewObject.Visibility],
            "contact": contact.Name}


def highlighted_contact():
    """Isolate a contact from the table, selected: the README's picture."""
    doc, group, widget = state["doc"], state["group"], state["table"]
    contact = next(c for c in group.Group if {c.BodyA, c.BodyB} == {"Axis", "Bearing-front"})
    widget.table.selectRow(widget.row_of(contact.Name))
    widget.isolate()
    FreeCADGui.updateGui()
    isolated = isolation_state(doc, contact)
    from contactwb.gui import actions
    actions.set_ghosted(doc, True)  # the contact is inside the bearing: see through it
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(contact)
    FreeCADGui.updateGui()
    shown = sorted(o.Label for o in doc.Objects if o.TypeId == "Part::Feature" and o.ViewObject.Visibility)
    view = FreeCADGui.activeDocument().activeView()
    view.viewIsometric()
    actions.zoom_to(contact, margin=3.0)
    from contactwb.gui import view_providers
    report["highlight"] = {"contact": [contact.BodyA, contact.BodyB], "shown_parts": shown, "isolated": isolated,
                           "highlighted": sorted(group.ViewObject.Proxy.overlay.highlighted) == [contact.Name],
                           "selection_colour": view_providers.hex_colour(view_providers.selection_colour()),
                           "png": save_view("gui_highlighted_contact.png")}
    widget.show_all()
    report["ghost_undone_by_show_all"] = not actions.is_ghosted(doc)
    FreeCADGui.Selection.clearSelection()
    report["after_show_all"] = sum(o.TypeId == "Part::Feature" and o.ViewObject.Visibility for o in doc.Objects)


def colours_and_paint():
    """Bug 7: colours never the selection's; the common area, not whole faces."""
    from contactwb.gui import view_providers
    group = state["group"]
    overlay = group.ViewObject.Proxy.overlay
    legend = view_providers.legend_colours()
    report["legend"] = legend
    highlight = [view_providers.hex_colour(c) for c in view_providers.highlight_colours()]
    report["highlight_colours"] = highlight
    report["legend_texts"] = []
    search = coin.SoSearchAction()
    search.setType(coin.SoText2.getClassTypeId())
    search.setInterest(coin.SoSearchAction.ALL)
    search.apply(overlay.root)
    for path in search.getPaths():
        report["legend_texts"].append(path.getTail().string.getValues()[0])
    report["common_contacts"] = overlay.common_contacts
    # the screws on the front cover: painted area against the contact's own area
    source = view_providers.FaceSource()
    checks = []
    for contact in group.Group:
        if contact.ContactType != "PLF" or not contact.BodyA.startswith(("Front-cover", "Back-cover")):
            continue
        meshes = source.common_meshes(contact, 1e-3)
        painted = 0.0
        for _, (points, triangles, _) in meshes[0]:
            a, b, c = (points[triangles[:, k]] for k in range(3))
            import numpy
            painted += float(numpy.linalg.norm(numpy.cross(b - a, c - a), axis=1).sum() / 2)
        face_area = sum(root.getSubObject(s).Area for root, subs in contact.FacesA for s in subs)
        checks.append({"label": contact.Label, "area": contact.Area.Value, "painted": painted,
                       "face_area": face_area})
    report["common_area_checks"] = checks
    # the other paint style, from the preferences page
    from contactwb.gui import preferences
    page = preferences.PreferencesPage()
    page.loadSettings()
    report["preferences_loaded"] = {"paint": page.paint.currentText(), "PLF": page.colours["PLF"].text()}
    page.paint.setCurrentIndex(1)
    page.saveSettings()
    group.ViewObject.Proxy.rebuild()
    report["whole_faces_common_contacts"] = overlay.common_contacts
    page.paint.setCurrentIndex(0)
    page.saveSettings()
    group.ViewObject.Proxy.rebuild()
    report["common_again"] = overlay.common_contacts


def stale_after_move_and_delete():
    from contactwb import export
    doc, group = state["doc"], state["group"]
    proxy = group.ViewObject.Proxy
    axis_contacts = sum("Axis" in (c.BodyA, c.BodyB) for c in group.Group)
    seal = by_label(doc, "Seal")
    seal_contacts = sum("Seal" in (c.BodyA, c.BodyB) for c in group.Group)
    before = len(group.Group)
    axis = by_label(doc, "Axis")
    placement = axis.Placement
    doc.openTransaction("Move axis")
    axis.Placement = FreeCAD.Placement(placement.Base + FreeCAD.Vector(0, 0, 300), placement.Rotation)
    doc.commitTransaction()
    FreeCADGui.updateGui()
    result = {"before": before, "axis_contacts": axis_contacts,
              "touched_after_move": "Touched" in group.State,
              "paint_hidden_while_stale": proxy.switch.whichChild.getValue() == coin.SO_SWITCH_NONE}
    doc.recompute()
    FreeCADGui.updateGui()
    result["after_recompute"] = len(group.Group)
    result["touched_after_recompute"] = "Touched" in group.State
    # The paint is redrawn once the recompute is over (a deferred rebuild, not during it): let the
    # event loop run it, 3 s at most.
    session_helpers.wait_for_drawing(group)
    result["paint_shown_again"] = proxy.switch.whichChild.getValue() == coin.SO_SWITCH_ALL
    result["drawn"] = len(proxy.overlay.names)
    axis.Placement = placement
    doc.recompute()
    FreeCADGui.updateGui()
    result["after_moving_back"] = len(group.Group)
    doc.openTransaction("Delete seal")
    doc.removeObject(seal.Name)
    doc.commitTransaction()
    FreeCADGui.updateGui()
    result["seal_contacts"] = seal_contacts
    result["touched_after_delete"] = "Touched" in group.State
    result["export_after_delete"] = len(export.to_json(group)["contacts"])
    doc.recompute()
    FreeCADGui.updateGui()
    result["after_delete_recompute"] = len(group.Group)
    result["table_rows"] = state["table"].table.rowCount()
    result["drawn_after_delete"] = len(proxy.overlay.names)
    while "Delete seal" in doc.UndoNames:  # the Seal back (the recompute's removals undone first)
        doc.undo()
    doc.recompute()
    FreeCADGui.updateGui()
    result["after_undo"] = len(group.Group)
    report["stale"] = result


def export_command():
    """Contacts_ExportContacts through its file dialog (answered by the test)."""
    doc, group = state["doc"], state["group"]
    path = os.path.join(out_dir, "workflow_export.json")
    original = QtWidgets.QFileDialog.getSaveFileName
    QtWidgets.QFileDialog.getSaveFileName = staticmethod(lambda *args, **kwargs: (path, "JSON (*.json)"))
    try:
        FreeCADGui.Selection.clearSelection()
        FreeCADGui.Selection.addSelection(group.Group[0])  # a contact: its analysis is exported
        FreeCADGui.runCommand("Contacts_ExportContacts")
    finally:
        QtWidgets.QFileDialog.getSaveFileName = original
        FreeCADGui.Selection.clearSelection()
    with open(path) as stream:
        data = json.load(stream)
    report["export"] = {"keys": sorted(data), "contacts": len(data["contacts"]), "bodies": len(data["bodies"]),
                        "contact_keys": list(data["contacts"][0])}


def joints():
    """Derive joints: Joint objects drawn as axis glyphs, the panel with the
    mobility and the liaison graph; the table lists them; undoable."""
    from contactwb.gui import contact_table, joint_view
    from contactwb.objects.contact_objects import is_joint
    doc, group = state["doc"], state["group"]
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(group)
    FreeCADGui.runCommand("Contacts_DeriveJoints")
    FreeCADGui.updateGui()
    found = [o for o in group.Group if is_joint(o)]
    panel = joint_view.current_panel
    glyphs = {o.Name: (o.ViewObject.Proxy.axes, o.ViewObject.Proxy.arrows) for o in found}
    result = {"joints": len(found), "pairs": len(group.PairSummary),
              "types": sorted({o.JointType for o in found}),
              "axis_bearing": next(([o.JointType, o.DOF] for o in found
                                    if {o.BodyA, o.BodyB} == {"Axis", "Bearing-front"}), None),
              "glyph_axes": sum(a for a, _ in glyphs.values()),
              "rotations": sum(len(o.AxisDirections) for o in found),
              "mobility": list(group.Mobility),
              "graph_png": bool(panel and panel.graph_path and panel.graph.item is not None),
              "undo": doc.UndoNames[0] if doc.UndoNames else None,
              "contacts_kept": sum(1 for c in group.Group if not is_joint(c))}
    widget = contact_table.dock().widget()
    widget.fill()
    result["table_rows"] = widget.table.rowCount()
    # the README picture: the rotor parts and the axis with their joint glyphs
    for obj in doc.Objects:
        if obj.TypeId == "Part::Feature":
            obj.ViewObject.Visibility = obj.Label in ("Axis", "Bearing-front", "Bearing-back", "Front-cover")
    for joint in found:
        joint.ViewObject.Visibility = {joint.BodyA, joint.BodyB} <= {"Axis", "Bearing-front", "Bearing-back",
                                                                      "Front-cover"}
    FreeCADGui.Selection.clearSelection()  # a selected group paints all its children in the selection colour
    widget.parent().hide()  # the table dock: room for the view
    widen_combo_view(620)
    view = FreeCADGui.activeDocument().activeView()
    view.viewIsometric()
    view.fitAll()
    result["png"] = grab_window("gui_joints.png")
    widget.parent().show()
    widen_combo_view()
    for obj in doc.Objects:
        if obj.TypeId == "Part::Feature":
            obj.ViewObject.Visibility = True
    FreeCADGui.Control.closeDialog()
    doc.undo()
    result["after_undo"] = sum(1 for o in group.Group if is_joint(o))
    doc.redo()
    result["after_redo"] = sum(1 for o in group.Group if is_joint(o))
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(group)
    FreeCADGui.runCommand("Contacts_ShowJoints")
    result["show_joints_panel"] = joint_view.current_panel is not panel
    FreeCADGui.Control.closeDialog()
    FreeCADGui.Selection.clearSelection()
    report["joints"] = result


def ghost_and_context_menu():
    from contactwb.gui import actions
    doc, group = state["doc"], state["group"]
    FreeCADGui.runCommand("Contacts_GhostBodies")
    ghosts = [b.obj.Label for b in actions.ghosted_objects(doc)]
    report["ghost"] = {"ghosted": sorted(ghosts),
                       "transparency": sorted({b.obj.ViewObject.Transparency for b in actions.ghosted_objects(doc)}),
                       "undo": doc.UndoNames[0] if doc.UndoNames else None}
    FreeCADGui.runCommand("Contacts_GhostBodies")
    report["ghost"]["restored"] = sorted({b.obj.ViewObject.Transparency for b in actions.ghosted_objects(doc)})
    menu = QtWidgets.QMenu()
    contact = group.Group[0]
    contact.ViewObject.Proxy.setupContextMenu(contact.ViewObject, menu)
    actions_by_text = {a.text(): a for a in menu.actions()}
    report["context_menu"] = sorted(actions_by_text)
    actions_by_text["Isolate with its parts"].trigger()
    FreeCADGui.updateGui()
    report["context_isolated"] = isolation_state(doc, contact)
    report["context_contact"] = sorted([contact.BodyA, contact.BodyB])
    report["isolate_undo"] = list(doc.UndoNames[:2])
    FreeCADGui.runCommand("Contacts_ShowAll")
    menu = QtWidgets.QMenu()
    group.ViewObject.Proxy.setupContextMenu(group.ViewObject, menu)
    report["analysis_menu"] = sorted(a.text() for a in menu.actions())


def partitions():
    from contactwb.gui import partitions_view
    doc = state["doc"]
    state["group"].ViewObject.Visibility = False
    shown = ("Axis", "Front-cover")
    for obj in doc.Objects:
        if obj.TypeId == "Part::Feature":
            obj.ViewObject.Visibility = obj.Label in shown
    FreeCADGui.Selection.clearSelection()
    for label in shown:
        FreeCADGui.Selection.addSelection(by_label(doc, label))
    FreeCADGui.runCommand("Contacts_ShowPartitions")
    FreeCADGui.Selection.clearSelection()
    view = partitions_view._views[doc.Name][0]
    camera_view = FreeCADGui.activeDocument().activeView()
    camera_view.viewIsometric()
    camera_view.fitAll()
    report["partitions"] = {"bodies": view.bodies, "counts": view.counts,
                            "colours": {kind: ["#" + "".join(f"{round(c * 255):02x}" for c in view.colour(kind, shade))
                                               for shade in range(4)] for kind in ("Plane", "Cylinder")},
                            "png": save_view("gui_partitions.png")}
    FreeCADGui.runCommand("Contacts_ShowPartitions")
    report["partitions"]["hidden_again"] = not partitions_view.is_shown(doc)
    for obj in doc.Objects:
        if obj.TypeId == "Part::Feature":
            obj.ViewObject.Visibility = True
    state["group"].ViewObject.Visibility = True


def save_and_reopen():
    doc, group = state["doc"], state["group"]
    folder = tempfile.mkdtemp(prefix="contacts-workflow-")
    path = os.path.join(folder, "motor_live.FCStd")
    labels = [c.Label for c in group.Group]
    name = group.Name
    doc = session_helpers.save_and_reopen(doc, path)
    group = doc.getObject(name)
    # The drawing of a reopened analysis waits until the document has finished opening (retried
    # every 50 ms): under load, one updateGui() was not enough (drawn 0 of 35 once, 27 Nov).
    session_helpers.wait_for_drawing(group)
    result = {"labels_same": [c.Label for c in group.Group] == labels, "scope": group.Scope,
              "live": group.UpdateOnRecompute, "drawn": len(group.ViewObject.Proxy.overlay.names),
              "half_angle_property": "HalfAngle" in group.Group[0].PropertiesList}
    axis = by_label(doc, "Axis")
    placement = axis.Placement
    axis.Placement = FreeCAD.Placement(placement.Base + FreeCAD.Vector(0, 0, 300), placement.Rotation)
    result["touched_after_move"] = "Touched" in group.State
    axis.Placement = placement
    doc.recompute()
    from contactwb.objects.contact_objects import is_contact, is_joint
    result["after_recompute"] = sum(1 for c in group.Group if is_contact(c))
    result["joints_after_recompute"] = sum(1 for c in group.Group if is_joint(c))
    result["joint_providers"] = sorted({type(c.ViewObject.Proxy).__name__ for c in group.Group if is_joint(c)})
    report["reopened"] = result
    FreeCAD.closeDocument(doc.Name)


def asm4_pick():
    """Bug 2: a pick in the 3D view of an Assembly4 document (a path through
    the links to a PartDesign feature's face) finds the contact, named after
    the links."""
    path = os.environ.get("CONTACTS_ASM4")
    if not path or not os.path.isfile(path):
        report["asm4"] = "skipped"
        return
    doc = FreeCAD.openDocument(path)
    FreeCADGui.updateGui()
    model = doc.getObject("Model")
    from contactwb import bodies
    picks = []
    for body in bodies.document_bodies(doc):
        face = {"base001": "Face4", "disk001": "Face2"}.get(body.name)
        if face:  # the pick: through the link and the PartDesign body to its tip feature
            picks.append(f"{body.subname}{body.obj.Tip.Name}.{face}")
    FreeCADGui.Selection.clearSelection()
    for subname in picks:
        FreeCADGui.Selection.addSelection(doc.Name, "Model", subname)
    resolved = [o.Name for o in FreeCADGui.Selection.getSelection(doc.Name)]
    panel = run_panel([("Model", s) for s in picks])
    scope = panel.scope_value()
    panel.accept()
    group = panel.result
    report["asm4"] = {"picks": picks, "resolved": resolved, "scope": scope,
                      "found": contact_keys(group) if group else None,
                      "sources": [[o.Name, list(s)] for o, s in group.Sources] if group else None}
    FreeCAD.closeDocument(doc.Name)


def cancel_in_panel():
    """Cancel inside the panel, while the search runs: nothing is added."""
    doc = FreeCAD.newDocument("CancelTest")
    import Part
    import contactwb
    doc.addObject("Part::Feature", "parts").Shape = Part.read(os.path.join(contactwb.SAMPLES_DIR, "motor.step"))
    doc.recompute()
    panel = run_panel()
    calls = []
    original = panel.progress

    def progress(stage, fraction):
        calls.append(stage)
        if len(calls) == 2:
            panel.cancel.click()  # the user presses Cancel search
        return original(stage, fraction)

    panel.progress = progress
    accepted = panel.accept()
    report["cancel"] = {"accepted": accepted, "status": panel.status.text(), "calls": len(calls),
                        "analyses": len(analyses(doc)), "undo": list(doc.UndoNames),
                        "cancel_enabled_after": panel.cancel.isEnabled()}
    panel.reject()
    FreeCAD.closeDocument(doc.Name)


def compound_import():
    """Bug 8: a STEP imported in FreeCAD's compound mode is one object named
    after the file; the bodies still get their product names."""
    import ImportGui
    from contactwb import core
    import contactwb
    step = os.path.join(contactwb.SAMPLES_DIR, "motor.step")
    FreeCAD.ParamGet("User parameter:BaseApp/Preferences/Mod/Import/hSTEP").SetBool("ReadShapeCompoundMode", True)
    doc = FreeCAD.newDocument("CompoundImport")
    import ImportGui
    ImportGui.insert(step, doc.Name)
    # File > Import records the file in the recent files (Gui::Application::
    # importFrom); FreeCADGui.insert refuses .step in 0.20, so as it would:
    recent = FreeCAD.ParamGet("User parameter:BaseApp/Preferences/RecentFiles")
    recent.SetString("MRU0", step)
    objects = [(o.Label, len(o.Shape.Solids)) for o in doc.Objects if hasattr(o, "Shape")]
    panel = run_panel()
    accepted = panel.accept()
    group = panel.result
    report["compound_run"] = [accepted, "" if accepted else panel.status.text(), FreeCAD.ActiveDocument.Name,
                              [o.Name for o in doc.Objects]]
    report["compound"] = {"objects": objects, "bodies": sorted({n for c in group.Group for n in (c.BodyA, c.BodyB)}),
                          "contacts": len(group.Group),
                          "products": sorted(b.name for b in core.contactcore.read_step(step).bodies)}
    FreeCAD.closeDocument(doc.Name)


def preferences_dialog():
    """The Contacts page is in FreeCAD's Preferences dialog (looked at, then closed)."""
    seen = {}

    def inspect(dialog):
        pages = [w for w in dialog.findChildren(QtWidgets.QWidget) if w.objectName() == "ContactsPreferences"]
        seen["page"] = bool(pages)
        if pages:
            combos = pages[0].findChildren(QtWidgets.QComboBox)
            seen["paint"] = combos[0].currentText() if combos else None
        dialog.reject()

    session_helpers.with_modal_dialog("Std_DlgPreferences", inspect)
    report["preferences_dialog"] = seen


def report_view():
    """The Report view's text: tracebacks and errors the workbench printed."""
    report["report_view"] = session_helpers.report_view_text()


for function in (open_sample, panel_whole_document, update_in_place, other_scopes, table,
                 highlighted_contact, colours_and_paint, stale_after_move_and_delete,
                 export_command, joints, ghost_and_context_menu, partitions, save_and_reopen, asm4_pick, cancel_in_panel,
                 compound_import, preferences_dialog, report_view):
    step(function)
session_helpers.write_report_and_exit(report)
