"""Assembly families with known contacts: bolted plate grids, one small case per
contact type, and hard cases (split faces, B-spline faces, inch units, clearance,
interference, line contact, coplanar faces with the same normal)."""
import math
from collections import OrderedDict

from samples_common import FreeCAD, Part, V, cyl, revolve, split_shape, one_solid, Part_, contact

STEEL = (0.70, 0.72, 0.75)
BLUE = (0.30, 0.45, 0.70)
DARK = (0.20, 0.20, 0.22)
GOLD = (0.85, 0.75, 0.35)
RED = (0.80, 0.25, 0.20)


def _pl(x=0.0, y=0.0, z=0.0):
    return FreeCAD.Placement(V(x, y, z), FreeCAD.Rotation())


# =========================================================================== grids
GRID_PITCH_X = 30.0     # plate length 40 -> 10 mm lap joints
GRID_PITCH_Y = 30.0     # plate width 20 -> 10 mm gap between rows
PLATE_T = 5.0
BOLT_R = 3.0


def grid_row_length(n):
    """Parts per row: L = 2 * ceil(sqrt(n / 2)) (a square-ish grid of plates)."""
    return 2 * int(math.ceil(math.sqrt(n / 2.0)))


def grid_formula(n):
    L = grid_row_length(n)
    rows = int(math.ceil(n / float(L)))
    return {'parts_per_row': L, 'rows': rows, 'PLF': n - rows, 'CLJ': n - rows}


def _grid_plate():
    s = Part.makeBox(40, 20, PLATE_T)
    for x in (5.0, 35.0):
        s = s.cut(cyl(BOLT_R, -1, PLATE_T + 1, x, 10.0))
    return one_solid(s)


def _grid_bolt():
    # shank r 3 (same radius as the plate holes) z 0..13 with a tip chamfer, head r 5 x 4
    prof = [(0, 0), (2.5, 0), (3.0, 0.5), (3.0, 13.0), (5.0, 13.0), (5.0, 16.5), (4.5, 17.0), (0, 17.0)]
    return revolve(prof)


def bolted_grid(n):
    """Bolted plate grid of exactly n parts (n >= 1).

    Rows of lap-jointed plates (40 x 20 x 5, holes r 3 at both ends) alternate between
    two levels (z 0..5 and 5..10); consecutive plates overlap by 10 mm and are joined by
    one bolt (shank r 3 = hole radius, head on the upper plate). A row is the part
    sequence Plate, Bolt, Plate, Bolt, ... of at most L = 2*ceil(sqrt(n/2)) parts; a row
    ending with a bolt has an 'end bolt' in the far hole of its last plate. Rows are
    30 mm apart (no contact between rows).

    Contacts of a row of k parts: k-1 PLF (plate/plate laps + bolt heads) and k-1 CLJ
    (bolt shanks in holes). With R = ceil(n / L) rows:
        PLF = n - R,  CLJ = n - R,  no partial contacts.

    Returns (parts, contacts, formula)."""
    assert n >= 1
    plate, bolt = _grid_plate(), _grid_bolt()
    f = grid_formula(n)
    L = f['parts_per_row']
    parts, contacts = [], []
    left, row = n, 0
    while left > 0:
        k = min(L, left)
        left -= k
        y = row * GRID_PITCH_Y
        plates = []   # (name, level)
        for i in range(k):
            j = i // 2
            if i % 2 == 0:       # plate j
                lvl = j % 2
                name = 'Plate-%d-%d' % (row, j)
                parts.append(Part_(name, plate, _pl(j * GRID_PITCH_X, y, lvl * PLATE_T), STEEL if lvl else BLUE))
                if plates:
                    contacts.append(contact(plates[-1][0], name, 'PLF'))
                plates.append((name, lvl))
            else:                # bolt after plate j
                name = 'Bolt-%d-%d' % (row, j)
                x = j * GRID_PITCH_X + 35.0
                joint = i + 1 < k
                if joint:
                    z = 2 * PLATE_T - 13.0
                    parts.append(Part_(name, bolt, _pl(x, y + 10.0, z), DARK))
                    nxt = 'Plate-%d-%d' % (row, j + 1)
                    upper = plates[-1][0] if plates[-1][1] == 1 else nxt
                    contacts += [contact(name, upper, 'PLF'), contact(name, plates[-1][0], 'CLJ'),
                                 contact(name, nxt, 'CLJ')]
                else:
                    top = PLATE_T * (plates[-1][1] + 1)
                    parts.append(Part_(name, bolt, _pl(x, y + 10.0, top - 13.0), DARK))
                    contacts += [contact(name, plates[-1][0], 'PLF'), contact(name, plates[-1][0], 'CLJ')]
        row += 1
    assert len(parts) == n and row == f['rows']
    tot = {}
    for c in contacts:
        tot[c['type']] = tot.get(c['type'], 0) + 1
    assert tot.get('PLF', 0) == f['PLF'] and tot.get('CLJ', 0) == f['CLJ'], (tot, f)
    formula = dict(f)
    formula['text'] = ('L = 2*ceil(sqrt(N/2)) parts per row, R = ceil(N/L) rows; '
                       'PLF = N - R, CLJ = N - R, partial = 0')
    return parts, contacts, formula


