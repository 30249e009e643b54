"""The derived mechanism as a robot model (issue 22, item 5; docs/mechanism.md),
headless and without FreeCAD: one link per rigid group, one joint per group
joint, written as URDF (a folder: MODEL.urdf and meshes/) or MJCF (FILE.xml
and FILE_meshes/ beside it).

    from contactwb.core import joints, mechanism
    assembly = meshes.read_step_assembly("motor.step")
    _, found = joints.joints_in_assembly(assembly, annotations="motor.annotations.json")
    model = mechanism.build_model(assembly, found)
    mechanism.write_urdf(model, assembly, "motor_urdf")

Units: metres, kilograms, radians (the assembly is in mm). Mass and inertia
come from the solids (OCCT GProp, Body.inertia) times one density
(DEFAULT_DENSITY, steel, unless given). Every link frame is parallel to the
assembly's axes: the ground link's at the assembly's origin, another link's
on its first rotation axis (else at its centre of mass); joint axes are
therefore given in the assembly's directions."""
import math
import os
import struct
from dataclasses import dataclass, field
from typing import List, Optional
from xml.sax.saxutils import quoteattr

from contactwb import core
from contactwb.core import meshes as mesh_api
from contactwb.core import output_files

DEFAULT_DENSITY = 7850.0   # kg/m^3: steel, for every body unless --density says otherwise
MM = 1e-3                  # metres per mm
FORMATS = ("urdf", "mjcf")


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
class Model:
    name: str
    ground: str            # the fixed link
    links: List[Link]      # parents before children
    joints: List[Joint]
    density: float
    notes: List[str] = field(default_factory=list)

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
        }


# ---------------------------------------------------------------- small vector helpers (no numpy in Debian's base)

def _sub(a, b):
    return tuple(x - y for x, y in zip(a, b))


def _dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def _scale(a, s):
    return tuple(x * s for x in a)


def _clean(value):
    """Round-off below 1e-15 shown as 0 (and -0 as 0)."""
    return 0.0 if abs(value) < 1e-15 else float(value)


def _clean_vec(values):
    return tuple(_clean(v) for v in values)


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
        parts.append((volume * kg_per_mm3, _scale(centre, MM), [[v * kg_per_mm3 * 1e-6 for v in row]
                                                                for row in tensor]))
    mass = sum(m for m, _, _ in parts)
    centre = tuple(sum(m * c[k] for m, c, _ in parts) / mass for k in range(3))
    inertia = [[0.0] * 3 for _ in range(3)]
    for m, c, tensor in parts:
        d = _sub(c, centre)
        d2 = _dot(d, d)
        for i in range(3):
            for j in range(3):
                inertia[i][j] += tensor[i][j] + m * ((d2 if i == j else 0.0) - d[i] * d[j])
    return mass, centre, [[_clean(v) for v in row] for row in inertia]


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
        if _dot(direction, g) > 1 - 1e-6:
            return True
    for i, g in enumerate(generators):
        for h in generators[i + 1:]:
            # direction = s g + t h with s, t >= 0: solve the 2x2 normal equations.
            gg, hh, gh = _dot(g, g), _dot(h, h), _dot(g, h)
            det = gg * hh - gh * gh
            if det < 1e-12:
                continue
            dg, dh = _dot(direction, g), _dot(direction, h)
            s, t = (dg * hh - dh * gh) / det, (dh * gg - dg * gh) / det
            rest = _sub(direction, tuple(s * a + t * b for a, b in zip(g, h)))
            if s >= -1e-9 and t >= -1e-9 and _dot(rest, rest) < 1e-12:
                return True
    return False


def _extent(vertices_mm, direction):
    """Length of the vertices' shadow on `direction`, metres."""
    values = [_dot(v, direction) for v in vertices_mm]
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
        generators = [_scale(g, flip) for g in joint.free_directions]
        for side in (+1, -1):
            if not _in_cone(_scale(direction, side), generators):
                free[side] = False
    return (-length if free[-1] else 0.0), (length if free[+1] else 0.0)


