"""The designer's annotations of contacts (docs/joints.md, "Annotations"):
fits and bonds the CAD model cannot show. A file is a JSON list of

    {"a": BODY, "b": BODY, "type": "CLJ", "intent": "interference", "fit": "H7/p6", "note": "..."}

"a" and "b" name two bodies (either order); "type" (optional) a contact
type (PLF, CLJ, ...) or a point/line contact type (sphere_on_plane, ...):
without it the entry covers every contact of the pair; "intent" is one of
clearance, transition, interference, bonded, ignored; "fit" (optional) an
ISO 286 fit code such as H7/g6, echoed; "note" (optional) free text.
Interference, transition and bonded contacts make their pair rigid in the
joints; ignored ones are left out."""
import json
import os
import re

from contactwb import core

INTENTS = ("clearance", "transition", "interference", "bonded", "ignored")
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


def resolve(annotations, names, contacts, higher_pairs=()):
    """Per contact and per higher pair, the (intent, fit) the annotations give
    ("" and None when none): ([(intent, fit)], [(intent, fit)]). `contacts`
    and `higher_pairs` have .body_a, .body_b and .type_name / .type. An entry
    that matches no contact, or names an unknown body, is an ArgumentError
    naming it; a later entry overrides an earlier one."""
    index = {name: i for i, name in enumerate(names)}
    contact_marks = [("", None)] * len(contacts)
    higher_marks = [("", None)] * len(higher_pairs)
    for note in annotations:
        for body in (note.a, note.b):
            if body not in index:
                raise core.ArgumentError(f"{note.describe()}: no body named '{body}'")
        pair = {index[note.a], index[note.b]}
        matched = 0
        for marks, items, type_of in ((contact_marks, contacts, lambda c: c.type_name),
                                      (higher_marks, higher_pairs, lambda h: h.type)):
            for k, item in enumerate(items):
                if {item.body_a, item.body_b} != pair:
                    continue
                if note.type and type_of(item) != note.type:
                    continue
                marks[k] = (note.intent, note.fit)
                matched += 1
        if not matched:
            raise core.ArgumentError(f"{note.describe()} matches no contact")
    return contact_marks, higher_marks
