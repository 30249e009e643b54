"""Export of a ContactAnalysis group's contacts (headless).

    from contactwb.document import export
    export.export_contacts(group, "motor_contacts.json")   # or .csv

The group is read back as a contactwb.core.analysis.Analysis (the CLI's
data), so both write through the same schema (contactwb.core.export)."""
import json

from contactwb.core.analysis import Analysis, BodyInfo, ContactRecord, StoredMass
from contactwb.core.export import (CONTACT_KEYS, CSV_COLUMNS, FORMATS, check_format,  # noqa: F401
                                   write_analysis)
from contactwb.core.export import contact_records as _records_of_document
from contactwb.document.units import tolerances_used
from contactwb.document.identify import (analyses, interferences_of, is_contact, is_contact_analysis,  # noqa: F401
                                         is_interference)


def _face_names(links):
    # Stored subnames run from the top-level object ("Part.Link.Face3"); the
    # CLI names a face on its body's object ("Face3").
    return [subname.rpartition(".")[2] for _, subnames in links for subname in subnames]


def live_contacts(group):
    """The group's contacts whose bodies still exist (a deleted body's
    contacts lose their face links; they go at the next recompute)."""
    return [c for c in group.Group if is_contact(c) and c.FacesA and c.FacesB]


def as_analysis(group):
    """The group as a contactwb.core.analysis.Analysis: the CLI's data, so that
    both export through the same schema (Analysis.to_json)."""
    if not is_contact_analysis(group):
        raise ValueError(f"'{getattr(group, 'Label', group)}' is not a contact analysis")
    contacts = []
    for contact in live_contacts(group):
        contacts.append(ContactRecord(
            type=contact.ContactType, a=contact.BodyA, b=contact.BodyB,
            faces_a=_face_names(contact.FacesA), faces_b=_face_names(contact.FacesB),
            area=contact.Area.Value, partial=bool(contact.Partial), span=contact.Span.Value,
            radius=contact.Radius.Value,
            half_angle=contact.HalfAngle.Value if hasattr(contact, "HalfAngle") else 0.0,
            point=(contact.Point.x, contact.Point.y, contact.Point.z),
            direction=(contact.Direction.x, contact.Direction.y, contact.Direction.z)))
    table = json.loads(getattr(group, "BodyTable", "") or "[]")
    stored = StoredMass([(b["volume"], tuple(b["center"])) for b in table])
    bodies = [BodyInfo(b["name"], b["path"], stored, index) for index, b in enumerate(table)]
    return Analysis(source=group.Document.Label, units="mm",
                    linear_tolerance=tolerances_used(group)[0],
                    angular_tolerance=tolerances_used(group)[1],
                    bodies=bodies, contacts=contacts, messages=list(group.Messages),
                    interferences=[(o.BodyA, o.BodyB, o.Volume.Value) for o in interferences_of(group)])


def to_json(group):
    """The JSON document of a group (a dict): the CLI's --json schema."""
    return as_analysis(group).to_json()


def contact_records(group):
    """The group's contacts as dicts with CONTACT_KEYS (the CLI's values)."""
    return _records_of_document(to_json(group))


def export_contacts(group, path):
    """Writes the contacts of a ContactAnalysis group to `path`, as JSON or
    CSV after its extension; returns the number of contacts written.
    Raises ValueError for another extension or a group that is not an
    analysis, OSError when the file cannot be written."""
    check_format(path)
    return write_analysis(as_analysis(group), path)
