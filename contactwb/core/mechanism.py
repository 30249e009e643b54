"""The derived mechanism as a robot model (issue 22, item 5; docs/mechanism.md),
headless and without FreeCAD: one link per rigid group, one joint per group
joint. Written as URDF or MJCF by contactwb.core.mechanism_export.

    from contactwb.core import joints, mechanism
    assembly = meshes.read_step_assembly("motor.step")
    _, found = joints.joints_in_assembly(assembly, annotations="motor.annotations.json")
    model = mechanism.build_model(assembly, found)

Units: metres, kilograms, radians (the assembly is in mm). Mass and inertia
come from the solids (OCCT GProp, Body.inertia) times one density
(DEFAULT_DENSITY, steel, unless given). Every link frame is parallel to the
assembly's axes: the ground link's at the assembly's origin, another link's
on its first rotation axis (else at its centre of mass); joint axes are
therefore given in the assembly's directions."""
import math
from dataclasses import dataclass, field
from typing import List, Optional

from contactwb import core

DEFAULT_DENSITY = 7850.0   # kg/m^3: steel, for every body unless --density says otherwise
MM = 1e-3                  # metres per mm


@dataclass
class Element:
    """One single-axis joint of a chain: kind "prismatic" or "revolute"."""
    kind: str
    axis: tuple            # unit vector, assembly axes
    origin: tuple          # metres, assembly frame: where the joint's frame sits
    lower: Optional[float] = None   # prismatic travel, metres (None: unlimited rotation)
    upper: Optional[float] = None
    mimic: Optional[tuple] = None   # (index of the element it follows, multiplier m/rad): helical


@dataclass
class Link:
    name: str
    bodies: List[str]
    body_indices: List[int]
    mass: float                    # kg
    centre: tuple                  # centre of mass, metres, assembly frame
    inertia: list                  # kg m^2 about the centre, assembly axes (3 rows)
    origin: tuple = (0.0, 0.0, 0.0)  # the link frame's origin, metres, assembly frame


@dataclass
class Joint:
    name: str
    parent: str
    child: str
    type: str              # the derived motion's name: rigid, revolute, cylindrical, ..., or "floating"
    elements: List[Element]
    note: str = ""


@dataclass
class Closure:
    """A pair joint that closes a loop of the groups' graph (docs/mechanism.md, "Loops"): left out of
    the tree (URDF is a tree), held in MJCF by an equality constraint where MuJoCo has one:
    "connect" (a point of link_a kept on the same point of link_b: a revolute or spherical
    closure), "weld" (a rigid one), else None (only named in the notes)."""
    name: str
    link_a: str            # MJCF body1: the anchor is given in its frame
    link_b: str
    type: str              # the pair joint's motion (revolute, spherical, cylindrical, ...)
    bodies: tuple          # the two bodies whose contacts make the closing pair joint
    anchor: tuple          # metres, assembly frame: the revolute axis' point or the sphere's centre
    axis: Optional[tuple]  # the revolute or cylindrical axis (unit), else None
    equality: Optional[str]
    kept_by_tree: bool = False  # both links turn and slide on the closure's own axis from one parent:
                                # the tree allows them nothing the closing joint forbids


@dataclass
class Model:
    name: str
    ground: str            # the fixed link
    links: List[Link]      # parents before children
    joints: List[Joint]
    density: float
    notes: List[str] = field(default_factory=list)
    closures: List[Closure] = field(default_factory=list)

    def link(self, name):
        return next(link for link in self.links if link.name == name)

    def to_json(self):
        """The summary the CLI prints under "export" (metres, kg)."""
        return {
            "name": self.name, "ground": self.ground, "density": self.density,
            "links": [{"name": l.name, "bodies": l.bodies, "mass": l.mass, "centre": list(l.centre),
                       "inertia": l.inertia, "origin": list(l.origin)} for l in self.links],
            "joints": [{"name": j.name, "type": j.type, "parent": j.parent, "child": j.child,
                        "elements": [{"kind": e.kind, "axis": list(e.axis), "origin": list(e.origin),
                                      "lower": e.lower, "upper": e.upper} for e in j.elements],
                        **({"note": j.note} if j.note else {})} for j in self.joints],
            "notes": self.notes,
            "closures": [{"name": c.name, "type": c.type, "links": [c.link_a, c.link_b], "bodies": list(c.bodies),
                          "anchor": list(c.anchor), "axis": list(c.axis) if c.axis else None,
                          "equality": c.equality, "kept_by_tree": c.kept_by_tree} for c in self.closures],
        }


# ---------------------------------------------------------------- small vector helpers (no numpy in Debian's base)

def vec_sub(a, b):
    return tuple(x - y for x, y in zip(a, b))


