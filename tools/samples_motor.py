"""BL17-class brushless DC motor replica (the paper's section 5 example).

Axis Z, back cover at z = 0, output shaft towards +Z. Body diameter 48 mm.
All dimensions in mm.  See motor_expected() for the 14 PLF + 21 CLJ contacts.

z layout:  Back-cover 0..8 | Body 8..48 (stator shoulder at 12) | Front-cover 43..58
           Bearing-back 2.7..7.7 | Rotor-back 14..38 | Rotor-front 38..44 |
           Bearing-front 44..49 | Seal 54..57 | Axis 4..70 | Screws 2.6..59
"""
import math

from samples_common import (FreeCAD, Part, V, revolve, polygon_prism, cyl, split_shape,
                            one_solid, Part_, contact)

# ---- main dimensions
R_OUT = 24.0          # body / covers outer radius
R_SHAFT = 4.0         # shaft and all bores on it
R_BRG = 8.0           # bearing outer radius (688-like 8x16x5)
W_BRG = 5.0
R_SEAL = 7.0
R_STATOR = 17.0       # stator outer = body bore
R_STATOR_IN = 11.0
R_MAG = 10.3          # magnet outer arc (air gap 0.7 to the stator)
H_ROTOR = 7.0         # half width of the square rotor yoke (magnet seats)
R_SCREW = 1.5         # M3 shank = hole radius (threads not modelled)
R_SCREW_HEAD = 2.75
P_SCREW = 14.5        # screw positions (+-14.5, +-14.5) -> 20.5 from the axis
R_EXTRA = 1.2         # 4 extra front-cover holes (smaller than the screws)

# 18 components (the paper's list: 1+1+1+4+2+1+1+1+1+1+4)
NAMES = ['Axis', 'Rotor-front', 'Rotor-back', 'Magnet-1', 'Magnet-2', 'Magnet-3',
         'Magnet-4', 'Bearing-front', 'Bearing-back', 'Seal', 'Stator', 'Body',
         'Back-cover', 'Front-cover', 'Screw-1', 'Screw-2', 'Screw-3', 'Screw-4']

SCREW_XY = [(P_SCREW, P_SCREW), (-P_SCREW, P_SCREW), (-P_SCREW, -P_SCREW), (P_SCREW, -P_SCREW)]

COLORS = {
    'Axis': (0.75, 0.75, 0.78), 'Rotor-front': (0.55, 0.58, 0.65), 'Rotor-back': (0.45, 0.48, 0.55),
    'Magnet': (0.80, 0.20, 0.20), 'Bearing': (0.85, 0.75, 0.35), 'Seal': (0.15, 0.15, 0.15),
    'Stator': (0.72, 0.45, 0.20), 'Body': (0.30, 0.45, 0.70), 'Back-cover': (0.35, 0.35, 0.38),
    'Front-cover': (0.35, 0.35, 0.38), 'Screw': (0.10, 0.10, 0.12),
}


def axis_shape():
    # shaft r=4 from z=4 to 70, 0.5 chamfers, circlip-like groove z 9..9.8 (r 3.6),
    # D-flat on the output end (x <= 3.3, z 62..70).
    prof = [(0, 4), (3.5, 4), (4, 4.5), (4, 9), (3.6, 9), (3.6, 9.8), (4, 9.8),
            (4, 69.5), (3.5, 70), (0, 70)]
    s = revolve(prof)
    s = s.cut(Part.makeBox(5, 10, 9, V(3.3, -5, 62)))
    s = one_solid(s)
    # CAD-like splits: shaft cylinder in two halves and cut at z = 26
    s = split_shape(s, 'y', 0.0)
    s = split_shape(s, 'z', 26.0)
    return s


def rotor_back_shape():
    h, c = H_ROTOR, 1.0
    pts = [(h, -h + c), (h, h - c), (h - c, h), (-h + c, h), (-h, h - c), (-h, -h + c),
           (-h + c, -h), (h - c, -h)]
    s = polygon_prism(pts, 14.0, 38.0)
    s = s.cut(cyl(R_SHAFT, 13, 39))
    for k in range(4):   # lightening holes
        a = math.radians(45 + 90 * k)
        s = s.cut(cyl(1.0, 13, 39, 5.5 * math.cos(a), 5.5 * math.sin(a)))
    s = one_solid(s)
    return split_shape(s, 'x', 0.0)


def magnet_shape():
    # flat bottom on the x = 7 flat of Rotor-back, outer arc r = 10.3, |y| <= 4.5
    s = cyl(R_MAG, 14.5, 37.5).common(Part.makeBox(5, 9, 23, V(H_ROTOR, -4.5, 14.5)))
    return one_solid(s)


