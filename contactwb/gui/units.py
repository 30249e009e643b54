"""Tolerance fields in mm and degrees: a tolerance is typed and read in the
unit the designer thinks in, with the digits it needs ("0.0009751 mm",
"0.00573 °"), where FreeCAD's unit schema would write "975.09 nm" and, with
two decimals, "0.01 °". Other units may be typed ("0.5 um", "1e-3 in",
"2e-4 rad"): FreeCAD's quantity parser converts them (contactwb.document.units)."""
import math

from PySide2 import QtGui, QtWidgets

from contactwb.document.units import SIGNIFICANT_DIGITS, parse_measure, plain_number  # noqa: F401  (this module's API)


class MeasureBox(QtWidgets.QDoubleSpinBox):
    """A length (unit "mm") or angle (unit "°") field: shows plain_number(value)
    and the unit; accepts any unit FreeCAD parses, converted."""

    def __init__(self, unit, value=0.0, parent=None):
        super().__init__(parent)
        self.unit = unit
        self.setDecimals(12)  # the value is kept to 1e-12 of its unit; the text shows what matters
        self.setRange(0.0, 1e9)
        self.setKeyboardTracking(False)
        self.setValue(value)

    def textFromValue(self, value):
        return f"{plain_number(value)} {self.unit}"

    def _parse(self, text):
        return parse_measure(text, self.unit)

    def valueFromText(self, text):
        value = self._parse(text)
        return self.value() if value is None else value

    def validate(self, text, position):
        value = self._parse(text)
        state = QtGui.QValidator.Acceptable if value is not None and value >= 0 else QtGui.QValidator.Intermediate
        return state, text, position

    def stepBy(self, steps):
        # a tenth of the value's order of magnitude: steps mean something at 1e-3 mm as at 1 mm
        value = self.value()
        step = 10 ** math.floor(math.log10(value)) / 10 if value > 0 else 1e-3
        self.setValue(max(0.0, value + steps * step))
