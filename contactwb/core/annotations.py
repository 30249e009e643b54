"""The designer's annotations of contacts (docs/joints.md, "Annotations"):
fits and bonds the CAD model cannot show. A file is a JSON list of

    {"a": BODY, "b": BODY, "type": "CLJ", "intent": "interference", "fit": "H7/p6", "note": "..."}

"a" and "b" name two bodies (either order); "type" (optional) a contact
type (PLF, CLJ, ...) or a point/line contact type (sphere_on_plane, ...):
without it the entry covers every contact of the pair; "intent" is one of
clearance, transition, interference, bonded, ignored, threaded (a screw
tightened in its thread: rigid like a bond, but undone by the disassembly,
where a bond never is); "fit" (optional) an
ISO 286 fit code such as H7/g6: evaluated at each cylindrical contact's
(CLJ) diameter (contactwb.core.iso286), its class must agree with a
clearance, transition or interference intent; "note" (optional) free text.
Interference, transition, bonded and threaded contacts make their pair rigid
in the joints; ignored ones are left out."""
import json
import os
import re

from contactwb import core
from contactwb.core import iso286

INTENTS = ("clearance", "transition", "interference", "bonded", "ignored", "threaded")
_KEYS = {"a", "b", "type", "intent", "fit", "note"}
# ISO 286: hole letters (upper case) and grade / shaft letters (lower case) and grade.
_FIT = re.compile(r"^(A|B|C|CD|D|E|EF|F|FG|G|H|JS|J|K|M|N|P|R|S|T|U|V|X|Y|Z|ZA|ZB|ZC)(0[01]?|[1-9]|1[0-8])/"
                  r"(a|b|c|cd|d|e|ef|f|fg|g|h|js|j|k|m|n|p|r|s|t|u|v|x|y|z|za|zb|zc)(0[01]?|[1-9]|1[0-8])$")


class Annotation:
    """One entry of an annotations list."""
    __slots__ = ("a", "b", "type", "intent", "fit", "note", "where")

    def __init__(self, a, b, intent, type=None, fit=None, note=None, where="annotation"):
        self.a, self.b, self.type, self.intent, self.fit, self.note, self.where = a, b, type, intent, fit, note, where

    def describe(self):
        kind = f" {self.type}" if self.type else ""
        return f"{self.where} ({self.a!r} - {self.b!r}{kind}, {self.intent})"


def parse(entries, source="annotations"):
    """Annotations from a list of dicts; core.ArgumentError naming the entry
    for anything malformed."""
    if not isinstance(entries, list):
        raise core.ArgumentError(f"{source}: expected a JSON list of annotations, got {type(entries).__name__}")
    out = []
    for index, entry in enumerate(entries):
        where = f"{source}: entry {index + 1}"
        if not isinstance(entry, dict):
            raise core.ArgumentError(f"{where}: expected an object with \"a\", \"b\" and \"intent\"")
        unknown = sorted(set(entry) - _KEYS)
        if unknown:
            raise core.ArgumentError(f"{where}: unknown field(s) {', '.join(unknown)} "
                                     f"(allowed: a, b, type, intent, fit, note)")
        for key in ("a", "b", "intent"):
            if not isinstance(entry.get(key), str) or not entry[key]:
                raise core.ArgumentError(f"{where}: \"{key}\" must be a non-empty string")
        if entry["intent"] not in INTENTS:
            raise core.ArgumentError(f"{where}: unknown intent '{entry['intent']}' (use {', '.join(INTENTS)})")
        for key in ("type", "fit", "note"):
            if key in entry and not isinstance(entry[key], str):
                raise core.ArgumentError(f"{where}: \"{key}\" must be a string")
        fit = entry.get("fit")
        if fit is not None and not _FIT.match(fit):
            raise core.ArgumentError(f"{where}: '{fit}' is not an ISO 286 fit code such as H7/g6 or H7/p6")
        if fit is not None and entry["intent"] in ("ignored", "threaded"):
            raise core.ArgumentError(f"{where}: {'an' if entry['intent'] == 'ignored' else 'a'} {entry['intent']} "
                                     f"contact has no fit ('{fit}')")
        out.append(Annotation(entry["a"], entry["b"], entry["intent"], entry.get("type"), fit, entry.get("note"),
                              where=f"{where}"))
    return out