def vec_dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def vec_scale(a, s):
    return tuple(x * s for x in a)


def clean_number(value):
    """Round-off below 1e-15 shown as 0 (and -0 as 0)."""
    return 0.0 if abs(value) < 1e-15 else float(value)


def clean_vector(values):
    return tuple(clean_number(v) for v in values)


def safe_name(name):
    """A link, joint and file name: letters, digits, '-', '_' and '.' kept, others '_'."""
    return "".join(c if c.isalnum() or c in "-_." else "_" for c in name) or "body"


# ---------------------------------------------------------------- mass properties

def link_mass(assembly, indices, density):
    """(mass kg, centre m, inertia kg m^2 about the centre, assembly axes) of bodies taken as one rigid
    link: each body's GProp volume integrals (mm^3, mm, mm^5 at unit density) scaled by `density`
    (kg/m^3) and added by the parallel-axis theorem."""
    kg_per_mm3 = density * 1e-9
    parts = []
    for index in indices:
        volume, centre, tensor = assembly.bodies[index].inertia()
        parts.append((volume * kg_per_mm3, vec_scale(centre, MM), [[v * kg_per_mm3 * 1e-6 for v in row]
                                                                for row in tensor]))
    mass = sum(m for m, _, _ in parts)
    centre = tuple(sum(m * c[k] for m, c, _ in parts) / mass for k in range(3))
    inertia = [[0.0] * 3 for _ in range(3)]
    for m, c, tensor in parts:
        d = vec_sub(c, centre)
        d2 = vec_dot(d, d)
        for i in range(3):
            for j in range(3):
                inertia[i][j] += tensor[i][j] + m * ((d2 if i == j else 0.0) - d[i] * d[j])
    return mass, centre, [[clean_number(v) for v in row] for row in inertia]


# ---------------------------------------------------------------- the tree of groups

def _group_name(assembly, group, used):
    """A group's link name: its largest body's name (ties: the first), made unique."""
    volumes = [(assembly.bodies[i].volume, -n) for n, i in enumerate(group)]
    best = group[-max(volumes)[1]]
    name, number = safe_name(assembly.bodies[best].name), 2
    base = name
    while name in used or name == "world":
        name = f"{base}.{number}"
        number += 1
    used.add(name)
    return name


def _in_cone(direction, generators):
    """True when `direction` is (within 1e-6) a non-negative combination of one or two generators:
    enough for the prismatic stops met here (a slide's own axis, or within a planar cone)."""
    for g in generators:
        if vec_dot(direction, g) > 1 - 1e-6:
            return True
    for i, g in enumerate(generators):
        for h in generators[i + 1:]:
            # direction = s g + t h with s, t >= 0: solve the 2x2 normal equations.
            gg, hh, gh = vec_dot(g, g), vec_dot(h, h), vec_dot(g, h)
            det = gg * hh - gh * gh
            if det < 1e-12:
                continue
            dg, dh = vec_dot(direction, g), vec_dot(direction, h)
            s, t = (dg * hh - dh * gh) / det, (dh * gg - dg * gh) / det
            rest = vec_sub(direction, tuple(s * a + t * b for a, b in zip(g, h)))
            if s >= -1e-9 and t >= -1e-9 and vec_dot(rest, rest) < 1e-12:
                return True
    return False


def _extent(vertices_mm, direction):
    """Length of the vertices' shadow on `direction`, metres."""
    values = [vec_dot(v, direction) for v in vertices_mm]
    return (max(values) - min(values)) * MM if values else 0.0


def _travel(direction, pair_joints, child_group, vertices_mm):
    """(lower, upper) travel of a prismatic element, metres: 0 on a side some pair joint between the
    two groups stops (its free directions exclude it), the child's length along the axis on a free
    side (beyond it the parts have parted: contacts give no other limit)."""
    length = _extent(vertices_mm, direction)
    free = {+1: True, -1: True}
    for joint in pair_joints:
        flip = 1.0 if joint.body_b in child_group else -1.0  # free directions are b's, relative to a
        if not joint.stops:
            continue  # bilateral: the slide is free both ways
        generators = [vec_scale(g, flip) for g in joint.free_directions]
        for side in (+1, -1):
            if not _in_cone(vec_scale(direction, side), generators):
                free[side] = False
    return (-length if free[-1] else 0.0), (length if free[+1] else 0.0)


