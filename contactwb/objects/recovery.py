"""Gives Contacts objects back their proxies after a round trip through a
FreeCAD without the workbench, and their view providers in the GUI.

FreeCAD 0.20 opening a document whose proxy module cannot be imported keeps
every property but sets the proxy to None; saving it then writes the proxy as
null, so the file no longer names `contactwb.objects.contact_objects`. The
objects are recognised here by their ProxyType property (version 2) or, for
older files, by the properties only their kind has, and get a fresh proxy,
migrated like any restored object. Documents made headless (no view provider
saved) get their view providers the same way when opened in the GUI (through
contactwb.objects.gui_hooks: contactwb/gui/viewproviders/attach.py).

The workbench's Init.py installs the observer (watch_restores); FreeCAD 0.20's
Python observers have no "restore finished" slot, but a document opened is
activated once it is fully restored."""
import FreeCAD

from contactwb.objects import contact_objects, gui_hooks, interferences, simulation_model

PROXY_CLASSES = {
    "ContactAnalysis": contact_objects.ContactAnalysis,
    "Contact": contact_objects.Contact,
    "Joint": contact_objects.Joint,
    "SimulationModel": simulation_model.SimulationModel,
    "Interference": interferences.Interference,
    "InterferenceGroup": interferences.InterferenceGroup,
}
# Version 1 files have no ProxyType: the properties only that kind has.
SIGNATURES = (
    ("ContactAnalysis", "App::DocumentObjectGroupPython", {"Scope", "BodyTable", "NumberBase", "Summary"}),
    ("Contact", "App::FeaturePython", {"ContactType", "BodyA", "BodyB", "FacesA", "FacesB"}),
    ("Joint", "App::FeaturePython", {"JointType", "DOF", "AxisDirections", "FreeDirections"}),
)


def proxy_type(obj):
    """The Contacts kind of a document object, with or without its proxy (None: not ours)."""
    if "ProxyType" in obj.PropertiesList and obj.ProxyType in PROXY_CLASSES:
        return obj.ProxyType
    properties = set(obj.PropertiesList)
    for kind, type_id, signature in SIGNATURES:
        if obj.TypeId == type_id and signature <= properties:
            return kind
    return None


def lost_proxy(obj):
    """Whether `obj` is a Contacts object whose proxy is gone."""
    if obj.TypeId not in ("App::FeaturePython", "App::DocumentObjectGroupPython", "Part::FeaturePython"):
        return False
    return getattr(obj, "Proxy", None) is None and proxy_type(obj) is not None


def restore_proxies(doc):
    """Gives every Contacts object of `doc` that lost its proxy a new one,
    migrated to the current version. Returns the names of the objects restored."""
    restored = []
    lost = [obj for obj in doc.Objects if lost_proxy(obj)]
    # analyses last: their migration counts their children, known by their proxies
    lost.sort(key=lambda obj: proxy_type(obj) == "ContactAnalysis")
    for obj in lost:
        kind = proxy_type(obj)
        proxy = PROXY_CLASSES[kind].__new__(PROXY_CLASSES[kind])
        proxy.loads(None)
        touched = "Touched" in obj.State
        obj.Proxy = proxy
        proxy.onDocumentRestored(obj)
        if not touched:
            obj.purgeTouched()  # its results are the saved ones: no recompute needed
        restored.append(obj.Name)
    if restored:
        FreeCAD.Console.PrintMessage(
            f"Contacts: {len(restored)} objects of '{doc.Label}' saved without the workbench "
            f"are Contacts objects again\n")
    # view providers too, once the GUI document has restored its own (the GUI's hook)
    gui_hooks.document_restored(doc.Name)
    return restored


class _RestoreWatcher:
    def slotActivateDocument(self, doc):
        try:
            if not doc.Restoring:
                restore_proxies(doc)
        except Exception as error:  # never break opening a document
            FreeCAD.Console.PrintError(f"Contacts: cannot restore the objects of '{doc.Label}': {error}\n")

    # FreeCAD 0.21 and later call it (0.20 has no such Python slot)
    slotFinishRestoreDocument = slotActivateDocument


_watcher = None


def watch_restores():
    """Installs (once) the observer restoring proxies of opened documents."""
    global _watcher
    if _watcher is None:
        _watcher = _RestoreWatcher()
        FreeCAD.addDocumentObserver(_watcher)
