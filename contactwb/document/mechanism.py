"""The mechanism export of a document's contact analysis (headless; the
command Contacts_ExportMechanism calls it): the analysis' parts (its Scope:
the document's visible solids, or its Sources for a Selection) and
tolerances, the designer's annotations from a JSON file (by default the
document's sidecar NAME.annotations.json when there is one), then
contactwb.core.mechanism_export writes URDF or MJCF (docs/mechanism.md).

    from contactwb.document import mechanism
    model, paths = mechanism.export_analysis(group, "urdf", "/tmp/motor_urdf")"""
import os

from contactwb import core
from contactwb.core import joints
from contactwb.core import mechanism_export
from contactwb.core.mechanism import DEFAULT_DENSITY
from contactwb.document import bodies as document_bodies
from contactwb.document import units
from contactwb.document.identify import is_contact_analysis
from contactwb.document.shapes import assembly_from_shapes


def sidecar_annotations(doc):
    """The document's annotation file beside it (motor.FCStd -> motor.annotations.json), or None."""
    if not getattr(doc, "FileName", ""):
        return None
    path = os.path.splitext(doc.FileName)[0] + ".annotations.json"
    return path if os.path.isfile(path) else None


def analysis_bodies(group):
    """The DocumentBodies an analysis covers: its Sources for Scope Selection, else every visible solid."""
    messages = []
    everything = document_bodies.document_bodies(group.Document, None, messages)
    if group.Scope == "Selection" and group.Sources:
        picked = document_bodies.bodies_of_selection(everything, list(group.Sources))
        if not picked:
            raise core.ContactsError(f"no visible solid in the parts of '{group.Label}'")
        return picked
    return everything


def export_analysis(group, fmt, path, density=DEFAULT_DENSITY, ground=None, annotations=None):
    """Writes the mechanism of a ContactAnalysis group as `fmt` "urdf" (path: a folder) or "mjcf"
    (path: an .xml file); `annotations`: a JSON file (None: none). Returns (Model, [paths written]).
    Raises core.ArgumentError for a bad format, path or ground, ContactsError when the analysis
    fails, OSError when a file cannot be written."""
    if not is_contact_analysis(group):
        raise core.ArgumentError(f"'{getattr(group, 'Label', group)}' is not a contact analysis")
    if fmt not in mechanism_export.FORMATS:
        raise core.ArgumentError(f"unknown mechanism format '{fmt}': use urdf or mjcf")
    if fmt == "mjcf" and not path.lower().endswith(".xml"):
        raise core.ArgumentError(f"'{path}': an MJCF file is an .xml file")
    bodies = analysis_bodies(group)
    assembly = assembly_from_shapes((b.name, b.shape) for b in bodies)
    linear, angular = units.tolerance_settings(group)
    _, found = joints.joints_in_assembly(assembly, group.Document.Label, linear, angular,
                                         face_name=lambda body, index: bodies[body].object_face_name(index),
                                         annotations=annotations)
    name = os.path.splitext(os.path.basename(group.Document.FileName))[0] if group.Document.FileName else \
        group.Document.Label
    return mechanism_export.export_mechanism(
        assembly, found, urdf_dir=path if fmt == "urdf" else None, mjcf_path=path if fmt == "mjcf" else None,
        density=density, ground=ground, name=name)
