"""View providers of the contact objects.

The ContactAnalysis group draws its contacts over the bodies: both sides'
faces, tessellated as the bodies are, pushed out of their body by the
tessellation's deflection and pulled towards the viewer by a polygon offset
so they show on the coincident body faces, coloured by contact type
(TYPE_COLOURS); partial contacts are lighter and striped, and ball contacts
(LAF, SPT) get their contact circle (their faces are drawn see-through). The drawing follows the group's
Visibility, and each side of a contact its body's. Each contact has its own
switch: hiding a Contact child hides its faces, and a contact is drawn in the
selection colour while it (or all of its faces) is selected. Double-clicking a
contact selects its faces on the bodies. The drawing is rebuilt from the
document when the view provider attaches (also on re-opening a file), when
contacts are added or deleted and when a body moves.

Saved files name these classes: ViewProviderContactAnalysis and
ViewProviderContact are permanent names."""
import math
import os
import weakref

import FreeCAD
import FreeCADGui
import numpy
from pivy import coin

import contactwb
from contactwb.objects.contact_objects import is_contact

# The legend: one colour per contact type (also the tree icons' colour). None
# is near FreeCAD's selection green or preselection yellow (legend_colours
# also keeps user-chosen colours away from them).
TYPE_COLOURS = {
    "PLF": "#ff8c1a",  # orange
    "CLJ": "#1f5fff",  # blue
    "CJU": "#9b30ff",  # purple
    "SPF": "#d7263d",  # red
    "LAF": "#00d2e6",  # cyan
    "SPT": "#ff2fd2",  # magenta
    "TRF": "#8b5a2b",  # brown
}
PREFERENCES = "User parameter:BaseApp/Preferences/Mod/Contacts"
MIN_COLOUR_DISTANCE = 0.25  # per channel (0..1): what still reads as another colour
UNKNOWN_COLOUR = "#808080"
CIRCLE_TYPES = ("LAF", "SPT")  # contact along a circle: area 0
PARTIAL_LIGHTEN = 0.45         # partial contacts: this far towards white
CIRCLE_FACE_TRANSPARENCY = 0.6  # the ball and its seat, behind the circle
CIRCLE_SEGMENTS = 96
CIRCLE_WIDTH = 4  # pixels


def rgb(colour):
    """(r, g, b) in 0..1 of a "#rrggbb" colour."""
    return tuple(int(colour[i:i + 2], 16) / 255 for i in (1, 3, 5))


def hex_colour(colour):
    return "#" + "".join(f"{round(max(0.0, min(1.0, c)) * 255):02x}" for c in colour)


def _distance(a, b):
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
    params = FreeCAD.ParamGet(PREFERENCES)
    avoid = highlight_colours()
    colours = {}
    for kind, default in TYPE_COLOURS.items():
        colour = rgb(params.GetString(f"Colour{kind}", default) or default)
        for _ in range(4):
            near = [c for c in avoid if _distance(colour, c) < MIN_COLOUR_DISTANCE]
            if not near:
                break
            # push every channel away from the colour it resembles
            colour = tuple(x - 0.4 if x >= c else x + 0.4 for x, c in zip(colour, near[0]))
            colour = tuple(max(0.0, min(1.0, x)) for x in colour)
        colours[kind] = hex_colour(colour)
    return colours


def paint_style():
    """"Common area" (default) or "Whole faces" (preferences)."""
    return FreeCAD.ParamGet(PREFERENCES).GetString("PaintStyle", "Common area") or "Common area"


def type_colour(kind, partial=False, colours=None):
    r, g, b = rgb((colours or legend_colours()).get(kind, UNKNOWN_COLOUR))
    if partial:
        r, g, b = (c + (1 - c) * PARTIAL_LIGHTEN for c in (r, g, b))
    return r, g, b


def contact_icon_path(kind):
    path = contactwb.icon_path(f"Contacts_{kind}")
    return path if os.path.isfile(path) else contactwb.icon_path("Contacts_FindContacts")


