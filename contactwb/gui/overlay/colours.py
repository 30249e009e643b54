"""The contact types' colours: the legend's defaults, the user's choices
(preferences) kept away from FreeCAD's selection and preselection colours,
and the lighter shade of partial contacts."""
import FreeCAD

from contactwb.core.kinds import CONTACT_TYPES
from contactwb.gui import settings
# The legend: one colour per contact type (also the tree icons' colour), from
# the one palette. None is near FreeCAD's selection green or preselection
# yellow (legend_colours also keeps user-chosen colours away from them).
from contactwb.gui.palette import TYPE_COLOURS, rgb  # noqa: F401 (rgb: the overlay's colours)
assert list(TYPE_COLOURS) == CONTACT_TYPES, "a colour for every contact type of contactwb.core.kinds"
MIN_COLOUR_DISTANCE = 0.25  # per channel (0..1): what still reads as another colour
UNKNOWN_COLOUR = "#808080"
PARTIAL_LIGHTEN = 0.45         # partial contacts: this far towards white


def hex_colour(colour):
    return "#" + "".join(f"{round(max(0.0, min(1.0, c)) * 255):02x}" for c in colour)


def distance(a, b):
    return max(abs(x - y) for x, y in zip(a, b))


def highlight_colours():
    """FreeCAD's selection and preselection colours (preferences)."""
    view = FreeCAD.ParamGet("User parameter:BaseApp/Preferences/View")
    return [tuple(((view.GetUnsigned(name, default) >> shift) & 0xFF) / 255 for shift in (24, 16, 8))
            for name, default in (("SelectionColor", 0x1CAD1C00), ("HighlightColor", 0xE1E11400))]


def legend_colours():
    """{type: "#rrggbb"}: the preferences' colours (default TYPE_COLOURS),
    each moved away from the selection and preselection colours when it is
    too near one of them (a selected contact must stand out)."""
    avoid = highlight_colours()
    colours = {}
    for kind, default in TYPE_COLOURS.items():
        colour = rgb(settings.colour_setting(kind, default))
        for _ in range(4):
            near = [c for c in avoid if distance(colour, c) < MIN_COLOUR_DISTANCE]
            if not near:
                break
            # push every channel away from the colour it resembles
            colour = tuple(x - 0.4 if x >= c else x + 0.4 for x, c in zip(colour, near[0]))
            colour = tuple(max(0.0, min(1.0, x)) for x in colour)
        colours[kind] = hex_colour(colour)
    return colours


def type_colour(kind, partial=False, colours=None):
    r, g, b = rgb((colours or legend_colours()).get(kind, UNKNOWN_COLOUR))
    if partial:
        r, g, b = (c + (1 - c) * PARTIAL_LIGHTEN for c in (r, g, b))
    return r, g, b


def selection_colour():
    """FreeCAD's selection colour (preferences), as (r, g, b) in 0..1."""
    packed = FreeCAD.ParamGet("User parameter:BaseApp/Preferences/View").GetUnsigned(
        "SelectionColor", 0x1CAD1C00)
    return tuple(((packed >> shift) & 0xFF) / 255 for shift in (24, 16, 8))
