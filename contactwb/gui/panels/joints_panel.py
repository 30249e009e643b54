"""The joints panel: the assembly's mobility (ground, degrees of freedom
explained: which bodies, which motions), the joints listed with their
motions (selection both ways with the tree and the 3D view's glyphs), and the
liaison graph (Graphviz, as `contacts --graph` draws it) in a zoomable view."""
import os
import subprocess
import tempfile

import FreeCAD
import FreeCADGui
from PySide2 import QtCore, QtGui, QtWidgets

from contactwb.document.identify import is_alive, is_joint

ZOOM_STEP = 1.25       # per wheel notch
MIN_SCALE, MAX_SCALE = 0.05, 20.0


def render_graph(dot_text, path, fmt="svg"):
    """The liaison graph drawn by Graphviz `dot` (SVG: scales without blur);
    the path, or None."""
    try:
        done = subprocess.run(["dot", f"-T{fmt}", "-o", path], input=dot_text, text=True,
                              capture_output=True, timeout=60)
    except (OSError, subprocess.TimeoutExpired) as error:
        FreeCAD.Console.PrintWarning(f"Contacts: cannot draw the liaison graph: {error}\n")
        return None
    if done.returncode != 0:
        FreeCAD.Console.PrintWarning(f"Contacts: dot failed: {done.stderr.strip()}\n")
        return None
    return path


class GraphView(QtWidgets.QGraphicsView):
    """The liaison graph at its natural size (Graphviz's 14 pt labels),
    zoomed by the wheel about the cursor, dragged to pan; Fit shows it whole."""

    def __init__(self, svg_path=None, parent=None):
        super().__init__(parent)
        self.setObjectName("ContactsLiaisonGraph")
        self.setScene(QtWidgets.QGraphicsScene(self))
        self.setDragMode(QtWidgets.QGraphicsView.ScrollHandDrag)
        self.setTransformationAnchor(QtWidgets.QGraphicsView.AnchorUnderMouse)
        self.setRenderHints(QtGui.QPainter.Antialiasing | QtGui.QPainter.SmoothPixmapTransform)
        self.setMinimumHeight(260)
        self.item = None
        if svg_path:
            from PySide2 import QtSvg
            self.item = QtSvg.QGraphicsSvgItem(svg_path)
            self.scene().addItem(self.item)
            self.setSceneRect(self.item.boundingRect())

    def scale_factor(self):
        return self.transform().m11()

    def zoom(self, factor):
        target = min(max(self.scale_factor() * factor, MIN_SCALE), MAX_SCALE)
        self.scale(target / self.scale_factor(), target / self.scale_factor())

    def wheelEvent(self, event):
        notches = event.angleDelta().y() / 120.0
        if notches:
            self.zoom(ZOOM_STEP ** notches)
        event.accept()

    def fit(self):
        if self.item is not None:
            self.fitInView(self.item, QtCore.Qt.KeepAspectRatio)


def joint_text(joint):
    """"J3 revolute: Body – Axis (1 DOF): 1 rotation about z through (0, 0, 8)"."""
    from contactwb.core.joints import describe_motion
    rotations = [(tuple(p), tuple(d)) for p, d in zip(joint.AxisPoints, joint.AxisDirections) if d.Length > 1e-12]
    translations = [tuple(d) for d in joint.Translations if d.Length > 1e-12]
    return f"{joint.Label} ({joint.DOF} DOF): {describe_motion(rotations, translations)}"


