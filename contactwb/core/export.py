"""Export formats of a contact analysis (no FreeCAD): the CLI's JSON document
(contactwb.core.analysis.Analysis.to_json) or CSV, one row per contact.

JSON: "source", "units", "tolerances", "bodies", "contacts" (CONTACT_KEYS;
faces are the bodies' "FaceN" names, span in degrees, lengths in mm, angular
tolerance in radians). CSV: a header, then one row per contact (faces
separated by spaces, point and direction as x, y, z columns). A document's
ContactAnalysis group is exported through contactwb.document.export."""
import csv
import json
import os

CONTACT_KEYS = ["type", "a", "b", "faces_a", "faces_b", "area", "partial", "span", "radius",
                "half_angle", "point", "direction"]
CSV_COLUMNS = ["type", "a", "b", "faces_a", "faces_b", "area", "partial", "span", "radius", "half_angle",
               "point_x", "point_y", "point_z", "direction_x", "direction_y", "direction_z"]
FORMATS = (".json", ".csv")


def check_format(path):
    """The extension of `path` (".json" or ".csv"); ValueError for another."""
    extension = os.path.splitext(path)[1].lower()
    if extension not in FORMATS:
        raise ValueError(f"cannot export contacts to '{path}': use a .json or .csv file")
    return extension


def contact_records(document):
    """The contacts of a JSON document (Analysis.to_json()) as dicts with CONTACT_KEYS."""
    return [{key: record[key] for key in CONTACT_KEYS} for record in document["contacts"]]


def csv_row(record):
    """A CSV_COLUMNS row of a contact record."""
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


def write_analysis(analysis, path):
    """Writes an Analysis to `path`, as JSON or CSV after its extension;
    returns the number of contacts written. ValueError for another extension,
    OSError when the file cannot be written."""
    extension = check_format(path)
    document = analysis.to_json()
    if extension == ".json":
        with open(path, "w", encoding="utf-8") as stream:
            json.dump(document, stream, indent=2)
            stream.write("\n")
        return len(document["contacts"])
    records = contact_records(document)
    with open(path, "w", encoding="utf-8", newline="") as stream:
        writer = csv.DictWriter(stream, fieldnames=CSV_COLUMNS)
        writer.writeheader()
        for record in records:
            writer.writerow(csv_row(record))
    return len(records)
