"""Proxies of the contact analysis (a group), of each contact and each joint
(its children), and their recompute.

Saved files refer to `contactwb.objects.contact_objects.ContactAnalysis`,
`...Contact` and `...Joint`: these names are permanent.

An analysis is live: it links every body it analysed (hidden `Bodies`), so it
is recomputed after they move or change shape, and `execute` finds the
contacts again (update_contact_analysis), updating its Contact and Joint
children in place. A document observer (contactwb.objects.body_watcher) marks
it touched as soon as one of its bodies moves, changes or is deleted, so the
tree shows it out of date before the recompute. New children get their view
providers through contactwb.objects.gui_hooks (set by the GUI)."""
import json
from math import degrees, radians

import FreeCAD

from contactwb import core
from contactwb.core import analysis as contact_analysis
from contactwb.core.kinds import CIRCLE_TYPES, CONTACT_TYPES, SCOPES  # noqa: F401  (SCOPES: this module's API)
from contactwb.document import bodies as document_bodies
from contactwb.document import units
from contactwb.document.units import tolerance_settings  # noqa: F401  (this module's API)
from contactwb.document.identify import (is_contact, is_contact_analysis, is_interference,  # noqa: F401
                                         is_interference_group, is_joint)
from contactwb.document.shapes import assembly_from_shapes, shape_from_brep
from contactwb.objects import gui_hooks, regions
from contactwb.objects.base import (PROXY_VERSION, VersionedProxy, add_property, add_read_only_group,  # noqa: F401
                                     set_if_changed, versioned)
from contactwb.objects.interferences import Interference, update_interferences  # noqa: F401  (saved files' name)
from contactwb.objects.body_watcher import (pending_removal, remove_after_recompute,  # noqa: F401
                                            watch_document)


# Inputs the user sets (task panel or property editor), results shown read-only.
ANALYSIS_RESULTS = ("LinearTolerance", "AngularTolerance", "BodyCount", "Summary", "Messages")
# The tolerance settings (text properties: the property editor shows them as typed, in any unit) and
# their units; the tolerances used, as text, and their exact values (issue 21 item 11).
TOLERANCE_SETTINGS = {"LinearToleranceSetting": units.LENGTH_UNIT, "AngularToleranceSetting": units.ANGLE_UNIT}
TOLERANCES_USED = {"LinearTolerance": ("LinearToleranceValue", units.LENGTH_UNIT),
                   "AngularTolerance": ("AngularToleranceValue", units.ANGLE_UNIT)}


def _tolerances_as_text(obj):
    """Files saved before 0.3 held the tolerances as quantities (App::PropertyLength and
    App::PropertyAngle, 0: the default): their values become the text properties' (and the hidden
    exact values'), so that such a file opens as it was and recomputes the same."""
    for name, unit in TOLERANCE_SETTINGS.items():
        if name in obj.PropertiesList and obj.getTypeIdOfProperty(name) != "App::PropertyString":
            value = getattr(obj, name).Value
            obj.removeProperty(name)
            obj.addProperty("App::PropertyString", name, "Contacts", "")
            setattr(obj, name, units.setting_text(value or None, unit))
    for name, (value_name, unit) in TOLERANCES_USED.items():
        if name in obj.PropertiesList and obj.getTypeIdOfProperty(name) != "App::PropertyString":
            value = getattr(obj, name).Value
            obj.removeProperty(name)
            kind = "App::PropertyLength" if unit == units.LENGTH_UNIT else "App::PropertyAngle"
            add_property(obj, kind, value_name, "Contacts", "", 2)
            setattr(obj, value_name, value)
            obj.addProperty("App::PropertyString", name, "Contacts", "")
            setattr(obj, name, units.tolerance_text(value, unit))


def set_tolerance_settings(group, linear, angular):
    """Writes the settings (linear mm, angular rad; None: the default) as text."""
    set_if_changed(group, "LinearToleranceSetting", units.setting_text(linear, units.LENGTH_UNIT))
    set_if_changed(group, "AngularToleranceSetting",
                   units.setting_text(degrees(angular) if angular else None, units.ANGLE_UNIT))


def _normalize_setting(obj, name):
    """A setting typed in the property editor ("0.5 um") rewritten as the panel
    writes it ("0.0005 mm"), so that both say the same; text that is not a
    tolerance is left as typed (the recompute names it)."""
    unit = TOLERANCE_SETTINGS[name]
    try:
        value = units.parse_setting(getattr(obj, name), unit)
    except ValueError:
        return
    text = units.setting_text(value, unit)
    if getattr(obj, name) != text:
        setattr(obj, name, text)


