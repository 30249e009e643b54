"""Shared helpers for the sample generators (tools/make_samples.py).

Runs inside FreeCAD's Python (headless library use is fine):
    /usr/bin/python3 tools/make_samples.py
FreeCAD must be imported before Part (the other order crashes on 0.20).
"""
import json
import os
import sys
import time

FREECAD_LIB = '/usr/lib/freecad-python3/lib'
if FREECAD_LIB not in sys.path and os.path.isdir(FREECAD_LIB):
    sys.path.append(FREECAD_LIB)

import FreeCAD  # noqa: E402  (must come before Part)
import Part  # noqa: E402

V = FreeCAD.Vector
BIG = 1000.0

RULE = ("One contact per pair of maximal partitions (adjacent faces with the same "
        "surface parameters merged) of two different bodies with the same surface "
        "parameters, opposite material sides and common area > 0 (LAF/SPT: a common "
        "circle). Clearances, interferences, line contacts and coplanar faces with "
        "the same normal are not contacts.")
PARTIAL_RULE = ("partial = revolution contact whose common angular span about the "
                "contact axis is < 180 deg (CLJ/CJU/LAF: surface axis; SPF: axis through "
                "the centre and the middle of the common patch; SPT: the ball's contact "
                "circle in the meridian plane of the torus)")


# --------------------------------------------------------------------------- geometry
def revolve(profile, angle=360.0, center=V(0, 0, 0), axis=V(0, 0, 1)):
    """Revolve a closed (r, z) profile drawn in the XZ plane about the Z axis.

    `profile` is a list starting with an (r, z) point; an item ('arc', (rm, zm))
    between two points makes a circular arc through (rm, zm) (fillets)."""
    seq = []
    for it in profile:
        if it[0] == 'arc':
            seq.append(('arc', V(it[1][0], 0, it[1][1])))
        else:
            seq.append(('pt', V(it[0], 0, it[1])))
    assert seq[0][0] == 'pt'
    n = len(seq)
    edges = []
    j = 0
    while j < n:
        p = seq[j][1]
        kind, q = seq[(j + 1) % n]
        if kind == 'arc':
            r = seq[(j + 2) % n][1]
            edges.append(Part.Arc(p, q, r).toShape())
            j += 2
        else:
            edges.append(Part.LineSegment(p, q).toShape())
            j += 1
    face = Part.Face(Part.Wire(edges))
    solid = face.revolve(center, axis, angle)
    if solid.ShapeType != 'Solid':
        solid = solid.Solids[0]
    return solid


def polygon_prism(points_xy, z0, z1):
    pts = [V(x, y, z0) for x, y in points_xy]
    pts.append(pts[0])
    face = Part.Face(Part.makePolygon(pts))
    return face.extrude(V(0, 0, z1 - z0))


def cyl(r, z0, z1, x=0.0, y=0.0):
    return Part.makeCylinder(r, z1 - z0, V(x, y, z0), V(0, 0, 1))


def cyl_dir(r, p0, d, length):
    return Part.makeCylinder(r, length, p0, d)


def split_shape(shape, axis, value):
    """Split every face of `shape` crossed by the plane {axis = value} (axis in
    'x','y','z') the way CAD exports do: cut the solid in two and fuse the halves
    back without removeSplitter, so faces stay split along the plane."""
    bb = shape.BoundBox
    m = 10.0
    lo = V(bb.XMin - m, bb.YMin - m, bb.ZMin - m)
    size = [bb.XLength + 2 * m, bb.YLength + 2 * m, bb.ZLength + 2 * m]
    idx = 'xyz'.index(axis)
    lo_a = [lo.x, lo.y, lo.z]
    size_a = list(size)
    size_a[idx] = value - lo_a[idx]
    box_a = Part.makeBox(size_a[0], size_a[1], size_a[2], V(*lo_a))
    lo_b = list(lo_a)
    lo_b[idx] = value
    size_b = list(size)
    size_b[idx] = (lo_a[idx] + size[idx]) - value
    box_b = Part.makeBox(size_b[0], size_b[1], size_b[2], V(*lo_b))
    a = shape.common(box_a)
    b = shape.common(box_b)
    if a.Volume < 1e-9 or b.Volume < 1e-9:
        return shape
    fused = a.fuse(b)
    solids = fused.Solids
    assert len(solids) == 1, 'split produced %d solids' % len(solids)
    s = solids[0]
    assert s.isValid()
    return s


