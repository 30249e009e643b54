"""Face geometry for the drawings: a contact's placed faces tessellated as their
bodies are (or the area the two sides share), pushed out of their body so they
show over it, and the circle of a ball contact."""
import itertools
import math

import FreeCAD
import numpy

CIRCLE_SEGMENTS = 96
# The common areas already computed, by contact and by where its faces are
# (see _common_key): a rebuild after a recompute or a move recomputes only
# the contacts whose bodies moved or changed.
COMMON_CACHE_SIZE = 4000
_common_cache = {}
# Whole faces tessellated and pushed out, by object path, while the object's
# placed shape stays the same OCCT shape at the same place (held: its memory
# is never another's): a rebuild after a recompute tessellates the faces of
# the bodies that moved or changed only. {(doc, root, prefix): (shape,
# placement, deflection, {element: mesh})}
_face_cache = {}
# The core's region meshes pushed out of their sides, by the region's points
# array (the regions cache keeps a region's arrays while its bodies stay put):
# {id(points): (points, deflection, result)}
_region_cache = {}


def vectors_array(vectors):
    """(n, 3) float array of FreeCAD vectors (or any (x, y, z) sequences):
    read as one flat stream, twice as fast as a tuple per vector."""
    return numpy.fromiter(itertools.chain.from_iterable(vectors), dtype=float,
                          count=3 * len(vectors)).reshape(-1, 3)


def triangles_array(triangles):
    """(m, 3) int64 array of (i, j, k) index triples."""
    return numpy.fromiter(itertools.chain.from_iterable(triangles), dtype=numpy.int64,
                          count=3 * len(triangles)).reshape(-1, 3)


def _bounded(cache, size=COMMON_CACHE_SIZE):
    """Makes room for one entry (the oldest goes)."""
    if len(cache) >= size:
        cache.pop(next(iter(cache)))


def circle_points(centre, axis, radius, segments=CIRCLE_SEGMENTS):
    axis = FreeCAD.Vector(axis)
    if axis.Length < 1e-12:
        return []
    axis.normalize()
    helper = FreeCAD.Vector(1, 0, 0) if abs(axis.x) < 0.9 else FreeCAD.Vector(0, 1, 0)
    u = axis.cross(helper).normalize()
    v = axis.cross(u)
    points = []
    for k in range(segments + 1):
        angle = 2 * math.pi * k / segments
        p = centre + u * (radius * math.cos(angle)) + v * (radius * math.sin(angle))
        points.append((p.x, p.y, p.z))
    return points


