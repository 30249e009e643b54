"""Bodies of a FreeCAD document: every visible solid with its global placement.

Walks the document tree the way the 3D view shows it: App::Part containers,
groups and App::Link (to parts or to containers) are entered, with their
placements applied; Part features and PartDesign bodies are leaves. A leaf
whose shape holds several solids gives one body per solid, and each body
keeps the map from its own face numbers to the object's FaceN names, so the
GUI can select the faces of a contact."""
from dataclasses import dataclass, field
from typing import List, Optional

from contactwb import core
from contactwb.document.identify import is_workbench_result
from contactwb.document.shapes import assembly_from_shapes

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


RECENT_FILES = "User parameter:BaseApp/Preferences/RecentFiles"
STEP_EXTENSIONS = (".step", ".stp")


def _label_stem(label):
    """"motor001" -> "motor": FreeCAD numbers an imported compound's label."""
    return label.rstrip("0123456789").rstrip("._- ").lower() or label.lower()


def _step_candidates(obj):
    """STEP files the object may come from: FreeCAD's recent files (File >
    Open and Import record them) and the document's folder, whose name
    matches the object's label."""
    import os
    import FreeCAD
    params = FreeCAD.ParamGet(RECENT_FILES)
    paths = [params.GetString(f"MRU{k}", "") for k in range(max(params.GetInt("RecentFiles", 4), 12))]
    folder = os.path.dirname(getattr(obj.Document, "FileName", "") or "")
    if folder and os.path.isdir(folder):
        paths += [os.path.join(folder, f) for f in sorted(os.listdir(folder))]
    stem = _label_stem(obj.Label)
    found = []
    for path in paths:
        base, extension = os.path.splitext(os.path.basename(path))
        if extension.lower() in STEP_EXTENSIONS and base.lower() == stem and os.path.isfile(path) \
                and path not in found:
            found.append(path)
    return found


def _product_names(obj, solids):
    """Names of a compound's solids (FreeCAD's compound import keeps one
    object named after the file): the STEP file's product names, matched by
    volume and centre of mass, when the file can be found and every solid
    matches; else None."""
    for path in _step_candidates(obj):
        try:
            assembly = core.contactcore.read_step(path)
        except Exception:
            continue
        products = [(b.name, b.volume, b.center) for b in assembly.bodies]
        names, used = [], set()
        for solid in solids:
            volume, centre = solid.Volume, solid.CenterOfMass
            size = max(solid.BoundBox.DiagonalLength, 1e-9)
            match = next((k for k, (_, v, c) in enumerate(products) if k not in used
                          and abs(v - volume) <= 1e-4 * max(abs(volume), 1e-9)
                          and max(abs(c[0] - centre.x), abs(c[1] - centre.y), abs(c[2] - centre.z)) <= 1e-4 * size),
                         None)
            if match is None:
                break
            used.add(match)
            names.append(products[match][0])
        if len(names) == len(solids):
            return names
    return None


def _split_solids(name, obj, root, subname, shape, containers):
    solids = shape.Solids
    if len(solids) <= 1:
        return [DocumentBody(name, obj, root, subname, solids[0] if solids else shape,
                             containers=containers)]
    object_faces = shape.Faces
    products = _product_names(obj, solids) if not subname else None
    bodies = []
    for k, solid in enumerate(solids, start=1):
        face_map = []
        for face in solid.Faces:
            index = next(i for i, f in enumerate(object_faces, start=1) if f.isSame(face))
            face_map.append(index)
        label = products[k - 1] if products else name if k == 1 else f"{name}.{k}"
        body = DocumentBody(label, obj, root, subname, solid, face_map, containers)
        body.product = bool(products)
        bodies.append(body)
    return bodies


_is_analysis_object = is_workbench_result  # the workbench's own results hold no solid


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
        if getattr(body, "product", False):
            continue
        for container in reversed(body.containers):
            if count[id(container)] == 1:
                body.name = container.Label + body.name[len(body.obj.Label):]
                break


def _make_names_unique(bodies):
    """The core's rule (".2", ".3", ... on repeats), in linear time: one implementation."""
    for body, name in zip(bodies, core.contactcore.unique_names([b.name for b in bodies])):
        body.name = name


def object_path(subname):
    """The object part of a selection subname ("Part.Link.Face3" -> "Part.Link.")."""
    if not subname or subname.endswith("."):
        return subname or ""
    prefix = subname.rpartition(".")[0]
    return prefix + "." if prefix else ""


def _element_face(subname):
    """N of a trailing "FaceN" in a selection subname, else None."""
    element = (subname or "").rpartition(".")[2]
    if element.startswith("Face") and element[4:].isdigit():
        return int(element[4:])
    return None


def _body_matches(body, root, subname):
    """Whether a selection (root object, subname) picks or contains this body."""
    path = object_path(subname)
    if body.root is root:
        if not (body.subname.startswith(path) or path.startswith(body.subname)):
            return False
    elif root is not body.obj and root not in body.containers \
            and body.obj.getLinkedObject(True) is not root:
        return False
    face = _element_face(subname)
    if face is not None and body.face_map is not None and path == body.subname:
        return face in body.face_map  # a face of one solid of a multi-solid feature
    return True


def bodies_of_selection(bodies, entries):
    """The bodies (of `bodies`, named for the whole document) that the
    selection entries pick: (object, [subnames]) pairs as the 3D view and the
    tree give them unresolved (top-level object, "Part.Link.Body.Pad.Face3"),
    or plain objects. A face or an inner feature picks its body (with the
    link's placement), a container all the bodies inside it. Contact analyses
    and contacts are ignored."""
    selected = []
    for entry in entries:
        root, subnames = entry if isinstance(entry, tuple) else (entry, [""])
        if _is_analysis_object(root):
            continue
        for subname in (subnames or [""]):
            target = root.getSubObject(subname, retType=1) if subname else root
            if not _is_analysis_object(target):
                selected.append((root, subname))
    # in document order, as the whole document's analysis lists them
    return [body for body in bodies if any(_body_matches(body, root, sub) for root, sub in selected)]


def body_link(body):
    """XLinkSub entry of a body: its top-level object and its path."""
    return (body.root, [body.subname])


def assembly_from_document(doc, objects=None, messages=None):
    """(contactcore.Assembly, [DocumentBody]) for a document or a selection."""
    bodies = document_bodies(doc, objects, messages)
    if not bodies:
        raise core.ContactsError(f"no visible solid in document '{doc.Label}'")
    return assembly_from_shapes((b.name, b.shape) for b in bodies), bodies