def selection_colour():
    """FreeCAD's selection colour (preferences), as (r, g, b) in 0..1."""
    packed = FreeCAD.ParamGet("User parameter:BaseApp/Preferences/View").GetUnsigned(
        "SelectionColor", 0x1CAD1C00)
    return tuple(((packed >> shift) & 0xFF) / 255 for shift in (24, 16, 8))


def _material(colour, transparency=0.0):
    # Mostly emissive: the type colour reads the same on every side of a
    # cylinder, while the diffuse part keeps a hint of the shape.
    material = coin.SoMaterial()
    material.diffuseColor.setValue(*(0.5 * c for c in colour))
    material.emissiveColor.setValue(*(0.6 * c for c in colour))
    material.ambientColor.setValue(0, 0, 0)
    material.specularColor.setValue(0, 0, 0)
    material.transparency.setValue(transparency)
    return material


def _line_material(colour):
    """Opaque flat colour (lines drawn with the BASE_COLOR light model)."""
    material = coin.SoMaterial()
    material.diffuseColor.setValue(*colour)
    material.transparency.setValue(0.0)
    return material


def _polygon_offset(factor, units):
    offset = coin.SoPolygonOffset()
    offset.factor.setValue(factor)
    offset.units.setValue(units)
    return offset


def _stripes():
    """Nodes striping what follows: a two-texel texture repeated along a
    fixed world direction (independent of the tessellation); the last one
    sets the period (_set_stripe_period)."""
    complexity = coin.SoComplexity()
    complexity.textureQuality.setValue(0.1)  # nearest texel: sharp stripes
    texture = coin.SoTexture2()
    texture.image.setValue(coin.SbVec2s(2, 1), 1, bytes([255, 150]))
    texture.model.setValue(coin.SoTexture2.MODULATE)
    texture.wrapS.setValue(coin.SoTexture2.REPEAT)
    texture.wrapT.setValue(coin.SoTexture2.REPEAT)
    coordinates = coin.SoTextureCoordinatePlane()
    coordinates.directionT.setValue(0, 0, 0)
    _set_stripe_period(coordinates, 1.0)
    return [complexity, texture, coordinates]


def _set_stripe_period(coordinates, period):
    """One light and one dark stripe every `period` mm along (1, 1, 1)."""
    step = 1.0 / (period * math.sqrt(3.0))
    coordinates.directionS.setValue(step, step, step)


TYPE_NAMES = {
    "PLF": "planar fit", "CLJ": "cylindrical joint", "CJU": "cone", "SPF": "spherical fit",
    "LAF": "ball in bore", "SPT": "ball in groove", "TRF": "torus fit",
}


def _left_out_of_fit_all():
    """An empty group that FreeCAD's View > Fit all leaves out: its own
    SoSkipBoundingGroup, which View3DInventorViewer::viewAll switches to
    EXCLUDE_BBOX while it fits. Held by Python as pivy holds the nodes it
    makes (one reference, dropped with the Python object)."""
    kind = coin.SoType.fromName(coin.SbName("SoSkipBoundingGroup"))
    if kind.isBad():  # pivy without FreeCAD's GUI loaded: no view to fit
        return coin.SoGroup()
    group = kind.createInstance()
    group.ref()
    group.thisown = True
    return group


def legend_node(entries, name="ContactsLegend"):
    """A legend drawn over the view's top-left corner: one line of text per
    (text, (r, g, b)) entry, in its colour. An annotation (named `name`) with
    its own camera, so it stays put whatever the view's camera does;
    unpickable. Its text would count at the legend camera's coordinates (near
    the origin) in the scene's bounding box and pull Fit all off the model:
    it is wrapped in a group Fit all leaves out, which is returned."""
    legend = coin.SoAnnotation()
    legend.setName(name)
    pick = coin.SoPickStyle()
    pick.style.setValue(coin.SoPickStyle.UNPICKABLE)
    camera = coin.SoOrthographicCamera()
    camera.viewportMapping.setValue(coin.SoCamera.LEAVE_ALONE)  # x, y in -1..1 across the view
    camera.height.setValue(2.0)
    camera.position.setValue(0, 0, 5)
    light = coin.SoLightModel()
    light.model.setValue(coin.SoLightModel.BASE_COLOR)
    font = coin.SoFont()
    font.size.setValue(16)
    font.name.setValue("sans:bold")
    for node in (pick, camera, light, font):
        legend.addChild(node)
    start = coin.SoTranslation()
    start.translation.setValue(-0.96, 0.9, 0)
    legend.addChild(start)
    for text, colour in entries:
        base = coin.SoBaseColor()
        base.rgb.setValue(*colour)
        label = coin.SoText2()
        label.string.setValue(text)
        step = coin.SoTranslation()
        step.translation.setValue(0, -0.055, 0)
        for node in (base, label, step):
            legend.addChild(node)
    left_out = _left_out_of_fit_all()
    left_out.addChild(legend)
    return left_out