def load(path):
    """Annotations from a JSON file."""
    if not os.path.isfile(path):
        raise core.ArgumentError(f"no such annotations file: '{path}'")
    try:
        with open(path, encoding="utf-8") as stream:
            entries = json.load(stream)
    except (OSError, UnicodeError, ValueError) as error:
        raise core.ArgumentError(f"cannot read annotations file '{path}': {error}")
    return parse(entries, source=f"annotations file '{path}'")


# Contact types whose radius is a fit's nominal diameter / 2 (ISO 286: features of size).
FIT_TYPES = ("CLJ",)
FIT_INTENTS = ("clearance", "transition", "interference")


def evaluate_fit(where, intent, code, contact_type, radius):
    """The iso286.Fit of `code` at a contact of `contact_type` and `radius`
    (mm), or None for a contact without a diameter (planes, cones...). An
    ArgumentError naming `where` for a code the tables refuse (unknown
    letter, diameter out of range) or a fit whose class contradicts a
    clearance, transition or interference intent."""
    if not code or contact_type not in FIT_TYPES:
        return None
    try:
        found = iso286.fit(code, 2 * radius)
    except iso286.FitError as error:
        raise core.ArgumentError(f"{where}: fit {code} at the {contact_type} contact of diameter "
                                 f"{2 * radius:g} mm: {error}") from None
    if intent in FIT_INTENTS and found.fit_class != intent:
        low, high = found.clearance
        raise core.ArgumentError(
            f"{where}: fit {code} at diameter {found.diameter:g} mm is a {found.fit_class} fit "
            f"(clearance {low:g} to {high:g} µm: hole {found.hole[0]:+g}/{found.hole[1]:+g}, shaft "
            f"{found.shaft[0]:+g}/{found.shaft[1]:+g} µm), not {intent}")
    return found


def resolve(annotations, names, contacts, higher_pairs=()):
    """Per contact and per higher pair, the (intent, fit, iso286.Fit) the
    annotations give (("", None, None) when none): ([...], [...]).
    `contacts` and `higher_pairs` have .body_a, .body_b and .type_name /
    .type (contacts also .radius). A fit applies to the cylindrical (CLJ)
    contacts an entry matches, evaluated at their diameter; other contacts
    of the entry get its intent only. An entry that matches no contact,
    names an unknown body, gives a fit and matches no cylindrical contact,
    or whose fit contradicts its intent, is an ArgumentError naming it; a
    later entry overrides an earlier one."""
    index = {name: i for i, name in enumerate(names)}
    contact_marks = [("", None, None)] * len(contacts)
    higher_marks = [("", None, None)] * len(higher_pairs)
    for note in annotations:
        for body in (note.a, note.b):
            if body not in index:
                raise core.ArgumentError(f"{note.describe()}: no body named '{body}'")
        pair = {index[note.a], index[note.b]}
        matched = fitted = 0
        for k, item in enumerate(contacts):
            if {item.body_a, item.body_b} != pair or (note.type and item.type_name != note.type):
                continue
            found = evaluate_fit(note.describe(), note.intent, note.fit, item.type_name, item.radius)
            fitted += found is not None
            contact_marks[k] = (note.intent, note.fit if found is not None else None, found)
            matched += 1
        for k, item in enumerate(higher_pairs):
            if {item.body_a, item.body_b} != pair or (note.type and item.type != note.type):
                continue
            higher_marks[k] = (note.intent, None, None)
            matched += 1
        if not matched:
            raise core.ArgumentError(f"{note.describe()} matches no contact")
        if note.fit and not fitted:
            raise core.ArgumentError(f"{note.describe()}: fit {note.fit} needs a cylindrical contact "
                                     f"({', '.join(FIT_TYPES)}) to give its diameter; the entry matches none")
    return contact_marks, higher_marks
