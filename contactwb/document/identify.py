"""What a document object is, for the workbench: its Contacts kind read from
its proxy's Type (duck typing, so it also works once a file is re-opened).
The proxies themselves are in contactwb.objects; the layers below them (the
document walk, the export) ask here."""

CONTACT_ANALYSIS = "ContactAnalysis"
CONTACT = "Contact"
JOINT = "Joint"
SIMULATION_MODEL = "SimulationModel"
INTERFERENCE = "Interference"
INTERFERENCE_GROUP = "InterferenceGroup"


def proxy_kind(obj):
    """The Type of the object's proxy (None: no proxy, or not ours)."""
    return getattr(getattr(obj, "Proxy", None), "Type", None)


def is_contact_analysis(obj):
    """Whether a document object is a ContactAnalysis group (also once re-opened)."""
    return proxy_kind(obj) == CONTACT_ANALYSIS


def is_contact(obj):
    """Whether a document object is one Contact of an analysis."""
    return proxy_kind(obj) == CONTACT


def is_joint(obj):
    """Whether a document object is one Joint of an analysis."""
    return proxy_kind(obj) == JOINT


def is_simulation_model(obj):
    """Whether a document object is a SimulationModel (also once re-opened)."""
    return proxy_kind(obj) == SIMULATION_MODEL


def is_interference(obj):
    """Whether a document object is one Interference of an analysis (two
    bodies' overlapping material, its solid as its Shape)."""
    return proxy_kind(obj) == INTERFERENCE


def is_interference_group(obj):
    """Whether a document object is the Interferences group of an analysis
    (its Interference objects, in the tree under the analysis)."""
    return proxy_kind(obj) == INTERFERENCE_GROUP


def interferences_of(analysis):
    """The Interference objects of an analysis: those of its Interferences
    group (and any held directly, as files saved before the group did)."""
    found = []
    for child in getattr(analysis, "Group", []):
        if is_interference(child):
            found.append(child)
        elif is_interference_group(child):
            found.extend(o for o in child.Group if is_interference(o))
    return found


def is_workbench_result(obj):
    """The workbench's own results (they link to bodies; an interference's
    solid is a result, never a body to analyse)."""
    return proxy_kind(obj) in (CONTACT_ANALYSIS, CONTACT, SIMULATION_MODEL, INTERFERENCE, INTERFERENCE_GROUP)


def analyses(doc):
    """The ContactAnalysis groups of a document. (Cheap enough for a
    command's IsActive on large documents: the type is checked first.)"""
    if doc is None:
        return []
    return [obj for obj in doc.Objects
            if obj.TypeId == "App::DocumentObjectGroupPython" and is_contact_analysis(obj)]


def is_alive(doc, obj):
    """Whether `obj` is still this document's object: not deleted, nor
    replaced by an undo (which brings back a new object of the same name);
    a reference kept across an undo must be checked before use."""
    if obj is None or doc is None:
        return False
    try:
        return doc.getObject(obj.Name) is obj
    except Exception:  # deleted: its attributes raise
        return False