def _elements(motion_type, rotations, translations, pitch, child_centre):
    """The chain of single-axis joints of a motion: translations first, then rotations (a
    cylindrical joint: slide then turn about the slid axis; planar: two slides then the turn)."""
    if motion_type == "spherical" and len(rotations) == 3:
        # Any three independent axes through the centre span the same motion: the assembly's x, y, z read best.
        rotations = [(rotations[0][0], axis) for axis in ((1, 0, 0), (0, 1, 0), (0, 0, 1))]
    anchor = _clean_vec(p * MM for p in rotations[0][0]) if rotations else child_centre
    out = []
    if motion_type == "helical" and rotations:
        point, direction = rotations[0]
        out.append(Element("revolute", _clean_vec(direction), anchor))
        out.append(Element("prismatic", _clean_vec(direction), anchor, mimic=(0, pitch * MM)))
        return out
    for direction in translations:
        out.append(Element("prismatic", _clean_vec(direction), anchor))
    for point, direction in rotations:
        out.append(Element("revolute", _clean_vec(direction), _clean_vec(p * MM for p in point)))
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
        links[g] = Link(link_names[g], [names[i] for i in group], list(group), mass, _clean_vec(centre), inertia)

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
    for (ga, gb), connecting in sorted(between.items()):
        pair = {ga, gb}
        if not any({link_names.index(j.parent), link_names.index(j.child)} == pair for j in joints_out):
            notes.append(f"loop not exported (URDF and a MJCF body tree are trees): {link_names[ga]} - "
                         f"{link_names[gb]} ({', '.join(sorted({j.type for j in connecting}))})")
    for g in range(len(groups)):
        if g not in seen:
            order.append(g)
            links[g].origin = links[g].centre
            joints_out.append(Joint(f"world__{link_names[g]}", "world", link_names[g], "floating", [],
                                    "touches nothing: a free body"))
            notes.append(f"{link_names[g]} touches no other group: exported as a free (floating) body")
    return Model(name=safe_name(name), ground=link_names[ground_group], links=[links[g] for g in order],
                 joints=joints_out, density=density, notes=notes)


# ---------------------------------------------------------------- meshes

def _binary_stl(vertices_m, triangles):
    out = [b"contacts mechanism export (metres)".ljust(80, b" "), struct.pack("<I", len(triangles))]
    for i, j, k in triangles:
        a, b, c = vertices_m[i], vertices_m[j], vertices_m[k]
        u, v = _sub(b, a), _sub(c, a)
        n = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
        length = math.sqrt(_dot(n, n)) or 1.0
        out.append(struct.pack("<12fH", *(x / length for x in n), *a, *b, *c, 0))
    return b"".join(out)


def _safe_folder(path):
    """Makes `path` a folder to write into; refuses a symbolic link or a file there (UnsafeTarget)."""
    if os.path.islink(path):
        raise output_files.UnsafeTarget(f"'{path}' is a symbolic link: the export never writes through one")
    if os.path.lexists(path) and not os.path.isdir(path):
        raise output_files.UnsafeTarget(f"'{path}' exists and is not a folder")
    os.makedirs(path, exist_ok=True)


def _write_meshes(model, mesh_results, folder):
    """Each body's mesh as binary STL in its link's frame (metres), in `folder`; returns
    {body index: file name} for the bodies with triangles."""
    _safe_folder(folder)
    files = {}
    used = set()
    for link in model.links:
        for index, body in zip(link.body_indices, link.bodies):
            mesh = mesh_results[index].mesh
            triangles = mesh.triangles
            if not triangles:
                continue
            file_name = safe_name(body) + ".stl"
            stem, number = file_name[:-4], 2
            while file_name in used:
                file_name = f"{stem}.{number}.stl"
                number += 1
            used.add(file_name)
            vertices = [_sub(_scale(v, MM), link.origin) for v in mesh.vertices]
            with output_files.output_file(os.path.join(folder, file_name), "wb") as stream:
                stream.write(_binary_stl(vertices, triangles))
            files[index] = file_name
    return files


def mesh_bodies(assembly, deflection=0.1, angle=0.5, linear=None, angular=None):
    """The bodies' meshes with `contacts mesh`'s tessellation (same defaults)."""
    return mesh_api.mesh_assembly(assembly, deflection, angle, 0.0, linear, angular)


