"""Quantities as FreeCAD's property editor writes them: the user's unit
schema and decimals (Preferences -> General -> Units), so that the tree's
description column, the contact table and the property editor say the same
(an Area of 150.8 mm^2 reads "1.51 cm^2" everywhere under the Standard
schema, "150.80 mm^2" under "Metric small parts & CNC"). Tolerances, typed
by the designer, are the exception: always mm and degrees (see
contactwb.gui.units), as the schema would write 0.000975 mm "975.00 nm"."""
import FreeCAD


def user_string(value, unit):
    """`value` in FreeCAD's internal unit (mm, mm^2, mm^3, degree) as the
    property editor shows a quantity of that `unit` (FreeCAD.Units.Area, ...)."""
    return FreeCAD.Units.Quantity(value, unit).UserString


def area_text(mm2):
    return user_string(mm2, FreeCAD.Units.Area)


def length_text(mm):
    return user_string(mm, FreeCAD.Units.Length)


def volume_text(mm3):
    return user_string(mm3, FreeCAD.Units.Volume)


def angle_text(degrees):
    return user_string(degrees, FreeCAD.Units.Angle)
