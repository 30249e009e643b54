"""Contact identification, headless and without FreeCAD: from a STEP file or
a contactcore.Assembly to typed contacts between named bodies (the paper's
list), with the table and JSON forms. Documents and Part shapes:
contactwb.document.analysis.

    from contactwb import analysis        # (this module and the document one)
    result = analysis.find_contacts_in_step("motor.step")
    print(result.table())
"""
import os
from collections import Counter, defaultdict
from dataclasses import dataclass, field
from math import degrees
from typing import Dict, List, Optional, Tuple

from contactwb import core
from contactwb.core.kinds import CONTACT_TYPES, TYPE_TITLES

TYPE_ORDER = CONTACT_TYPES


class _MassTable:
    """Volumes and centres of an assembly's bodies, all computed at the first
    question (in C++, on all cores, each shared shape once), then the
    assembly let go."""

    def __init__(self, assembly):
        self._assembly = assembly
        self._values = None

    def get(self, index):
        if self._values is None:
            self._assembly.compute_mass_properties()
            self._values = [(b.volume, b.center) for b in self._assembly.bodies]
            self._assembly = None
        return self._values[index]


class BodyInfo:
    """A body of the result; its volume (mm^3) and center (mm) are computed
    when first read, never twice."""
    __slots__ = ("name", "path", "_mass", "_index")

    def __init__(self, name, path, mass_table, index):
        self.name, self.path, self._mass, self._index = name, path, mass_table, index

    @property
    def volume(self) -> float:
        return self._mass.get(self._index)[0]

    @property
    def center(self) -> Tuple[float, float, float]:
        return self._mass.get(self._index)[1]

    def __repr__(self):
        return f"BodyInfo(name={self.name!r}, path={self.path!r})"


class StoredMass:
    """Volumes and centres known already (as a document's analysis stored
    them): BodyInfo's mass table without an assembly."""

    def __init__(self, values):
        self.values = values

    def get(self, index):
        return self.values[index]


@dataclass
class SkippedRecord:
    """A candidate pair whose test failed (an OCCT exception): skipped, the rest kept.
    `message` is the error; Analysis.messages has a readable line for it."""
    a: str
    b: str
    faces_a: List[str]
    faces_b: List[str]
    message: str


@dataclass
class ContactRecord:
    type: str
    a: str                   # body names, in assembly order
    b: str
    faces_a: List[str]       # "FaceN" of a's document object (or solid, for STEP)
    faces_b: List[str]
    area: float              # mm^2; 0 for circle contacts (LAF, SPT)
    partial: bool
    span: float              # common angular span, degrees (revolution contacts)
    radius: float
    half_angle: float        # degrees (CJU)
    point: Tuple[float, float, float]
    direction: Tuple[float, float, float]
    body_a: int = 0
    body_b: int = 0
    intent: str = ""            # the designer's annotation (contactwb.core.annotations), "" when none
    fit: Optional[str] = None   # its ISO 286 fit code, when given (cylindrical contacts)
    fit_detail: Optional[object] = None  # contactwb.core.iso286.Fit of that code at the contact's diameter

    def __str__(self):
        extra = f", partial {self.span:.0f} deg" if self.partial else ""
        return f"{self.type} {self.a} <-> {self.b} (area {self.area:.3f} mm2{extra})"


def printable(text):
    """A line of a table with its control characters (terminal escapes, CR,
    LF, ... from body names) shown as \\x.. escapes: a name cannot retitle the
    terminal or fake a line of the table."""
    if text.isprintable():
        return text
    return "".join(c if c.isprintable() else
                   (f"\\x{ord(c):02x}" if ord(c) < 0x100 else f"\\u{ord(c):04x}") for c in text)