# ---------------------------------------------------------------- URDF

def _num(value):
    """12 significant digits: 0.01, not 0.009999999999999992 (the core's round-off in mm / 1000)."""
    return format(_clean(float(value)), ".12g")


def _xyz(values):
    return " ".join(_num(v) for v in values)


def _urdf_inertial(link):
    c = _sub(link.centre, link.origin)
    i = link.inertia
    return (f'    <inertial>\n      <origin xyz="{_xyz(c)}" rpy="0 0 0"/>\n      <mass value="{_num(link.mass)}"/>\n'
            f'      <inertia ixx="{_num(i[0][0])}" ixy="{_num(i[0][1])}" ixz="{_num(i[0][2])}" '
            f'iyy="{_num(i[1][1])}" iyz="{_num(i[1][2])}" izz="{_num(i[2][2])}"/>\n    </inertial>\n')


URDF_JOINT_OF_ELEMENT = {"prismatic": "prismatic", "revolute": "continuous"}


def urdf_text(model, mesh_files, mesh_folder):
    """The URDF document: a fixed joint from "world" to the ground link; a one-axis motion as one
    joint (continuous for a rotation: contacts give no angular limit; prismatic with its travel);
    a motion of several axes (cylindrical, planar, spherical, ...) as a chain of one-axis joints
    through massless links NAME__1, NAME__2, ... (URDF has no cylindrical or spherical joint); a
    helical motion as a continuous joint and a prismatic one mimicking it (multiplier: the pitch)."""
    lines = [f'<?xml version="1.0"?>\n<robot name={quoteattr(model.name)}>\n',
             f"  <!-- Exported by contacts (docs/mechanism.md): metres, kg, density {model.density:g} kg/m^3 -->\n"]
    for note in model.notes:
        lines.append(f"  <!-- {note.replace('--', '- -')} -->\n")
    lines.append('  <link name="world"/>\n')
    lines.append(f'  <joint name={quoteattr("world__" + model.ground)} type="fixed">\n'
                 f'    <parent link="world"/>\n    <child link={quoteattr(model.ground)}/>\n'
                 f'    <origin xyz="0 0 0" rpy="0 0 0"/>\n  </joint>\n')
    for link in model.links:
        lines.append(f"  <link name={quoteattr(link.name)}>\n")
        lines.append(_urdf_inertial(link))
        for index, body in zip(link.body_indices, link.bodies):
            if index in mesh_files:
                path = f"{mesh_folder}/{mesh_files[index]}"
                lines.append(f'    <visual name={quoteattr(body)}>\n      <origin xyz="0 0 0" rpy="0 0 0"/>\n'
                             f'      <geometry><mesh filename={quoteattr(path)}/></geometry>\n    </visual>\n')
        lines.append("  </link>\n")
    origins = {link.name: link.origin for link in model.links}
    origins["world"] = (0.0, 0.0, 0.0)
    for joint in model.joints:
        if joint.note:
            lines.append(f"  <!-- {joint.name}: {joint.note.replace('--', '- -')} -->\n")
        if joint.type == "floating":
            lines.append(f'  <joint name={quoteattr(joint.name)} type="floating">\n'
                         f'    <parent link="world"/>\n    <child link={quoteattr(joint.child)}/>\n'
                         f'    <origin xyz="{_xyz(origins[joint.child])}" rpy="0 0 0"/>\n  </joint>\n')
            continue
        if not joint.elements:
            lines.append(f'  <joint name={quoteattr(joint.name)} type="fixed">\n'
                         f'    <parent link={quoteattr(joint.parent)}/>\n    <child link={quoteattr(joint.child)}/>\n'
                         f'    <origin xyz="{_xyz(_sub(origins[joint.child], origins[joint.parent]))}" rpy="0 0 0"/>\n'
                         f'  </joint>\n')
            continue
        previous, previous_origin = joint.parent, origins[joint.parent]
        count = len(joint.elements)
        names = [joint.name if count == 1 else f"{joint.name}__{k + 1}" for k in range(count)]
        for k, element in enumerate(joint.elements):
            child = joint.child if k == count - 1 else f"{joint.name}__{k + 1}"
            if k < count - 1:
                lines.append(f"  <link name={quoteattr(child)}/>\n")  # massless: the chain's next axis
            urdf_type = URDF_JOINT_OF_ELEMENT[element.kind]
            lines.append(f'  <joint name={quoteattr(names[k])} type="{urdf_type}">\n'
                         f'    <parent link={quoteattr(previous)}/>\n    <child link={quoteattr(child)}/>\n'
                         f'    <origin xyz="{_xyz(_sub(element.origin, previous_origin))}" rpy="0 0 0"/>\n'
                         f'    <axis xyz="{_xyz(element.axis)}"/>\n')
            if urdf_type == "prismatic":
                lower, upper = (element.lower, element.upper) if element.lower is not None else (-1.0, 1.0)
                lines.append(f'    <limit lower="{_num(lower)}" upper="{_num(upper)}" effort="1000" velocity="1"/>\n')
            if element.mimic is not None:
                lines.append(f'    <mimic joint={quoteattr(names[element.mimic[0]])} '
                             f'multiplier="{_num(element.mimic[1])}" offset="0"/>\n')
            lines.append("  </joint>\n")
            previous, previous_origin = child, element.origin
    lines.append("</robot>\n")
    return "".join(lines)