def _analysis_properties(obj):
    if "Sources" in obj.PropertiesList and obj.getTypeIdOfProperty("Sources") == "App::PropertyLinkList":
        # 0.1 files: a local-scope link list, which refused objects inside App::Part (bug 5)
        old = list(obj.Sources)
        obj.removeProperty("Sources")
        obj.addProperty("App::PropertyXLinkSubList", "Sources", "Contacts", "")
        obj.Sources = [(o, [""]) for o in old]
    add_property(obj, "App::PropertyXLinkSubList", "Sources", "Contacts",
         "Parts analysed, with their path in the document (Scope Selection or PartAgainstRest)")
    add_property(obj, "App::PropertyEnumeration", "Scope", "Contacts",
         "Document: every visible solid; Selection: the Sources only; "
         "PartAgainstRest: the Sources against every other visible solid")
    if not obj.Scope:
        obj.Scope = SCOPES
        obj.Scope = "Selection" if obj.Sources else "Document"
    _tolerances_as_text(obj)  # files saved before the tolerances were text (0.2)
    add_property(obj, "App::PropertyString", "LinearToleranceSetting", "Contacts",
         "Linear tolerance to use, in any length unit ('0.001 mm', '0.5 um'; "
         f"'{units.DEFAULT_SETTING[units.LENGTH_UNIT]}': the core chooses)")
    add_property(obj, "App::PropertyString", "AngularToleranceSetting", "Contacts",
         "Angular tolerance to use, in any angle unit ('0.01 deg', '2e-4 rad'; "
         f"'{units.DEFAULT_SETTING[units.ANGLE_UNIT]}': the core's)")
    for name, unit in TOLERANCE_SETTINGS.items():
        if not getattr(obj, name):
            setattr(obj, name, units.setting_text(None, unit))
    add_property(obj, "App::PropertyStringList", "ContactTypes", "Contacts",
         "Contact types to look for (empty: all)")
    add_property(obj, "App::PropertyLength", "ClearanceGap", "Contacts",
         "Also report clearance fits whose radii differ by less than this, and coaxial overlaps "
         "(press fits drawn oversize) by less than this (0: none)")
    add_property(obj, "App::PropertyBool", "UpdateOnRecompute", "Contacts",
         "Find the contacts again when the bodies move or change (off: a snapshot that "
         "follows the moved faces)")
    # the tolerances used: as the panel writes them, the exact values hidden (export, expressions)
    add_property(obj, "App::PropertyString", "LinearTolerance", "Contacts", "Linear tolerance used", 1)
    add_property(obj, "App::PropertyString", "AngularTolerance", "Contacts", "Angular tolerance used", 1)
    add_property(obj, "App::PropertyLength", "LinearToleranceValue", "Contacts", "Linear tolerance used, exact", 2)
    add_property(obj, "App::PropertyAngle", "AngularToleranceValue", "Contacts", "Angular tolerance used, exact", 2)
    add_property(obj, "App::PropertyInteger", "BodyCount", "Contacts", "Bodies analysed", 1)
    add_property(obj, "App::PropertyStringList", "Summary", "Contacts", "Counts by contact type", 1)
    add_property(obj, "App::PropertyStringList", "PairSummary", "Contacts", "Counts by body pair", 1)
    add_property(obj, "App::PropertyStringList", "Messages", "Contacts", "What was skipped and why", 1)
    add_property(obj, "App::PropertyStringList", "Clearances", "Contacts", "Clearance fits found", 1)
    # Hidden: what the analysis depends on, and the CLI's body table (export)
    add_property(obj, "App::PropertyXLinkSubList", "Bodies", "Contacts", "Bodies analysed (their paths)", 2)
    add_property(obj, "App::PropertyString", "BodyTable", "Contacts", "Bodies as JSON (name, path, volume, center)", 2)
    add_property(obj, "App::PropertyInteger", "NumberBase", "Contacts", "Contact numbers start after this", 2)
    # Joints (stage 4): derived from the contacts when DeriveJoints is on
    add_property(obj, "App::PropertyBool", "DeriveJoints", "Joints",
         "Also derive the joints each body pair's contacts allow, and the assembly's mobility")
    add_property(obj, "App::PropertyString", "Ground", "Joints", "Body held still (empty: the largest by volume)")
    add_property(obj, "App::PropertyStringList", "Mobility", "Joints", "Degrees of freedom and rigid groups", 1)
    add_property(obj, "App::PropertyString", "LiaisonGraph", "Joints", "The liaison graph (Graphviz DOT)", 2)
    # version 2
    add_property(obj, "App::PropertyInteger", "ContactCount", "Contacts", "Contacts found (shown in the group)", 1)
    add_property(obj, "App::PropertyInteger", "JointCount", "Joints", "Joints derived", 1)
    # numbers by identity, never given twice in a document (added where missing)
    add_property(obj, "App::PropertyInteger", "LastNumber", "Contacts", "Highest contact number issued", 2)
    # recorded in the undo history with the edits and recomputes, so that an
    # undo or redo knows whether the contacts it restores are current
    add_property(obj, "App::PropertyBool", "OutOfDate", "Contacts", "Bodies changed since the last search", 2)
    add_property(obj, "App::PropertyInteger", "InterferenceCount", "Contacts",
                 "Pairs of bodies whose material overlaps", 1)
    add_property(obj, "App::PropertyStringList", "Interferences", "Contacts",
                 "Overlapping pairs with their common volume", 1)
    add_property(obj, "App::PropertyInteger", "LastInterferenceNumber", "Contacts",
                 "Highest interference number issued (I1, I2, ...)", 2)
    # the designer's annotations by contact identity, so that a contact lost and found again (a part
    # moved away and back) gets its intent and fit back
    add_property(obj, "App::PropertyString", "Annotations", "Contacts",
                 "Intent and fit of each annotated contact, by body pair and faces (JSON)", 2)