def one_solid(shape):
    s = shape.Solids
    assert len(s) == 1, 'expected one solid, got %d' % len(s)
    assert s[0].isValid()
    return s[0]


# --------------------------------------------------------------------------- output
class Part_:
    """A component: label, shape (local), placement, colour."""

    def __init__(self, label, shape, placement=None, color=(0.7, 0.7, 0.7)):
        self.label = label
        self.shape = shape
        self.placement = placement or FreeCAD.Placement()
        self.color = color


def export_assembly(parts, out_dir, name, write_fcstd=True, write_step=True, unit=None,
                    share_shapes=False, timings_out=None):
    """Write NAME.step (product name = label) and NAME.FCStd (one Part::Feature per
    part, Label = name, Placement = global placement). Returns list of paths.

    Import.export writes one PRODUCT per distinct shape: with share_shapes=False every
    object gets its own copy, so every part has a PRODUCT named after it; with
    share_shapes=True (big grids) parts of one kind share one product and the part
    names are the NEXT_ASSEMBLY_USAGE_OCCURRENCE names."""
    import Import
    os.makedirs(out_dir, exist_ok=True)
    timings = {}
    t0 = time.time()
    doc = FreeCAD.newDocument(name.replace('-', '_').replace('.', '_'))
    objs = []
    # our labels are unique already: skip FreeCAD's O(n) label uniqueness check per
    # object (10,000 parts: 25 s -> 4 s), then restore the user's preference
    grp = FreeCAD.ParamGet('User parameter:BaseApp/Preferences/Document')
    had = 'DuplicateLabels' in (dict((k, v) for _, k, v in (grp.GetContents() or [])))
    old_dup = grp.GetBool('DuplicateLabels', False)
    grp.SetBool('DuplicateLabels', True)
    try:
        for i, p in enumerate(parts):
            o = doc.addObject('Part::Feature', 'Part%d' % i)
            o.Shape = p.shape if share_shapes else p.shape.copy()
            o.Placement = p.placement
            o.Label = p.label
            objs.append(o)
    finally:
        if had:
            grp.SetBool('DuplicateLabels', old_dup)
        else:
            grp.RemBool('DuplicateLabels')
    assert [o.Label for o in objs] == [p.label for p in parts], 'labels got renamed'
    assert len(set(o.Label for o in objs)) == len(objs), 'duplicate part names'
    timings['objects'] = time.time() - t0
    doc.recompute()
    paths = []
    if write_step:
        step = os.path.join(out_dir, name + '.step')
        old = None
        if unit:
            old = Part.exportUnits()['write.step.unit']
            Part.exportUnits(unit)
        t = time.time()
        try:
            Import.export(objs, step)
        finally:
            if old is not None:
                Part.exportUnits(old)
        timings['import_export'] = time.time() - t
        _strip_step_timestamp(step)
        paths.append(step)
    if write_fcstd:
        fc = os.path.join(out_dir, name + '.FCStd')
        t = time.time()
        _set_colors(objs, parts)
        doc.saveAs(fc)
        _add_gui_document(fc, objs, parts)
        timings['fcstd'] = time.time() - t
        paths.append(fc)
    FreeCAD.closeDocument(doc.Name)
    if timings_out is not None:
        timings_out.update(timings)
    return paths


