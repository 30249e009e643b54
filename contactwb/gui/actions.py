"""What the commands, the contact table and the context menus do to the view:
select a contact's faces, zoom to it, isolate it with its two parts, ghost the
geometry that touches nothing, show everything again; run a command on an
object (the context menus)."""
import FreeCADGui

from contactwb.document import bodies
from contactwb.document.identify import analyses, is_contact, is_contact_analysis

GHOST_TRANSPARENCY = 85
ISOLATE_OTHERS_TRANSPARENCY = 95  # Isolate: the parts not in the contact, faint context


def analysis_of(contact):
    return next((p for p in contact.InList if is_contact_analysis(p)), None)


def contact_bodies(contact):
    """[(root, object path)] of the contact's two bodies."""
    paths = []
    for links in (contact.FacesA, contact.FacesB):
        for root, subnames in links:
            for subname in subnames:
                prefix = subname.rpartition(".")[0]
                path = (root, prefix + "." if prefix else "")
                if path not in paths:
                    paths.append(path)
    return paths


def select_contact(contact, faces=False):
    """Selects the contact in the tree (faces=False) or its faces in the view."""
    if faces:
        select_contact_faces(contact)
    else:
        FreeCADGui.Selection.clearSelection()
        FreeCADGui.Selection.addSelection(contact)


def contact_box(contact):
    """Bounding box of the contact's common region (of its smaller side's
    faces when there is none: the common area lies within both sides, and a
    shaft's whole face is long)."""
    from contactwb.gui.panels import contact_extent
    return contact_extent.contact_box(contact)


def zoom_to(contact, margin=1.3):
    """Frames the contact: the camera, keeping its direction, fitted on the
    bounding box of the contact's common region (Coin's viewBoundingBox: the
    box's bounding sphere fills 1/margin of the smaller side of the view)."""
    from pivy import coin
    box = contact_box(contact)
    if not box.isValid():
        return
    view = FreeCADGui.activeDocument().activeView()
    camera = view.getCameraNode()
    # a flat box (a plane contact) gets a little depth: a box of no depth has no sphere to fit
    pad = max(box.DiagonalLength * 0.02, 1e-3)
    bounds = coin.SbBox3f(box.XMin - pad, box.YMin - pad, box.ZMin - pad, box.XMax + pad, box.YMax + pad,
                          box.ZMax + pad)
    width, height = view.getSize()
    camera.viewBoundingBox(bounds, width / max(height, 1), max(margin, 1.0))


def _body_objects(doc):
    """Every leaf object shown as a body, with the containers above it."""
    return bodies.document_bodies(doc)


_isolated = {}  # document name -> bodies an older isolate() hid (none now: it ghosts), for show_all()


def isolate(contact):
    """Ghosts everything else and shows the contact's faces: every other part
    faint (ISOLATE_OTHERS_TRANSPARENCY, still there for context, never
    hidden), the contact's two parts see-through (GHOST_TRANSPARENCY) so that
    its paint shows even inside them, every other contact's paint hidden.
    View-only: transparency of the view providers, no undo entry."""
    doc = contact.Document
    keep = contact_bodies(contact)
    kept, others = [], []
    for body in _body_objects(doc):
        if any(body.root is root and body.subname.startswith(path) for root, path in keep):
            kept.append(body)
        else:
            others.append(body)
    _ghost(doc, others, ISOLATE_OTHERS_TRANSPARENCY)
    _ghost(doc, kept)  # last: a part linked twice (one bearing in two places) keeps the nearer level
    for group in analyses(doc):
        for other in group.Group:
            if is_contact(other) and other.ViewObject.Visibility != (other is contact):
                other.ViewObject.Visibility = other is contact
    group = analysis_of(contact)
    if group is not None and not group.ViewObject.Visibility:
        group.ViewObject.Visibility = True  # the contact's paint is drawn under its analysis


def _set_body_visibility(body, shown):
    if body.subname:
        parent_path, _, name = body.subname[:-1].rpartition(".")
        parent = body.root.getSubObject(parent_path + ".", retType=1) if parent_path else body.root
        if hasattr(parent, "setElementVisible") and parent.isElementVisible(name) >= 0:
            parent.setElementVisible(name, shown)
            return
    body.obj.ViewObject.Visibility = shown


def show_all(doc):
    """The bodies isolate() hid and every contact shown again, ghosting undone."""
    for body in _isolated.pop(doc.Name, []):
        try:
            _set_body_visibility(body, True)
        except Exception:  # deleted since
            pass
    for group in analyses(doc):
        for contact in group.Group:
            if is_contact(contact):
                contact.ViewObject.Visibility = True
    set_ghosted(doc, False)


def ghosted_objects(doc):
    """The bodies that ghosting makes see-through: all of them, so that
    only the contacts' paint (drawn opaque) stands out."""
    return _body_objects(doc)


_ghosted = {}  # document name -> {object name: transparency before ghosting}


def _ghost(doc, bodies_to_ghost, transparency=GHOST_TRANSPARENCY):
    """Makes these bodies see-through, remembering their transparency."""
    saved = _ghosted.setdefault(doc.Name, {})
    for body in bodies_to_ghost:
        vobj = getattr(body.obj.getLinkedObject(True), "ViewObject", None)
        if vobj is None or not hasattr(vobj, "Transparency"):
            continue
        saved.setdefault(vobj.Object.Name, vobj.Transparency)
        if vobj.Transparency != transparency:
            vobj.Transparency = transparency


def set_ghosted(doc, ghosted):
    """Makes the bodies see-through around the painted contacts (or restores them)."""
    if ghosted:
        _ghost(doc, ghosted_objects(doc))
        return
    for name, transparency in _ghosted.pop(doc.Name, {}).items():
        obj = doc.getObject(name)
        if obj is not None:
            obj.ViewObject.Transparency = transparency


def is_ghosted(doc):
    return bool(_ghosted.get(doc.Name))


def select_contact_faces(contact):
    """Selects both sides' faces of a contact in the 3D view."""
    FreeCADGui.Selection.clearSelection()
    for links in (contact.FacesA, contact.FacesB):
        for root, subnames in links:
            for subname in subnames:
                FreeCADGui.Selection.addSelection(root.Document.Name, root.Name, subname)


def run_isolate(contact):
    """Contacts_IsolateContact on `contact` (a context menu's entry)."""
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(contact)
    FreeCADGui.runCommand("Contacts_IsolateContact")


def export_analysis(group):
    """Contacts_ExportContacts on `group` (a context menu's entry; None: nothing)."""
    if group is None:
        return
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(group)
    FreeCADGui.runCommand("Contacts_ExportContacts")
