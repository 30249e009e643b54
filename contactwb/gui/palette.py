"""The workbench's one palette: the contact types' colours, the partitions'
colours derived from them (a plane partition in the planar fit's orange
family, a cylinder in the cylindrical joint's blue, ...), shades that tell
adjacent partitions of one type apart, and the joint glyphs' colours. None
of them is near FreeCAD's default selection green (0.11, 0.68, 0.11) or
preselection yellow (0.88, 0.88, 0.08)."""
import colorsys

# One colour per contact type (the legend, the paint, the tree icons).
TYPE_COLOURS = {
    "PLF": "#ff8c1a",  # orange
    "CLJ": "#1f5fff",  # blue
    "CJU": "#9b30ff",  # purple
    "SPF": "#d7263d",  # red
    "LAF": "#00d2e6",  # cyan
    "SPT": "#ff2fd2",  # magenta
    "TRF": "#8b5a2b",  # brown
}

# Interferences (parts that overlap): their solids in the tree and the 3D view,
# their legend entry and their rows in the table.
INTERFERENCE_COLOUR = "#e60d0d"

# A partition's surface -> the contact type whose hue family colours it: the
# partitions view and the contacts' paint read alike (planes orange as PLF).
SURFACE_FAMILY = {"Plane": "PLF", "Cylinder": "CLJ", "Cone": "CJU", "Sphere": "SPF", "Torus": "TRF"}
OTHER_SURFACE_COLOUR = "#9a9a9a"

# Shades of a family, as (lightness change, saturation factor) in HLS: the
# base colour first, then lighter and darker ones. Adjacent partitions of one
# type get different shades (a greedy colouring of their adjacency).
SHADES = ((0.0, 1.0), (0.22, 0.85), (-0.2, 1.0), (0.36, 0.7))

# Joint glyphs: rotation axes dark red, free translations teal.
JOINT_ROTATION = (0.75, 0.05, 0.1)
JOINT_TRANSLATION = (0.0, 0.42, 0.6)
JOINT_RIGID = (0.45, 0.45, 0.45)


def rgb(colour):
    """(r, g, b) in 0..1 of a "#rrggbb" colour."""
    return tuple(int(colour[i:i + 2], 16) / 255 for i in (1, 3, 5))


def hue(colour):
    """The hue of (r, g, b), degrees."""
    return colorsys.rgb_to_hls(*colour)[0] * 360.0


def shade(colour, index):
    """The index-th shade (SHADES, cycling) of (r, g, b)."""
    lightness_change, saturation_factor = SHADES[index % len(SHADES)]
    h, lightness, s = colorsys.rgb_to_hls(*colour)
    return colorsys.hls_to_rgb(h, min(0.9, max(0.12, lightness + lightness_change)),
                               min(1.0, s * saturation_factor))


def surface_colour(kind, shade_index=0, type_colours=None):
    """(r, g, b) of a partition of surface `kind` ("Plane", ...) in its
    contact type's family; `type_colours` the legend's (user) colours."""
    family = SURFACE_FAMILY.get(kind)
    if family is None:
        return shade(rgb(OTHER_SURFACE_COLOUR), shade_index)
    return shade(rgb((type_colours or TYPE_COLOURS)[family]), shade_index)


def greedy_shades(count, neighbours):
    """A shade index per item 0..count-1 such that neighbours (a dict item ->
    set of items of the same type it touches) differ where the SHADES allow."""
    chosen = {}
    for item in range(count):
        taken = {chosen[n] for n in neighbours.get(item, ()) if n in chosen}
        chosen[item] = next((k for k in range(len(SHADES)) if k not in taken), len(taken) % len(SHADES))
    return [chosen[item] for item in range(count)]
