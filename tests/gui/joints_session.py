"""Runs inside the FreeCAD GUI (freecad tests/gui/joints_session.py under Xvfb)
for tests/gui/test_gui_joints.py: issue 21 items 9 and 10 on the motor. Find
contacts, Derive joints; the joints panel (the DOF count explained, the
joints listed), the liaison graph zoomed with the wheel; a joint selected in
the panel is selected and highlighted in the view, one selected in the tree
selects its row; a click on a glyph in the 3D view selects its joint; the
glyphs' labels; the joint arrows' colour against the selection green.
Screenshots go to $CONTACTS_GUI_OUT."""
import os
import sys

import FreeCAD
import FreeCADGui
from PySide2 import QtCore, QtGui, QtWidgets
from pivy import coin

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))  # the shared session helpers
import session_helpers  # noqa: E402
from session_helpers import settle  # noqa: E402

out_dir = os.environ["CONTACTS_GUI_OUT"]
report = {"errors": {}}
state = {}


step = session_helpers.stepper(report["errors"])


def save_view(name, width=900, height=650):
    return session_helpers.save_view(out_dir, name, width, height, "Current")


def derive_joints():
    from contactwb.document.identify import analyses, is_joint
    from contactwb.gui.panels import joints_panel, task_panel
    main = FreeCADGui.getMainWindow()
    main.resize(1400, 1000)
    FreeCADGui.activateWorkbench("ContactsWorkbench")
    FreeCADGui.runCommand("Contacts_OpenSample")
    settle()
    doc = FreeCAD.ActiveDocument
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.runCommand("Contacts_FindContacts")
    settle()
    task_panel.current.accept()
    settle()
    (group,) = analyses(doc)
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(group)
    FreeCADGui.runCommand("Contacts_DeriveJoints")
    settle()
    FreeCADGui.Selection.clearSelection()
    settle()
    panel = joints_panel.current_panel
    joints = [o for o in group.Group if is_joint(o)]
    state.update(doc=doc, group=group, panel=panel, joints=joints)
    report["derive"] = {"joints": len(joints), "panel": panel is not None, "mobility": list(group.Mobility),
                        "mobility_text": panel.mobility.text() if panel else "",
                        "rows": [panel.joints.item(r).text() for r in range(panel.joints.count())] if panel else []}


def graph_zoom():
    panel = state["panel"]
    view = panel.graph
    result = {"has_graph": view.item is not None, "scale_open": view.scale_factor(),
              "scene": [view.sceneRect().width(), view.sceneRect().height()]}

    def wheel(notches):
        centre = QtCore.QPointF(view.viewport().width() / 2, view.viewport().height() / 2)
        event = QtGui.QWheelEvent(centre, view.viewport().mapToGlobal(centre.toPoint()), QtCore.QPoint(0, 0),
                                  QtCore.QPoint(0, 120 * notches), QtCore.Qt.NoButton, QtCore.Qt.NoModifier,
                                  QtCore.Qt.NoScrollPhase, False)
        QtWidgets.QApplication.sendEvent(view.viewport(), event)
        settle()
        return view.scale_factor()

    result["after_2_up"] = wheel(1) and wheel(1)
    result["after_4_down"] = wheel(-1) and wheel(-1) and wheel(-1) and wheel(-1)
    panel.actual_button.click()
    result["actual"] = view.scale_factor()
    form = panel.form
    form.resize(560, 900)
    settle()
    result["png"] = os.path.join(out_dir, "gui_joints_panel.png")
    form.grab().save(result["png"])
    report["graph"] = result


