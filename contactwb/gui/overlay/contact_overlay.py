"""The Coin drawing of a ContactAnalysis group's contacts.

Both sides' faces, tessellated as the bodies are, pushed out of their body by
the tessellation's deflection and pulled towards the viewer by a polygon
offset so they show on the coincident body faces, coloured by contact type
(contactwb.gui.overlay.colours); partial contacts are lighter and striped, and
ball contacts (LAF, SPT) get their contact circle (their faces are drawn
see-through). Each contact has its own switch: hidden, shown, or drawn in the
selection colour while it (or all of its faces) is selected; each side shows
while its body is shown. The view provider
(contactwb.gui.viewproviders.contact_analysis) owns the overlay and rebuilds
it; the observer following the selection and the bodies is
contactwb.gui.overlay.watcher."""
import FreeCAD
import numpy
from pivy import coin

from contactwb.core.kinds import CIRCLE_TYPES, CONTACT_TYPES, TYPE_NAMES
from contactwb.document.identify import interferences_of
from contactwb.objects import regions
from contactwb.gui.overlay.coin_nodes import (legend_node, line_material, material, polygon_offset,
                                              set_stripe_period, stripes, unlit_polyline)
from contactwb.gui.overlay.colours import TYPE_COLOURS, legend_colours, selection_colour, type_colour
from contactwb.gui.overlay.faces import FaceSource, circle_points
from contactwb.gui.palette import INTERFERENCE_COLOUR, rgb
from contactwb.gui.settings import paint_style

CIRCLE_FACE_TRANSPARENCY = 0.6  # the ball and its seat, behind the circle
CIRCLE_WIDTH = 4  # pixels


class TypeLayer:
    """The faces of one (type, partial) kind: one material and one coordinate
    node shared by the face sets of all contacts of that kind."""

    def __init__(self, kind, partial, colours=None):
        self.kind, self.partial = kind, partial
        self.node = coin.SoSeparator()
        self.node.setName(f"Contacts_{kind}{'_partial' if partial else ''}")
        transparency = CIRCLE_FACE_TRANSPARENCY if kind in CIRCLE_TYPES else 0.0
        self.node.addChild(material(type_colour(kind, partial, colours), transparency))
        self.stripe_nodes = stripes() if partial else []
        for node in self.stripe_nodes:
            self.node.addChild(node)
        self.coordinates = coin.SoCoordinate3()
        self.node.addChild(self.coordinates)
        self.circle_material = line_material(type_colour(kind, partial, colours))
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
            set_stripe_period(self.stripe_nodes[-1], max(self.box.DiagonalLength / 30.0, 1e-3))


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
        self.on_recomputed = None  # WeakMethod: the document was recomputed, or undone
        self.triangles = 0
        self.faces = 0
        self.circles = 0
        self.common_contacts = 0  # contacts drawn as their common area
        self.core_contacts = 0  # of which the core's regions
        self.interferences = 0  # counted in the legend
        self.region_generation = None  # of the analysis' regions drawn (contactwb.objects.regions)
        self.colours = dict(TYPE_COLOURS)
        self.legend = None
        self.failures = []

    def build(self, contacts, common_area=None, fuzzy=1e-3, group=None):
        """(Re)builds the drawing of `contacts` (Contact document objects):
        the area each contact's sides share (common_area, default the
        preferences' paint style) or their whole faces. The shared areas
        come from the core's regions cached with `group` (their analysis),
        else from a Boolean of the faces here."""
        if common_area is None:
            common_area = paint_style() == "Common area"
        self.colours = legend_colours()
        self.common_contacts = self.core_contacts = 0
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
        for node in (pick, hints, polygon_offset(0.0, -1.0)):
            self.root.addChild(node)
        highlight_material = material(selection_colour())
        highlight_offset = polygon_offset(0.0, -3.0)  # over the same face drawn unselected

        highlight_circle = line_material(selection_colour())
        source = FaceSource()
        layers = {}
        for contact in contacts:
            kind = contact.ContactType
            key = (kind, bool(contact.Partial))
            if key not in layers:
                layers[key] = TypeLayer(*key, colours=self.colours)
            layer = layers[key]
            sides, face_keys = [], set()
            common = None
            if common_area and kind not in CIRCLE_TYPES:
                common = source.core_meshes(group, contact)
                if common is not None:
                    self.core_contacts += 1
                else:
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
            # A selected contact shows through the parts around it (a screw's
            # bore inside the covers): an annotation, drawn after the scene
            # without the depth test.
            normal, highlight = coin.SoSeparator(), coin.SoAnnotation()
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
        kinds = [k for k in CONTACT_TYPES if any(key[0] == k for key in layers)]
        counts = {k: sum(1 for c in contacts if c.ContactType == k) for k in kinds}
        entries = [(f"{k} {TYPE_NAMES[k]} ({counts[k]})", type_colour(k, False, self.colours)) for k in kinds]
        self.interferences = len(interferences_of(group)) if group is not None else 0
        if self.interferences:
            entries.append((f"Interferences ({self.interferences})", rgb(INTERFERENCE_COLOUR)))
        self.legend = legend_node(entries, stack=(self.doc_name, ("analysis", id(self))))
        self.root.addChild(self.legend)
        self.names = tuple(c.Name for c in contacts)
        self.region_generation = regions.generation(group) if group is not None else None
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
        points = circle_points(contact.Point, contact.Direction, float(contact.Radius.Value))
        if not points:
            return None
        return unlit_polyline(points, CIRCLE_WIDTH)  # a group: under a separator with its material

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
