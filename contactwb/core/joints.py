"""Joints and mobility, headless and without FreeCAD: from contacts to kinematic joints per body
pair, the assembly's degrees of freedom, its rigid groups and the liaison
graph (docs/joints.md).

    from contactwb import joints
    result, found = joints.joints_in_step("motor.step")
    print(found.table())
    found.write_graph("motor.svg")

Documents and Part shapes: contactwb.document.analysis (joints_in_document).
"""
import os
import shutil
import subprocess
from dataclasses import dataclass, field
from typing import List, Optional

from contactwb import core
from contactwb.core import analysis
from contactwb.core import annotations as annotation_api


def _vec(values):
    return [float(v) for v in values]


def _rotations(axes):
    return [{"point": _vec(point), "direction": _vec(direction)} for point, direction in axes]


@dataclass
class JointRecord:
    a: str                 # body names; the joint is b's motion relative to a
    b: str
    type: str              # ISO 3952: rigid, revolute, prismatic, cylindrical, spherical, planar, ...
    dof: int
    rotations: List[dict]  # [{"point": [x, y, z], "direction": [x, y, z]}]
    translations: List[dict]  # [{"direction": [x, y, z]}]
    free_directions: List[list]  # generators of the cone in which b can leave a
    contacts: List[int]    # indices into the analysis' contacts
    one_sided: int = 0     # number of one-sided stops
    body_a: int = 0
    body_b: int = 0
    higher_pairs: List[int] = field(default_factory=list)  # indices into the analysis' higher_pairs
    annotated_rigid: bool = False  # held rigid by an annotated press fit or bond

    def to_json(self):
        out = {"a": self.a, "b": self.b, "type": self.type, "dof": self.dof, "rotations": self.rotations,
               "translations": self.translations, "free_directions": self.free_directions,
               "contacts": self.contacts, "higher_pairs": self.higher_pairs}
        if self.annotated_rigid:  # only with --annotations
            out["annotated_rigid"] = True
        return out


@dataclass
class Mobility:
    ground: str
    dof: int
    passive: int
    groups: List[List[str]]
    group_joints: List[dict]

    def to_json(self):
        return {"ground": self.ground, "dof": self.dof, "passive": self.passive, "groups": self.groups,
                "group_joints": self.group_joints}


