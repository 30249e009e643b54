"""make_contact_analysis(): find the contacts of a document (a selection, or
one part against the rest) and record them in the tree as a ContactAnalysis
group of Contact objects, headless. Finding them again in place is the
group's own recompute (contactwb.objects.contact_objects.update_contact_analysis)."""

import FreeCAD

from contactwb.core.kinds import CONTACT_TYPES, SCOPES
from contactwb.document.identify import is_contact, is_contact_analysis
from contactwb.objects import gui_hooks
from contactwb.objects.contact_objects import ContactAnalysis, set_tolerance_settings, update_contact_analysis
from contactwb.objects.contact_objects import contact_label, contact_label2  # noqa: F401  (their old home)


def _source_entries(objects):
    """XLinkSub entries of objects or (object, [subnames]) selection entries,
    without contact analyses and contacts (selected while re-running)."""
    entries = []
    for entry in objects or []:
        obj, subnames = entry if isinstance(entry, tuple) else (entry, [""])
        if is_contact_analysis(obj) or is_contact(obj):
            continue
        entries.append((obj, list(subnames) or [""]))
    return entries


def _scope_key(entries):
    return sorted((obj.Name, tuple(sorted(s for s in subnames if s))) for obj, subnames in entries)


def analysis_of_scope(doc, scope, objects=None):
    """The document's analysis with this scope and these parts (objects or
    selection entries, as make_contact_analysis takes them), or None: Find
    contacts run again on the same scope updates it instead of adding one."""
    entries = _source_entries(objects) if scope != "Document" else []
    wanted = _scope_key(entries)
    for group in doc.Objects:
        if not is_contact_analysis(group) or group.Scope != scope:
            continue
        if scope == "Document" or _scope_key((o, list(subs)) for o, subs in group.Sources) == wanted:
            return group
    return None


def make_contact_analysis(doc=None, objects=None, linear=None, angular=None, progress=None,
                          name="Contacts", scope=None, types=None, clearance_gap=0.0, group=None,
                          derive_joints=None):
    """Runs contact identification and records the result in `doc`.

    objects: the parts (objects, or (object, [subnames]) entries as the
    selection gives them); scope: "Document" (default without objects),
    "Selection" (default with objects: only those) or "PartAgainstRest" (the
    objects against every other visible solid). linear (mm) / angular (rad):
    tolerances, None for the model's defaults; types: contact types kept
    (None: all). group: an existing ContactAnalysis to update in place
    instead of adding one. derive_joints: also derive the joints (None:
    keep the group's setting). Returns the ContactAnalysis; raises
    contactwb.core.ContactsError on bad input and contactwb.core.Cancelled
    when `progress` cancels (nothing is added then)."""
    doc = doc or (group.Document if group is not None else FreeCAD.ActiveDocument)
    if doc is None:
        raise ValueError("no document")
    entries = _source_entries(objects)
    scope = scope or ("Selection" if entries else "Document")
    if scope not in SCOPES:
        raise ValueError(f"unknown scope '{scope}' (use one of {', '.join(SCOPES)})")
    unknown = sorted(set(types or []) - set(CONTACT_TYPES))
    if unknown:
        raise ValueError(f"unknown contact types {unknown} (use {', '.join(CONTACT_TYPES)})")
    created = group is None
    if created:
        group = doc.addObject("App::DocumentObjectGroupPython", name)
        ContactAnalysis(group)
        gui_hooks.new_object(group)
    previous = {key: getattr(group, key) for key in
                ("Scope", "Sources", "LinearToleranceSetting", "AngularToleranceSetting",
                 "ContactTypes", "ClearanceGap", "DeriveJoints")}
    group.Scope = scope
    group.Sources = entries
    set_tolerance_settings(group, linear, angular)
    group.ContactTypes = list(types or [])
    group.ClearanceGap = clearance_gap or 0.0
    if derive_joints is not None:
        group.DeriveJoints = bool(derive_joints)
    try:
        update_contact_analysis(group, progress)
    except BaseException:
        if created:
            doc.removeObject(group.Name)
        else:
            for key, value in previous.items():
                setattr(group, key, value)
        raise
    group.purgeTouched()
    gui_hooks.analysis_found(group)
    return group