# =========================================================================== cases
def case_ball_joint():
    """SPF: ball stud (sphere r 8 + neck r 3) in a spherical cup of the same radius."""
    sock = Part.makeBox(30, 30, 20, V(-15, -15, 0))
    sock = sock.cut(Part.makeSphere(8, V(0, 0, 10))).cut(cyl(5, 10, 21))
    ball = Part.makeSphere(8, V(0, 0, 10)).fuse(cyl(3, 10, 35))
    parts = [Part_('Socket', one_solid(sock), color=BLUE), Part_('Ball-stud', one_solid(ball), color=STEEL)]
    return parts, [contact('Socket', 'Ball-stud', 'SPF')], ['ball r 8 in a closed cup, neck r 3 in a r 5 opening'], None


def case_taper_pin():
    """CJU: taper pin (half angle 5 deg) in a taper hole with the same apex."""
    t = math.tan(math.radians(5))
    r0 = 5.0
    block = Part.makeBox(30, 30, 20, V(-15, -15, 0)).cut(Part.makeCone(r0, r0 + 20 * t, 20, V(0, 0, 0)))
    pin = Part.makeCone(r0 - 5 * t, r0 + 25 * t, 30, V(0, 0, -5))
    parts = [Part_('Block', one_solid(block), color=BLUE), Part_('Taper-pin', pin, color=STEEL)]
    return parts, [contact('Block', 'Taper-pin', 'CJU')], ['pin longer than the hole on both sides'], None


def case_ball_in_bore():
    """LAF: ball r 5 inside a bore r 5 (contact along the ball's equator)."""
    block = Part.makeBox(30, 30, 30, V(-15, -15, 0)).cut(cyl(5, -1, 31))
    ball = Part.makeSphere(5, V(0, 0, 15))
    parts = [Part_('Block', one_solid(block), color=BLUE), Part_('Ball', ball, color=STEEL)]
    return parts, [contact('Block', 'Ball', 'LAF')], ['contact is a circle: Boolean common area is 0'], None


def case_cradle_120():
    """Partial CLJ: shaft r 10 lying in a 120-degree cylindrical cradle."""
    block = Part.makeBox(40, 30, 15, V(-20, -15, -20))   # top at z = -5 = -r cos 60
    block = block.cut(Part.makeCylinder(10, 42, V(-21, 0, 0), V(1, 0, 0)))
    shaft = Part.makeCylinder(10, 60, V(-30, 0, 0), V(1, 0, 0))
    parts = [Part_('Cradle', one_solid(block), color=BLUE), Part_('Shaft', shaft, color=STEEL)]
    return (parts, [contact('Cradle', 'Shaft', 'CLJ', 1, partial=1)],
            ['common angular span 120 deg -> partial; the cradle rims touch the shaft only along lines'], None)