def _circle_points(centre, axis, radius, segments=CIRCLE_SEGMENTS):
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
            face = shape.getElement(element)
            points, triangles = face.tessellate(deflection)
            if triangles:
                points = numpy.array([(p.x, p.y, p.z) for p in points], dtype=float)
                triangles = numpy.array(triangles, dtype=numpy.int64).reshape(-1, 3)
                mesh = (_pushed_out(points, triangles, deflection), triangles, face.BoundBox)
        except Exception as error:  # a deleted or broken body: draw the rest
            self.failures.append(f"{root.Label}.{subname}: {error}")
        self._meshes[key] = mesh
        return mesh

    def _face(self, root, subname):
        prefix, _, element = subname.rpartition(".")
        prefix = prefix + "." if prefix else ""
        shape, deflection = self._object_shape(root, prefix)
        return shape.getElement(element), deflection

    def common_meshes(self, contact, fuzzy):
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
                points = numpy.array([(p.x, p.y, p.z) for p in points], dtype=float)
                triangles = numpy.array(triangles, dtype=numpy.int64).reshape(-1, 3)
                # the common face keeps side A's orientation: out of A is into B
                for side, sign in ((0, 1.0), (1, -1.0)):
                    meshes[side].append(((contact.Name, side, k),
                                         (_pushed_out(points, triangles, sign * deflection), triangles,
                                          piece.BoundBox)))
            return meshes if meshes[0] else None
        except Exception as error:  # drawing only: fall back to the whole faces
            self.failures.append(f"{contact.Label}: common area: {error}")
            return None


def _pushed_out(points, triangles, distance):
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


class _TypeLayer:
    """The faces of one (type, partial) kind: one material and one coordinate
    node shared by the face sets of all contacts of that kind."""

    def __init__(self, kind, partial, colours=None):
        self.kind, self.partial = kind, partial
        self.node = coin.SoSeparator()
        self.node.setName(f"Contacts_{kind}{'_partial' if partial else ''}")
        transparency = CIRCLE_FACE_TRANSPARENCY if kind in CIRCLE_TYPES else 0.0
        self.node.addChild(_material(type_colour(kind, partial, colours), transparency))
        self.stripe_nodes = _stripes() if partial else []
        for node in self.stripe_nodes:
            self.node.addChild(node)
        self.coordinates = coin.SoCoordinate3()
        self.node.addChild(self.coordinates)
        self.circle_material = _line_material(type_colour(kind, partial, colours))
        self.points = []   # point arrays, in coordinate order
        self.count = 0     # points so far
        self.face_rows = {}  # face key -> its triangles' rows of coordIndex (m, 4)
        self.box = FreeCAD.BoundBox()

    def add_face(self, key, mesh):
        """coordIndex rows (i, j, k, -1) of the face's triangles."""
        if key not in self.face_rows:
            points, triangles, box = mesh
            rows = numpy.full((len(triangles), 4), -1, dtype=numpy.int32)
            rows[:, :3] = triangles + self.count
            self.face_rows[key] = rows
            self.points.append(points)
            self.count += len(points)
            self.box.add(box)
        return self.face_rows[key]

    def finish(self):
        if self.points:
            points = numpy.vstack(self.points)  # pivy takes numpy arrays as they are
            self.coordinates.point.setValues(0, len(points), points)
        if self.stripe_nodes and self.box.isValid():
            # about 30 stripes across the partial contacts
            _set_stripe_period(self.stripe_nodes[-1], max(self.box.DiagonalLength / 30.0, 1e-3))


