"""Joints in the 3D view and the joints panel.

A Joint is drawn as axis glyphs at the centre of its contacts: each rotation
axis a dark red line through its point with a ring around it, each free
translation a green arrow; a rigid joint a small grey ball. The joints panel
lists the assembly's mobility (ground, degrees of freedom, rigid groups) and
shows the liaison graph (Graphviz, as `contacts --graph` draws it).

Saved files name ViewProviderJoint: a permanent name."""
import math
import os
import subprocess
import tempfile

import FreeCAD
import FreeCADGui
from pivy import coin

import contactwb
from contactwb.gui.view_providers import _ViewProvider  # nothing to save, like every view provider here

ROTATION_COLOUR = (0.75, 0.05, 0.1)
TRANSLATION_COLOUR = (0.1, 0.6, 0.15)
RIGID_COLOUR = (0.45, 0.45, 0.45)
GLYPH_WIDTH = 4


def _line(points, colour, width=GLYPH_WIDTH):
    node = coin.SoSeparator()
    material = coin.SoMaterial()
    material.diffuseColor.setValue(*colour)
    style = coin.SoDrawStyle()
    style.lineWidth.setValue(width)
    light = coin.SoLightModel()
    light.model.setValue(coin.SoLightModel.BASE_COLOR)
    coordinates = coin.SoCoordinate3()
    coordinates.point.setValues(0, len(points), points)
    lines = coin.SoLineSet()
    lines.numVertices.setValue(len(points))
    for child in (material, style, light, coordinates, lines):
        node.addChild(child)
    return node


def _ring(centre, axis, radius, segments=48):
    axis = FreeCAD.Vector(axis).normalize()
    helper = FreeCAD.Vector(1, 0, 0) if abs(axis.x) < 0.9 else FreeCAD.Vector(0, 1, 0)
    u = axis.cross(helper).normalize()
    v = axis.cross(u)
    return [tuple(centre + u * (radius * math.cos(2 * math.pi * k / segments))
                  + v * (radius * math.sin(2 * math.pi * k / segments))) for k in range(segments + 1)]


def _cone(tip, direction, length, colour):
    """A cone of `length` pointing along `direction`, its tip at `tip`."""
    node = coin.SoSeparator()
    material = coin.SoMaterial()
    material.diffuseColor.setValue(*colour)
    transform = coin.SoTransform()
    centre = tip - direction * (length / 2)
    transform.translation.setValue(centre.x, centre.y, centre.z)
    # SoCone points along +y
    rotation = FreeCAD.Rotation(FreeCAD.Vector(0, 1, 0), direction)
    transform.rotation.setValue(*rotation.Q)
    cone = coin.SoCone()
    cone.height.setValue(length)
    cone.bottomRadius.setValue(length * 0.35)
    for child in (material, transform, cone):
        node.addChild(child)
    return node


def joint_glyphs(joint):
    """Coin nodes drawing a Joint; (node, rotation axes, translation arrows)."""
    root = coin.SoSeparator()
    pick = coin.SoPickStyle()
    pick.style.setValue(coin.SoPickStyle.UNPICKABLE)
    root.addChild(pick)
    length = max(float(joint.GlyphLength.Value), 1e-3)
    axes = arrows = 0
    for point, direction in zip(joint.AxisPoints, joint.AxisDirections):
        if direction.Length < 1e-12:
            continue
        direction = FreeCAD.Vector(direction).normalize()
        # the axis line through the point nearest the contacts' centre
        foot = point + direction * (joint.Centre - point).dot(direction)
        ends = [tuple(foot - direction * (length / 2)), tuple(foot + direction * (length / 2))]
        root.addChild(_line(ends, ROTATION_COLOUR))
        root.addChild(_line(_ring(foot + direction * (length * 0.3), direction, length * 0.12),
                            ROTATION_COLOUR, GLYPH_WIDTH - 1))
        axes += 1
    for direction in joint.Translations:
        if direction.Length < 1e-12:
            continue
        direction = FreeCAD.Vector(direction).normalize()
        tip = joint.Centre + direction * (length * 0.45)
        root.addChild(_line([tuple(joint.Centre), tuple(tip - direction * (length * 0.08))], TRANSLATION_COLOUR))
        root.addChild(_cone(tip, direction, length * 0.1, TRANSLATION_COLOUR))
        arrows += 1
    if not axes and not arrows:  # rigid: a ball where the contacts hold
        node = coin.SoSeparator()
        material = coin.SoMaterial()
        material.diffuseColor.setValue(*RIGID_COLOUR)
        translation = coin.SoTranslation()
        translation.translation.setValue(*tuple(joint.Centre))
        sphere = coin.SoSphere()
        sphere.radius.setValue(length * 0.04)
        for child in (material, translation, sphere):
            node.addChild(child)
        root.addChild(node)
    return root, axes, arrows


