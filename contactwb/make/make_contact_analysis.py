"""make_contact_analysis(): find the contacts of a document (a selection, or
one part against the rest) and record them in the tree as a ContactAnalysis
group of Contact objects; update_contact_analysis() finds them again in place
(the group's recompute, the task panel's re-run)."""
import json
from math import degrees, radians

import FreeCAD

from contactwb import analysis as contact_analysis
from contactwb import bodies as document_bodies
from contactwb import core
from contactwb.objects.contact_objects import (CONTACT_TYPES, SCOPES, Contact, ContactAnalysis, Joint,
                                               count_children, is_contact, is_contact_analysis, is_joint)

EN_DASH = "\u2013"


def _face_links(body, face_names):
    """XLinkSub entries selecting the faces on the body's path."""
    return [(body.root, [body.subname + name for name in face_names])]


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


def contact_label(kind, number, a, b):
    """"PLF 3: Axis – Rotor-front": unique through its number (FreeCAD would
    otherwise rename a duplicate by changing its trailing digits, which can
    name another part)."""
    return f"{kind} {number}: {a} {EN_DASH} {b}"


def contact_label2(record):
    """The tree's description column: area, span or radius."""
    if record.type in ("LAF", "SPT"):
        return f"circle r {record.radius:.4g} mm"
    text = f"{record.area:.4g} mm\u00b2"
    if record.partial:
        text += f", span {record.span:.0f}\u00b0"
    return text


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


def _find(bodies, source, linear, angular, progress):
    """(analysis.Analysis, contactcore.Assembly, contactcore.ContactsResult)."""
    assembly = core.assembly_from_shapes((b.name, b.shape) for b in bodies)
    face_name = lambda body, index: bodies[body].object_face_name(index)  # noqa: E731
    raw = core.contactcore.find_contacts(assembly, linear=linear, angular=angular, progress=progress)
    return contact_analysis._analysis(source, assembly, raw, face_name), assembly, raw


def _clearance_lines(raw, gap, names):
    """Clearance fits (radii within `gap` mm: a fit with play, not a contact)."""
    if gap <= 0:
        return []
    return [f"{names[c.body_a]} {EN_DASH} {names[c.body_b]}: {c.kind}, gap {c.gap:.4g} mm"
            for c in core.contactcore.find_clearances(raw, gap)]


def _numbers_in_use(doc, group):
    used = set()
    for other in doc.Objects:
        if other is not group and is_contact_analysis(other):
            used.update(c.Number for c in other.Group if is_contact(c))
    return used


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
    linear = group.LinearToleranceSetting.Value or None
    angular = radians(group.AngularToleranceSetting.Value) or None
    result, assembly, raw = _find(bodies, doc.Label, linear, angular, progress)
    result.messages.extend(messages)
    wanted = set(group.ContactTypes) or set(CONTACT_TYPES)
    kept = [index for index, r in enumerate(result.contacts) if r.type in wanted and
            (focus is None or id(bodies[r.body_a]) in focus or id(bodies[r.body_b]) in focus)]
    records = [result.contacts[index] for index in kept]

    group.Bodies = [document_bodies.body_link(b) for b in bodies]
    group.BodyTable = json.dumps([{"name": b.name, "path": b.path, "volume": b.volume,
                                   "center": list(b.center)} for b in result.bodies])
    group.LinearTolerance = result.linear_tolerance
    group.AngularTolerance = degrees(result.angular_tolerance)
    group.BodyCount = len(result.bodies)
    shown = contact_analysis.Analysis(result.source, result.units, result.linear_tolerance,
                                      result.angular_tolerance, result.bodies, records)
    group.Summary = [f"{kind}: {count}" for kind, count in sorted(shown.counts().items())]
    group.PairSummary = [f"{a} {EN_DASH} {b}: " + ", ".join(f"{n} {k}" for k, n in sorted(types.items()))
                         for (a, b), types in shown.by_pair().items()]
    group.Messages = result.messages
    group.Clearances = _clearance_lines(raw, group.ClearanceGap.Value, [b.name for b in result.bodies])
    _update_children(doc, group, records, bodies)
    if group.DeriveJoints:
        _update_joints(doc, group, assembly, raw, result, kept, bodies)
    else:
        remove_after_recompute(doc, [o for o in group.Group if is_joint(o)])
        group.Group = [o for o in group.Group if not is_joint(o)]
        group.Mobility, group.LiaisonGraph = [], ""
    count_children(group)
    return group


