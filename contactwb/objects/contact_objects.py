"""Proxies of the contact analysis (a group) and of each contact (a child).

Saved files refer to `contactwb.objects.contact_objects.ContactAnalysis` and
`...Contact`: these names are permanent.

An analysis is live: it links every body it analysed (hidden `Bodies`), so it
is recomputed after they move or change shape, and `execute` finds the
contacts again, updating its Contact children in place. A document observer
marks it touched as soon as one of its bodies moves, changes or is deleted,
so the tree shows it out of date before the recompute."""

SCOPES = ["Document", "Selection", "PartAgainstRest"]
CONTACT_TYPES = ["PLF", "CLJ", "CJU", "SPF", "LAF", "SPT", "TRF"]

# Version of the objects' properties, saved in each object's ProxyVersion.
# A property, not the proxy's dumps() state: FreeCAD 0.20 opening a file
# without the workbench drops the proxy, and saving writes it as null; plain
# properties survive (contactwb.objects.recovery gives the proxy back).
#   1: files saved before ProxyVersion existed (0.1.0);
#   2: ProxyType, ProxyVersion; the analysis counts its contacts and joints.
PROXY_VERSION = 2


def is_contact_analysis(obj):
    """Whether a document object is a ContactAnalysis group (also once re-opened)."""
    return getattr(getattr(obj, "Proxy", None), "Type", None) == "ContactAnalysis"


def is_contact(obj):
    """Whether a document object is one Contact of an analysis."""
    return getattr(getattr(obj, "Proxy", None), "Type", None) == "Contact"


def _add(obj, kind, name, group, doc, mode=None):
    """Adds a property unless the object has it (files saved by older versions)."""
    if name not in obj.PropertiesList:
        obj.addProperty(kind, name, group, doc)
    if mode is not None:
        obj.setEditorMode(name, mode)


def _versioned(obj, proxy_type):
    """Adds the type and version records; returns the version the object was
    saved with (1: before they existed)."""
    saved = obj.ProxyVersion if "ProxyVersion" in obj.PropertiesList else 1
    _add(obj, "App::PropertyString", "ProxyType", "Version",
         "Kind of Contacts object (lets the workbench give a lost proxy back)", 2)
    _add(obj, "App::PropertyInteger", "ProxyVersion", "Version",
         "Version of the Contacts object's properties", 2)
    obj.ProxyType = proxy_type
    if saved > PROXY_VERSION:
        import FreeCAD
        FreeCAD.Console.PrintWarning(
            f"Contacts: '{obj.Label}' was saved by a newer Contacts (object version {saved}, "
            f"this one knows {PROXY_VERSION}); its newer properties are kept as they are\n")
    else:
        obj.ProxyVersion = PROXY_VERSION
    return saved


class _VersionedProxy:
    """What every Contacts proxy does on creation and restore: keep its type,
    add or migrate its version records, then its own properties (added only
    where missing, so older files gain the new ones)."""
    TYPE = None  # each proxy sets TYPE and add_properties(obj)

    def __init__(self, obj):
        obj.Proxy = self
        self.Type = self.TYPE
        _versioned(obj, self.TYPE)
        self.add_properties(obj)

    def onDocumentRestored(self, obj):
        obj.Proxy = self
        _versioned(obj, self.TYPE)
        self.add_properties(obj)

    def dumps(self):
        return None

    def loads(self, state):
        self.Type = self.TYPE


# Inputs the user sets (task panel or property editor), results shown read-only.
ANALYSIS_RESULTS = ("LinearTolerance", "AngularTolerance", "BodyCount", "Summary", "Messages")


