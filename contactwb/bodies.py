"""Bodies of a FreeCAD document: every visible solid with its global placement.

Walks the document tree the way the 3D view shows it: App::Part containers,
groups and App::Link (to parts or to containers) are entered, with their
placements applied; Part features and PartDesign bodies are leaves. A leaf
whose shape holds several solids gives one body per solid, and each body
keeps the map from its own face numbers to the object's FaceN names, so the
GUI can select the faces of a contact."""
from dataclasses import dataclass, field
from typing import List, Optional

LEAF_TYPES = ("Part::Feature", "PartDesign::Body")


@dataclass
class DocumentBody:
    """One solid of a document, placed globally."""
    name: str                 # unique: the object's Label, ".N" for further solids
    obj: object               # the leaf document object (a link when the body is a link)
    root: object              # the top-level object of its path
    subname: str              # path from root to obj, "Part.Link." style ("" when obj is root)
    shape: object             # Part.Shape, a single solid, global placement
    face_map: Optional[List[int]] = field(default=None)  # body face i+1 -> object FaceN
    containers: List[object] = field(default_factory=list)  # enclosing parts/links, outermost first

    def object_face_name(self, body_face_index):
        """FreeCAD's "FaceN" on `obj` for the body's face number (1-based)."""
        if self.face_map is None:
            return f"Face{body_face_index}"
        return f"Face{self.face_map[body_face_index - 1]}"


def _is_leaf(obj):
    linked = obj.getLinkedObject(True)
    return any(linked.isDerivedFrom(t) for t in LEAF_TYPES) and not linked.isDerivedFrom("App::Part")


def _child_visible(parent, child_name, child):
    visible = parent.isElementVisible(child_name) if hasattr(parent, "isElementVisible") else -1
    if visible < 0:
        return bool(getattr(child, "Visibility", True))
    return bool(visible)


def _global_shape(root, subname):
    import Part
    return Part.getShape(root, subname, needSubElement=False, transform=True)


def _split_solids(name, obj, root, subname, shape, containers):
    solids = shape.Solids
    if len(solids) <= 1:
        return [DocumentBody(name, obj, root, subname, solids[0] if solids else shape,
                             containers=containers)]
    object_faces = shape.Faces
    bodies = []
    for k, solid in enumerate(solids, start=1):
        face_map = []
        for face in solid.Faces:
            index = next(i for i, f in enumerate(object_faces, start=1) if f.isSame(face))
            face_map.append(index)
        label = name if k == 1 else f"{name}.{k}"
        bodies.append(DocumentBody(label, obj, root, subname, solid, face_map, containers))
    return bodies


def _is_analysis_object(obj):
    """The workbench's own results (they link to bodies but hold no solid)."""
    from contactwb.objects.contact_objects import is_contact, is_contact_analysis
    return is_contact_analysis(obj) or is_contact(obj)


def _roots(doc):
    """Visible top-level objects. A body linked only by a contact analysis is
    still top-level: the analysis refers to it, it does not contain it."""
    return [o for o in doc.Objects
            if not _is_analysis_object(o) and getattr(o, "Visibility", True)
            and all(_is_analysis_object(parent) for parent in o.InList)]


def document_bodies(doc, objects=None, messages=None):
    """Bodies of `doc` (or of the given objects and what they contain).

    Only visible objects count (hidden ones are construction inputs, or the
    originals of linked parts). Objects whose shape has no solid are reported
    in `messages` (a list, if given) and skipped."""
    roots = list(objects) if objects is not None else _roots(doc)
    bodies = []

    def visit(root, obj, subname, containers):
        if _is_leaf(obj):
            shape = _global_shape(root, subname)
            if shape.isNull() or not shape.Solids:
                if messages is not None and shape.isNull():
                    messages.append(f"skipped '{obj.Label}': it has no shape (not restored or not recomputed: "
                                    "the document may be damaged)")
                if messages is not None and not shape.isNull() and shape.Faces:
                    messages.append(f"skipped '{obj.Label}': no solid (surface model or open shell)")
                return
            bodies.extend(_split_solids(obj.Label, obj, root, subname, shape, containers))
            return
        if obj is not root and (obj.isDerivedFrom("App::Link") or obj.isDerivedFrom("App::Part")):
            containers = containers + [obj]
        for child_name in obj.getSubObjects():
            child = obj.getSubObject(child_name, retType=1)
            if child is None or not _child_visible(obj, child_name, child):
                continue
            visit(root, child, subname + child_name, containers)

    for root in roots:
        visit(root, root, "", [])
    _name_after_containers(bodies)
    _make_names_unique(bodies)
    return bodies


def _name_after_containers(bodies):
    """A body alone in a part or link takes that container's label (the part
    "base" rather than its PartDesign "Body"), as the user named it."""
    count = {}
    for body in bodies:
        for container in body.containers:
            count[id(container)] = count.get(id(container), 0) + 1
    for body in bodies:
        for container in reversed(body.containers):
            if count[id(container)] == 1:
                body.name = container.Label + body.name[len(body.obj.Label):]
                break


def _make_names_unique(bodies):
    used = set()
    for body in bodies:
        name, n = body.name, 2
        while name in used:
            name, n = f"{body.name}.{n}", n + 1
        used.add(name)
        body.name = name


def assembly_from_document(doc, objects=None, messages=None):
    """(contactcore.Assembly, [DocumentBody]) for a document or a selection."""
    from contactwb import core
    bodies = document_bodies(doc, objects, messages)
    if not bodies:
        raise core.ContactsError(f"no visible solid in document '{doc.Label}'")
    return core.assembly_from_shapes((b.name, b.shape) for b in bodies), bodies