@dataclass
class Joints:
    source: str
    joints: List[JointRecord]
    mobility: Mobility
    dot: str                                   # the liaison graph, Graphviz DOT
    clearances: List[dict] = field(default_factory=list)
    interferences: List[dict] = field(default_factory=list)
    clearance_gap: float = 0.0
    raw: Optional[object] = None  # (contactcore.ContactsResult, .JointsResult, .MobilityResult)
    _body_index: dict = field(default_factory=dict, repr=False)

    def to_json(self):
        """The CLI's --joints --json additions."""
        return {"joints": [j.to_json() for j in self.joints], "mobility": self.mobility.to_json()}

    def table(self, interferences=True):
        """The joint table, the mobility and the rigid groups, as text (and the
        interferences, unless the contact table beside it lists them already)."""
        lines = [f"Joints of {self.source} (b relative to a): {len(self.joints)} body pairs"]
        width = max([len(j.a) for j in self.joints] + [len(j.b) for j in self.joints] + [4])
        for j in self.joints:
            axes = [f"turns about {_fmt(r['direction'])} through {_fmt(r['point'])}" for r in j.rotations]
            axes += [f"slides along {_fmt(t['direction'])}" for t in j.translations]
            if j.type in ("rigid",):
                axes = ["held by annotated fits or bonds"] if j.annotated_rigid else []
            leaves = (f"; leaves along {', '.join(_fmt(d) for d in j.free_directions)}"
                      if j.free_directions and len(j.free_directions) <= 4 else
                      f"; leaves within a cone of {len(j.free_directions)} directions" if j.free_directions else
                      "; cannot leave by a translation")
            lines.append(f"  {j.a:<{width}}  <->  {j.b:<{width}}  {j.type} ({j.dof})"
                         f"{': ' + '; '.join(axes) if axes else ''}{leaves}")
        m = self.mobility
        lines.append("")
        lines.append(f"Mobility (ground {m.ground}): {m.dof} DOF, of which {m.passive} passive spins; "
                     f"{len(m.groups)} rigid groups")
        for index, (group, motion) in enumerate(zip(m.groups, m.group_joints), start=1):
            head = "ground" if index == 1 else f"{motion['type']} ({motion['dof']})"
            axes = [f"turns about {_fmt(r['direction'])} through {_fmt(r['point'])}" for r in motion["rotations"]]
            axes += [f"slides along {_fmt(t['direction'])}" for t in motion["translations"]]
            lines.append(f"  {index}. {head}: {', '.join(group)}" + (f"; {'; '.join(axes)}" if axes else ""))
            spins = sorted({s["body"] for s in motion["passive_spins"]})
            if spins:
                lines.append(f"     passive spins: {', '.join(spins)}")
        if self.clearance_gap > 0:
            lines.append("")
            lines.append(f"Clearance fits (gap < {self.clearance_gap:g} mm, not contacts): {len(self.clearances)}")
            for c in self.clearances:
                lines.append(f"  {c['a']:<{width}}  <->  {c['b']:<{width}}  {c['kind']} gap {c['gap']:.4g} mm")
        if interferences and self.interferences:
            lines.append("")
            lines.append(f"Interferences (overlapping material, not contacts): {len(self.interferences)}")
            for i in self.interferences:
                lines.append(f"  {i['a']:<{width}}  <->  {i['b']:<{width}}  {i['volume']:.4g} mm3")
        return "\n".join(analysis.printable(line) for line in lines)

    def free_directions_of(self, body):
        """Directions in which `body` (a name) can translate out, every part it
        touches held still: generators of that cone, [] when it cannot."""
        raw, found, _ = self.raw
        if body not in self._body_index:
            raise core.ArgumentError(f"no body named '{body}'")
        index = self._body_index[body]
        return [_vec(d) for d in core.contactcore.body_free_directions(raw, found, index)]

    def write_graph(self, path):
        """Writes the liaison graph: .dot as text, .svg or .png rendered by Graphviz `dot`."""
        extension = os.path.splitext(path)[1].lower()
        if extension == ".dot":
            with open(path, "w", encoding="utf-8") as out:
                out.write(self.dot)
            return path
        if extension not in (".svg", ".png"):
            raise core.ContactsError(f"graph file '{path}': use .svg, .png or .dot")
        dot = shutil.which("dot")
        if not dot:
            raise core.ContactsError("Graphviz 'dot' is not installed (Debian package graphviz): "
                                     f"cannot write '{path}'; write a .dot file instead")
        done = subprocess.run([dot, f"-T{extension[1:]}", "-o", path], input=self.dot.encode("utf-8"),
                              capture_output=True, check=False)
        if done.returncode != 0:
            raise core.ContactsError(f"Graphviz failed on '{path}': {done.stderr.decode(errors='replace').strip()}")
        return path


def _fmt(values):
    return "(" + ", ".join(f"{v:.4g}" if abs(v) > 1e-12 else "0" for v in values) + ")"


AXIS_NAMES = {(1, 0, 0): "x", (0, 1, 0): "y", (0, 0, 1): "z"}


def direction_name(direction):
    """"z" for (0, 0, ±1) (an axis, either sense), else the vector."""
    for axis, name in AXIS_NAMES.items():
        if abs(abs(sum(a * d for a, d in zip(axis, direction))) - 1.0) <= 1e-9:
            return name
    return _fmt(direction)


def describe_motion(rotations, translations):
    """"1 rotation about z through (0, 0, 30.6); 1 translation along z":
    the free motions of a joint or a rigid group, in words. `rotations`:
    [(point, direction)], `translations`: [direction]."""
    parts = []
    if rotations:
        axes = [f"{direction_name(d)} through {_fmt(p)}" for p, d in rotations]
        parts.append(f"{len(rotations)} rotation{'s' if len(rotations) > 1 else ''} about {', '.join(axes)}")
    if translations:
        parts.append(f"{len(translations)} translation{'s' if len(translations) > 1 else ''} along "
                     + ", ".join(direction_name(d) for d in translations))
    return "; ".join(parts) or "no motion"


def _ground_index(names, ground):
    if ground is None:
        return -1  # the core picks the largest by volume
    if ground not in names:
        raise core.ArgumentError(f"no body named '{ground}' to ground; bodies: {', '.join(names)}")
    return names.index(ground)