class ViewProviderJoint(_ViewProvider):
    """Draws its Joint's glyphs (over the bodies: an annotation)."""

    def attach(self, vobj):
        super().attach(vobj)
        self.glyphs = coin.SoAnnotation()
        self.glyphs.setName("JointGlyphs")
        self.axes = self.arrows = 0
        vobj.addDisplayMode(self.glyphs, "Glyphs")

    def getDisplayModes(self, vobj):
        return ["Glyphs"]

    def getDefaultDisplayMode(self):
        return "Glyphs"

    def setDisplayMode(self, mode):
        return mode

    def updateData(self, obj, prop):
        if prop in ("AxisPoints", "AxisDirections", "Translations", "Centre", "GlyphLength"):
            self.redraw()

    def redraw(self):
        glyphs = getattr(self, "glyphs", None)
        if glyphs is None:
            return
        glyphs.removeAllChildren()
        try:
            node, self.axes, self.arrows = joint_glyphs(self.Object)
        except Exception as error:  # drawing only
            FreeCAD.Console.PrintWarning(f"Contacts: cannot draw joint '{self.Object.Label}': {error}\n")
            return
        glyphs.addChild(node)

    def getIcon(self):
        return contactwb.icon_path("Contacts_DeriveJoints")

    def doubleClicked(self, vobj):
        """Selects the faces of the joint's contacts."""
        FreeCADGui.Selection.clearSelection()
        for contact in vobj.Object.Contacts:
            for links in (contact.FacesA, contact.FacesB):
                for root, subnames in links:
                    for subname in subnames:
                        FreeCADGui.Selection.addSelection(root.Document.Name, root.Name, subname)
        return True


def render_graph(dot_text, path):
    """The liaison graph as a PNG (Graphviz `dot`); the path, or None."""
    try:
        done = subprocess.run(["dot", "-Tpng", "-Gdpi=80", "-o", path], input=dot_text, text=True,
                              capture_output=True, timeout=60)
    except (OSError, subprocess.TimeoutExpired) as error:
        FreeCAD.Console.PrintWarning(f"Contacts: cannot draw the liaison graph: {error}\n")
        return None
    if done.returncode != 0:
        FreeCAD.Console.PrintWarning(f"Contacts: dot failed: {done.stderr.strip()}\n")
        return None
    return path


class JointsPanel:
    """Task panel: the mobility lines, the rigid groups and the liaison graph."""

    def __init__(self, group):
        from PySide2 import QtCore, QtGui, QtWidgets
        self.group = group
        self.form = QtWidgets.QWidget()
        self.form.setObjectName("ContactsJointsPanel")
        self.form.setWindowTitle(f"Joints of {group.Label}")
        layout = QtWidgets.QVBoxLayout(self.form)
        self.mobility = QtWidgets.QLabel("<br>".join(group.Mobility) or "No joints derived.")
        self.mobility.setWordWrap(True)
        layout.addWidget(self.mobility)
        self.graph = QtWidgets.QLabel()
        self.graph.setAlignment(QtCore.Qt.AlignCenter)
        self.graph_path = None
        if group.LiaisonGraph:
            path = os.path.join(tempfile.mkdtemp(prefix="contacts-graph-"), "liaison_graph.png")
            self.graph_path = render_graph(group.LiaisonGraph, path)
        if self.graph_path:
            pixmap = QtGui.QPixmap(self.graph_path)
            if pixmap.width() > 560:
                pixmap = pixmap.scaledToWidth(560, QtCore.Qt.SmoothTransformation)
            self.graph.setPixmap(pixmap)
        else:
            self.graph.setText("(no liaison graph)")
        scroll = QtWidgets.QScrollArea()
        scroll.setWidget(self.graph)
        scroll.setWidgetResizable(True)
        layout.addWidget(scroll, 1)

    def getStandardButtons(self):
        from PySide2 import QtWidgets
        return int(QtWidgets.QDialogButtonBox.Close)

    def reject(self):
        FreeCADGui.Control.closeDialog()
        return True


current_panel = None


def open_joints_panel(group):
    global current_panel
    if FreeCADGui.Control.activeDialog():
        FreeCADGui.Control.closeDialog()
    current_panel = JointsPanel(group)
    FreeCADGui.Control.showDialog(current_panel)
    return current_panel