def count_children(obj):
    """Sets ContactCount and JointCount from the group's children."""
    contacts = sum(1 for child in obj.Group if is_contact(child))
    joints = sum(1 for child in obj.Group if is_joint(child))
    if obj.ContactCount != contacts:
        obj.ContactCount = contacts
    if obj.JointCount != joints:
        obj.JointCount = joints


def migrate_analysis(obj):
    """Brings a ContactAnalysis saved by an older version up to date: adds the
    properties it lacks with the values its saved contents give."""
    saved = versioned(obj, "ContactAnalysis")
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
        versioned(obj, self.Type)
        _analysis_properties(obj)
        obj.UpdateOnRecompute = True
        watch_document(obj.Document)

    def onDocumentRestored(self, obj):
        obj.Proxy = self
        migrate_analysis(obj)
        watch_document(obj.Document)

    def onChanged(self, obj, prop):
        if prop in TOLERANCE_SETTINGS and not obj.Document.Restoring \
                and obj.getTypeIdOfProperty(prop) == "App::PropertyString":
            _normalize_setting(obj, prop)

    def execute(self, obj):
        if not obj.UpdateOnRecompute:
            return
        update_contact_analysis(obj)

    def dumps(self):
        return None

    def loads(self, state):
        self.Type = "ContactAnalysis"


def _contact_properties(obj):
    add_read_only_group(obj, "Contact", [
        ("App::PropertyString", "ContactType", ", ".join(CONTACT_TYPES[:-1]) + " or " + CONTACT_TYPES[-1]),
        ("App::PropertyInteger", "Number", "Number of the contact in its label"),
        ("App::PropertyString", "BodyA", "First body"),
        ("App::PropertyString", "BodyB", "Second body"),
        ("App::PropertyXLinkSubList", "FacesA", "Faces of the first body in contact"),
        ("App::PropertyXLinkSubList", "FacesB", "Faces of the second body in contact"),
        ("App::PropertyArea", "Area", "Common area (0 for circle contacts)"),
        ("App::PropertyBool", "Partial", "Revolution contact spanning under 180 degrees"),
        ("App::PropertyAngle", "Span", "Common angular span"),
        ("App::PropertyLength", "Radius", "Radius (cylinder, sphere, ball)"),
        ("App::PropertyAngle", "HalfAngle", "Half-angle of the cone (CJU)"),
        ("App::PropertyVector", "Point", "A point of the contact (axis point, centre)"),
        ("App::PropertyVector", "Direction", "Normal of the first body, or axis"),
    ])
    _annotation_properties(obj)


# The designer's intent of a contact (docs/joints.md, "Annotations"); "none": not annotated.
INTENT_CHOICES = ["none", "clearance", "transition", "interference", "bonded", "ignored", "threaded"]


