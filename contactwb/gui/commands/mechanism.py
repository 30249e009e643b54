"""Contacts_ExportMechanism: the derived mechanism of the selected contact
analysis (or the document's only one) written as URDF or MJCF, the same
files as `contacts FILE --export-urdf DIR` / `--export-mjcf FILE.xml`
(contactwb.document.mechanism; docs/mechanism.md)."""
import os

import FreeCAD
import FreeCADGui

import contactwb
from contactwb.document.identify import analyses, is_contact, is_contact_analysis, is_joint
from contactwb.gui.dialogs import show_error

FORMATS = [("urdf", "URDF: a folder (NAME.urdf and meshes/)"), ("mjcf", "MJCF (MuJoCo): an .xml file")]
MOST_BODIES = "(the group with the most bodies)"


def _analysis(doc):
    """The selected analysis (or the one holding a selected contact or joint), else the only one."""
    for obj in FreeCADGui.Selection.getSelection(doc.Name):
        if is_contact_analysis(obj):
            return obj
        if is_contact(obj) or is_joint(obj):
            found = next((p for p in obj.InList if is_contact_analysis(p)), None)
            if found is not None:
                return found
    found = analyses(doc)
    return found[0] if len(found) == 1 else None


def _add_path_row(form, label, edit, browse):
    """A form row: the path field `edit` and a Browse... button calling `browse`."""
    from PySide2 import QtWidgets
    button = QtWidgets.QPushButton("Browse...")
    button.clicked.connect(browse)
    row = QtWidgets.QHBoxLayout()
    row.addWidget(edit)
    row.addWidget(button)
    form.addRow(label, row)


class ExportMechanismDialog:
    """Format, path, annotation file, density and ground of the export (a modal QDialog)."""

    def __init__(self, group, parent=None):
        import json
        from PySide2 import QtWidgets
        from contactwb.core.mechanism import DEFAULT_DENSITY
        from contactwb.document.mechanism import sidecar_annotations
        self.group = group
        doc = group.Document
        self.folder = os.path.dirname(doc.FileName) if doc.FileName else os.path.expanduser("~")
        self.stem = os.path.splitext(os.path.basename(doc.FileName))[0] if doc.FileName else doc.Label
        self.widget = QtWidgets.QDialog(parent)
        self.widget.setObjectName("ContactsExportMechanism")
        self.widget.setWindowTitle("Export mechanism")
        form = QtWidgets.QFormLayout(self.widget)
        self.format = QtWidgets.QComboBox()
        for _, text in FORMATS:
            self.format.addItem(text)
        form.addRow("Format:", self.format)
        self.path = QtWidgets.QLineEdit()
        _add_path_row(form, "Write to:", self.path, self.browse_path)
        self.annotations = QtWidgets.QLineEdit(sidecar_annotations(doc) or "")
        self.annotations.setPlaceholderText("none: contacts as drawn")
        _add_path_row(form, "Annotations:", self.annotations, self.browse_annotations)
        self.density = QtWidgets.QDoubleSpinBox()
        self.density.setRange(1.0, 100000.0)
        self.density.setDecimals(1)
        self.density.setSuffix(" kg/m\u00b3")
        self.density.setValue(DEFAULT_DENSITY)
        form.addRow("Density:", self.density)
        self.ground = QtWidgets.QComboBox()
        self.ground.addItem(MOST_BODIES)
        for body in json.loads(getattr(group, "BodyTable", "") or "[]"):
            self.ground.addItem(body["name"])
        form.addRow("Ground:", self.ground)
        buttons = QtWidgets.QDialogButtonBox(QtWidgets.QDialogButtonBox.Ok | QtWidgets.QDialogButtonBox.Cancel)
        buttons.accepted.connect(self.accept)
        buttons.rejected.connect(self.widget.reject)
        form.addRow(buttons)
        self.format.currentIndexChanged.connect(self.suggest_path)
        self.suggest_path()

    def fmt(self):
        return FORMATS[self.format.currentIndex()][0]

    def suggest_path(self, *_):
        name = f"{self.stem}_urdf" if self.fmt() == "urdf" else f"{self.stem}.xml"
        self.path.setText(os.path.join(self.folder, name))

    def browse_path(self):
        from PySide2 import QtWidgets
        if self.fmt() == "urdf":
            chosen = QtWidgets.QFileDialog.getExistingDirectory(self.widget, "URDF folder", self.folder)
        else:
            chosen, _ = QtWidgets.QFileDialog.getSaveFileName(self.widget, "MJCF file", self.path.text(),
                                                              "MJCF (*.xml)")
        if chosen:
            self.path.setText(chosen)

    def browse_annotations(self):
        from PySide2 import QtWidgets
        chosen, _ = QtWidgets.QFileDialog.getOpenFileName(self.widget, "Annotations", self.folder,
                                                          "Annotations (*.json)")
        if chosen:
            self.annotations.setText(chosen)

    def accept(self):
        path = self.path.text().strip()
        if not path:
            show_error("Name where to write the mechanism.")
            return
        if self.fmt() == "mjcf" and not path.lower().endswith(".xml"):
            self.path.setText(path + ".xml")
        self.widget.accept()

    def values(self):
        """(format, path, density, ground body or None, annotations file or None)."""
        ground = self.ground.currentText()
        return (self.fmt(), self.path.text().strip(), self.density.value(),
                None if ground == MOST_BODIES else ground, self.annotations.text().strip() or None)