def path_visible(root, prefix):
    """Whether the object at `prefix` ("Part.Link." style, "" for root
    itself) under `root` is shown: every object on the path must be."""
    if not root.Visibility:
        return False
    parent = root
    for name in prefix.split(".")[:-1]:
        child = parent.getSubObject(name + ".", retType=1)
        if child is None:
            return False
        # Links and groups may show a child their own way (link element visibility).
        visible = parent.isElementVisible(name) if hasattr(parent, "isElementVisible") else -1
        if not (child.Visibility if visible < 0 else visible):
            return False
        parent = child
    return True


class ContactOverlay:
    """The Coin drawing of a ContactAnalysis group's contacts.

    Per contact, a switch (hidden / shown / highlighted) over its two sides;
    each side's faces show while their body is shown, so hiding a body lets
    one see its partners' contact faces."""

    def __init__(self, doc_name):
        self.doc_name = doc_name
        self.root = coin.SoSeparator()
        self.root.setName("ContactOverlay")
        self.switches = {}     # Contact name -> SoSwitch (0 shown, 1 highlighted)
        self.sides = {}        # Contact name -> [(SoSwitch, {body path key})] faces A, B, circle
        self.face_keys = {}    # Contact name -> {(root name, subname)}
        self.visible = {}      # Contact name -> bool (the Contact's Visibility)
        self.highlighted = set()
        self.bodies = {}       # body path key (doc, root name, prefix) -> (root, prefix)
        self.path_names = set()  # names of the objects on the body paths
        self.names = ()        # the contacts drawn, in order
        self.on_body_changed = None  # WeakMethod: a body moved or changed shape
        self.triangles = 0
        self.faces = 0
        self.circles = 0
        self.common_contacts = 0  # contacts drawn as their common area
        self.colours = dict(TYPE_COLOURS)
        self.legend = None
        self.failures = []

    def build(self, contacts, common_area=None, fuzzy=1e-3):
        """(Re)builds the drawing of `contacts` (Contact document objects):
        the area each contact's sides share (common_area, default the
        preferences' paint style) or their whole faces."""
        if common_area is None:
            common_area = paint_style() == "Common area"
        self.colours = legend_colours()
        self.common_contacts = 0
        self.root.removeAllChildren()
        self.switches, self.sides, self.face_keys, self.visible = {}, {}, {}, {}
        self.highlighted, self.bodies, self.path_names = set(), {}, set()
        self.triangles = self.faces = self.circles = 0
        pick = coin.SoPickStyle()
        pick.style.setValue(coin.SoPickStyle.UNPICKABLE)  # clicks reach the body faces below
        hints = coin.SoShapeHints()
        # Known ordering with an unknown shape type turns on two-sided lighting:
        # the two sides of a contact have opposite normals and must look alike.
        hints.vertexOrdering.setValue(coin.SoShapeHints.COUNTERCLOCKWISE)
        hints.shapeType.setValue(coin.SoShapeHints.UNKNOWN_SHAPE_TYPE)
        hints.creaseAngle.setValue(0.6)
        # FreeCAD pushes the bodies' faces back (polygon offset 1, 1, so that
        # their edges show); ours, already out of their body, need a pull of
        # one unit only: more would bring hidden faces through thin walls.
        for node in (pick, hints, _polygon_offset(0.0, -1.0)):
            self.root.addChild(node)
        highlight_material = _material(selection_colour())
        highlight_offset = _polygon_offset(0.0, -3.0)  # over the same face drawn unselected
        highlight_circle = _line_material(selection_colour())
        source = FaceSource()
        layers = {}
        for contact in contacts:
            kind = contact.ContactType
            key = (kind, bool(contact.Partial))
            if key not in layers:
                layers[key] = _TypeLayer(*key, colours=self.colours)
            layer = layers[key]
            sides, face_keys = [], set()
            common = None
            if common_area and kind not in CIRCLE_TYPES:
                common = source.common_meshes(contact, fuzzy)
                if common is not None:
                    self.common_contacts += 1
            for side_index, links in enumerate((contact.FacesA, contact.FacesB)):
                side, bodies = coin.SoSwitch(), set()
                rows = []
                for root, subnames in links:
                    for subname in subnames:
                        bodies.add(self._body(root, subname))
                        face_keys.add((root.Name, subname))
                        if common is not None:
                            continue
                        mesh = source.mesh(root, subname)
                        if mesh is None:
                            continue
                        face_key = (root.Document.Name, root.Name, subname)
                        if face_key not in layer.face_rows:
                            self.faces += 1
                        rows.append(layer.add_face(face_key, mesh))
                for key, mesh in (common[side_index] if common is not None else []):
                    self.faces += 1
                    rows.append(layer.add_face(key, mesh))
                if rows:
                    indices = numpy.vstack(rows).ravel()
                    face_set = coin.SoIndexedFaceSet()
                    face_set.coordIndex.setValues(0, len(indices), indices)
                    side.addChild(face_set)
                    self.triangles += len(indices) // 4
                sides.append((side, bodies))
            circle = self._circle(contact) if kind in CIRCLE_TYPES else None
            if circle is not None:
                circle_side = coin.SoSwitch()  # shown with either side
                circle_side.addChild(circle)
                sides.append((circle_side, sides[0][1] | sides[1][1]))
                self.circles += 1
            # Branch 0 draws the contact in its layer's colour, branch 1 in the
            # selection colour; both share the side nodes (Coin graphs are DAGs).
            switch = coin.SoSwitch()
            switch.setName(contact.Name)
            normal, highlight = coin.SoSeparator(), coin.SoSeparator()
            highlight.addChild(highlight_material)
            highlight.addChild(highlight_offset)
            for branch, circle_material in ((normal, layer.circle_material), (highlight, highlight_circle)):
                branch.addChild(sides[0][0])
                branch.addChild(sides[1][0])
                if circle is not None:
                    circle_node = coin.SoSeparator()
                    circle_node.addChild(circle_material)
                    circle_node.addChild(sides[2][0])
                    branch.addChild(circle_node)
            switch.addChild(normal)
            switch.addChild(highlight)
            layer.node.addChild(switch)
            self.switches[contact.Name] = switch
            self.sides[contact.Name] = sides
            self.face_keys[contact.Name] = face_keys
            self.visible[contact.Name] = bool(contact.Visibility)
            self._update_switch(contact.Name)
        for key in sorted(layers):
            layers[key].finish()
            self.root.addChild(layers[key].node)
        kinds = [k for k in TYPE_COLOURS if any(key[0] == k for key in layers)]
        counts = {k: sum(1 for c in contacts if c.ContactType == k) for k in kinds}
        self.legend = legend_node([(f"{k} {TYPE_NAMES[k]} ({counts[k]})", type_colour(k, False, self.colours))
                                   for k in kinds])
        self.root.addChild(self.legend)
        self.names = tuple(c.Name for c in contacts)
        self.failures = source.failures
        self.update_bodies()

    def _body(self, root, subname):
        """Key of the body path holding a face; remembers the path."""
        prefix = subname.rpartition(".")[0]
        prefix = prefix + "." if prefix else ""
        key = (root.Document.Name, root.Name, prefix)
        if key not in self.bodies:
            self.bodies[key] = (root, prefix)
            self.path_names.add(root.Name)
            self.path_names.update(prefix.split(".")[:-1])
        return key

    @staticmethod
    def _circle(contact):
        points = _circle_points(contact.Point, contact.Direction, float(contact.Radius.Value))
        if not points:
            return None
        node = coin.SoGroup()  # under a separator with its material
        style = coin.SoDrawStyle()
        style.lineWidth.setValue(CIRCLE_WIDTH)
        light = coin.SoLightModel()
        light.model.setValue(coin.SoLightModel.BASE_COLOR)
        coordinates = coin.SoCoordinate3()
        coordinates.point.setValues(0, len(points), points)
        lines = coin.SoLineSet()
        lines.numVertices.setValue(len(points))
        for child in (style, light, coordinates, lines):
            node.addChild(child)
        return node

    def update_bodies(self):
        """Shows each side whose body is shown (after a Visibility change)."""
        shown = {}
        for key, (root, prefix) in self.bodies.items():
            try:
                shown[key] = path_visible(root, prefix)
            except Exception:  # a deleted body
                shown[key] = False
        for sides in self.sides.values():
            for switch, bodies in sides:
                visible = any(shown[key] for key in bodies)
                switch.whichChild.setValue(coin.SO_SWITCH_ALL if visible else coin.SO_SWITCH_NONE)

    def _update_switch(self, name):
        switch = self.switches.get(name)
        if switch is None:
            return
        if not self.visible.get(name, True):
            switch.whichChild.setValue(coin.SO_SWITCH_NONE)
        else:
            switch.whichChild.setValue(1 if name in self.highlighted else 0)

    def set_visible(self, name, visible):
        self.visible[name] = bool(visible)
        self._update_switch(name)

    def highlight(self, selected_objects, selected_faces):
        """Highlights the contacts selected themselves or by all their faces
        (what double-clicking a contact selects)."""
        highlighted = {name for name, keys in self.face_keys.items()
                       if name in selected_objects or (keys and keys <= selected_faces)}
        changed = highlighted ^ self.highlighted
        self.highlighted = highlighted
        for name in changed:
            self._update_switch(name)