class JointsPanel:
    """Task panel: the mobility explained, the joints, the liaison graph."""

    def __init__(self, group):
        self.group = group
        self.doc_name = group.Document.Name
        self._syncing = False
        self.form = QtWidgets.QWidget()
        self.form.setObjectName("ContactsJointsPanel")
        self.form.setWindowTitle(f"Joints of {group.Label}")
        layout = QtWidgets.QVBoxLayout(self.form)
        self.mobility = QtWidgets.QLabel(self._mobility_html())
        self.mobility.setWordWrap(True)
        self.mobility.setTextInteractionFlags(QtCore.Qt.TextSelectableByMouse)
        layout.addWidget(self.mobility)
        layout.addWidget(QtWidgets.QLabel("<b>Joints</b> (select one to find it in the view):"))
        self.joints = QtWidgets.QListWidget()
        self.joints.setObjectName("ContactsJointList")
        self.joints.setSelectionMode(QtWidgets.QAbstractItemView.ExtendedSelection)
        self.joints.setWordWrap(True)
        for joint in self.joint_objects():
            item = QtWidgets.QListWidgetItem(joint_text(joint))
            item.setData(QtCore.Qt.UserRole, joint.Name)
            self.joints.addItem(item)
        layout.addWidget(self.joints, 1)
        graph_row = QtWidgets.QHBoxLayout()
        graph_row.addWidget(QtWidgets.QLabel("<b>Liaison graph</b> (wheel: zoom, drag: pan)"))
        graph_row.addStretch(1)
        self.fit_button = QtWidgets.QPushButton("Fit")
        self.actual_button = QtWidgets.QPushButton("1:1")
        graph_row.addWidget(self.fit_button)
        graph_row.addWidget(self.actual_button)
        layout.addLayout(graph_row)
        self.graph_path = None
        if group.LiaisonGraph:
            path = os.path.join(tempfile.mkdtemp(prefix="contacts-graph-"), "liaison_graph.svg")
            self.graph_path = render_graph(group.LiaisonGraph, path)
        self.graph = GraphView(self.graph_path)
        if self.graph_path is None:
            self.graph.scene().addText("(no liaison graph)")
        layout.addWidget(self.graph, 2)
        self.fit_button.clicked.connect(self.graph.fit)
        self.actual_button.clicked.connect(lambda: self.graph.zoom(1.0 / self.graph.scale_factor()))
        self.joints.itemSelectionChanged.connect(self._rows_selected)
        FreeCADGui.Selection.addObserver(self)
        self.form.destroyed.connect(lambda *_: self._close())  # closed by FreeCAD, not by its button
        self.sync_from_selection()

    def _mobility_html(self):
        lines = list(self.group.Mobility)
        if not lines:
            return "No joints derived."
        return "<br>".join(lines[:2]) + "<ul>" + "".join(f"<li>{line}</li>" for line in lines[2:]) + "</ul>"

    def joint_objects(self):
        return [o for o in self.group.Group if is_joint(o)]

    # --- selection, both ways -------------------------------------------
    def _rows_selected(self):
        if self._syncing:
            return
        doc = FreeCAD.getDocument(self.doc_name)
        self._syncing = True
        try:
            FreeCADGui.Selection.clearSelection()
            for item in self.joints.selectedItems():
                joint = doc.getObject(item.data(QtCore.Qt.UserRole))
                if joint is not None:
                    FreeCADGui.Selection.addSelection(joint)
        finally:
            self._syncing = False

    def sync_from_selection(self):
        """Selects the rows of the joints selected in the tree or the view."""
        if self._syncing:
            return
        selected = {o.Name for o in FreeCADGui.Selection.getSelection(self.doc_name) if is_joint(o)}
        self._syncing = True
        try:
            for row in range(self.joints.count()):
                item = self.joints.item(row)
                item.setSelected(item.data(QtCore.Qt.UserRole) in selected)
                if item.isSelected():
                    self.joints.scrollToItem(item)
        finally:
            self._syncing = False

    def _sync(self, *_):
        try:
            doc = FreeCAD.listDocuments().get(self.doc_name)
            if is_alive(doc, self.group):
                self.sync_from_selection()
        except Exception as error:  # an observer must never break the selection
            FreeCAD.Console.PrintWarning(f"Contacts: joints panel selection failed: {error}\n")

    addSelection = removeSelection = setSelection = clearSelection = _sync

    def getStandardButtons(self):
        return int(QtWidgets.QDialogButtonBox.Close)

    def _close(self):
        try:
            FreeCADGui.Selection.removeObserver(self)
        except Exception:
            pass

    def reject(self):
        self._close()
        FreeCADGui.Control.closeDialog()
        return True


current_panel = None


def open_joints_panel(group):
    global current_panel
    if FreeCADGui.Control.activeDialog():
        if current_panel is not None:
            current_panel._close()
        FreeCADGui.Control.closeDialog()
    current_panel = JointsPanel(group)
    FreeCADGui.Control.showDialog(current_panel)
    return current_panel