def _analysis_properties(obj):
    if "Sources" in obj.PropertiesList and obj.getTypeIdOfProperty("Sources") == "App::PropertyLinkList":
        # 0.1 files: a local-scope link list, which refused objects inside App::Part (bug 5)
        old = list(obj.Sources)
        obj.removeProperty("Sources")
        obj.addProperty("App::PropertyXLinkSubList", "Sources", "Contacts", "")
        obj.Sources = [(o, [""]) for o in old]
    _add(obj, "App::PropertyXLinkSubList", "Sources", "Contacts",
         "Parts analysed, with their path in the document (Scope Selection or PartAgainstRest)")
    _add(obj, "App::PropertyEnumeration", "Scope", "Contacts",
         "Document: every visible solid; Selection: the Sources only; "
         "PartAgainstRest: the Sources against every other visible solid")
    if not obj.Scope:
        obj.Scope = SCOPES
        obj.Scope = "Selection" if obj.Sources else "Document"
    _add(obj, "App::PropertyLength", "LinearToleranceSetting", "Contacts",
         "Linear tolerance to use (0: scaled to the model)")
    _add(obj, "App::PropertyAngle", "AngularToleranceSetting", "Contacts",
         "Angular tolerance to use (0: the default)")
    _add(obj, "App::PropertyStringList", "ContactTypes", "Contacts",
         "Contact types to look for (empty: all)")
    _add(obj, "App::PropertyLength", "ClearanceGap", "Contacts",
         "Also report clearance fits whose radii differ by less than this (0: none)")
    _add(obj, "App::PropertyBool", "UpdateOnRecompute", "Contacts",
         "Find the contacts again when the bodies move or change (off: a snapshot that "
         "follows the moved faces)")
    _add(obj, "App::PropertyLength", "LinearTolerance", "Contacts", "Linear tolerance used", 1)
    _add(obj, "App::PropertyAngle", "AngularTolerance", "Contacts", "Angular tolerance used", 1)
    _add(obj, "App::PropertyInteger", "BodyCount", "Contacts", "Bodies analysed", 1)
    _add(obj, "App::PropertyStringList", "Summary", "Contacts", "Counts by contact type", 1)
    _add(obj, "App::PropertyStringList", "PairSummary", "Contacts", "Counts by body pair", 1)
    _add(obj, "App::PropertyStringList", "Messages", "Contacts", "What was skipped and why", 1)
    _add(obj, "App::PropertyStringList", "Clearances", "Contacts", "Clearance fits found", 1)
    # Hidden: what the analysis depends on, and the CLI's body table (export)
    _add(obj, "App::PropertyXLinkSubList", "Bodies", "Contacts", "Bodies analysed (their paths)", 2)
    _add(obj, "App::PropertyString", "BodyTable", "Contacts", "Bodies as JSON (name, path, volume, center)", 2)
    _add(obj, "App::PropertyInteger", "NumberBase", "Contacts", "Contact numbers start after this", 2)
    # Joints (stage 4): derived from the contacts when DeriveJoints is on
    _add(obj, "App::PropertyBool", "DeriveJoints", "Joints",
         "Also derive the joints each body pair's contacts allow, and the assembly's mobility")
    _add(obj, "App::PropertyString", "Ground", "Joints", "Body held still (empty: the largest by volume)")
    _add(obj, "App::PropertyStringList", "Mobility", "Joints", "Degrees of freedom and rigid groups", 1)
    _add(obj, "App::PropertyString", "LiaisonGraph", "Joints", "The liaison graph (Graphviz DOT)", 2)
    # version 2
    _add(obj, "App::PropertyInteger", "ContactCount", "Contacts", "Contacts found (shown in the group)", 1)
    _add(obj, "App::PropertyInteger", "JointCount", "Joints", "Joints derived", 1)


def count_children(obj):
    """Sets ContactCount and JointCount from the group's children."""
    obj.ContactCount = sum(1 for child in obj.Group if is_contact(child))
    obj.JointCount = sum(1 for child in obj.Group if is_joint(child))


def migrate_analysis(obj):
    """Brings a ContactAnalysis saved by an older version up to date: adds the
    properties it lacks with the values its saved contents give."""
    saved = _versioned(obj, "ContactAnalysis")
    fresh = "UpdateOnRecompute" not in obj.PropertiesList
    _analysis_properties(obj)
    if fresh:  # 0.1 files: analyses were always live
        obj.UpdateOnRecompute = True
    if saved < 2:
        count_children(obj)
    return saved


class ContactAnalysis:
    """A group holding the contacts found among some objects; recomputing it
    finds them again (in place) when its bodies moved or changed."""

    def __init__(self, obj):
        obj.Proxy = self
        self.Type = "ContactAnalysis"
        _versioned(obj, self.Type)
        _analysis_properties(obj)
        obj.UpdateOnRecompute = True
        watch_document(obj.Document)

    def onDocumentRestored(self, obj):
        obj.Proxy = self
        migrate_analysis(obj)
        watch_document(obj.Document)

    def execute(self, obj):
        if not obj.UpdateOnRecompute:
            return
        from contactwb.make.make_contact_analysis import update_contact_analysis
        update_contact_analysis(obj)

    def dumps(self):
        return None

    def loads(self, state):
        self.Type = "ContactAnalysis"


def _contact_properties(obj):
    _add(obj, "App::PropertyString", "ContactType", "Contact", "PLF, CLJ, CJU, SPF, LAF, SPT or TRF")
    _add(obj, "App::PropertyInteger", "Number", "Contact", "Number of the contact in its label")
    _add(obj, "App::PropertyString", "BodyA", "Contact", "First body")
    _add(obj, "App::PropertyString", "BodyB", "Contact", "Second body")
    _add(obj, "App::PropertyXLinkSubList", "FacesA", "Contact", "Faces of the first body in contact")
    _add(obj, "App::PropertyXLinkSubList", "FacesB", "Contact", "Faces of the second body in contact")
    _add(obj, "App::PropertyArea", "Area", "Contact", "Common area (0 for circle contacts)")
    _add(obj, "App::PropertyBool", "Partial", "Contact", "Revolution contact spanning under 180 degrees")
    _add(obj, "App::PropertyAngle", "Span", "Contact", "Common angular span")
    _add(obj, "App::PropertyLength", "Radius", "Contact", "Radius (cylinder, sphere, ball)")
    _add(obj, "App::PropertyAngle", "HalfAngle", "Contact", "Half-angle of the cone (CJU)")
    _add(obj, "App::PropertyVector", "Point", "Contact", "A point of the contact (axis point, centre)")
    _add(obj, "App::PropertyVector", "Direction", "Contact", "Normal of the first body, or axis")
    for name in obj.PropertiesList:
        if obj.getGroupOfProperty(name) == "Contact":
            obj.setEditorMode(name, 1)