class _ViewProvider:
    """What both view providers share: nothing to save."""

    def __init__(self, vobj):
        vobj.Proxy = self

    def attach(self, vobj):
        self.Object = vobj.Object

    def getIcon(self):
        return contactwb.icon_path("Contacts_FindContacts")

    # Nothing to save (the drawing is rebuilt from the document). FreeCAD 0.20
    # under Python 3.11 asks __getstate__ before dumps: both must say so.
    def __getstate__(self):
        return None

    def __setstate__(self, state):
        return None

    def dumps(self):
        return None

    def loads(self, state):
        return None


class ViewProviderContactAnalysis(_ViewProvider):
    """Draws the group's contacts (ContactOverlay) under a switch of its own
    that follows the group's Visibility. (Not as a display mode: a group with
    display modes shows again any child one hides.)"""

    def attach(self, vobj):
        super().attach(vobj)
        self._stale, self._scheduled = False, False
        self.overlay = ContactOverlay(vobj.Object.Document.Name)
        # weak: the overlay must not keep a closed document's view provider alive
        self.overlay.on_body_changed = weakref.WeakMethod(self.schedule_rebuild)
        self.switch = coin.SoSwitch()
        self.switch.setName("ContactsSwitch")
        self.switch.addChild(self.overlay.root)
        vobj.RootNode.addChild(self.switch)
        self.onChanged(vobj, "Visibility")
        _Watcher.register(self.overlay)
        # Drawn once the document is loaded (on restore the bodies are meshed
        # by then, and their triangulation is reused); a new analysis is drawn
        # at once by attach() below.
        self.schedule_rebuild()

    def onChanged(self, vobj, prop):
        if prop == "Visibility":
            self.update_switch()

    def is_stale(self):
        """Whether the analysis waits for a recompute after its bodies
        changed: its paint would show contacts that may no longer exist."""
        obj = getattr(self, "Object", None)
        try:
            return bool(getattr(obj, "UpdateOnRecompute", False)) and "Touched" in obj.State
        except Exception:
            return False

    def update_switch(self):
        switch = getattr(self, "switch", None)
        if switch is None:
            return
        shown = self.Object.ViewObject.Visibility and not self.is_stale()
        switch.whichChild.setValue(coin.SO_SWITCH_ALL if shown else coin.SO_SWITCH_NONE)

    def updateData(self, obj, prop):
        # Contacts deleted, added or found again (Bodies is set by every run):
        # redraw. (Group alone is also announced after every attach.)
        overlay = getattr(self, "overlay", None)
        if overlay is None:
            return
        if prop == "Bodies" or (prop == "Group" and
                                tuple(c.Name for c in obj.Group if is_contact(c)) != overlay.names):
            self.schedule_rebuild()

    def schedule_rebuild(self):
        """Rebuilds once the current operation (loading, a recompute, a move
        of many bodies) is over."""
        self._stale = True
        if not self._scheduled:
            from PySide2 import QtCore
            self._scheduled = True
            QtCore.QTimer.singleShot(0, self._deferred_rebuild)

    def _deferred_rebuild(self):
        self._scheduled = False
        if not self._stale:
            return
        try:
            self.Object.ViewObject.Visibility  # raises once the group is deleted
        except Exception:
            return
        self.rebuild()

    def rebuild(self):
        """Draws the group's contacts now."""
        self._stale = False
        contacts = [c for c in self.Object.Group if is_contact(c) and c.FacesA and c.FacesB]
        self.update_switch()
        fuzzy = max(10 * self.Object.LinearTolerance.Value, 1e-4)
        try:
            self.overlay.build(contacts, fuzzy=fuzzy)
        except Exception as error:  # a drawing problem must not break the document
            FreeCAD.Console.PrintError(f"Contacts: cannot draw '{self.Object.Label}': {error}\n")
            return
        if self.overlay.failures:
            FreeCAD.Console.PrintWarning(
                f"Contacts: {len(self.overlay.failures)} faces of '{self.Object.Label}' not drawn, "
                f"first: {self.overlay.failures[0]}\n")
        _Watcher.refresh_highlight(self.Object.Document.Name)

    def claimChildren(self):
        return self.Object.Group

    def setEdit(self, vobj, mode=0):
        """Double-click or Edit: the task panel, to find the contacts again."""
        if mode != 0:
            return None
        from contactwb.gui import task_panel
        task_panel.open_panel(vobj.Object.Document, vobj.Object)
        return True

    def unsetEdit(self, vobj, mode=0):
        return None

    def doubleClicked(self, vobj):
        from contactwb.gui import task_panel
        task_panel.open_panel(vobj.Object.Document, vobj.Object)
        return True

    def setupContextMenu(self, vobj, menu):
        group = vobj.Object
        _add_action(menu, "Find contacts again...", lambda: _open_panel(group))
        _add_action(menu, "Contact table", lambda: FreeCADGui.runCommand("Contacts_ShowContactTable"))
        _add_action(menu, "Export contacts...", lambda: _export(group))


