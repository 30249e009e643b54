"""The joints panel: the assembly's mobility (ground, degrees of freedom,
rigid groups) and the liaison graph (Graphviz, as `contacts --graph` draws it)."""
import os
import subprocess
import tempfile

import FreeCAD
import FreeCADGui


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