def _annotation_properties(obj):
    """The designer's annotation, set by the user (Contacts_AnnotateContact, the
    property editor) and kept when the contact is found again (same object:
    identity by body pair and partitions)."""
    fresh = "Intent" not in obj.PropertiesList
    add_property(obj, "App::PropertyEnumeration", "Intent", "Annotation",
                 "The designer's intent: a fit (clearance, transition, interference), bonded (glued, welded, "
                 "staked), threaded (a screw tightened in its thread: undone by the disassembly, a bond never "
                 "is) or ignored; interference, transition, bonded and threaded make the pair rigid in the "
                 "joints, ignored leaves the contact out")
    if fresh:
        obj.Intent = INTENT_CHOICES
        obj.Intent = "none"
    elif list(obj.getEnumerationsOfProperty("Intent")) != INTENT_CHOICES:
        # A document saved before an intent was added: the new choices, the contact's own kept.
        current = obj.Intent
        obj.Intent = INTENT_CHOICES
        obj.Intent = current
    add_property(obj, "App::PropertyString", "Fit", "Annotation",
                 "ISO 286 fit code such as H7/g6 (cylindrical contacts), its class checked against the intent")
    add_property(obj, "App::PropertyString", "FitClass", "Annotation",
                 "Class and limits of the fit at the contact's diameter (ISO 286)", 1)


def intent_of(obj):
    """The core's intent string of a Contact object ("" when not annotated)."""
    intent = getattr(obj, "Intent", "none")
    return "" if intent == "none" else intent


def check_annotation(obj, intent=None, fit=None):
    """The iso286.Fit of a Contact's annotation (None without a fit or for a
    contact without a diameter); core.ArgumentError naming the contact when
    the fit is unknown, out of range or contradicts the intent. `intent` and
    `fit` default to the object's own."""
    from contactwb.core import annotations
    intent = intent_of(obj) if intent is None else ("" if intent == "none" else intent)
    fit = (obj.Fit if fit is None else fit).strip()
    if not fit:
        return None
    where = f"contact '{obj.Label}'"
    if intent in ("ignored", "threaded"):
        raise core.ArgumentError(f"{where}: {'an' if intent == 'ignored' else 'a'} {intent} contact has no "
                                 f"fit ('{fit}')")
    if obj.ContactType not in annotations.FIT_TYPES:
        raise core.ArgumentError(f"{where}: fit {fit} needs a cylindrical contact "
                                 f"({', '.join(annotations.FIT_TYPES)}) to give its diameter, not "
                                 f"{obj.ContactType}")
    return annotations.evaluate_fit(where, intent, fit, obj.ContactType, obj.Radius.Value)


def _update_fit_classes(contacts):
    """FitClass of each annotated contact, from its fit at its (new) diameter."""
    for obj in contacts:
        found = check_annotation(obj)
        text = "" if found is None else (f"{found.fit_class} at diameter {found.diameter:g} mm: clearance "
                                         f"{found.clearance[0]:g} to {found.clearance[1]:g} \u00b5m")
        set_if_changed(obj, "FitClass", text)


class Contact(VersionedProxy):
    """One functional contact: its type, the two bodies and their faces."""
    TYPE = "Contact"  # version 2 added only the version records
    add_properties = staticmethod(_contact_properties)


def _joint_properties(obj):
    add_read_only_group(obj, "Joint", [
        ("App::PropertyString", "JointType",
         "ISO 3952 name: rigid, revolute, prismatic, helical, cylindrical, spherical, planar, ..."),
        ("App::PropertyInteger", "DOF", "Degrees of freedom of body B relative to body A"),
        ("App::PropertyString", "BodyA", "First body"),
        ("App::PropertyString", "BodyB", "Second body (moving relative to the first)"),
        ("App::PropertyVectorList", "AxisPoints", "A point of each rotation axis (mm)"),
        ("App::PropertyVectorList", "AxisDirections", "Direction of each rotation axis"),
        ("App::PropertyVectorList", "Translations", "Directions of free translation"),
        ("App::PropertyVectorList", "FreeDirections", "Generators of the cone of directions in which B can leave A"),
        ("App::PropertyVector", "Centre", "Centre of the pair's contacts (where glyphs are drawn)"),
        ("App::PropertyLength", "GlyphLength", "Length of the axis glyphs"),
        ("App::PropertyLinkListHidden", "Contacts", "The contacts making this joint"),
    ])