class ViewProviderContact(_ViewProvider):
    """A contact: drawn by its group's overlay; its Visibility switches its
    part of that drawing."""

    def attach(self, vobj):
        super().attach(vobj)
        # An empty display mode: without one the tree greys the contact out
        # as if it were hidden.
        vobj.addDisplayMode(coin.SoGroup(), "Overlay")

    def getDisplayModes(self, vobj):
        return ["Overlay"]

    def getDefaultDisplayMode(self):
        return "Overlay"

    def setDisplayMode(self, mode):
        return mode

    def getIcon(self):
        return contact_icon_path(getattr(getattr(self, "Object", None), "ContactType", ""))

    def doubleClicked(self, vobj):
        select_contact_faces(vobj.Object)
        return True

    def setupContextMenu(self, vobj, menu):
        from contactwb.gui import actions
        contact = vobj.Object
        _add_action(menu, "Select faces", lambda: select_contact_faces(contact))
        _add_action(menu, "Zoom to contact", lambda: actions.zoom_to(contact))
        _add_action(menu, "Isolate with its parts", lambda: _isolate(contact))
        _add_action(menu, "Export contacts...", lambda: _export(actions.analysis_of(contact)))

    def onChanged(self, vobj, prop):
        if prop != "Visibility":
            return
        for overlay in _overlays_of(vobj.Object):
            overlay.set_visible(vobj.Object.Name, vobj.Visibility)


