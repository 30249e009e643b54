"""make_contact_analysis(): find the contacts of a document (or a selection)
and record them in the tree as a ContactAnalysis group of Contact objects."""
from math import degrees

import FreeCAD

from contactwb import analysis as contact_analysis
from contactwb.objects.contact_objects import Contact, ContactAnalysis


def _face_links(body, face_names):
    """XLinkSub entries selecting the faces on the body's path."""
    return [(body.root, [body.subname + name for name in face_names])]


def make_contact_analysis(doc=None, objects=None, linear=None, angular=None, progress=None,
                          name="Contacts"):
    """Runs contact identification and adds the result to `doc`.

    objects: analyse only these (and what they contain); default every visible
    solid. Returns the ContactAnalysis object; its Group holds one Contact per
    contact. Raises contactwb.core.ContactsError on bad input and
    contactwb.core.Cancelled when `progress` cancels (nothing is added then)."""
    doc = doc or FreeCAD.ActiveDocument
    if doc is None:
        raise ValueError("no document")
    result, bodies = contact_analysis.find_contacts_in_document(doc, objects, linear, angular, progress)

    group = doc.addObject("App::DocumentObjectGroupPython", name)
    ContactAnalysis(group)
    group.Sources = list(objects or [])
    group.LinearTolerance = result.linear_tolerance
    group.AngularTolerance = degrees(result.angular_tolerance)
    group.BodyCount = len(result.bodies)
    group.Summary = [f"{kind}: {count}" for kind, count in sorted(result.counts().items())]
    group.Messages = result.messages
    children = []
    for record in result.contacts:
        obj = doc.addObject("App::FeaturePython", f"{record.type}")
        Contact(obj)
        obj.Label = f"{record.type} {record.a} - {record.b}"
        obj.ContactType = record.type
        obj.BodyA, obj.BodyB = record.a, record.b
        obj.FacesA = _face_links(bodies[record.body_a], record.faces_a)
        obj.FacesB = _face_links(bodies[record.body_b], record.faces_b)
        obj.Area = record.area
        obj.Partial = record.partial
        obj.Span = record.span
        obj.Radius = record.radius
        obj.Point = FreeCAD.Vector(*record.point)
        obj.Direction = FreeCAD.Vector(*record.direction)
        children.append(obj)
    group.Group = children
    if FreeCAD.GuiUp:
        from contactwb.gui import view_providers
        view_providers.attach(group)
    return group