class Contacts_ExportMechanism:
    """Writes the derived mechanism (links from the rigid groups, joints from the group joints) of a
    contact analysis as URDF or MJCF."""

    def GetResources(self):
        return {
            "Pixmap": contactwb.icon_path("Contacts_ExportMechanism"),
            "MenuText": "Export mechanism...",
            "ToolTip": "Write the mechanism derived from the selected analysis (or the only one) for a robot "
                       "simulator: one link per rigid group (mass and inertia from the solids, meshes), one "
                       "joint per group joint, the ground fixed; URDF (a folder) or MJCF (an .xml file)",
        }

    def IsActive(self):
        return FreeCAD.ActiveDocument is not None and bool(analyses(FreeCAD.ActiveDocument))

    def Activated(self):
        from PySide2 import QtWidgets
        doc = FreeCAD.ActiveDocument
        group = _analysis(doc)
        if group is None:
            show_error("Select the contact analysis whose mechanism to export (the document holds several).")
            return None
        dialog = ExportMechanismDialog(group, FreeCADGui.getMainWindow())
        if dialog.widget.exec_() != QtWidgets.QDialog.Accepted:
            return None
        return self.export(group, *dialog.values())

    @staticmethod
    def export(group, fmt, path, density, ground, annotations):
        """Writes the files (a wait cursor meanwhile); returns the Model, or None after an error shown."""
        from PySide2 import QtCore, QtWidgets
        from contactwb import core
        from contactwb.core import output_files
        from contactwb.document import mechanism
        QtWidgets.QApplication.setOverrideCursor(QtCore.Qt.WaitCursor)
        try:
            model, written = mechanism.export_analysis(group, fmt, path, density, ground, annotations)
        except (core.ContactsError, output_files.UnsafeTarget, OSError, ValueError) as error:
            QtWidgets.QApplication.restoreOverrideCursor()
            show_error(f"cannot export the mechanism of '{group.Label}': {error}")
            return None
        QtWidgets.QApplication.restoreOverrideCursor()
        joints = ", ".join(f"{j.child} {j.type}" for j in model.joints) or "no joint"
        FreeCAD.Console.PrintMessage(f"Contacts: mechanism of '{group.Label}': {len(model.links)} links "
                                     f"(ground {model.ground}; {joints}) written to {', '.join(written)}\n")
        for note in model.notes:
            FreeCAD.Console.PrintWarning(f"Contacts: {note}\n")
        return model


COMMANDS = {"Contacts_ExportMechanism": Contacts_ExportMechanism}