class Joint(VersionedProxy):
    """The kinematic joint two bodies' contacts allow (contactcore.find_joints)."""
    TYPE = "Joint"  # version 2 added only the version records
    add_properties = staticmethod(_joint_properties)


# --- the recompute ------------------------------------------------------

EN_DASH = "\u2013"


def _face_links(body, face_names):
    """XLinkSub entries selecting the faces on the body's path."""
    return [(body.root, [body.subname + name for name in face_names])]


def contact_label(kind, number, a, b):
    """"PLF 3: Axis – Rotor-front": unique through its number (FreeCAD would
    otherwise rename a duplicate by changing its trailing digits, which can
    name another part)."""
    return f"{kind} {number}: {a} {EN_DASH} {b}"


def contact_label2(record):
    """The tree's description column: area, span or radius."""
    if record.type in CIRCLE_TYPES:
        return f"circle r {units.length_text(record.radius)}"
    text = units.area_text(record.area)
    if record.partial:
        text += f", span {units.angle_text(record.span)}"
    return text


def relabel_quantities(doc):
    """The quantities' texts a recompute wrote (the tree's description column,
    the interference lines) written again as the property editor now writes
    them: the user changed the unit schema or the decimals
    (contactwb.gui.units.watch_unit_preferences). Nothing is recomputed."""
    from types import SimpleNamespace
    from contactwb.objects import interferences
    for group in [o for o in doc.Objects if is_contact_analysis(o)]:
        for obj in group.Group:
            if is_contact(obj):
                record = SimpleNamespace(type=obj.ContactType, area=obj.Area.Value, partial=obj.Partial,
                                         span=obj.Span.Value, radius=obj.Radius.Value)
                set_if_changed(obj, "Label2", contact_label2(record))
        interferences.relabel(group)


def _choose_bodies(doc, group, messages):
    """(bodies to analyse, indices of the focus bodies or None)."""
    everything = document_bodies.document_bodies(doc, None, messages)
    scope = group.Scope
    if scope == "Document":
        return everything, None
    picked = document_bodies.bodies_of_selection(everything, list(group.Sources))
    if not picked:
        if not group.Sources:
            raise core.ContactsError(f"scope {scope} of '{group.Label}' needs parts (Sources is empty)")
        names = ", ".join(f"{o.Label}{'.' + s if s else ''}" for o, subs in group.Sources for s in subs)
        raise core.ContactsError(f"no visible solid in the parts of '{group.Label}': {names}")
    if scope == "Selection":
        return picked, None
    return everything, {id(b) for b in picked}


def _find(bodies, source, linear, angular, progress, region_bodies=False, group=None):
    """(analysis.Analysis, contactcore.Assembly, contactcore.ContactsResult);
    `region_bodies`: the common regions to compute (contactwb.objects.regions);
    `group`: the analysis whose unchanged core bodies are reused (its
    regions.assembly_of), with what the core's last search found for them
    (regions.memo_of), else every body crosses as BRep and is searched anew."""
    assembly = regions.assembly_of(group, bodies) if group is not None else \
        assembly_from_shapes((b.name, b.shape) for b in bodies)
    face_name = lambda body, index: bodies[body].object_face_name(index)  # noqa: E731
    raw = core.contactcore.find_contacts(assembly, linear=linear, angular=angular, progress=progress,
                                         regions=region_bodies,
                                         memo=regions.memo_of(group) if group is not None else None)
    return contact_analysis.analysis_of_result(source, assembly, raw, face_name), assembly, raw


def _clearance_lines(raw, gap, names):
    """Clearance fits (radii within `gap` mm: a fit with play, not a contact)."""
    if gap <= 0:
        return []
    return [f"{names[c.body_a]} {EN_DASH} {names[c.body_b]}: {c.kind}, " +
            (f"gap {c.gap:.4g} mm (proposed: clearance)" if c.gap > 0 else
             f"coaxial overlap {-c.gap:.4g} mm (proposed: interference)")
            for c in core.contactcore.find_clearances(raw, gap)]


def contact_key(body_a, body_b, faces_a, faces_b):
    """A contact's identity: its body pair and partition pair (the faces of
    each side), the same before and after a move or a recompute."""
    return (body_a, body_b, tuple(faces_a), tuple(faces_b))


