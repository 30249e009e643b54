"""Tolerance fields in mm and degrees: a tolerance is typed and read in the
unit the designer thinks in, with the digits it needs ("0.0009751 mm",
"0.00573 °"), where FreeCAD's unit schema would write "975.09 nm" and, with
two decimals, "0.01 °". Other units may be typed ("0.5 um", "1e-3 in",
"0.1 mrad"): FreeCAD's quantity parser converts them."""
import math

import FreeCAD
from PySide2 import QtGui, QtWidgets

SIGNIFICANT_DIGITS = 4


def plain_number(value, significant=SIGNIFICANT_DIGITS):
    """`value` with `significant` digits, fixed-point (no exponent), trailing zeros dropped."""
    if value == 0 or not math.isfinite(value):
        return "0" if value == 0 else str(value)
    decimals = max(0, significant - 1 - math.floor(math.log10(abs(value))))
    text = f"{value:.{decimals}f}"
    return text.rstrip("0").rstrip(".") if "." in text else text


class MeasureBox(QtWidgets.QDoubleSpinBox):
    """A length (unit "mm") or angle (unit "°") field: shows plain_number(value)
    and the unit; accepts any unit FreeCAD parses, converted."""

    def __init__(self, unit, value=0.0, parent=None):
        super().__init__(parent)
        self.unit = unit
        self._internal = "mm" if unit == "mm" else "deg"
        self.setDecimals(12)  # the value is kept to 1e-12 of its unit; the text shows what matters
        self.setRange(0.0, 1e9)
        self.setKeyboardTracking(False)
        self.setValue(value)

    def textFromValue(self, value):
        return f"{plain_number(value)} {self.unit}"

    def _parse(self, text):
        text = text.strip()
        if not text:
            return None
        try:
            quantity = FreeCAD.Units.Quantity(text.replace("\u00b0", " deg"))
        except Exception:
            return None
        if quantity.Unit == FreeCAD.Units.Quantity("1").Unit:  # a bare number: this field's unit
            return quantity.Value
        try:
            return quantity.getValueAs(self._internal).Value
        except Exception:  # another kind of quantity (an area typed in a length field)
            return None

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