def _set_colors(objs, parts):
    # ShapeColor is a ViewObject property; headless documents have no ViewObject.
    # Store the colour as a plain property so the GUI renderer can apply it.
    for o, p in zip(objs, parts):
        if 'PartColor' not in o.PropertiesList:
            o.addProperty('App::PropertyColor', 'PartColor', 'Sample', 'display colour')
        o.PartColor = tuple(p.color)


def _add_gui_document(fcstd, objs, parts):
    """Headless FreeCAD saves no GuiDocument.xml, so the GUI would open every object
    hidden and grey. Add one with Visibility and ShapeColor per object."""
    import zipfile
    lines = ["<?xml version='1.0' encoding='utf-8'?>",
             '<Document SchemaVersion="1" HasExpansion="1">', '    <Expand />',
             '    <ViewProviderData Count="%d">' % len(objs)]
    for o, p in zip(objs, parts):
        r, g, b = [int(round(255 * c)) for c in p.color[:3]]
        packed = (r << 24) | (g << 16) | (b << 8)
        lines += ['        <ViewProvider name="%s" expanded="0">' % o.Name,
                  '            <Properties Count="2">',
                  '                <Property name="ShapeColor" type="App::PropertyColor" status="1">',
                  '                    <PropertyColor value="%d"/>' % packed,
                  '                </Property>',
                  '                <Property name="Visibility" type="App::PropertyBool" status="1">',
                  '                    <Bool value="true"/>',
                  '                </Property>',
                  '            </Properties>',
                  '        </ViewProvider>']
    lines += ['    </ViewProviderData>', '    <Camera settings=""/>', '</Document>', '']
    with zipfile.ZipFile(fcstd, 'a', zipfile.ZIP_DEFLATED) as z:
        z.writestr('GuiDocument.xml', '\n'.join(lines))


def _strip_step_timestamp(path):
    """Make the STEP header deterministic (no time stamp, no absolute path) so
    regenerating gives identical files."""
    with open(path, 'r', errors='replace') as f:
        txt = f.read()
    import re
    txt = re.sub(r"FILE_NAME\('[^']*','[^']*'", "FILE_NAME('%s','2000-01-01T00:00:00'"
                 % os.path.basename(path), txt, count=1)
    with open(path, 'w') as f:
        f.write(txt)


def write_expected(path, name, bodies, contacts, notes=None, extra=None):
    """Write NAME.expected.json (schema "contactwb-expected/1"):

    name, schema, units ("mm"), rule, partial_rule (texts), bodies (part names in
    STEP/FCStd order), contacts: [{a, b, type, count[, partial]}] (unordered pairs, one
    entry per pair and type; count = number of partition-pair contacts; partial = how
    many of them are partial), totals {type: n}, partial {type: n}, optional notes,
    formula (grids), step_unit (cases), step_names."""
    totals = {}
    partial = {}
    for c in contacts:
        totals[c['type']] = totals.get(c['type'], 0) + c['count']
        if c.get('partial'):
            partial[c['type']] = partial.get(c['type'], 0) + c['partial']
    data = {
        'name': name,
        'schema': 'contactwb-expected/1',
        'units': 'mm',
        'rule': RULE,
        'partial_rule': PARTIAL_RULE,
        'bodies': list(bodies),
        'contacts': contacts,
        'totals': dict(sorted(totals.items())),
        'partial': dict(sorted(partial.items())),
    }
    if notes:
        data['notes'] = notes
    if extra:
        data.update(extra)
    # one contact per line keeps big files small and diffs readable
    body = dict(data)
    body['contacts'] = '@CONTACTS@'
    txt = json.dumps(body, indent=1)
    rows = ',\n'.join('  ' + json.dumps(c) for c in contacts)
    txt = txt.replace('"@CONTACTS@"', '[\n' + rows + '\n ]' if contacts else '[]')
    with open(path, 'w') as f:
        f.write(txt + '\n')
    assert json.loads(txt) == data
    return data


def contact(a, b, typ, count=1, partial=0):
    d = {'a': a, 'b': b, 'type': typ, 'count': count}
    if partial:
        d['partial'] = partial
    return d