def selection_both_ways():
    """Panel row -> selection and highlight; tree selection -> panel row."""
    from contactwb.gui.overlay.colours import selection_colour
    panel, joints = state["panel"], state["joints"]
    axis_joint = next(j for j in joints if {j.BodyA, j.BodyB} == {"Body", "Axis"} or
                      {j.BodyA, j.BodyB} == {"Bearing-front", "Axis"})
    row = next(r for r in range(panel.joints.count())
               if panel.joints.item(r).data(QtCore.Qt.UserRole) == axis_joint.Name)
    panel.joints.clearSelection()
    panel.joints.item(row).setSelected(True)
    settle()
    proxy = axis_joint.ViewObject.Proxy
    materials = coin.SoSearchAction()
    materials.setType(coin.SoMaterial.getClassTypeId())
    materials.setInterest(coin.SoSearchAction.ALL)
    materials.apply(proxy.glyphs)
    colours = sorted({tuple(round(c, 3) for c in path.getTail().diffuseColor[0].getValue())
                      for path in materials.getPaths()})
    result = {"selected": [o.Name for o in FreeCADGui.Selection.getSelection(state["doc"].Name)],
              "joint": axis_joint.Name, "highlighted": proxy.highlighted, "glyph_colours": colours,
              "selection_colour": [round(c, 3) for c in selection_colour()]}
    # the tree (or any selection) -> the panel's row
    other = next(j for j in joints if j is not axis_joint)
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(other)
    settle()
    result["other"] = other.Name
    result["rows_selected"] = [i.data(QtCore.Qt.UserRole) for i in panel.joints.selectedItems()]
    result["old_unhighlighted"] = not proxy.highlighted
    FreeCADGui.Selection.clearSelection()
    settle()
    report["selection"] = result


def glyph_pick_and_labels():
    """Only the seal and its joints shown (glyphs inside the motor are behind
    its parts, which pick first): a click on the seal's arrow selects its joint."""
    doc, joints, panel = state["doc"], state["joints"], state["panel"]
    for obj in doc.Objects:
        if obj.TypeId == "Part::Feature":
            obj.ViewObject.Visibility = obj.Label == "Seal"
    for joint in joints:
        joint.ViewObject.Visibility = "Seal" in (joint.BodyA, joint.BodyB)
    group = state["group"]
    group.ViewObject.Proxy.switch.whichChild.setValue(coin.SO_SWITCH_NONE)  # the paint aside
    view = FreeCADGui.activeDocument().activeView()
    view.viewIsometric()
    view.fitAll()
    settle()
    seal = next(j for j in joints if "Seal" in (j.BodyA, j.BodyB) and len(j.Translations))
    width, height = view.getSize()
    result = {"joint": seal.Name, "hits": [], "labels": []}
    centre = FreeCAD.Vector(seal.Centre)
    direction = FreeCAD.Vector(seal.Translations[0]).normalize()
    length = seal.GlyphLength.Value
    for k in range(1, 10):  # along the arrow's shaft
        point = centre + direction * (length * 0.4 * k / 10)
        x, y = view.getPointOnScreen(point)
        info = view.getObjectInfo((int(x), int(y)))
        result["hits"].append([int(x), int(y), info.get("Object") if info else None])
    hit = next((h for h in result["hits"] if h[2] == seal.Name), None)
    result["clicked"] = None
    if hit is not None:
        # a real click there: the viewer's widget, Qt's y from the top
        widget = view.graphicsView().viewport()
        # the view's pixels (Coin's, y up) to the widget's (Qt's, y down; the GL viewport may be scaled)
        position = QtCore.QPointF(hit[0] * widget.width() / width,
                                  widget.height() - hit[1] * widget.height() / height)
        FreeCADGui.Selection.clearSelection()
        for kind, button, buttons in ((QtCore.QEvent.MouseMove, QtCore.Qt.NoButton, QtCore.Qt.NoButton),
                                      (QtCore.QEvent.MouseButtonPress, QtCore.Qt.LeftButton, QtCore.Qt.LeftButton),
                                      (QtCore.QEvent.MouseButtonRelease, QtCore.Qt.LeftButton, QtCore.Qt.NoButton)):
            event = QtGui.QMouseEvent(kind, position, widget.mapToGlobal(position.toPoint()), button, buttons,
                                      QtCore.Qt.NoModifier)
            QtWidgets.QApplication.sendEvent(widget, event)
            settle()
        result["clicked"] = [o.Name for o in FreeCADGui.Selection.getSelection(doc.Name)]
        result["rows_after_click"] = [i.data(QtCore.Qt.UserRole) for i in panel.joints.selectedItems()]
    # the labels: one SoText2 per joint shown, "J<n> <type>"
    for joint in joints:
        texts = coin.SoSearchAction()
        texts.setType(coin.SoText2.getClassTypeId())
        texts.setInterest(coin.SoSearchAction.ALL)
        texts.apply(joint.ViewObject.Proxy.glyphs)
        result["labels"].append([joint.Label, [path.getTail().string.getValues()[0] for path in texts.getPaths()]])
    result["png"] = save_view("gui_joint_glyphs.png")
    report["pick"] = result


