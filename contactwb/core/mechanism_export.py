"""The derived mechanism's files (docs/mechanism.md): URDF (a folder:
MODEL.urdf and meshes/) or MJCF (FILE.xml and FILE_meshes/ beside it), the
meshes as binary STL in metres, every file through a temporary name renamed
into place (output_files: never through a symbolic link, never outside the
output folder). The model itself: contactwb.core.mechanism.

    from contactwb.core import mechanism_export
    model, paths = mechanism_export.export_mechanism(assembly, found, urdf_dir="motor_urdf")
"""
import math
import os
import struct
from xml.sax.saxutils import quoteattr

from contactwb.core import meshes as mesh_api
from contactwb.core import output_files
from contactwb.core.mechanism import (DEFAULT_DENSITY, MM, build_model, clean_number, safe_name, vec_dot,
                                      vec_scale, vec_sub)

FORMATS = ("urdf", "mjcf")


# ---------------------------------------------------------------- meshes

def _binary_stl(vertices_m, triangles):
    out = [b"contacts mechanism export (metres)".ljust(80, b" "), struct.pack("<I", len(triangles))]
    for i, j, k in triangles:
        a, b, c = vertices_m[i], vertices_m[j], vertices_m[k]
        u, v = vec_sub(b, a), vec_sub(c, a)
        n = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
        length = math.sqrt(vec_dot(n, n)) or 1.0
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
            vertices = [vec_sub(vec_scale(v, MM), link.origin) for v in mesh.vertices]
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
    return format(clean_number(float(value)), ".12g")


def _xyz(values):
    return " ".join(_num(v) for v in values)


def _urdf_inertial(link):
    c = vec_sub(link.centre, link.origin)
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
                         f'    <origin xyz="{_xyz(vec_sub(origins[joint.child], origins[joint.parent]))}" rpy="0 0 0"/>\n'
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
                         f'    <origin xyz="{_xyz(vec_sub(element.origin, previous_origin))}" rpy="0 0 0"/>\n'
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
    c = vec_sub(link.centre, link.origin)
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
        pos = vec_sub(link.origin, parent_origin)
        out.append(f'{indent}<body name={quoteattr(link.name)} pos="{_xyz(pos)}">\n')
        inner = indent + "  "
        out.append(_mjcf_inertial(link, inner))
        if joint is not None and joint.note:
            out.append(f"{inner}<!-- {joint.note.replace('--', '- -')} -->\n")
        if joint is not None and joint.type == "floating":
            out.append(f"{inner}<freejoint name={quoteattr(joint.name)}/>\n")
        elif joint is not None and joint.type == "spherical":
            out.append(f'{inner}<joint name={quoteattr(joint.name)} type="ball" '
                       f'pos="{_xyz(vec_sub(joint.elements[0].origin, link.origin))}"/>\n')
        elif joint is not None:
            count = len(joint.elements)
            for k, element in enumerate(joint.elements):
                name = joint.name if count == 1 else f"{joint.name}__{k + 1}"
                kind = "hinge" if element.kind == "revolute" else "slide"
                limit = ""
                if kind == "slide" and element.lower is not None:
                    limit = f' limited="true" range="{_num(element.lower)} {_num(element.upper)}"'
                out.append(f'{inner}<joint name={quoteattr(name)} type="{kind}" '
                           f'pos="{_xyz(vec_sub(element.origin, link.origin))}" axis="{_xyz(element.axis)}"{limit}/>\n')
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
    closing = [c for c in model.closures if c.equality]
    if equalities or closing:
        out.append("  <equality>\n")
        for follower, leader, ratio in equalities:
            out.append(f'    <joint joint1={quoteattr(follower)} joint2={quoteattr(leader)} '
                       f'polycoef="0 {_num(ratio)} 0 0 0"/>\n')
        for closure in closing:
            out.append(_mjcf_closure(closure, links[closure.link_a]))
        out.append("  </equality>\n")
    out.append("</mujoco>\n")
    return "".join(out)


# A loop's equality constraint made stiff: MuJoCo's constraints are soft (by default a closed loop
# sags by tenths of a millimetre under gravity); impedance 0.9999 and a time constant of twice the
# default 2 ms step (the least MuJoCo accepts) keep it closed to well under a micrometre.
CLOSURE_SOLREF = "0.004 1"
CLOSURE_SOLIMP = "0.9999 0.9999 0.001"


def _mjcf_closure(closure, link_a):
    """The <equality> element holding a loop's closing pair joint: `connect` keeps the anchor (a
    revolute axis' point, a sphere's centre) of link_a on the same point of link_b (the compiler
    takes link_b's point from the exported pose); `weld` keeps their relative pose. A revolute
    closure's axis direction is left to the loop's other joints (parallel axes in a planar loop)."""
    common = (f'name={quoteattr(closure.name)} body1={quoteattr(closure.link_a)} body2={quoteattr(closure.link_b)} '
              f'solref="{CLOSURE_SOLREF}" solimp="{CLOSURE_SOLIMP}"')
    if closure.equality == "connect":
        return f'    <connect {common} anchor="{_xyz(vec_sub(closure.anchor, link_a.origin))}"/>\n'
    return f"    <weld {common}/>\n"


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