def rotor_front_shape():
    # flange r 9.5 (z 38..40.5) + hub r 6 (z 40.5..44), bore r 4, fillet r 0.5 at hub root
    f = 0.5
    prof = [(4, 38), (9.0, 38), (9.5, 38.5), (9.5, 40.5), (6 + f, 40.5),
            ('arc', (6 + f - f * math.cos(math.radians(45)), 40.5 + f - f * math.sin(math.radians(45)))),
            (6, 40.5 + f), (6, 43.7), (5.7, 44), (4, 44)]
    s = revolve(prof)
    return split_shape(s, 'y', 0.0)


def bearing_shape():
    # inner+outer ring as one solid, 0.3 chamfers, shield recesses r 5.2..6.8, depth 0.3
    prof = [(4.3, 0), (5.2, 0), (5.2, 0.3), (6.8, 0.3), (6.8, 0), (7.7, 0), (8, 0.3),
            (8, 4.7), (7.7, 5), (6.8, 5), (6.8, 4.7), (5.2, 4.7), (5.2, 5), (4.3, 5),
            (4, 4.7), (4, 0.3)]
    return revolve(prof)


def seal_shape():
    # ring r 4..7, z 54..57, front groove r 5..5.5, lip chamfer at the front bore
    prof = [(4.3, 54), (6.7, 54), (7, 54.3), (7, 56.7), (6.7, 57), (5.5, 57), (5.5, 56.4),
            (5.0, 56.4), (5.0, 57), (4.6, 57), (4, 56.4), (4, 54.3)]
    return revolve(prof)


def stator_shape():
    prof = [(11, 12), (16.7, 12), (17, 12.3), (17, 39.7), (16.7, 40), (11, 40)]
    s = revolve(prof)
    for k in range(9):   # 9 winding slots
        slot = Part.makeBox(4.0, 2.0, 30, V(10.5, -1.0, 11))
        slot.rotate(V(0, 0, 0), V(0, 0, 1), 20 + 40 * k)
        s = s.cut(slot)
    return one_solid(s)


def body_shape():
    prof = [(15, 8), (23.5, 8), (24, 8.5), (24, 47.5), (23.5, 48), (17.5, 48), (17, 47.5),
            (17, 12), (15, 12)]
    s = revolve(prof)
    for x, y in SCREW_XY:
        s = s.cut(cyl(R_SCREW, 7, 49, x, y))
    s = s.cut(Part.makeCylinder(2.5, 10, V(15, 0, 20), V(1, 0, 0)))   # cable exit
    s = one_solid(s)
    s = split_shape(s, 'x', 0.0)
    s = split_shape(s, 'y', 0.0)
    return s


def back_cover_shape():
    prof = [(6.2, 0), (23.5, 0), (24, 0.5), (24, 7.5), (23.5, 8), (8.4, 8), (8, 7.6),
            (8, 2.7), (6.2, 2.7)]
    s = revolve(prof)
    tip = R_SCREW / math.tan(math.radians(59))
    for x, y in SCREW_XY:   # blind tapped holes (drawn at the shank radius)
        s = s.cut(cyl(R_SCREW, 2, 9, x, y))
        s = s.cut(Part.makeCone(0, R_SCREW, tip, V(x, y, 2 - tip)))
    s = one_solid(s)
    return split_shape(s, 'y', 0.0)


def front_cover_shape():
    f = 0.5
    prof = [(7, 49.3), (8, 49.3), (8, 43.4), (8.4, 43), (10.2, 43), (10.5, 43.3), (10.5, 48),
            (23.5, 48), (24, 48.5), (24, 55.5), (23.5, 56), (11 + f, 56),
            ('arc', (11 + f - f * math.cos(math.radians(45)), 56 + f - f * math.sin(math.radians(45)))),
            (11, 56 + f), (11, 57.7), (10.7, 58), (7.4, 58), (7, 57.6)]
    s = revolve(prof)
    for x, y in SCREW_XY:
        s = s.cut(cyl(R_SCREW, 47, 57, x, y))
    for x, y in [(14, 0), (0, 14), (-14, 0), (0, -14)]:
        s = s.cut(cyl(R_EXTRA, 47, 57, x, y))
    s = one_solid(s)
    s = split_shape(s, 'y', 0.0)
    s = split_shape(s, 'z', 52.0)
    return s


def screw_shape():
    # socket head cap screw M3: shank r 1.5 from the tip z = 2.6 to the head z = 56,
    # head r 2.75 x 3 with a top fillet and a hex socket
    f = 0.3
    prof = [(0, 2.6), (1.2, 2.6), (1.5, 2.9), (1.5, 56), (R_SCREW_HEAD, 56),
            (R_SCREW_HEAD, 59 - f),
            ('arc', (R_SCREW_HEAD - f + f * math.cos(math.radians(45)), 59 - f + f * math.sin(math.radians(45)))),
            (R_SCREW_HEAD - f, 59), (0, 59)]
    s = revolve(prof)
    rc = 1.25 / math.cos(math.radians(30))
    hexpts = [(rc * math.cos(math.radians(60 * k)), rc * math.sin(math.radians(60 * k))) for k in range(6)]
    s = s.cut(polygon_prism(hexpts, 57.5, 59.5))
    return one_solid(s)


