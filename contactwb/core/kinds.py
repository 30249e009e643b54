"""The contact types and analysis scopes: the one list every layer reads (the
analysis table, the document objects, the task panel, the contact table, the
legend and the preferences). Colours are the GUI's (contactwb.gui.overlay.colours)."""
from dataclasses import dataclass


@dataclass(frozen=True)
class ContactKind:
    code: str      # the paper's three letters, as the core names the type
    title: str     # heading of the analysis table
    name: str      # short name (legend, task panel, preferences)
    circle: bool   # a contact along a circle: area 0 (ball contacts)


KINDS = (
    ContactKind("PLF", "Planar fits", "planar fit", False),
    ContactKind("CLJ", "Cylindrical joints", "cylindrical joint", False),
    ContactKind("CJU", "Cylindrical joints, unidirectional (cones)", "cone", False),
    ContactKind("SPF", "Spherical fits", "spherical fit", False),
    ContactKind("LAF", "Linear annular fits (ball in bore)", "ball in bore", True),
    ContactKind("SPT", "Balls in torus grooves", "ball in groove", True),
    ContactKind("TRF", "Torus fits", "torus fit", False),
)
BY_CODE = {kind.code: kind for kind in KINDS}

CONTACT_TYPES = [kind.code for kind in KINDS]            # in table order
TYPE_TITLES = {kind.code: kind.title for kind in KINDS}
TYPE_NAMES = {kind.code: kind.name for kind in KINDS}
CIRCLE_TYPES = tuple(kind.code for kind in KINDS if kind.circle)

# What a ContactAnalysis looks at: every visible solid, the chosen parts only,
# or the chosen parts against every other visible solid.
SCOPES = ["Document", "Selection", "PartAgainstRest"]


def is_circle_type(code):
    return code in CIRCLE_TYPES