def _face_names(links):
    """The face names ("Face3") of an XLinkSub list, without the object path."""
    return [sub.rpartition(".")[2] for _, subs in links for sub in subs]


def key_of_contact(obj):
    return contact_key(obj.BodyA, obj.BodyB, _face_names(obj.FacesA), _face_names(obj.FacesB))


def key_of_record(record):
    return contact_key(record.a, record.b, record.faces_a, record.faces_b)


def _highest_number(doc):
    """The highest contact number any analysis of the document issued (also
    to contacts since removed: a number is never given twice)."""
    highest = 0
    for obj in doc.Objects:
        if is_contact_analysis(obj):
            highest = max(highest, getattr(obj, "LastNumber", 0), obj.NumberBase)
        elif is_contact(obj):
            highest = max(highest, obj.Number)
    return highest


def update_contact_analysis(group, progress=None):
    """Finds the contacts of `group` again from its inputs (Scope, Sources,
    tolerance settings, ContactTypes, ClearanceGap) and updates the group in
    place: its Contact children are reused, added or removed. Raises
    contactwb.core.ContactsError on bad input and contactwb.core.Cancelled
    when `progress` cancels (the group is left as it was then)."""
    doc = group.Document
    messages = []
    bodies, focus = _choose_bodies(doc, group, messages)
    if not bodies:
        raise core.ContactsError(f"no visible solid in document '{doc.Label}'")
    linear, angular = tolerance_settings(group)
    settings = (linear, angular)
    result, assembly, raw = _find(bodies, doc.Label, linear, angular, progress,
                                  regions.region_bodies(group, bodies, settings), group)
    painted = regions.store(group, bodies, settings, assembly, raw, result.contacts, key_of_record)
    regions.reuse_masses(group, bodies, assembly, result)  # the unchanged bodies' volumes and centres kept
    result.messages.extend(messages)
    wanted = set(group.ContactTypes) or set(CONTACT_TYPES)
    kept = [index for index, r in enumerate(result.contacts) if r.type in wanted and
            (focus is None or id(bodies[r.body_a]) in focus or id(bodies[r.body_b]) in focus)]
    records = [result.contacts[index] for index in kept]

    set_if_changed(group, "Bodies", [document_bodies.body_link(b) for b in bodies], ordered=False)
    set_if_changed(group, "BodyTable", json.dumps([{"name": b.name, "path": b.path, "volume": b.volume,
                                                    "center": list(b.center)} for b in result.bodies]))
    set_if_changed(group, "LinearToleranceValue", result.linear_tolerance)
    set_if_changed(group, "AngularToleranceValue", degrees(result.angular_tolerance))
    set_if_changed(group, "LinearTolerance", units.tolerance_text(result.linear_tolerance, units.LENGTH_UNIT))
    set_if_changed(group, "AngularTolerance", units.tolerance_text(degrees(result.angular_tolerance),
                                                                   units.ANGLE_UNIT))
    set_if_changed(group, "BodyCount", len(result.bodies))
    shown = contact_analysis.Analysis(result.source, result.units, result.linear_tolerance,
                                      result.angular_tolerance, result.bodies, records)
    set_if_changed(group, "Summary", [f"{kind}: {count}" for kind, count in sorted(shown.counts().items())])
    set_if_changed(group, "PairSummary", [f"{a} {EN_DASH} {b}: " + ", ".join(f"{n} {k}" for k, n in sorted(types.items()))
                                          for (a, b), types in shown.by_pair().items()])
    set_if_changed(group, "Messages", result.messages)
    set_if_changed(group, "Clearances", _clearance_lines(raw, group.ClearanceGap.Value,
                                                         [b.name for b in result.bodies]))
    _update_children(doc, group, records, bodies)
    _update_fit_classes([o for o in group.Group if is_contact(o)])
    update_interferences(doc, group, result.interferences, bodies, painted.solids)
    if group.DeriveJoints:
        _update_joints(doc, group, assembly, raw, result, kept, bodies)
    else:
        remove_after_recompute(doc, [o for o in group.Group if is_joint(o)])
        set_if_changed(group, "Group", [o for o in group.Group if not is_joint(o)])
        set_if_changed(group, "Mobility", [])
        set_if_changed(group, "LiaisonGraph", "")
    count_children(group)
    set_if_changed(group, "OutOfDate", False)
    return group