def motor_parts():
    """Return the list of Part_ (label, shape, placement, colour) in NAMES order."""
    parts = []
    parts.append(Part_('Axis', axis_shape(), color=COLORS['Axis']))
    parts.append(Part_('Rotor-front', rotor_front_shape(), color=COLORS['Rotor-front']))
    parts.append(Part_('Rotor-back', rotor_back_shape(), color=COLORS['Rotor-back']))
    mag = magnet_shape()
    for k in range(4):
        pl = FreeCAD.Placement(V(0, 0, 0), FreeCAD.Rotation(V(0, 0, 1), 90 * k))
        parts.append(Part_('Magnet-%d' % (k + 1), mag, pl, COLORS['Magnet']))
    brg = bearing_shape()
    parts.append(Part_('Bearing-front', split_shape(brg.translated(V(0, 0, 44)), 'y', 0.0),
                       color=COLORS['Bearing']))
    parts.append(Part_('Bearing-back', brg, FreeCAD.Placement(V(0, 0, 2.7), FreeCAD.Rotation()),
                       COLORS['Bearing']))
    parts.append(Part_('Seal', seal_shape(), color=COLORS['Seal']))
    parts.append(Part_('Stator', stator_shape(), color=COLORS['Stator']))
    parts.append(Part_('Body', body_shape(), color=COLORS['Body']))
    parts.append(Part_('Back-cover', back_cover_shape(), color=COLORS['Back-cover']))
    parts.append(Part_('Front-cover', front_cover_shape(), color=COLORS['Front-cover']))
    scr = screw_shape()
    for k, (x, y) in enumerate(SCREW_XY):
        parts.append(Part_('Screw-%d' % (k + 1), scr, FreeCAD.Placement(V(x, y, 0), FreeCAD.Rotation()),
                           COLORS['Screw']))
    assert [p.label for p in parts] == NAMES
    return parts


def motor_expected():
    """The paper's list (section 5): 14 PLF + 21 CLJ."""
    c = []
    for k in range(1, 5):
        c.append(contact('Rotor-back', 'Magnet-%d' % k, 'PLF'))
    c += [contact('Rotor-front', 'Rotor-back', 'PLF'), contact('Rotor-front', 'Bearing-front', 'PLF'),
          contact('Back-cover', 'Bearing-back', 'PLF'), contact('Body', 'Back-cover', 'PLF'),
          contact('Body', 'Stator', 'PLF'), contact('Body', 'Front-cover', 'PLF')]
    for k in range(1, 5):
        c.append(contact('Screw-%d' % k, 'Front-cover', 'PLF'))
    c += [contact('Axis', 'Rotor-front', 'CLJ'), contact('Axis', 'Rotor-back', 'CLJ'),
          contact('Axis', 'Bearing-front', 'CLJ'), contact('Axis', 'Bearing-back', 'CLJ'),
          contact('Axis', 'Seal', 'CLJ'), contact('Back-cover', 'Bearing-back', 'CLJ'),
          contact('Front-cover', 'Bearing-front', 'CLJ'), contact('Front-cover', 'Seal', 'CLJ'),
          contact('Stator', 'Body', 'CLJ')]
    for k in range(1, 5):
        c += [contact('Screw-%d' % k, 'Body', 'CLJ'), contact('Screw-%d' % k, 'Back-cover', 'CLJ'),
              contact('Screw-%d' % k, 'Front-cover', 'CLJ')]
    return c


MOTOR_NOTES = [
    "BL17-class brushless DC motor replica, body diameter 48 mm, length 70 mm incl. shaft.",
    "Not contacts by design: Axis has no planar contact (shaft ends and groove are free); "
    "Bearing-front front face has 0.3 mm axial clearance to the Front-cover pocket bottom; "
    "Bearing-back inner ring is free over the 6.2 mm relief hole (only the outer ring seats); "
    "magnets are flat-bottomed on the Rotor-back flats (no cylinder contact), 0.5 mm below "
    "Rotor-front and 0.7 mm radial air gap to the Stator; Seal has axial clearance both sides.",
    "Split faces (merging needed): Axis split by y=0 and z=26; Rotor-back by x=0; Rotor-front "
    "and Bearing-front by y=0; Body by x=0 and y=0; Back-cover by y=0; Front-cover by y=0 and z=52.",
]