def _update_joints(doc, group, assembly, raw, result, kept, bodies):
    """Joint children from contactcore.find_joints (reused in place like the
    contacts), the mobility lines and the liaison graph's DOT."""
    cc = core.contactcore
    names = [b.name for b in result.bodies]
    found = cc.find_joints(assembly, raw)
    ground = names.index(group.Ground) if group.Ground in names else \
        max(range(len(names)), key=lambda i: result.bodies[i].volume)
    mobility = cc.assembly_mobility(assembly, raw, found, ground)
    group.LiaisonGraph = cc.liaison_graph_dot(assembly, found, mobility)
    lines = [f"Ground: {names[mobility.ground]}" if mobility.ground >= 0 else "Ground: none",
             f"Degrees of freedom: {mobility.dof} ({mobility.passive} passive spins)"]
    for number, (members, motion) in enumerate(zip(mobility.groups, mobility.group_motions), start=1):
        lines.append(f"Rigid group {number}: {', '.join(names[i] for i in members)} "
                     f"({motion.type}, {motion.dof} DOF)")
    group.Mobility = lines
    contacts = [c for c in group.Group if is_contact(c)]
    position = {raw_index: k for k, raw_index in enumerate(kept)}
    old = [o for o in group.Group if is_joint(o)]
    joints = []
    for pair in found.joints:
        mine = [contacts[position[i]] for i in pair.contacts if i in position]
        if not mine:  # a pair outside the scope shown
            continue
        index = len(joints)
        if index < len(old):
            obj = old[index]
        else:
            obj = doc.addObject("App::FeaturePython", "Joint")
            Joint(obj)
            if FreeCAD.GuiUp:
                from contactwb.gui import joint_view
                joint_view.ViewProviderJoint(obj.ViewObject)
        obj.Label = obj.Name
        a, b = names[pair.body_a], names[pair.body_b]
        obj.JointType, obj.DOF, obj.BodyA, obj.BodyB = pair.type, pair.dof, a, b
        obj.AxisPoints = [FreeCAD.Vector(*point) for point, _ in pair.rotations]
        obj.AxisDirections = [FreeCAD.Vector(*direction) for _, direction in pair.rotations]
        obj.Translations = [FreeCAD.Vector(*d) for d in pair.translations]
        obj.FreeDirections = [FreeCAD.Vector(*d) for d in pair.free_directions]
        centre = FreeCAD.Vector()
        for contact in mine:
            centre += contact.Point
        obj.Centre = centre * (1.0 / len(mine))
        obj.GlyphLength = 0.6 * min(bodies[pair.body_a].shape.BoundBox.DiagonalLength,
                                    bodies[pair.body_b].shape.BoundBox.DiagonalLength)
        obj.Contacts = mine
        obj.Label = f"J{group.NumberBase + index + 1} {pair.type}: {a} {EN_DASH} {b}"
        obj.Label2 = f"{pair.dof} DOF"
        joints.append(obj)
    remove_after_recompute(doc, old[len(joints):])
    group.Group = contacts + joints
    for obj in joints:
        obj.purgeTouched()


def _update_children(doc, group, records, bodies):
    old = [c for c in group.Group if is_contact(c)]
    others = [c for c in group.Group if not is_contact(c)]  # joints: updated after
    # Contacts no analysis holds any more (an undo can bring them back):
    # they would keep labels the live contacts need.
    orphans = [o for o in doc.Objects if is_contact(o) and o not in old
               and not any(is_contact_analysis(p) for p in o.InList)]
    remove_after_recompute(doc, orphans)
    used = _numbers_in_use(doc, group)
    base = group.NumberBase
    if any(base + k in used for k in range(1, len(records) + 1)):
        base = max(used)
    mine = set(old) | set(orphans)
    taken = {o.Label for o in doc.Objects if o not in mine}
    labels = lambda b: [contact_label(r.type, b + k + 1, r.a, r.b) for k, r in enumerate(records)]  # noqa: E731
    if taken.intersection(labels(base)):
        # another object holds one of the labels: number after every contact
        base = max([base] + list(used) + [o.Number for o in doc.Objects if is_contact(o)])
    group.NumberBase = base
    children = []
    for index, record in enumerate(records):
        if index < len(old):
            obj = old[index]
        else:
            obj = doc.addObject("App::FeaturePython", record.type)
            Contact(obj)
            if FreeCAD.GuiUp:
                from contactwb.gui import view_providers
                view_providers.ViewProviderContact(obj.ViewObject)
        children.append(obj)
    for obj in children + orphans:
        obj.Label = obj.Name  # frees the labels for the contacts that will take them
    remove_after_recompute(doc, old[len(records):])
    for index, (obj, record) in enumerate(zip(children, records)):
        number = base + index + 1
        obj.ContactType = record.type
        obj.Number = number
        obj.BodyA, obj.BodyB = record.a, record.b
        obj.FacesA = _face_links(bodies[record.body_a], record.faces_a)
        obj.FacesB = _face_links(bodies[record.body_b], record.faces_b)
        obj.Area = record.area
        obj.Partial = record.partial
        obj.Span = record.span
        obj.Radius = record.radius
        obj.HalfAngle = record.half_angle
        obj.Point = FreeCAD.Vector(*record.point)
        obj.Direction = FreeCAD.Vector(*record.direction)
        obj.Label = contact_label(record.type, number, record.a, record.b)
        obj.Label2 = contact_label2(record)
    group.Group = children + others
    for obj in children:
        obj.purgeTouched()  # results, not edits: no second execute of the group


def remove_after_recompute(doc, objects):
    """Removes contacts no longer found: at once outside a recompute; inside
    one (the group's execute), once it is over, since FreeCAD defers and
    mixes up removals made while recomputing."""
    if not objects:
        return
    if not doc.Recomputing:
        for obj in objects:
            doc.removeObject(obj.Name)
        return
    from contactwb.objects.contact_objects import pending_removal
    pending_removal(doc, [obj.Name for obj in objects])


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
        if FreeCAD.GuiUp:
            from contactwb.gui import view_providers
            view_providers.ViewProviderContactAnalysis(group.ViewObject)
    previous = {key: getattr(group, key) for key in
                ("Scope", "Sources", "LinearToleranceSetting", "AngularToleranceSetting",
                 "ContactTypes", "ClearanceGap", "DeriveJoints")}
    group.Scope = scope
    group.Sources = entries
    group.LinearToleranceSetting = linear or 0.0
    group.AngularToleranceSetting = degrees(angular) if angular else 0.0
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
    if FreeCAD.GuiUp:
        from contactwb.gui import view_providers
        view_providers.attach(group)
    return group