def case_ball_bearing():
    """SPT: 8 balls r 4 in torus raceways (minor radius 4, pitch radius 20) of an inner
    and an outer ring; no ball-ball contact. Each groove holds its ball over 120 deg of
    the ball's meridian circle -> every SPT contact is partial."""
    rp, rb, n = 20.0, 4.0, 8
    tor = Part.makeTorus(rp, rb)
    inner = revolve([(10, -5), (18, -5), (18, 5), (10, 5)]).cut(tor)
    outer = revolve([(22, -5), (30, -5), (30, 5), (22, 5)]).cut(tor)
    parts = [Part_('Inner-ring', one_solid(inner), color=GOLD), Part_('Outer-ring', one_solid(outer), color=GOLD)]
    contacts = []
    for k in range(n):
        a = 2 * math.pi * k / n
        name = 'Ball-%d' % (k + 1)
        parts.append(Part_(name, Part.makeSphere(rb, V(rp * math.cos(a), rp * math.sin(a), 0)), color=STEEL))
        contacts += [contact(name, 'Inner-ring', 'SPT', 1, partial=1),
                     contact(name, 'Outer-ring', 'SPT', 1, partial=1)]
    return parts, contacts, ['groove span 120 deg per ring (ring radii 18 and 22, pitch 20, ball 4)'], None


def case_oring_groove():
    """TRF: O-ring (torus R 10, r 1.5) in a toroidal groove of a shaft r 10."""
    tor = Part.makeTorus(10, 1.5, V(0, 0, 20))
    shaft = cyl(10, 0, 40).cut(tor)
    parts = [Part_('Shaft', one_solid(shaft), color=STEEL), Part_('O-ring', tor, color=DARK)]
    return parts, [contact('Shaft', 'O-ring', 'TRF')], ['the O-ring fills the groove half of its tube'], None


def _pin_block_shapes():
    plate = Part.makeBox(60, 40, 8, V(-30, -20, -8)).cut(cyl(5, -9, 1))
    block = Part.makeBox(30, 30, 20, V(-15, -15, 0)).cut(cyl(5, -1, 21))
    pin = revolve([(0, -12), (4.5, -12), (5, -11.5), (5, 20), (8, 20), (8, 24.5), (7.5, 25), (0, 25)])
    return one_solid(plate), one_solid(block), pin


PIN_BLOCK_CONTACTS = [('Plate', 'Block', 'PLF'), ('Pin', 'Block', 'PLF'), ('Pin', 'Block', 'CLJ'),
                      ('Pin', 'Plate', 'CLJ')]


def _pin_block(shapes, notes, unit=None):
    plate, block, pin = shapes
    parts = [Part_('Plate', plate, color=BLUE), Part_('Block', block, color=STEEL), Part_('Pin', pin, color=DARK)]
    return parts, [contact(a, b, t) for a, b, t in PIN_BLOCK_CONTACTS], notes, unit


def case_pin_block():
    """Reference for the hard cases: block on a plate, headed pin through both."""
    return _pin_block(_pin_block_shapes(), ['reference of split_faces, nurbs and inch'])


def case_split_faces():
    """pin_block with faces split into several (same answer as unsplit)."""
    plate, block, pin = _pin_block_shapes()
    plate = split_shape(split_shape(plate, 'x', 0.0), 'y', 0.0)
    block = split_shape(split_shape(split_shape(block, 'x', 0.0), 'y', 0.0), 'z', 10.0)
    pin = split_shape(split_shape(split_shape(pin, 'x', 0.0), 'z', 5.0), 'z', -4.0)
    return _pin_block((plate, block, pin), ['every face of pin_block cut by x=0 / y=0 / z planes'])


def case_nurbs():
    """pin_block with every face converted to B-spline (Shape.toNurbs())."""
    shapes = [s.toNurbs() for s in _pin_block_shapes()]
    shapes = [one_solid(s) for s in shapes]
    for s in shapes:
        assert all(f.Surface.__class__.__name__ == 'BSplineSurface' for f in s.Faces)
    return _pin_block(shapes, ['all faces BSplineSurface: the reader must recognise planes and cylinders'])