def write_urdf(model, assembly, out_dir, mesh_results=None):
    """Writes out_dir/NAME.urdf and out_dir/meshes/*.stl (each file through a temporary name, never
    through a symbolic link, never outside out_dir); returns the URDF's path."""
    _safe_folder(out_dir)
    mesh_results = mesh_bodies(assembly) if mesh_results is None else mesh_results
    files = _write_meshes(model, mesh_results, os.path.join(out_dir, "meshes"))
    path = os.path.join(out_dir, model.name + ".urdf")
    with output_files.output_file(path, encoding="utf-8") as stream:
        stream.write(urdf_text(model, files, "meshes"))
    return path


# ---------------------------------------------------------------- MJCF

def _mjcf_inertial(link, indent):
    c = _sub(link.centre, link.origin)
    i = link.inertia
    return (f'{indent}<inertial pos="{_xyz(c)}" mass="{_num(link.mass)}" fullinertia="{_num(i[0][0])} '
            f'{_num(i[1][1])} {_num(i[2][2])} {_num(i[0][1])} {_num(i[0][2])} {_num(i[1][2])}"/>\n')


def mjcf_text(model, mesh_files, mesh_folder):
    """The MJCF document: the ground link a body welded to the world (no joint); every other group a
    body nested in its parent with its motion's joints in order (slide for a translation, hinge for a
    rotation, ball for a spherical motion, a freejoint for a floating group), a helical motion's
    slide tied to its hinge by an equality constraint (the pitch). Mesh geoms are visual only
    (contype and conaffinity 0): the joints carry the contacts (MuJoCo would collide the meshes'
    convex hulls, and press-fitted parts overlap)."""
    links = {link.name: link for link in model.links}
    children = {}
    for joint in model.joints:
        children.setdefault(joint.parent, []).append(joint)
    equalities = []
    out = [f'<mujoco model={quoteattr(model.name)}>\n',
           f"  <!-- Exported by contacts (docs/mechanism.md): metres, kg, density {model.density:g} kg/m^3 -->\n"]
    for note in model.notes:
        out.append(f"  <!-- {note.replace('--', '- -')} -->\n")
    out.append(f'  <compiler angle="radian" meshdir={quoteattr(mesh_folder)} inertiafromgeom="false"/>\n'
               '  <option gravity="0 0 -9.81"/>\n  <asset>\n')
    for index, file_name in sorted(mesh_files.items()):
        out.append(f'    <mesh name={quoteattr("mesh_" + file_name[:-4])} file={quoteattr(file_name)}/>\n')
    out.append("  </asset>\n  <worldbody>\n")

    def body(link, parent_origin, joint, indent):
        pos = _sub(link.origin, parent_origin)
        out.append(f'{indent}<body name={quoteattr(link.name)} pos="{_xyz(pos)}">\n')
        inner = indent + "  "
        out.append(_mjcf_inertial(link, inner))
        if joint is not None and joint.note:
            out.append(f"{inner}<!-- {joint.note.replace('--', '- -')} -->\n")
        if joint is not None and joint.type == "floating":
            out.append(f"{inner}<freejoint name={quoteattr(joint.name)}/>\n")
        elif joint is not None and joint.type == "spherical":
            out.append(f'{inner}<joint name={quoteattr(joint.name)} type="ball" '
                       f'pos="{_xyz(_sub(joint.elements[0].origin, link.origin))}"/>\n')
        elif joint is not None:
            count = len(joint.elements)
            for k, element in enumerate(joint.elements):
                name = joint.name if count == 1 else f"{joint.name}__{k + 1}"
                kind = "hinge" if element.kind == "revolute" else "slide"
                limit = ""
                if kind == "slide" and element.lower is not None:
                    limit = f' limited="true" range="{_num(element.lower)} {_num(element.upper)}"'
                out.append(f'{inner}<joint name={quoteattr(name)} type="{kind}" '
                           f'pos="{_xyz(_sub(element.origin, link.origin))}" axis="{_xyz(element.axis)}"{limit}/>\n')
                if element.mimic is not None:
                    leader = joint.name if count == 1 else f"{joint.name}__{element.mimic[0] + 1}"
                    equalities.append((name, leader, element.mimic[1]))
        for index, body_name in zip(link.body_indices, link.bodies):
            if index in mesh_files:
                out.append(f'{inner}<geom name={quoteattr(body_name)} type="mesh" '
                           f'mesh={quoteattr("mesh_" + mesh_files[index][:-4])} contype="0" conaffinity="0"/>\n')
        for child_joint in children.get(link.name, []):
            body(links[child_joint.child], link.origin, child_joint, inner)
        out.append(f"{indent}</body>\n")

    body(links[model.ground], (0.0, 0.0, 0.0), None, "    ")
    for joint in children.get("world", []):
        body(links[joint.child], (0.0, 0.0, 0.0), joint, "    ")
    out.append("  </worldbody>\n")
    if equalities:
        out.append("  <equality>\n")
        for follower, leader, ratio in equalities:
            out.append(f'    <joint joint1={quoteattr(follower)} joint2={quoteattr(leader)} '
                       f'polycoef="0 {_num(ratio)} 0 0 0"/>\n')
        out.append("  </equality>\n")
    out.append("</mujoco>\n")
    return "".join(out)


