"""The workbench's quantities as text, one way everywhere (issue 21 item 11):
the tree's description column, the contact table, the task panel and the
property editor say the same thing.

Results (areas, volumes, spans, radii, angles) are quantity properties
(App::PropertyArea, ...), which FreeCAD's property editor writes in the
user's unit schema with the user's decimals (Preferences -> General -> Units):
the tree and the table use that same text (an area of 150.8 mm^2 reads
"1.51 cm^2" everywhere under the Standard schema, "150.80 mm^2" under
"Metric small parts & CNC"), unless it would hide the value (fewer than two
significant digits: "0.00 mm^2" for 0.004 mm^2), where they write the digits
it needs in the schema's unit ("0.004 mm^2").

Tolerances are the exception: they lie far below the schema's decimals
(1e-4 rad is "0.01 °" with two decimals, 0.000975 mm "975.10 nm"), so they
are written in mm and degrees with the digits they need ("0.0009751 mm",
"0.00573 °"), and the analysis keeps them as text properties the property
editor shows as such (the exact values in hidden quantity properties)."""
import math
from decimal import Decimal

import FreeCAD

SIGNIFICANT_DIGITS = 4   # a tolerance's text
LENGTH_UNIT, ANGLE_UNIT = "mm", "\u00b0"
# a tolerance setting's text when none is set (the core chooses)
DEFAULT_SETTING = {LENGTH_UNIT: "scaled to the model", ANGLE_UNIT: "default"}


def plain_number(value, significant=SIGNIFICANT_DIGITS):
    """`value` with `significant` digits, fixed-point (no exponent), trailing zeros dropped."""
    if value == 0 or not math.isfinite(value):
        return "0" if value == 0 else str(value)
    decimals = max(0, significant - 1 - math.floor(math.log10(abs(value))))
    text = f"{value:.{decimals}f}"
    return text.rstrip("0").rstrip(".") if "." in text else text


def exact_number(value):
    """`value` fixed-point with every digit a double carries that matters (12
    significant): a setting the designer typed, written back unchanged."""
    text = format(Decimal(f"{value:.12g}"), "f")
    return text.rstrip("0").rstrip(".") if "." in text else text


def user_string(value, unit):
    """`value` in FreeCAD's internal unit (mm, mm^2, mm^3, degree) as the
    property editor shows a quantity of that `unit` (FreeCAD.Units.Area, ...),
    with the digits it needs when the user's decimals would hide it."""
    quantity = FreeCAD.Units.Quantity(value, unit)
    text, factor, unit_text = quantity.getUserPreferred()
    shown = value / factor if factor else value
    if value == 0 or not math.isfinite(shown):
        return text
    try:
        written = float(text[:len(text) - len(unit_text)].strip().replace(",", "."))
    except ValueError:  # a schema writing feet and inches, or a locale's grouping: as FreeCAD writes it
        return text
    if abs(written - shown) <= 0.05 * abs(shown):  # two significant digits or more
        return text
    return f"{plain_number(shown, 2)} {unit_text}".rstrip()


def area_text(mm2):
    return user_string(mm2, FreeCAD.Units.Area)


def length_text(mm):
    return user_string(mm, FreeCAD.Units.Length)


def volume_text(mm3):
    return user_string(mm3, FreeCAD.Units.Volume)


def angle_text(degrees):
    return user_string(degrees, FreeCAD.Units.Angle)


def tolerance_text(value, unit):
    """A tolerance (mm or degrees) as the panel, the preferences and the
    property editor show it: "0.0009751 mm", "0.00573 °"."""
    return f"{plain_number(value)} {unit}"


def setting_text(value, unit):
    """A tolerance setting (mm or degrees, None: the core chooses) as its
    text property holds it: "0.0005 mm", "scaled to the model"."""
    return f"{exact_number(value)} {unit}" if value else DEFAULT_SETTING[unit]


def parse_measure(text, unit):
    """A length (unit "mm") or angle (unit "°") typed in any unit FreeCAD
    parses ("0.5 um", "1e-3 in", "0.1 mrad"; a bare number is in `unit`): its
    value in mm or degrees, or None when `text` is not one."""
    text = text.strip()
    if not text:
        return None
    try:
        quantity = FreeCAD.Units.Quantity(text.replace("\u00b0", " deg"))
    except Exception:
        return None
    if quantity.Unit == FreeCAD.Units.Quantity("1").Unit:  # a bare number: the field's unit
        return quantity.Value
    try:
        return quantity.getValueAs("mm" if unit == LENGTH_UNIT else "deg").Value
    except Exception:  # another kind of quantity (an area typed in a length field)
        return None


def parse_setting(text, unit):
    """A tolerance setting's text: its value in mm or degrees, None for the
    default (the default's words, empty, or 0). Raises ValueError naming the
    text when it is neither a length/angle nor the default."""
    stripped = text.strip()
    if stripped.lower() in ("", DEFAULT_SETTING[unit]):
        return None
    value = parse_measure(stripped, unit)
    if value is None or value < 0:
        kind = "length" if unit == LENGTH_UNIT else "angle"
        raise ValueError(f"tolerance setting '{text}' is not a positive {kind} (type e.g. "
                         f"{'0.001 mm or 0.5 um' if unit == LENGTH_UNIT else '0.01 deg or 2e-4 rad'}, "
                         f"or '{DEFAULT_SETTING[unit]}')")
    return value or None


def tolerance_settings(group):
    """(linear mm or None, angular rad or None): an analysis' tolerance settings
    (None: the core's default). Raises contactwb.core.ContactsError naming the
    analysis and the text when a setting is neither a tolerance nor the default."""
    from contactwb import core
    values = []
    for name, unit in (("LinearToleranceSetting", LENGTH_UNIT), ("AngularToleranceSetting", ANGLE_UNIT)):
        setting = getattr(group, name)
        if not isinstance(setting, str):  # a file of 0.2 or before not migrated (opened without the workbench)
            values.append(setting.Value or None)
            continue
        try:
            values.append(parse_setting(setting, unit))
        except ValueError as error:
            raise core.ContactsError(f"analysis '{group.Label}': {name}: {error}") from None
    linear, angular = values
    return linear, (math.radians(angular) if angular else None)


def tolerances_used(group):
    """(linear mm, angular rad): the tolerances an analysis used, exact."""
    if "LinearToleranceValue" in group.PropertiesList:
        return group.LinearToleranceValue.Value, math.radians(group.AngularToleranceValue.Value)
    return group.LinearTolerance.Value, math.radians(group.AngularTolerance.Value)  # 0.2 and before
