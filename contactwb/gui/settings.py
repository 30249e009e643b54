"""The workbench's preferences (User parameter:BaseApp/Preferences/Mod/Contacts):
where they are kept and how they are read. The page editing them is
contactwb.gui.preferences."""
import FreeCAD

PREFERENCES = "User parameter:BaseApp/Preferences/Mod/Contacts"
PAINT_STYLES = ["Common area", "Whole faces"]


def params():
    """The workbench's parameter group."""
    return FreeCAD.ParamGet(PREFERENCES)


def paint_style():
    """"Common area" (default) or "Whole faces" (preferences)."""
    return params().GetString("PaintStyle", "Common area") or "Common area"


def colour_setting(kind, default):
    """The colour the user chose for a contact type ("#rrggbb"), else `default`."""
    return params().GetString(f"Colour{kind}", default) or default