def mjcf_mesh_folder(path):
    """The folder of an MJCF file's meshes: FILE_meshes beside FILE.xml."""
    stem = os.path.splitext(os.path.basename(path))[0]
    return safe_name(stem) + "_meshes"


def write_mjcf(model, assembly, path, mesh_results=None):
    """Writes the MJCF file `path` and its meshes in FILE_meshes/ beside it (temporary names renamed
    into place, never through a symbolic link); returns `path`."""
    output_files.check_target(path)
    folder = os.path.dirname(os.path.abspath(path))
    mesh_results = mesh_bodies(assembly) if mesh_results is None else mesh_results
    mesh_folder = mjcf_mesh_folder(path)
    files = _write_meshes(model, mesh_results, os.path.join(folder, mesh_folder))
    with output_files.output_file(path, encoding="utf-8") as stream:
        stream.write(mjcf_text(model, files, mesh_folder))
    return path


def export_mechanism(assembly, found, urdf_dir=None, mjcf_path=None, density=DEFAULT_DENSITY, ground=None,
                     name="mechanism", deflection=0.1, angle=0.5):
    """Builds the Model once and writes the formats asked; returns (model, [paths written])."""
    mesh_results = mesh_bodies(assembly, deflection, angle)
    model = build_model(assembly, found, density, ground, name, mesh_results)
    written = []
    if urdf_dir is not None:
        written.append(write_urdf(model, assembly, urdf_dir, mesh_results))
    if mjcf_path is not None:
        written.append(write_mjcf(model, assembly, mjcf_path, mesh_results))
    return model, written
