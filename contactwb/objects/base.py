"""What every Contacts proxy shares: properties added only where missing (so
files saved by older versions gain the new ones) and the version records."""

# Version of the objects' properties, saved in each object's ProxyVersion.
# A property, not the proxy's dumps() state: FreeCAD 0.20 opening a file
# without the workbench drops the proxy, and saving writes it as null; plain
# properties survive (contactwb.objects.recovery gives the proxy back).
#   1: files saved before ProxyVersion existed (0.1.0);
#   2: ProxyType, ProxyVersion; the analysis counts its contacts and joints.
PROXY_VERSION = 2


def add_property(obj, kind, name, group, doc, mode=None):
    """Adds a property unless the object has it (files saved by older versions)."""
    if name not in obj.PropertiesList:
        obj.addProperty(kind, name, group, doc)
    if mode is not None:
        obj.setEditorMode(name, mode)


def add_read_only_group(obj, group, properties):
    """Adds the (kind, name, doc) properties of `group` where missing, and makes
    every property of the group read-only (results a recompute writes)."""
    for kind, name, doc in properties:
        add_property(obj, kind, name, group, doc)
    for name in obj.PropertiesList:
        if obj.getGroupOfProperty(name) == group:
            obj.setEditorMode(name, 1)


def versioned(obj, proxy_type):
    """Adds the type and version records; returns the version the object was
    saved with (1: before they existed)."""
    saved = obj.ProxyVersion if "ProxyVersion" in obj.PropertiesList else 1
    add_property(obj, "App::PropertyString", "ProxyType", "Version",
                 "Kind of Contacts object (lets the workbench give a lost proxy back)", 2)
    add_property(obj, "App::PropertyInteger", "ProxyVersion", "Version",
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


class VersionedProxy:
    """What every Contacts proxy does on creation and restore: keep its type,
    add or migrate its version records, then its own properties (added only
    where missing, so older files gain the new ones)."""
    TYPE = None  # each proxy sets TYPE and add_properties(obj)

    def __init__(self, obj):
        obj.Proxy = self
        self.Type = self.TYPE
        versioned(obj, self.TYPE)
        self.add_properties(obj)

    def onDocumentRestored(self, obj):
        obj.Proxy = self
        versioned(obj, self.TYPE)
        self.add_properties(obj)

    def dumps(self):
        return None

    def loads(self, state):
        self.Type = self.TYPE


def _comparable(value):
    if hasattr(value, "Value") and hasattr(value, "Unit"):  # a Quantity
        return round(value.Value, 12)
    if isinstance(value, float):
        return round(value, 12)
    if isinstance(value, (list, tuple)):
        return [_comparable(v) for v in value]
    if hasattr(value, "Name") and hasattr(value, "Document"):  # a document object
        return value.Name
    if hasattr(value, "x") and hasattr(value, "z"):  # a vector
        return (round(value.x, 12), round(value.y, 12), round(value.z, 12))
    return value


def set_if_changed(obj, name, value, ordered=True):
    """Assigns only a new value: an unchanged result records nothing in the
    undo history and touches nothing. ordered=False: a list compared as a
    set (FreeCAD may reorder a link list's entries)."""
    old, new = _comparable(getattr(obj, name)), _comparable(value)
    if not ordered:
        old, new = sorted(map(repr, old)), sorted(map(repr, new))
    if old != new:
        setattr(obj, name, value)
