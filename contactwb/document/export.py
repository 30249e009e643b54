"""Export of a ContactAnalysis group's contacts (headless).

    from contactwb import export
    export.export_contacts(group, "motor_contacts.json")   # or .csv

JSON: the CLI's `--json` document, built by the same function
(contactwb.analysis.Analysis.to_json): "source", "units", "tolerances",
"bodies", "contacts" (CONTACT_KEYS; faces are the bodies' "FaceN" names, span in degrees,
lengths in mm, angular tolerance in radians). CSV: a header, then one row per
contact (faces separated by spaces, point and direction as x, y, z columns)."""
import csv
import json
import os
from math import radians

from contactwb.analysis import Analysis, BodyInfo, ContactRecord
from contactwb.objects.contact_objects import is_contact, is_contact_analysis

CONTACT_KEYS = ["type", "a", "b", "faces_a", "faces_b", "area", "partial", "span", "radius",
                "half_angle", "point", "direction"]
CSV_COLUMNS = ["type", "a", "b", "faces_a", "faces_b", "area", "partial", "span", "radius", "half_angle",
               "point_x", "point_y", "point_z", "direction_x", "direction_y", "direction_z"]
FORMATS = (".json", ".csv")


def analyses(doc):
    """The ContactAnalysis groups of a document. (Cheap enough for a
    command's IsActive on large documents: the type is checked first.)"""
    if doc is None:
        return []
    return [obj for obj in doc.Objects
            if obj.TypeId == "App::DocumentObjectGroupPython" and is_contact_analysis(obj)]


def _face_names(links):
    # Stored subnames run from the top-level object ("Part.Link.Face3"); the
    # CLI names a face on its body's object ("Face3").
    return [subname.rpartition(".")[2] for _, subnames in links for subname in subnames]


def live_contacts(group):
    """The group's contacts whose bodies still exist (a deleted body's
    contacts lose their face links; they go at the next recompute)."""
    return [c for c in group.Group if is_contact(c) and c.FacesA and c.FacesB]


class _StoredMass:
    """Volumes and centres as the analysis stored them (BodyInfo's mass table)."""

    def __init__(self, values):
        self.values = values

    def get(self, index):
        return self.values[index]


def as_analysis(group):
    """The group as a contactwb.analysis.Analysis: the CLI's data, so that
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
    stored = _StoredMass([(b["volume"], tuple(b["center"])) for b in table])
    bodies = [BodyInfo(b["name"], b["path"], stored, index) for index, b in enumerate(table)]
    return Analysis(source=group.Document.Label, units="mm",
                    linear_tolerance=group.LinearTolerance.Value,
                    angular_tolerance=radians(group.AngularTolerance.Value),
                    bodies=bodies, contacts=contacts, messages=list(group.Messages))


def to_json(group):
    """The JSON document of a group (a dict): the CLI's --json schema."""
    return as_analysis(group).to_json()


def contact_records(group):
    """The group's contacts as dicts with CONTACT_KEYS (the CLI's values)."""
    return [{key: record[key] for key in CONTACT_KEYS} for record in to_json(group)["contacts"]]


def _csv_row(record):
    row = dict(record)
    row["faces_a"] = " ".join(record["faces_a"])
    row["faces_b"] = " ".join(record["faces_b"])
    row["partial"] = "true" if record["partial"] else "false"
    for key in ("point", "direction"):
        for axis, value in zip("xyz", row.pop(key)):
            row[f"{key}_{axis}"] = repr(value)
    for key in ("area", "span", "radius", "half_angle"):
        row[key] = repr(record[key])
    return row


def export_contacts(group, path):
    """Writes the contacts of a ContactAnalysis group to `path`, as JSON or
    CSV after its extension; returns the number of contacts written.
    Raises ValueError for another extension or a group that is not an
    analysis, OSError when the file cannot be written."""
    extension = os.path.splitext(path)[1].lower()
    if extension not in FORMATS:
        raise ValueError(f"cannot export contacts to '{path}': use a .json or .csv file")
    if extension == ".json":
        document = to_json(group)
        with open(path, "w", encoding="utf-8") as stream:
            json.dump(document, stream, indent=2)
            stream.write("\n")
        return len(document["contacts"])
    records = contact_records(group)
    with open(path, "w", encoding="utf-8", newline="") as stream:
        writer = csv.DictWriter(stream, fieldnames=CSV_COLUMNS)
        writer.writeheader()
        for record in records:
            writer.writerow(_csv_row(record))
    return len(records)