@dataclass
class Analysis:
    source: str
    units: str
    linear_tolerance: float
    angular_tolerance: float
    bodies: List[BodyInfo]
    contacts: List[ContactRecord]
    messages: List[str] = field(default_factory=list)
    interferences: List[Tuple[str, str, float]] = field(default_factory=list)  # (a, b, volume mm^3)
    body_pairs: int = 0
    candidates: int = 0
    times: Dict[str, float] = field(default_factory=dict)
    skipped: List[SkippedRecord] = field(default_factory=list)
    # Bodies whose solid is not valid: {"body", "faces": ["Face3", ...], "reason"}
    invalid_bodies: List[dict] = field(default_factory=list)
    # Point and line contacts, apart from `contacts` (docs/joints.md): {"type", "kind", "a", "b",
    # "faces_a", "faces_b", "point", "normal", "start", "end", "length"}
    higher_pairs: List[dict] = field(default_factory=list)

    def counts(self):
        """Counter of contact types."""
        return Counter(c.type for c in self.contacts)

    def by_pair(self):
        """{(a, b): Counter of types} in assembly order."""
        pairs = defaultdict(Counter)
        for c in self.contacts:
            pairs[(c.a, c.b)][c.type] += 1
        return dict(pairs)

    def to_json(self):
        """A JSON-ready dict (the CLI's --json)."""
        return {
            "source": self.source,
            "units": self.units,
            "tolerances": {"linear": self.linear_tolerance, "angular": self.angular_tolerance},
            "bodies": [{"name": b.name, "path": b.path, "volume": b.volume, "center": list(b.center)}
                       for b in self.bodies],
            "contacts": [_contact_json(c) for c in self.contacts],
            "totals": dict(self.counts()),
            "skipped": [{"a": s.a, "b": s.b, "faces_a": s.faces_a, "faces_b": s.faces_b, "message": s.message}
                        for s in self.skipped],
            "interferences": [{"a": a, "b": b, "volume": v} for a, b, v in self.interferences],
            "higher_pairs": self.higher_pairs,
            "invalid_bodies": self.invalid_bodies,
            "messages": self.messages,
            "times": self.times,
        }

    def table(self):
        """The paper's table: per type, the body pairs and their counts, then totals."""
        lines = [f"Contacts of {self.source}: {len(self.bodies)} bodies (file units {self.units}), "
                 f"tolerances {self.linear_tolerance:.3g} mm, {self.angular_tolerance:.3g} rad"]
        for message in self.messages:
            lines.append(f"  note: {message}")
        width = max((len(b.name) for b in self.bodies), default=4)
        counts = self.counts()
        for kind in TYPE_ORDER:
            if not counts[kind]:
                continue
            lines.append("")
            lines.append(f"{TYPE_TITLES[kind]} ({kind}): {counts[kind]}")
            pairs = Counter((c.a, c.b) for c in self.contacts if c.type == kind)
            partial = Counter((c.a, c.b) for c in self.contacts if c.type == kind and c.partial)
            for (a, b), n in pairs.items():
                note = f"  ({partial[(a, b)]} partial)" if partial[(a, b)] else ""
                lines.append(f"  {a:<{width}}  <->  {b:<{width}}  {n}{note}")
        if self.higher_pairs:
            lines.append("")
            lines.append(f"Point and line contacts (higher pairs, apart from the contacts above): "
                         f"{len(self.higher_pairs)}")
            for h in self.higher_pairs:
                centre = "(" + ", ".join(f"{v:.4g}" for v in h["point"]) + ")"
                where = (f"along {h['length']:.4g} mm" if h["kind"] == "line" else
                         f"along a circle r {h['radius']:.4g} about {centre}" if h["kind"] == "circle" else
                         f"at {centre}")
                lines.append(f"  {h['a']:<{width}}  <->  {h['b']:<{width}}  {h['type']} {where}")
        if self.interferences:
            lines.append("")
            lines.append(f"Interferences (overlapping material, not contacts): {len(self.interferences)}")
            for a, b, volume in self.interferences:
                lines.append(f"  {a:<{width}}  <->  {b:<{width}}  {volume:.6g} mm3")
        if self.invalid_bodies:
            lines.append("")
            lines.append(f"Invalid solids (their contacts may be wrong): {len(self.invalid_bodies)}")
            for invalid in self.invalid_bodies:
                lines.append(f"  {invalid['body']:<{width}}  {invalid['reason']}: {', '.join(invalid['faces']) or 'whole solid'}")
        lines.append("")
        summary = ", ".join(f"{counts[k]} {k}" for k in TYPE_ORDER if counts[k])
        lines.append(f"Total: {len(self.contacts)} contacts ({summary or 'none'}) "
                     f"between {len(self.by_pair())} body pairs")
        if self.skipped:
            pairs = ", ".join(f"{s.a} <-> {s.b}" for s in self.skipped)
            lines.append(f"Skipped {len(self.skipped)} candidate pair(s) whose test failed, the rest kept "
                         f"(see the notes): {pairs}")
        return "\n".join(printable(line) for line in lines)


def _contact_json(c):
    out = {"type": c.type, "a": c.a, "b": c.b, "faces_a": c.faces_a, "faces_b": c.faces_b, "area": c.area,
           "partial": c.partial, "span": c.span, "radius": c.radius, "half_angle": c.half_angle,
           "point": list(c.point), "direction": list(c.direction)}
    if c.intent:  # annotated (--annotations): the designer's intent and fit, echoed
        out["intent"] = c.intent
        out["fit"] = c.fit
        if c.fit_detail is not None:  # the fit's class and limits at this diameter (µm)
            out["fit_class"] = c.fit_detail.fit_class
            out["fit_limits"] = c.fit_detail.to_json()
    return out


def analysis_of_result(source, assembly, result, face_name=None):
    """The Analysis of a core result; converting a huge result (millions of
    pairs) can run out of memory inside pybind11, which then raises
    RuntimeError("Could not allocate ...") or TypeError("Unable to convert
    function return value ..."): a MemoryError."""
    try:
        return _convert_result(source, assembly, result, face_name)
    except (RuntimeError, TypeError) as error:
        if "Could not allocate" in str(error) or "Unable to convert function return value" in str(error):
            raise MemoryError(f"out of memory (handing the result to Python: {error})") from error
        raise