def joints_in_assembly(assembly, source="assembly", linear=None, angular=None, progress=None, face_name=None,
                       ground=None, clearance_gap=0.0, max_pairs=None, check_solids="quick", annotations=None):
    """(analysis.Analysis, Joints) of a contactcore.Assembly: contacts, then
    joints, mobility and liaison graph. `ground`: a body name (default: the
    largest by volume). `clearance_gap` > 0 also lists clearance fits.
    `annotations`: the designer's fits and bonds (contactwb.core.annotations:
    a list of Annotation, of dicts, or a JSON file's path): press fits and
    bonds make their pairs rigid, ignored contacts are left out."""
    cc = core.contactcore
    names = [b.name for b in assembly.bodies]
    ground_index = _ground_index(names, ground)
    notes = None
    if annotations is not None:  # checked before the work, resolved after the contacts
        notes = (annotation_api.load(annotations) if isinstance(annotations, (str, os.PathLike)) else
                 annotation_api.parse(annotations) if annotations and isinstance(annotations[0], dict) else
                 list(annotations))
    raw = cc.find_contacts(assembly, linear=linear, angular=angular, progress=progress, max_pairs=max_pairs,
                           clearance_gap=clearance_gap, check_solids=check_solids)
    result = analysis.analysis_of_result(source, assembly, raw, face_name)
    contact_marks, higher_marks = [], []
    if notes is not None:
        contact_marks, higher_marks = annotation_api.resolve(notes, names, raw.contacts, raw.higher_pairs)
        for record, (intent, fit) in zip(result.contacts, contact_marks):
            record.intent, record.fit = intent, fit
    found = cc.find_joints(assembly, raw, contact_intents=[intent for intent, _ in contact_marks],
                           higher_pair_intents=[intent for intent, _ in higher_marks])
    mobility = cc.assembly_mobility(assembly, raw, found, ground_index)
    records = [JointRecord(
        a=names[j.body_a], b=names[j.body_b], type=j.type, dof=j.dof, rotations=_rotations(j.rotations),
        translations=[{"direction": _vec(d)} for d in j.translations],
        free_directions=[_vec(d) for d in j.free_directions], contacts=list(j.contacts),
        one_sided=len(j.stops), body_a=j.body_a, body_b=j.body_b,
        higher_pairs=list(j.higher_pairs), annotated_rigid=j.annotated_rigid) for j in found.joints]
    group_joints = []
    for group, motion in zip(mobility.groups, mobility.group_motions):
        group_joints.append({
            "group": motion.group, "bodies": [names[i] for i in group], "type": motion.type, "dof": motion.dof,
            "rotations": _rotations(motion.rotations),
            "translations": [{"direction": _vec(d)} for d in motion.translations],
            "passive_spins": [{"body": names[s.body], "point": _vec(s.point), "direction": _vec(s.direction)}
                              for s in motion.passive_spins]})
    record = Mobility(ground=names[mobility.ground] if mobility.ground >= 0 else "", dof=mobility.dof,
                      passive=mobility.passive, groups=[[names[i] for i in g] for g in mobility.groups],
                      group_joints=group_joints)
    clearances = [{"a": names[c.body_a], "b": names[c.body_b], "kind": c.kind, "gap": c.gap}
                  for c in raw.clearances]
    return result, Joints(source=source, joints=records, mobility=record,
                          dot=cc.liaison_graph_dot(assembly, found, mobility), clearances=clearances,
                          interferences=interferences_of(raw, names), clearance_gap=clearance_gap,
                          raw=(raw, found, mobility), _body_index={name: i for i, name in enumerate(names)})


def interferences_of(raw, names):
    """The contact result's interferences (overlapping bodies, with volume), when the core found any."""
    return [{"a": names[i.body_a], "b": names[i.body_b], "volume": i.volume}
            for i in getattr(raw, "interferences", None) or []]


def joints_in_step(path, linear=None, angular=None, progress=None, ground=None, clearance_gap=0.0,
                   max_pairs=None, check_solids="quick", max_bodies=None,
                   annotations=None):
    """(analysis.Analysis, Joints) of a STEP file, read in C++."""
    if not os.path.isfile(path):
        raise core.InputError(f"no such file: '{path}'")
    assembly = core.contactcore.read_step(os.fsencode(os.path.abspath(path)), progress=progress,
                                          **analysis.max_bodies_keyword(max_bodies))  # bytes: non-UTF-8 names work
    try:
        return joints_in_assembly(assembly, os.path.basename(path), linear, angular, progress, ground=ground,
                                  clearance_gap=clearance_gap, max_pairs=max_pairs, check_solids=check_solids,
                                  annotations=annotations)
    except core.Cancelled:
        raise
    except core.ContactsError as error:
        raise type(error)(f"{error} in file '{path}'") from error  # same class: usage errors stay usage errors