def _elements(motion_type, rotations, translations, pitch, child_centre):
    """The chain of single-axis joints of a motion: translations first, then rotations (a
    cylindrical joint: slide then turn about the slid axis; planar: two slides then the turn)."""
    if motion_type == "spherical" and len(rotations) == 3:
        # Any three independent axes through the centre span the same motion: the assembly's x, y, z read best.
        rotations = [(rotations[0][0], axis) for axis in ((1, 0, 0), (0, 1, 0), (0, 0, 1))]
    anchor = clean_vector(p * MM for p in rotations[0][0]) if rotations else child_centre
    out = []
    if motion_type == "helical" and rotations:
        point, direction = rotations[0]
        out.append(Element("revolute", clean_vector(direction), anchor))
        out.append(Element("prismatic", clean_vector(direction), anchor, mimic=(0, pitch * MM)))
        return out
    for direction in translations:
        out.append(Element("prismatic", clean_vector(direction), anchor))
    for point, direction in rotations:
        out.append(Element("revolute", clean_vector(direction), clean_vector(p * MM for p in point)))
    return out


def build_model(assembly, found, density=DEFAULT_DENSITY, ground=None, name="mechanism", mesh_results=None):
    """The Model of a joints analysis (contactwb.core.joints.Joints with .raw): one link per rigid
    group, the ground link the group of `ground` (a body name) or else the group with the most bodies
    (ties: the one holding the analysis' ground). Each other group hangs from the ground by its
    motion relative to the ground (GroupMotion) when it touches the ground group; from the group it
    was reached through otherwise (the pair joint between them allowing least), loops cut with a
    note; a group touching nothing is floating. `mesh_results` (mesh_assembly's, per body) give the
    prismatic travels (the child's length along the axis)."""
    if not density > 0 or not math.isfinite(density):
        raise core.ArgumentError(f"density must be a positive, finite number of kg/m^3, got {density}")
    cc = core.contactcore
    raw, pairs, mobility = found.raw
    names = [b.name for b in assembly.bodies]
    groups = [list(g) for g in mobility.groups]
    if ground is not None:
        if ground not in names:
            raise core.ArgumentError(f"no body named '{ground}' to ground; bodies: {', '.join(names)}")
        wanted = names.index(ground)
    else:
        most = max(len(g) for g in groups)
        wanted = mobility.ground if len(groups[mobility.group_of_body[mobility.ground]]) == most else \
            next(g for g in groups if len(g) == most)[0]
    if mobility.group_of_body[wanted] != mobility.group_of_body[mobility.ground]:
        # Group motions are relative to the analysis' ground: solve again with this one.
        mobility = cc.assembly_mobility(assembly, raw, pairs, wanted)
        groups = [list(g) for g in mobility.groups]
    ground_group = mobility.group_of_body[wanted]
    used = set()
    link_names = [_group_name(assembly, g, used) for g in groups]
    notes = []

    def vertices_of(group):
        if mesh_results is None:
            return []
        return [v for i in group for v in mesh_results[i].mesh.vertices]

    links = {}
    for g, group in enumerate(groups):
        mass, centre, inertia = link_mass(assembly, group, density)
        links[g] = Link(link_names[g], [names[i] for i in group], list(group), mass, clean_vector(centre), inertia)

    between = {}  # (group, group) -> pair joints, each pair of groups once
    for joint in pairs.joints:
        ga, gb = mobility.group_of_body[joint.body_a], mobility.group_of_body[joint.body_b]
        if ga != gb:
            between.setdefault((min(ga, gb), max(ga, gb)), []).append(joint)
    neighbours = {g: set() for g in range(len(groups))}
    for ga, gb in between:
        neighbours[ga].add(gb)
        neighbours[gb].add(ga)

    order, joints_out, seen = [ground_group], [], {ground_group}
    queue = [ground_group]
    while queue:
        parent = queue.pop(0)
        for child in sorted(neighbours[parent]):
            if child in seen:
                continue
            seen.add(child)
            order.append(child)
            queue.append(child)
            connecting = between[(min(parent, child), max(parent, child))]
            child_set = set(groups[child])
            note = ""
            if parent == ground_group:
                motion = mobility.group_motions[child]
                kind, rotations, translations, pitch = motion.type, motion.rotations, motion.translations, motion.pitch
            else:
                joint = min(connecting, key=lambda j: j.dof)
                kind, rotations, translations, pitch = joint.type, joint.rotations, joint.translations, joint.pitch
                if len(connecting) > 1:
                    note = (f"{len(connecting)} pair joints between {link_names[parent]} and {link_names[child]}: "
                            f"the one allowing least ({joint.type}, {names[joint.body_a]}-{names[joint.body_b]}) "
                            "exported")
            elements = _elements(kind, rotations, translations, pitch, links[child].centre)
            for element in elements:
                if element.kind == "prismatic" and element.mimic is None:
                    element.lower, element.upper = _travel(element.axis, connecting, child_set,
                                                           vertices_of(groups[child]))
            if kind == "helical":
                note = (note + "; " if note else "") + (f"helical: the slide follows the turn "
                                                        f"({pitch:g} mm/rad)")
            type_name = "rigid" if not elements else kind
            joints_out.append(Joint(f"{link_names[parent]}__{link_names[child]}", link_names[parent],
                                    link_names[child], type_name, elements, note))
            links[child].origin = elements[-1].origin if elements else links[child].centre
    closures = []
    for (ga, gb), connecting in sorted(between.items()):
        pair = {ga, gb}
        if any({link_names.index(j.parent), link_names.index(j.child)} == pair for j in joints_out):
            continue
        closure = _closure(connecting, link_names[ga], link_names[gb], names)
        if _kept_by_the_tree(closure, joints_out):
            closure.equality = None
            closure.kept_by_tree = True
        closures.append(closure)
        notes.append(_closure_note(closure, connecting))
    for g in range(len(groups)):
        if g not in seen:
            order.append(g)
            links[g].origin = links[g].centre
            joints_out.append(Joint(f"world__{link_names[g]}", "world", link_names[g], "floating", [],
                                    "touches nothing: a free body"))
            notes.append(f"{link_names[g]} touches no other group: exported as a free (floating) body")
    return Model(name=safe_name(name), ground=link_names[ground_group], links=[links[g] for g in order],
                 joints=joints_out, density=density, notes=notes, closures=closures)