def _convert_result(source, assembly, result, face_name=None):
    core_bodies = assembly.bodies
    names = [b.name for b in core_bodies]
    face_name = face_name or (lambda body, index: f"Face{index}")
    contacts = []
    for c in result.contacts:
        contacts.append(ContactRecord(
            type=c.type_name, a=names[c.body_a], b=names[c.body_b],
            faces_a=[face_name(c.body_a, f) for f in c.faces_a],
            faces_b=[face_name(c.body_b, f) for f in c.faces_b],
            area=c.area, partial=c.partial, span=degrees(c.span), radius=c.radius,
            half_angle=degrees(c.half_angle), point=c.point, direction=c.direction,
            body_a=c.body_a, body_b=c.body_b))
    messages = list(assembly.messages) + list(getattr(result, "messages", []))
    # Faces OCCT could not evaluate were typed Other and skipped: say which.
    for name, body in zip(names, result.partitions):
        if body.status != "ok":
            messages.append(f"body '{name}': {body.status}")
    skipped = []
    for s in result.skipped:
        skipped.append(SkippedRecord(
            a=names[s.body_a], b=names[s.body_b], faces_a=[face_name(s.body_a, f) for f in s.faces_a],
            faces_b=[face_name(s.body_b, f) for f in s.faces_b], message=s.message))
    mass = _MassTable(assembly)
    times = {"partitions": result.times.partitions, "broad_phase": result.times.broad_phase,
             "candidates": result.times.candidates, "area": result.times.area,
             "validity": result.times.validity, "interferences": result.times.interferences}
    return Analysis(
        source=source, units=assembly.units,
        linear_tolerance=result.tolerances.linear, angular_tolerance=result.tolerances.angular,
        bodies=[BodyInfo(b.name, b.path, mass, i) for i, b in enumerate(core_bodies)],
        contacts=contacts, messages=messages, body_pairs=len(result.body_pairs),
        interferences=[(names[i.body_a], names[i.body_b], i.volume) for i in result.interferences],
        candidates=result.candidates, times=times, skipped=skipped,
        invalid_bodies=[{"body": names[i.body], "faces": [face_name(i.body, f) for f in i.faces], "reason": i.reason}
                        for i in getattr(result, "invalid_bodies", [])],
        higher_pairs=[_higher_pair_dict(h, names, face_name) for h in getattr(result, "higher_pairs", [])])


def _higher_pair_dict(h, names, face_name):
    """One point, line or circle contact as --json lists it (a circle also
    has its "axis" and "radius"; its "point" is the centre)."""
    out = {"type": h.type, "kind": h.kind, "a": names[h.body_a], "b": names[h.body_b],
           "faces_a": [face_name(h.body_a, f) for f in h.faces_a],
           "faces_b": [face_name(h.body_b, f) for f in h.faces_b],
           "point": list(h.point), "normal": list(h.normal), "start": list(h.start),
           "end": list(h.end), "length": h.length}
    if h.kind == "circle":
        out["axis"] = list(h.axis)
        out["radius"] = h.radius
    return out


def find_contacts_in_assembly(assembly, source="assembly", linear=None, angular=None, progress=None,
                              face_name=None, threads=0, max_pairs=None, check_solids="quick"):
    """Contacts of a contactcore.Assembly, on `threads` threads (0: all
    cores). `progress(stage, fraction)` may return False to cancel (raises
    contactwb.core.Cancelled). More than `max_pairs` body pairs with meeting
    boxes (default 2,000,000) raise ContactsError. `check_solids` "full" adds
    OCCT's whole BRepCheck_Analyzer and faces crossing each other to the
    solid checks. The core result is
    not kept: only what the Analysis reports."""
    result = core.contactcore.find_contacts(assembly, linear=linear, angular=angular, progress=progress,
                                            threads=threads, max_pairs=max_pairs, check_solids=check_solids)
    return analysis_of_result(source, assembly, result, face_name)


def max_bodies_keyword(max_bodies):
    """read_step's keyword for a limit given (None: its default)."""
    return {} if max_bodies is None else {"max_bodies": int(max_bodies)}


def find_contacts_in_step(path, linear=None, angular=None, progress=None, max_pairs=None, check_solids="quick",
                          max_bodies=None):
    """Contacts of a STEP file, read in C++ (no FreeCAD needed). An assembly expanding to more than
    `max_bodies` instances (default one million) is refused before it is expanded."""
    if "\0" in str(path):
        raise core.InputError(f"the path contains a NUL character: {path!r}")
    if os.path.isdir(path):
        raise core.InputError(f"a directory, not a file: '{path}'")
    if not os.path.isfile(path):
        raise core.InputError(f"no such file: '{path}'")
    # As bytes: a file name that is not UTF-8 reaches OCCT unchanged.
    assembly = core.contactcore.read_step(os.fsencode(os.path.abspath(path)), progress=progress,
                                          **max_bodies_keyword(max_bodies))  # errors name the file
    try:
        return find_contacts_in_assembly(assembly, os.path.basename(path), linear, angular, progress,
                                         max_pairs=max_pairs, check_solids=check_solids)
    except core.Cancelled:
        raise
    except (core.ContactsError, MemoryError) as error:
        raise type(error)(f"{error} in file '{path}'") from error  # same class: callers tell input from options

