"""The interferences of a contact analysis (bodies whose material overlaps: a
modelling error, not a contact), as interference checkers show them: an
Interferences group under the analysis holding one Interference per
overlapping pair, its common volume and the overlapping solid as its Shape
(drawn red by the GUI). The analysis' recompute creates, updates and removes
them (update_interferences), inside its own undo entry; the group exists
while there is at least one interference.

Identity: an interference is its body pair. Found again, it keeps its object,
name and number (`I3`); a new pair gets the next number never issued in the
document (the analyses' hidden LastInterferenceNumber), so two analyses never
share one.

Saved files name `contactwb.objects.interferences.InterferenceGroup` and
`...Interference` (files saved before this module name
`contactwb.objects.contact_objects.Interference`, which is the same class):
permanent names."""
from contactwb.document import units
from contactwb.document.identify import interferences_of, is_contact, is_interference, is_interference_group
from contactwb.document.shapes import shape_from_brep
from contactwb.objects import gui_hooks
from contactwb.objects.base import VersionedProxy, add_read_only_group, set_if_changed
from contactwb.objects.body_watcher import remove_after_recompute

EN_DASH = "\u2013"
GROUP_LABEL = "Interferences"


def _interference_properties(obj):
    add_read_only_group(obj, "Interference", [
        ("App::PropertyString", "BodyA", "First body"),
        ("App::PropertyString", "BodyB", "Second body"),
        ("App::PropertyVolume", "Volume", "Volume of the material both bodies occupy (its solid is the Shape)"),
        ("App::PropertyInteger", "Number", "Number of the interference in its label (I1, I2, ...)"),
    ])


class Interference(VersionedProxy):
    """Two bodies whose material overlaps (a modelling error, not a contact):
    the pair, the common volume, and the overlapping solid as its Shape (a
    Part feature, so it shows in the view; the GUI draws it red)."""
    TYPE = "Interference"
    add_properties = staticmethod(_interference_properties)


def _group_properties(obj):
    add_read_only_group(obj, "Interferences", [
        ("App::PropertyInteger", "Count", "Overlapping pairs of bodies in the group"),
        ("App::PropertyVolume", "TotalVolume", "Sum of the overlapping volumes"),
    ])


class InterferenceGroup(VersionedProxy):
    """The Interferences group of an analysis (an App::DocumentObjectGroupPython
    child of the ContactAnalysis): its Interference objects."""
    TYPE = "InterferenceGroup"
    add_properties = staticmethod(_group_properties)


def interference_label(number, a, b):
    """"I2: Body – Screw-1": the table's number, the pair (the volume is in
    the description column, as a contact's area)."""
    return f"I{number}: {a} {EN_DASH} {b}"


def volume_text(volume):
    """As the property editor writes the Volume (the user's unit schema)."""
    return units.volume_text(volume)


def relabel(analysis):
    """The interferences' volumes written again (the user changed the unit schema)."""
    holders = [o for o in analysis.Group if is_interference_group(o)]
    found = [o for o in interferences_of(analysis)]
    for obj in found:
        set_if_changed(obj, "Label2", volume_text(obj.Volume.Value))
    for holder in holders:
        set_if_changed(holder, "Label2", f"{holder.Count}, {volume_text(holder.TotalVolume.Value)}")
    set_if_changed(analysis, "Interferences", [f"{o.BodyA} {EN_DASH} {o.BodyB}: {volume_text(o.Volume.Value)}"
                                               for o in found])


def _same_solid(old, new):
    """Whether an interference's stored solid is already `new` (unchanged
    bodies: nothing to record)."""
    if old.isNull() or new.isNull():
        return old.isNull() == new.isNull()
    return abs(old.Volume - new.Volume) <= 1e-9 * max(1.0, abs(new.Volume)) and \
        (old.BoundBox.Center - new.BoundBox.Center).Length <= 1e-9 and \
        abs(old.BoundBox.DiagonalLength - new.BoundBox.DiagonalLength) <= 1e-9


def _highest_number(doc):
    """The highest interference number issued in the document (by any
    analysis, also to interferences since removed)."""
    highest = 0
    for obj in doc.Objects:
        if is_interference(obj):
            highest = max(highest, getattr(obj, "Number", 0))
        highest = max(highest, getattr(obj, "LastInterferenceNumber", 0) or 0)
    return highest


def _interference_group(doc, analysis):
    """The analysis' Interferences group, made when missing."""
    for child in analysis.Group:
        if is_interference_group(child):
            return child
    holder = doc.addObject("App::DocumentObjectGroupPython", "Interferences")
    InterferenceGroup(holder)
    holder.Label = GROUP_LABEL
    gui_hooks.new_object(holder)
    return holder


def update_interferences(doc, analysis, interferences, bodies, solids=None):
    """The analysis' Interferences group and its Interference objects after a
    search: `interferences` the core's [(body A, body B, volume)], `solids`
    {pair: BRep text} the core's overlapping solids (else the Boolean common
    of the two bodies, made only for the pairs the core found overlapping).
    A pair found again keeps its object and number; vanished pairs are
    removed, and the group with them when none is left."""
    solids = solids or {}
    by_name = {b.name: b for b in bodies}
    old = {}
    for obj in interferences_of(analysis):
        old.setdefault((obj.BodyA, obj.BodyB), obj)
    holders = [o for o in analysis.Group if is_interference_group(o)]
    highest = max(_highest_number(doc), analysis.LastInterferenceNumber)
    found = []
    for a, b, volume in interferences:
        obj = old.pop((a, b), None)
        if obj is None:
            obj = doc.addObject("Part::FeaturePython", "Interference")
            Interference(obj)
            gui_hooks.new_object(obj)
        if not obj.Number:  # new, or saved before interferences had numbers
            highest += 1
            obj.Number = highest
        set_if_changed(obj, "BodyA", a)
        set_if_changed(obj, "BodyB", b)
        set_if_changed(obj, "Volume", volume)
        if (a, b) in solids or (a in by_name and b in by_name):
            common = shape_from_brep(solids[(a, b)]) if (a, b) in solids else by_name[a].shape.common(by_name[b].shape)
            if not _same_solid(obj.Shape, common):
                obj.Shape = common
        set_if_changed(obj, "Label", interference_label(obj.Number, a, b))
        set_if_changed(obj, "Label2", volume_text(volume))
        found.append(obj)
    set_if_changed(analysis, "LastInterferenceNumber", highest)
    contacts = [o for o in analysis.Group if is_contact(o)]
    others = [o for o in analysis.Group if not is_contact(o) and not is_interference(o)
              and not is_interference_group(o)]
    holder = _interference_group(doc, analysis) if found else None
    # out of the analysis first (an object belongs to one group), then into its group
    set_if_changed(analysis, "Group", contacts + ([holder] if holder else []) + others)
    removed = list(old.values()) + [h for h in holders if h is not holder]
    for extra in holders:
        if extra is not holder:
            set_if_changed(extra, "Group", [])
    if holder is not None:
        set_if_changed(holder, "Group", found)
        set_if_changed(holder, "Count", len(found))
        set_if_changed(holder, "TotalVolume", sum(o.Volume.Value for o in found))
        set_if_changed(holder, "Label2", f"{len(found)}, {volume_text(holder.TotalVolume.Value)}")
    remove_after_recompute(doc, removed)
    set_if_changed(analysis, "InterferenceCount", len(found))
    set_if_changed(analysis, "Interferences", [f"{o.BodyA} {EN_DASH} {o.BodyB}: {volume_text(o.Volume.Value)}"
                                               for o in found])
    for obj in found + ([holder] if holder else []):
        obj.purgeTouched()
