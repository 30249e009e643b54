"""The workbench's page in FreeCAD's Preferences: default tolerances, the
contact colours and the paint style (stored under
User parameter:BaseApp/Preferences/Mod/Contacts)."""
import math

from PySide2 import QtGui, QtWidgets

from contactwb.core.kinds import TYPE_NAMES
from contactwb.gui import settings
from contactwb.gui.overlay.colours import TYPE_COLOURS
from contactwb.gui.settings import PAINT_STYLES, PREFERENCES  # noqa: F401  (this module's names before)
from contactwb.gui.units import MeasureBox, plain_number


def default_angular():
    """The core's default angular tolerance, radians."""
    from contactwb import core
    return core.contactcore.Tolerances().angular


class PreferencesPage:
    """FreeCAD calls loadSettings when the dialog opens, saveSettings on OK."""

    def __init__(self, parent=None):
        self.form = QtWidgets.QWidget(parent)
        self.form.setObjectName("ContactsPreferences")
        self.form.setWindowTitle("Contacts")
        layout = QtWidgets.QFormLayout(self.form)
        self.linear = MeasureBox("mm")
        self.linear.setRange(0, 10)
        self.linear.setSpecialValueText("scaled to the model")
        self.angular = MeasureBox("\u00b0")
        self.angular.setRange(0, 10)
        # the core's own default, in degrees (0.00573 deg = 1e-4 rad), not a rounded "0.01"
        self.angular.setSpecialValueText(f"default ({plain_number(math.degrees(default_angular()))} \u00b0)")
        self.paint = QtWidgets.QComboBox()
        self.paint.addItems(PAINT_STYLES)
        layout.addRow("Default linear tolerance:", self.linear)
        layout.addRow("Default angular tolerance:", self.angular)
        layout.addRow("Paint contacts as:", self.paint)
        self.colours = {}
        for kind in TYPE_COLOURS:
            button = QtWidgets.QPushButton()
            button.clicked.connect(lambda checked=False, k=kind: self._pick(k))
            self.colours[kind] = button
            layout.addRow(f"{kind} ({TYPE_NAMES[kind]}):", button)
        note = QtWidgets.QLabel("Colours too near the selection or preselection colour are moved away "
                                "from it when drawn.")
        note.setWordWrap(True)
        layout.addRow(note)

    def _set_colour(self, kind, colour):
        button = self.colours[kind]
        button.setText(colour)
        button.setStyleSheet(f"background-color: {colour}")

    def _pick(self, kind):
        chosen = QtWidgets.QColorDialog.getColor(QtGui.QColor(self.colours[kind].text()), self.form)
        if chosen.isValid():
            self._set_colour(kind, chosen.name())

    def loadSettings(self):
        params = settings.params()
        self.linear.setValue(params.GetFloat("LinearTolerance", 0.0))
        self.angular.setValue(params.GetFloat("AngularTolerance", 0.0))
        style = settings.paint_style()
        self.paint.setCurrentIndex(PAINT_STYLES.index(style) if style in PAINT_STYLES else 0)
        for kind, default in TYPE_COLOURS.items():
            self._set_colour(kind, settings.colour_setting(kind, default))

    def saveSettings(self):
        params = settings.params()
        params.SetFloat("LinearTolerance", self.linear.value())
        params.SetFloat("AngularTolerance", self.angular.value())
        params.SetString("PaintStyle", self.paint.currentText())
        for kind, button in self.colours.items():
            params.SetString(f"Colour{kind}", button.text())