class Contact(_VersionedProxy):
    """One functional contact: its type, the two bodies and their faces."""
    TYPE = "Contact"  # version 2 added only the version records
    add_properties = staticmethod(_contact_properties)


class _BodyWatcher:
    """Marks an analysis touched when a body it depends on moves, changes
    shape or is deleted (FreeCAD itself only recomputes it, silently)."""

    WATCHED = ("Placement", "Shape", "LinkPlacement", "LinkedObject", "Group")

    def __init__(self):
        self.documents = set()
        self.pending = {}  # document name -> contacts to remove once its recompute is over

    @staticmethod
    def _analyses(doc):
        return [o for o in doc.Objects
                if o.TypeId == "App::DocumentObjectGroupPython" and is_contact_analysis(o)]

    def _touch_dependents(self, obj, deleted=False):
        doc = obj.Document
        if doc.Name not in self.documents or is_contact(obj) or is_contact_analysis(obj) or is_joint(obj):
            return
        for group in self._analyses(doc):
            if not getattr(group, "UpdateOnRecompute", False):
                continue
            if group.Name == obj.Name or "Touched" in group.State:
                continue
            if obj in group.OutListRecursive:
                group.touch()

    def slotChangedObject(self, obj, prop):
        if prop not in self.WATCHED:
            return
        try:
            self._touch_dependents(obj)
        except Exception:  # an observer must never break an edit
            pass

    def slotCreatedObject(self, obj):
        # a new part (or one brought back by an undo): the document-wide
        # analyses may have missed its contacts
        try:
            doc = obj.Document
            if doc.Recomputing or doc.Name not in self.documents:
                return
            if not (hasattr(obj, "Shape") or obj.isDerivedFrom("App::Link") or obj.isDerivedFrom("App::Part")):
                return
            for group in self._analyses(doc):
                if group.UpdateOnRecompute and group.Scope != "Selection":
                    group.touch()
        except Exception:
            pass

    def slotRecomputedDocument(self, doc):
        names = self.pending.pop(doc.Name, [])
        for name in names:
            if doc.getObject(name) is not None:
                doc.removeObject(name)

    def slotDeletedObject(self, obj):
        try:
            self._touch_dependents(obj, deleted=True)
        except Exception:
            pass


_watcher = None


def watch_document(doc):
    """Installs (once) the observer marking this document's analyses touched."""
    global _watcher
    import FreeCAD
    if _watcher is None:
        _watcher = _BodyWatcher()
        FreeCAD.addDocumentObserver(_watcher)
    _watcher.documents.add(doc.Name)


def pending_removal(doc, names):
    """Contacts to remove once the document's recompute is over."""
    watch_document(doc)
    _watcher.pending.setdefault(doc.Name, []).extend(names)


def is_joint(obj):
    """Whether a document object is one Joint of an analysis."""
    return getattr(getattr(obj, "Proxy", None), "Type", None) == "Joint"


def _joint_properties(obj):
    _add(obj, "App::PropertyString", "JointType", "Joint",
         "ISO 3952 name: rigid, revolute, prismatic, helical, cylindrical, spherical, planar, ...")
    _add(obj, "App::PropertyInteger", "DOF", "Joint", "Degrees of freedom of body B relative to body A")
    _add(obj, "App::PropertyString", "BodyA", "Joint", "First body")
    _add(obj, "App::PropertyString", "BodyB", "Joint", "Second body (moving relative to the first)")
    _add(obj, "App::PropertyVectorList", "AxisPoints", "Joint", "A point of each rotation axis (mm)")
    _add(obj, "App::PropertyVectorList", "AxisDirections", "Joint", "Direction of each rotation axis")
    _add(obj, "App::PropertyVectorList", "Translations", "Joint", "Directions of free translation")
    _add(obj, "App::PropertyVectorList", "FreeDirections", "Joint",
         "Generators of the cone of directions in which B can leave A")
    _add(obj, "App::PropertyVector", "Centre", "Joint", "Centre of the pair's contacts (where glyphs are drawn)")
    _add(obj, "App::PropertyLength", "GlyphLength", "Joint", "Length of the axis glyphs")
    _add(obj, "App::PropertyLinkListHidden", "Contacts", "Joint", "The contacts making this joint")
    for name in obj.PropertiesList:
        if obj.getGroupOfProperty(name) == "Joint":
            obj.setEditorMode(name, 1)


class Joint(_VersionedProxy):
    """The kinematic joint two bodies' contacts allow (contactcore.find_joints)."""
    TYPE = "Joint"  # version 2 added only the version records
    add_properties = staticmethod(_joint_properties)
