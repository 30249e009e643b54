"""Where a contact is, for the table and the camera: the region its two sides
share (the Boolean common of their faces, kept per contact until its faces
move), its bounding box (what Zoom to frames) and, for a plane contact, its
extent in the plane (what the table shows instead of a span or radius of 0)."""
import FreeCAD

FUZZY = 1e-3  # mm: faces within this distance are one surface (the paint's value)
WHOLE_SIDE_TOLERANCE = 1e-6  # relative: a side whose faces' area is the contact's is the common region
CACHE_SIZE = 4000
_cache = {}  # key of the contact's faces (see _key) -> [Part.Face] of the common region


def _placed_faces(links):
    """[(Part.Face placed in the document, key)] of one side's XLinkSub links."""
    import Part
    faces = []
    for root, subnames in links:
        for subname in subnames:
            prefix, _, element = subname.rpartition(".")
            shape = Part.getShape(root, prefix + "." if prefix else "", transform=True)
            face = shape.getElement(element)
            box = face.BoundBox
            faces.append((face, (root.Name, subname, round(face.Area, 9),
                                 tuple(round(v, 9) for v in (box.XMin, box.YMin, box.ZMin,
                                                             box.XMax, box.YMax, box.ZMax)))))
    return faces


def common_faces(contact):
    """The faces the contact's two sides share ([] when there is none, as
    for a ball on a circle). When one side's faces are as large as the
    contact's (exact) area, the region is that side whole: no Boolean.
    Cached while the faces stay put."""
    sides = [_placed_faces(contact.FacesA), _placed_faces(contact.FacesB)]
    key = (contact.Document.Name, contact.Name, tuple(k for side in sides for _, k in side))
    if key not in _cache:
        area = contact.Area.Value
        whole = [side for side in sides
                 if side and area > 0 and abs(sum(f.Area for f, _ in side) - area) <= WHOLE_SIDE_TOLERANCE * area]
        if whole:
            pieces = [face for face, _ in whole[0]]
        else:
            pieces = []
            for face_a, _ in sides[0]:
                for face_b, _ in sides[1]:
                    if face_a.BoundBox.intersect(face_b.BoundBox):
                        pieces.extend(f for f in face_a.common(face_b, FUZZY).Faces if f.Area > 0)
        if len(_cache) >= CACHE_SIZE:
            _cache.pop(next(iter(_cache)))
        _cache[key] = pieces
    return _cache[key]


def side_box(contact):
    """Bounding box of the smaller side's faces (the common region lies in both)."""
    boxes = []
    for links in (contact.FacesA, contact.FacesB):
        box = FreeCAD.BoundBox()
        for face, _ in _placed_faces(links):
            box.add(face.BoundBox)
        if box.isValid():
            boxes.append(box)
    return min(boxes, key=lambda b: b.DiagonalLength) if boxes else FreeCAD.BoundBox()


def contact_box(contact):
    """Bounding box of the common region (of the smaller side's faces when
    there is none to be had: circle contacts, a failed Boolean)."""
    box = FreeCAD.BoundBox()
    try:
        for face in common_faces(contact):
            box.add(face.BoundBox)
    except Exception:  # drawing help only: fall back to the faces
        box = FreeCAD.BoundBox()
    return box if box.isValid() else side_box(contact)


def plane_extent(contact):
    """(length, width) in mm of the common region of a plane contact,
    measured in the plane (a frame whose z is the contact's normal), longest
    first; None when the contact has no common region."""
    faces = common_faces(contact)
    if not faces:
        return None
    normal = FreeCAD.Vector(contact.Direction)
    if normal.Length < 1e-12:
        normal = faces[0].normalAt(*faces[0].ParameterRange[::2])
    to_plane = FreeCAD.Placement(FreeCAD.Vector(), FreeCAD.Rotation(FreeCAD.Vector(0, 0, 1), normal)).inverse()
    box = FreeCAD.BoundBox()
    for face in faces:
        local = face.copy()
        local.transformShape(to_plane.toMatrix())
        box.add(local.BoundBox)
    return tuple(sorted((box.XLength, box.YLength), reverse=True))


def extent_text(contact):
    """The table's Extent cell: "40.00 mm × 5.00 mm" for a plane contact
    (the property editor's units), "" otherwise."""
    from contactwb.document import units
    if contact.ContactType != "PLF":
        return ""
    try:
        extent = plane_extent(contact)
    except Exception:  # a broken body: the other columns still hold
        return "?"
    return f"{units.length_text(extent[0])} \u00d7 {units.length_text(extent[1])}" if extent else ""