class FaceSource:
    """Placed faces of a contact's XLinkSub links, each tessellated once.

    A face is taken from its object's placed shape (one Part.getShape per
    object path, sharing the body's geometry) and tessellated asking for the
    deflection the body's view provider uses, so that OCCT mostly reuses the
    body's own triangulation. Where the triangulations still differ (a body
    meshed later, or by other rules), the body's triangles may lie up to one
    deflection outside ours: the vertices are pushed out of the body's
    material by that much (along the outward normals of OCCT's triangles),
    and the polygon offset takes care of the rest."""

    def __init__(self):
        self._shapes = {}
        self._meshes = {}
        self.failures = []

    def _object_shape(self, root, prefix):
        key = (root.Document.Name, root.Name, prefix)
        if key not in self._shapes:
            import Part
            shape = Part.getShape(root, prefix, transform=True)
            leaf = root.getSubObject(prefix, retType=1) if prefix else root
            leaf = leaf.getLinkedObject(True) if leaf is not None else None
            deviation = getattr(getattr(leaf, "ViewObject", None), "Deviation", 0.5)
            box = shape.BoundBox if not shape.isNull() else None
            # ViewProviderPartExt's deflection: box size sum / 300 * Deviation (%).
            size = (box.XLength + box.YLength + box.ZLength) if box and box.isValid() else 1.0
            self._shapes[key] = (shape, max(size / 300.0 * deviation, 1e-4))
        return self._shapes[key]

    def mesh(self, root, subname):
        """(points (n, 3) array, triangles (m, 3) int array, BoundBox) of the
        face, or None when it cannot be had."""
        key = (root.Document.Name, root.Name, subname)
        if key in self._meshes:
            return self._meshes[key]
        mesh = None
        try:
            prefix, _, element = subname.rpartition(".")
            prefix = prefix + "." if prefix else ""
            shape, deflection = self._object_shape(root, prefix)
            object_key = (root.Document.Name, root.Name, prefix)
            placement = tuple(shape.Placement.toMatrix().A)
            held = _face_cache.get(object_key)
            if held is None or held[1] != placement or held[2] != deflection or not held[0].isPartner(shape):
                _bounded(_face_cache)
                held = _face_cache[object_key] = (shape, placement, deflection, {})
            meshes = held[3]
            if element in meshes:
                mesh = meshes[element]
            else:
                face = shape.getElement(element)
                points, triangles = face.tessellate(deflection)
                if triangles:
                    points, triangles = vectors_array(points), triangles_array(triangles)
                    mesh = (pushed_out(points, triangles, deflection), triangles, face.BoundBox)
                meshes[element] = mesh
        except Exception as error:  # a deleted or broken body: draw the rest
            self.failures.append(f"{root.Label}.{subname}: {error}")
        self._meshes[key] = mesh
        return mesh

    def _face(self, root, subname):
        prefix, _, element = subname.rpartition(".")
        prefix = prefix + "." if prefix else ""
        shape, deflection = self._object_shape(root, prefix)
        return shape.getElement(element), deflection

    def _common_key(self, contact, fuzzy):
        """Where the contact's faces are: each face's object path, placement
        (of the placed shape), area and box; the same key, the same common
        area (a body moved or reshaped changes its faces' keys)."""
        key = [contact.Document.Name, contact.Name, round(fuzzy, 12)]
        for links in (contact.FacesA, contact.FacesB):
            for root, subnames in links:
                for subname in subnames:
                    prefix, _, element = subname.rpartition(".")
                    prefix = prefix + "." if prefix else ""
                    shape, deflection = self._object_shape(root, prefix)
                    face = shape.getElement(element)
                    box = face.BoundBox
                    key.append((root.Name, subname, round(deflection, 9),
                                tuple(round(v, 9) for v in shape.Placement.toMatrix().A),
                                round(face.Area, 9),
                                tuple(round(v, 9) for v in (box.XMin, box.YMin, box.ZMin,
                                                            box.XMax, box.YMax, box.ZMax))))
        return tuple(key)

    def core_meshes(self, group, contact):
        """common_meshes_now()'s answer from the core's regions, cached with
        the analysis (contactwb.objects.regions): computed by the core at
        the analysis' recompute (or now, once, after a file was opened).
        None for a snapshot analysis (UpdateOnRecompute off: its bodies
        may have moved since) or when the core has none."""
        from contactwb.objects import regions
        from contactwb.objects.contact_objects import compute_regions, key_of_contact
        if group is None or not getattr(group, "UpdateOnRecompute", False):
            return None
        try:
            if not regions.has_regions(group):
                compute_regions(group)
            found = regions.meshes_of(group, key_of_contact(contact))
        except Exception as error:  # drawing only: the Booleans below instead
            self.failures.append(f"{contact.Label}: core region: {error}")
            return None
        if not found:
            return None
        meshes = ([], [])
        for k, (points, triangles, deflection) in enumerate(found):
            if not len(triangles):
                continue
            held = _region_cache.get(id(points))
            if held is None or held[0] is not points or held[1] != deflection:
                low, high = points.min(axis=0), points.max(axis=0)
                box = FreeCAD.BoundBox(*low, *high)
                triangles = triangles.astype(numpy.int64)
                # oriented out of side A: pushed out of A along it, out of B against it
                pushed = [(pushed_out(points, triangles, sign * deflection), triangles, box) for sign in (1.0, -1.0)]
                _bounded(_region_cache)
                held = _region_cache[id(points)] = (points, deflection, pushed)
            for side in (0, 1):
                meshes[side].append(((contact.Name, side, k), held[2][side]))
        return meshes if meshes[0] else None

    def common_meshes(self, contact, fuzzy):
        """common_meshes_now(), from the cache when the contact's faces have
        not moved or changed since it was last computed."""
        try:
            key = self._common_key(contact, fuzzy)
        except Exception:  # a deleted or broken body: no caching
            return self.common_meshes_now(contact, fuzzy)
        if key not in _common_cache:
            if len(_common_cache) >= COMMON_CACHE_SIZE:
                _common_cache.pop(next(iter(_common_cache)))
            _common_cache[key] = self.common_meshes_now(contact, fuzzy)
        return _common_cache[key]

    def common_meshes_now(self, contact, fuzzy):
        """[(key, mesh) of side A, (key, mesh) of side B]: the area the two
        sides' faces share (Boolean common with a fuzzy value, for drawing
        only), pushed out of each side's body; None when there is none to
        be had (then the whole faces are drawn)."""
        try:
            sides = []
            for links in (contact.FacesA, contact.FacesB):
                sides.append([self._face(root, subname) for root, subnames in links for subname in subnames])
            pieces = []
            for face_a, deflection in sides[0]:
                for face_b, _ in sides[1]:
                    if not face_a.BoundBox.intersect(face_b.BoundBox):
                        continue
                    common = face_a.common(face_b, fuzzy)
                    pieces.extend((piece, deflection) for piece in common.Faces if piece.Area > 0)
            if not pieces:
                return None
            meshes = ([], [])
            for k, (piece, deflection) in enumerate(pieces):
                points, triangles = piece.tessellate(deflection)
                if not triangles:
                    continue
                points, triangles = vectors_array(points), triangles_array(triangles)
                # the common face keeps side A's orientation: out of A is into B
                for side, sign in ((0, 1.0), (1, -1.0)):
                    meshes[side].append(((contact.Name, side, k),
                                         (pushed_out(points, triangles, sign * deflection), triangles,
                                          piece.BoundBox)))
            return meshes if meshes[0] else None
        except Exception as error:  # drawing only: fall back to the whole faces
            self.failures.append(f"{contact.Label}: common area: {error}")
            return None


def pushed_out(points, triangles, distance):
    """Points moved by `distance` along their vertex normals (the area-weighted
    mean of the normals of their triangles, which OCCT winds outwards)."""
    corners = points[triangles]
    normals = numpy.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    vertex_normals = numpy.zeros_like(points)
    for k in range(3):
        for axis in range(3):
            vertex_normals[:, axis] += numpy.bincount(triangles[:, k], weights=normals[:, axis],
                                                      minlength=len(points))
    lengths = numpy.linalg.norm(vertex_normals, axis=1)
    lengths[lengths == 0] = 1.0
    return points + vertex_normals * (distance / lengths)[:, None]