def compute_regions(group):
    """The common regions of an analysis whose regions are not cached (a file
    just opened), for its paint: the core run on its bodies as they are now
    (contactwb.objects.regions). The document is not changed."""
    bodies, _ = _choose_bodies(group.Document, group, [])
    if not bodies:
        return None
    linear, angular = tolerance_settings(group)
    settings = (linear, angular)
    result, assembly, raw = _find(bodies, group.Document.Label, linear, angular, None,
                                  regions.region_bodies(group, bodies, settings), group)
    return regions.store(group, bodies, settings, assembly, raw, result.contacts, key_of_record)


def _update_joints(doc, group, assembly, raw, result, kept, bodies):
    """Joint children from contactcore.find_joints (reused in place like the
    contacts), the mobility lines and the liaison graph's DOT."""
    cc = core.contactcore
    names = [b.name for b in result.bodies]
    contacts = [c for c in group.Group if is_contact(c)]
    # The designer's annotations, per core contact: those of the objects shown
    # (contacts filtered out of the group have none).
    intents = [""] * len(raw.contacts)
    for position_in_group, raw_index in enumerate(kept):
        intents[raw_index] = intent_of(contacts[position_in_group])
    found = cc.find_joints(assembly, raw, contact_intents=intents) if any(intents) else \
        cc.find_joints(assembly, raw)
    ground = names.index(group.Ground) if group.Ground in names else \
        max(range(len(names)), key=lambda i: result.bodies[i].volume)
    mobility = cc.assembly_mobility(assembly, raw, found, ground)
    set_if_changed(group, "LiaisonGraph", cc.liaison_graph_dot(assembly, found, mobility))
    # Each count explained: which bodies move, how (the core's group motions
    # and passive spins, in words: contactwb.core.joints.describe_motion)
    from contactwb.core.joints import describe_motion, direction_name
    spinning = sorted({names[s.body] for s in mobility.passive_spins})
    lines = [f"Ground: {names[mobility.ground]}" if mobility.ground >= 0 else "Ground: none",
             f"Degrees of freedom: {mobility.dof} ({mobility.passive} passive spins): "
             f"{mobility.dof - mobility.passive} that move rigid groups (each group's own motions below), "
             f"{mobility.passive} turning a part about its own axis without moving anything else"
             + (f" ({', '.join(spinning)})" if spinning else "")]
    for number, (members, motion) in enumerate(zip(mobility.groups, mobility.group_motions), start=1):
        spins = [f"{names[s.body]} about {direction_name(s.direction)}" for s in motion.passive_spins]
        lines.append(f"Rigid group {number}: {', '.join(names[i] for i in members)} "
                     f"({motion.type}, {motion.dof} DOF): "
                     + ("held by the ground" if number == 1 and mobility.ground in members
                        else describe_motion(list(motion.rotations), [tuple(d) for d in motion.translations]))
                     + (f"; passive spins: {', '.join(spins)}" if spins else ""))
    set_if_changed(group, "Mobility", lines)
    position = {raw_index: k for k, raw_index in enumerate(kept)}
    old = {}  # (body A, body B) -> its Joint: a pair keeps its joint object
    for obj in group.Group:
        if is_joint(obj):
            old.setdefault((obj.BodyA, obj.BodyB), obj)
    joints = []
    for pair in found.joints:
        mine = [contacts[position[i]] for i in pair.contacts if i in position]
        if not mine:  # a pair outside the scope shown
            continue
        a, b = names[pair.body_a], names[pair.body_b]
        obj = old.pop((a, b), None)
        if obj is None:
            obj = doc.addObject("App::FeaturePython", "Joint")
            Joint(obj)
            gui_hooks.new_object(obj)
        set_if_changed(obj, "JointType", pair.type)
        set_if_changed(obj, "DOF", pair.dof)
        set_if_changed(obj, "BodyA", a)
        set_if_changed(obj, "BodyB", b)
        set_if_changed(obj, "AxisPoints", [FreeCAD.Vector(*point) for point, _ in pair.rotations])
        set_if_changed(obj, "AxisDirections", [FreeCAD.Vector(*direction) for _, direction in pair.rotations])
        set_if_changed(obj, "Translations", [FreeCAD.Vector(*d) for d in pair.translations])
        set_if_changed(obj, "FreeDirections", [FreeCAD.Vector(*d) for d in pair.free_directions])
        centre = FreeCAD.Vector()
        for contact in mine:
            centre += contact.Point
        set_if_changed(obj, "Centre", centre * (1.0 / len(mine)))
        set_if_changed(obj, "GlyphLength", 0.6 * min(bodies[pair.body_a].shape.BoundBox.DiagonalLength,
                                                     bodies[pair.body_b].shape.BoundBox.DiagonalLength))
        set_if_changed(obj, "Contacts", mine)
        joints.append(obj)
    # joints numbered in the order of their pairs (J1, J2, ... after the group's base)
    for index, obj in enumerate(joints):
        set_if_changed(obj, "Label", f"J{group.NumberBase + index + 1} {obj.JointType}: "
                                     f"{obj.BodyA} {EN_DASH} {obj.BodyB}")
        set_if_changed(obj, "Label2", f"{obj.DOF} DOF")
    remove_after_recompute(doc, list(old.values()))
    set_if_changed(group, "Group", contacts + [o for o in group.Group if is_interference_group(o)] + joints)
    for obj in joints:
        obj.purgeTouched()