def _add_action(menu, text, slot):
    action = menu.addAction(text)
    action.triggered.connect(slot)
    return action


def _open_panel(group):
    from contactwb.gui import task_panel
    task_panel.open_panel(group.Document, group)


def _isolate(contact):
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(contact)
    FreeCADGui.runCommand("Contacts_IsolateContact")


def _export(group):
    if group is None:
        return
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(group)
    FreeCADGui.runCommand("Contacts_ExportContacts")


def _overlays_of(contact):
    """The overlays drawing a Contact (its groups')."""
    for parent in contact.InList:
        proxy = getattr(getattr(parent, "ViewObject", None), "Proxy", None)
        overlay = getattr(proxy, "overlay", None)
        if overlay is not None:
            yield overlay


class _Watcher:
    """The session's one selection and document observer: highlights the
    selected contacts and follows the bodies' Visibility, for every overlay
    alive (a weak set: closed documents drop out)."""

    overlays = weakref.WeakSet()
    _installed = None

    @classmethod
    def register(cls, overlay):
        cls.overlays.add(overlay)
        if cls._installed is None:
            cls._installed = cls()
            FreeCADGui.Selection.addObserver(cls._installed)
            FreeCAD.addDocumentObserver(cls._installed)

    @classmethod
    def refresh_highlight(cls, doc_name):
        overlays = [o for o in list(cls.overlays) if o.doc_name == doc_name]
        if not overlays:
            return
        objects, faces = set(), set()
        for selected in FreeCADGui.Selection.getSelectionEx(doc_name, 0):
            if not selected.SubElementNames:
                objects.add(selected.ObjectName)
            for subname in selected.SubElementNames:
                faces.add((selected.ObjectName, subname))
        for overlay in overlays:
            overlay.highlight(objects, faces)

    def _selection_changed(self, doc_name):
        try:
            self.refresh_highlight(doc_name)
        except Exception as error:  # an observer must never break the selection
            FreeCAD.Console.PrintWarning(f"Contacts: highlight failed: {error}\n")

    def addSelection(self, doc, obj, sub, pnt):
        self._selection_changed(doc)

    def removeSelection(self, doc, obj, sub):
        self._selection_changed(doc)

    def setSelection(self, doc):
        self._selection_changed(doc)

    def clearSelection(self, doc):
        for name in [doc] if doc else FreeCAD.listDocuments():
            self._selection_changed(name)

    def slotDeletedObject(self, obj):
        # a body deleted: its contacts lose their links; redraw without them
        try:
            for overlay in list(self.overlays):
                if overlay.doc_name == obj.Document.Name and obj.Name in overlay.path_names:
                    method = overlay.on_body_changed
                    rebuild = method() if method is not None else None
                    if rebuild is not None:
                        rebuild()
        except Exception as error:
            FreeCAD.Console.PrintWarning(f"Contacts: cannot follow the bodies: {error}\n")

    def slotChangedObject(self, obj, prop):
        if prop not in ("Visibility", "Placement", "Shape") or not self.overlays:
            return
        try:
            doc_name = obj.Document.Name
            for overlay in list(self.overlays):
                if overlay.doc_name != doc_name or obj.Name not in overlay.path_names:
                    continue
                if prop == "Visibility":
                    overlay.update_bodies()
                else:  # a body moved or changed: redraw its faces
                    method = overlay.on_body_changed
                    rebuild = method() if method is not None else None
                    if rebuild is not None:
                        rebuild()
        except Exception as error:
            FreeCAD.Console.PrintWarning(f"Contacts: cannot follow the bodies: {error}\n")


def select_contact_faces(contact):
    """Selects both sides' faces of a contact in the 3D view."""
    FreeCADGui.Selection.clearSelection()
    for links in (contact.FacesA, contact.FacesB):
        for root, subnames in links:
            for subname in subnames:
                FreeCADGui.Selection.addSelection(root.Document.Name, root.Name, subname)


def attach(group):
    """Gives a ContactAnalysis group and its contacts their view providers,
    and draws the contacts."""
    provider = group.ViewObject.Proxy
    if not isinstance(provider, ViewProviderContactAnalysis):
        provider = ViewProviderContactAnalysis(group.ViewObject)
    for child in group.Group:
        if is_contact(child) and not isinstance(child.ViewObject.Proxy, ViewProviderContact):
            ViewProviderContact(child.ViewObject)
    provider.rebuild()