def palette_and_legends():
    """Show partitions beside the contacts' paint, a second analysis: the
    partitions in their contact types' families, adjacent ones of one type
    in different shades, the three legends stacked apart."""
    import colorsys
    import Part
    from contactwb.gui import palette
    from contactwb.gui.overlay import legend_stack
    from contactwb.gui.overlay import partitions as partitions_view
    from contactwb.gui.overlay.colours import legend_colours
    from contactwb.make import make_contact_analysis
    doc, group = state["doc"], state["group"]
    FreeCADGui.Control.closeDialog()
    for obj in doc.Objects:
        if obj.TypeId == "Part::Feature":
            obj.ViewObject.Visibility = obj.Label in ("Axis", "Front-cover", "Seal")
    for joint in state["joints"]:
        joint.ViewObject.Visibility = False
    group.ViewObject.Proxy.switch.whichChild.setValue(coin.SO_SWITCH_ALL)
    seal = doc.getObjectsByLabel("Seal")[0]
    second = make_contact_analysis(doc, [seal], scope="PartAgainstRest")
    doc.recompute()
    settle()
    FreeCADGui.Selection.clearSelection()
    for label in ("Axis", "Front-cover"):
        FreeCADGui.Selection.addSelection(doc.getObjectsByLabel(label)[0])
    FreeCADGui.runCommand("Contacts_ShowPartitions")
    FreeCADGui.Selection.clearSelection()
    settle()
    view = partitions_view._views[doc.Name][0]
    hues = {f"{kind}/{shade}": palette.hue(view.colour(kind, shade))
            for kind in ("Plane", "Cylinder") for shade in range(4)}
    type_hues = {kind: palette.hue(palette.rgb(legend_colours()[code])) for kind, code in
                 (("Plane", "PLF"), ("Cylinder", "CLJ"))}
    # adjacency found again with OCCT's edge ancestors (not the view's edge map)
    from contactwb import core
    pairs = []
    for label in ("Axis", "Front-cover"):
        shape = doc.getObjectsByLabel(label)[0].Shape
        partitions = core.contactcore.partition_brep(shape.exportBrepToString()).partitions
        partition_of = {f: k for k, p in enumerate(partitions) for f in p.faces}
        kinds_shades = view.shades[view.bodies.index(label)]
        found_pairs = set()
        for edge in shape.Edges:
            faces = shape.ancestorsOfType(edge, Part.Face)
            found = sorted({partition_of[k + 1] for face in faces for k, f in enumerate(shape.Faces)
                            if f.isSame(face)})
            for i in found:
                for j in found:
                    if i < j and kinds_shades[i][0] == kinds_shades[j][0]:
                        found_pairs.add((i, j))
        pairs += [[label, i, j, kinds_shades[i], kinds_shades[j]] for i, j in sorted(found_pairs)]
    view3d = FreeCADGui.activeDocument().activeView()
    view3d.viewIsometric()
    view3d.fitAll()
    report["palette"] = {
        "hues": {f"{k}": h for k, h in hues.items()}, "type_hues": type_hues,
        "adjacent_pairs": pairs,
        "legends": {str(k): v for k, v in legend_stack.extents(doc.Name).items()},
        "analyses": [group.Name, second.Name],
        "png": save_view("gui_partitions_legends.png")}
    FreeCADGui.runCommand("Contacts_ShowPartitions")
    report["palette"]["legends_after_hide"] = len(legend_stack.extents(doc.Name))


def arrow_colour():
    from contactwb.gui.overlay import joint_glyphs
    from contactwb.gui.overlay.colours import selection_colour
    report["arrow"] = {"translation": list(joint_glyphs.TRANSLATION_COLOUR),
                       "rotation": list(joint_glyphs.ROTATION_COLOUR), "selection": list(selection_colour())}


for function in (derive_joints, graph_zoom, selection_both_ways, glyph_pick_and_labels, arrow_colour,
                 palette_and_legends):
    step(function)
session_helpers.write_report_and_exit(report)
