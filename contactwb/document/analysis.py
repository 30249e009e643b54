"""Contacts and joints of FreeCAD documents and Part shapes: the document's
bodies (contactwb.document.bodies) handed to the headless analyses
(contactwb.core.analysis, contactwb.core.joints), faces named as the
objects' FaceN."""
from contactwb.core import analysis, joints
from contactwb.document import bodies as document_bodies
from contactwb.document.shapes import assembly_from_shapes


def find_contacts_in_shapes(named_shapes, source="shapes", linear=None, angular=None, progress=None,
                            max_pairs=None):
    """Contacts between (name, Part.Shape) pairs placed globally."""
    assembly = assembly_from_shapes(named_shapes)
    return analysis.find_contacts_in_assembly(assembly, source, linear, angular, progress, max_pairs=max_pairs)


def find_contacts_in_document(doc, objects=None, linear=None, angular=None, progress=None, max_pairs=None,
                              check_solids="quick"):
    """Contacts of a FreeCAD document's visible solids (or of a selection).
    Returns (Analysis, [DocumentBody]); face names are the objects' FaceN."""
    messages = []
    assembly, bodies = document_bodies.assembly_from_document(doc, objects, messages)
    result = analysis.find_contacts_in_assembly(
        assembly, doc.Label, linear, angular, progress,
        face_name=lambda body, index: bodies[body].object_face_name(index), max_pairs=max_pairs,
        check_solids=check_solids)
    result.messages.extend(messages)
    return result, bodies


def joints_in_shapes(named_shapes, source="shapes", linear=None, angular=None, ground=None, clearance_gap=0.0,
                     annotations=None):
    """(analysis.Analysis, Joints) of (name, Part.Shape) pairs placed globally."""
    return joints.joints_in_assembly(assembly_from_shapes(named_shapes), source, linear, angular, ground=ground,
                                     clearance_gap=clearance_gap, annotations=annotations)


def joints_in_document(doc, objects=None, linear=None, angular=None, progress=None, ground=None,
                       clearance_gap=0.0, max_pairs=None, check_solids="quick", annotations=None):
    """(analysis.Analysis, Joints, [DocumentBody]) of a FreeCAD document's visible solids."""
    messages = []
    assembly, bodies = document_bodies.assembly_from_document(doc, objects, messages)
    result, found = joints.joints_in_assembly(
        assembly, doc.Label, linear, angular, progress,
        face_name=lambda body, index: bodies[body].object_face_name(index), ground=ground,
        clearance_gap=clearance_gap, max_pairs=max_pairs, check_solids=check_solids, annotations=annotations)
    result.messages.extend(messages)
    return result, found, bodies