def _key_text(key):
    return json.dumps([key[0], key[1], list(key[2]), list(key[3])])


def _remembered_annotations(group, contacts):
    """{identity: [intent, fit]}: the group's record of annotations updated
    with `contacts`' own (theirs win; a contact not annotated any more is
    forgotten; contacts not among them are remembered)."""
    try:
        remembered = dict(json.loads(getattr(group, "Annotations", "") or "[]"))
    except (ValueError, TypeError):
        remembered = {}
    for obj in contacts:
        key = _key_text(key_of_contact(obj))
        if intent_of(obj) or obj.Fit:
            remembered[key] = [obj.Intent, obj.Fit]
        else:
            remembered.pop(key, None)
    return remembered


def _update_children(doc, group, records, bodies):
    """Updates the group's Contact children to `records`, by identity (body
    pair and partition pair): a contact found again keeps its object, name
    and number; a new one gets a new object and the next number of the
    document; a vanished one is removed."""
    old = [c for c in group.Group if is_contact(c)]
    others = [c for c in group.Group if not is_contact(c)]  # joints: updated after
    # Contacts no analysis holds any more (left by an older version's undo)
    orphans = [o for o in doc.Objects if is_contact(o) and o not in old
               and not any(is_contact_analysis(p) for p in o.InList)]
    by_key = {}  # identity -> its objects (a list: two contacts may share faces)
    for obj in old:
        by_key.setdefault(key_of_contact(obj), []).append(obj)
    highest = max(_highest_number(doc), getattr(group, "LastNumber", 0))
    remembered = _remembered_annotations(group, old)
    children = []
    for record in records:
        same = by_key.get(key_of_record(record))
        obj = same.pop(0) if same else None
        if obj is None:
            obj = doc.addObject("App::FeaturePython", record.type)
            Contact(obj)
            gui_hooks.new_object(obj)
            highest += 1
            obj.Number = highest
            mark = remembered.get(_key_text(key_of_record(record)))
            if mark:  # annotated before it was lost
                obj.Intent, obj.Fit = mark
        children.append(obj)
    vanished = [o for o in old if o not in children]
    remove_after_recompute(doc, vanished + orphans)
    for obj, record in zip(children, records):
        set_if_changed(obj, "ContactType", record.type)
        set_if_changed(obj, "BodyA", record.a)
        set_if_changed(obj, "BodyB", record.b)
        set_if_changed(obj, "FacesA", _face_links(bodies[record.body_a], record.faces_a))
        set_if_changed(obj, "FacesB", _face_links(bodies[record.body_b], record.faces_b))
        set_if_changed(obj, "Area", record.area)
        set_if_changed(obj, "Partial", record.partial)
        set_if_changed(obj, "Span", record.span)
        set_if_changed(obj, "Radius", record.radius)
        set_if_changed(obj, "HalfAngle", record.half_angle)
        set_if_changed(obj, "Point", FreeCAD.Vector(*record.point))
        set_if_changed(obj, "Direction", FreeCAD.Vector(*record.direction))
        set_if_changed(obj, "Label", contact_label(record.type, obj.Number, record.a, record.b))
        set_if_changed(obj, "Label2", contact_label2(record))
    set_if_changed(group, "LastNumber", highest)
    set_if_changed(group, "Annotations", json.dumps(sorted(_remembered_annotations(group, children).items())))
    set_if_changed(group, "Group", children + others)
    for obj in children:
        obj.purgeTouched()  # results, not edits: no second execute of the group