def case_inch():
    """pin_block written with STEP length unit INCH (geometry identical in mm)."""
    return _pin_block(_pin_block_shapes(), [
        'STEP written with CONVERSION_BASED_UNIT INCH: FreeCAD 0.20 reads the preference '
        'User parameter:BaseApp/Preferences/Mod/Part/STEP, Unit (int: 0 mm, 1 m, 2 inch) only when '
        'the Part module initialises; at run time the generator calls Part.exportUnits("INCH") and '
        'restores the previous unit afterwards'], unit='INCH')


def case_clearance():
    """Clearance fit: shaft r 4.95 in a hole r 5, cover 0.05 above the block: no contact."""
    block = Part.makeBox(30, 30, 20, V(-15, -15, 0)).cut(cyl(5, -1, 21))
    shaft = cyl(4.95, -5, 15)
    cover = Part.makeBox(30, 30, 5, V(-15, -15, 20.05)).cut(cyl(6, 19, 26))
    parts = [Part_('Block', one_solid(block), color=BLUE), Part_('Shaft', shaft, color=STEEL),
             Part_('Cover', one_solid(cover), color=DARK)]
    return parts, [], ['radial gap 0.05 and planar gap 0.05: no contact'], None


def case_interference():
    """Interference: shaft r 5.05 in a hole r 5, cover overlapping 0.05: no contact."""
    block = Part.makeBox(30, 30, 20, V(-15, -15, 0)).cut(cyl(5, -1, 21))
    shaft = cyl(5.05, -5, 15)
    cover = Part.makeBox(30, 30, 5, V(-15, -15, 19.95)).cut(cyl(6, 19, 26))
    parts = [Part_('Block', one_solid(block), color=BLUE), Part_('Shaft', shaft, color=STEEL),
             Part_('Cover', one_solid(cover), color=DARK)]
    return parts, [], ['overlapping volumes (0.05) are interferences, not contacts'], None


def case_line_contact():
    """Cylinder lying on a plane (line contact) and a ball on it (point contact)."""
    plate = Part.makeBox(60, 60, 5, V(-30, -30, -5))
    roller = Part.makeCylinder(5, 40, V(-20, -10, 5), V(1, 0, 0))
    ball = Part.makeSphere(5, V(0, 15, 5))
    parts = [Part_('Plate', plate, color=BLUE), Part_('Roller', roller, color=STEEL),
             Part_('Ball', ball, color=DARK)]
    return parts, [], ['line and point contacts have no common area: no contact'], None


def case_coplanar_same_normal():
    """Two blocks side by side (10 mm apart) on a plate, top faces coplanar: only the
    two block/plate bottoms are PLF."""
    plate = Part.makeBox(80, 40, 5, V(-40, -20, -5))
    b1 = Part.makeBox(30, 30, 10, V(-35, -15, 0))
    b2 = Part.makeBox(30, 30, 10, V(5, -15, 0))
    parts = [Part_('Plate', plate, color=BLUE), Part_('Block-1', b1, color=STEEL),
             Part_('Block-2', b2, color=STEEL)]
    return (parts, [contact('Block-1', 'Plate', 'PLF'), contact('Block-2', 'Plate', 'PLF')],
            ['top faces of Block-1 and Block-2 are coplanar with the same normal: not a contact'], None)


CASES = OrderedDict([
    ('ball_joint', case_ball_joint),
    ('taper_pin', case_taper_pin),
    ('ball_in_bore', case_ball_in_bore),
    ('cradle_120', case_cradle_120),
    ('ball_bearing', case_ball_bearing),
    ('oring_groove', case_oring_groove),
    ('pin_block', case_pin_block),
    ('split_faces', case_split_faces),
    ('nurbs', case_nurbs),
    ('inch', case_inch),
    ('clearance', case_clearance),
    ('interference', case_interference),
    ('line_contact', case_line_contact),
    ('coplanar_same_normal', case_coplanar_same_normal),
])