# MuJoCo's equality constraints for a closing pair joint: a point held (connect) or the whole pose (weld).
EQUALITY_OF_CLOSURE = {"revolute": "connect", "spherical": "connect", "rigid": "weld"}


def _closure(connecting, name_a, name_b, names):
    """The Closure of the pair joints `connecting` between two groups already joined in the tree:
    the one allowing least (as the tree's choice)."""
    joint = min(connecting, key=lambda j: j.dof)
    kind = "rigid" if joint.dof == 0 else joint.type
    anchor, axis = (0.0, 0.0, 0.0), None
    if joint.rotations:
        anchor = clean_vector(p * MM for p in joint.rotations[0][0])
        if kind in ("revolute", "cylindrical"):
            axis = clean_vector(joint.rotations[0][1])
    equality = EQUALITY_OF_CLOSURE.get(kind)
    if kind in ("revolute", "spherical") and not joint.rotations:
        equality = None
    return Closure(f"{name_a}__{name_b}", name_a, name_b, kind, (names[joint.body_a], names[joint.body_b]),
                   anchor, axis, equality)


def _on_line(element, closure):
    """True when a chain element moves along or about the closure's axis line (m, 1e-9)."""
    if abs(abs(vec_dot(element.axis, closure.axis)) - 1) > 1e-9:
        return False
    if element.kind == "prismatic":
        return True
    offset = vec_sub(element.origin, closure.anchor)
    along = vec_dot(offset, closure.axis)
    rest = vec_sub(offset, vec_scale(closure.axis, along))
    return vec_dot(rest, rest) < 1e-18


def _kept_by_the_tree(closure, tree_joints):
    """True when the closing joint (revolute or cylindrical) needs no constraint: its two links hang
    from one parent by joints that only turn about, or slide along, its own axis (their relative
    motion is then one the closing joint allows: revolute closures need turns only)."""
    if closure.axis is None or closure.type not in ("revolute", "cylindrical"):
        return False
    by_child = {j.child: j for j in tree_joints}
    a, b = by_child.get(closure.link_a), by_child.get(closure.link_b)
    if a is None or b is None or a.parent != b.parent:
        return False
    for joint in (a, b):
        for element in joint.elements:
            if not _on_line(element, closure) or (closure.type == "revolute" and element.kind == "prismatic"):
                return False
    return True


def _closure_note(closure, connecting):
    where = ""
    if closure.axis is not None:
        where = (f" about ({', '.join(f'{v:.4g}' for v in closure.axis)}) through "
                 f"({', '.join(f'{v:.4g}' for v in closure.anchor)}) m")
    elif closure.type == "spherical":
        where = f" about ({', '.join(f'{v:.4g}' for v in closure.anchor)}) m"
    if closure.kept_by_tree:
        mjcf = ("nothing to hold in MJCF either: both links move only on its axis from the same parent, "
                "which it allows")
    elif closure.equality:
        mjcf = f"MJCF closes it with an <equality> {closure.equality}"
    else:
        mjcf = f"MJCF has no equality constraint for a {closure.type} closure: left out there too"
    others = f" ({len(connecting)} pair joints, the one allowing least)" if len(connecting) > 1 else ""
    return (f"loop closed by joint {closure.name} ({closure.type}{where}, {closure.bodies[0]}-{closure.bodies[1]}"
            f"{others}): left out of the URDF (a tree); {mjcf}")
