"""`contacts FILE --export-urdf DIR` and `--export-mjcf FILE.xml`: the checks
made before any work (exit 2) and the export after the joints
(contactwb.core.mechanism_export; docs/mechanism.md)."""
import os
import sys

from contactwb.cli.process import EXIT_FAILED, EXIT_INPUT, EXIT_OK, EXIT_USAGE, escape_controls


def check_export_arguments(args):
    """The problem with the export options (a usage error), or None."""
    from contactwb.core import output_files
    if args.density is not None and not (args.export_urdf or args.export_mjcf):
        return "--density goes with --export-urdf or --export-mjcf"
    if args.disassembly and (args.export_urdf or args.export_mjcf):
        return "--disassembly cannot be combined with --export-urdf or --export-mjcf"
    if args.export_urdf:
        out = os.fsdecode(args.export_urdf)
        if os.path.islink(out):
            return f"--export-urdf '{out}' is a symbolic link: name a folder (the export never writes through a link)"
        if os.path.lexists(out) and not os.path.isdir(out):
            return f"--export-urdf '{out}' exists and is not a folder: name a folder (new or existing)"
        try:
            output_files.check_target(os.path.join(out, "model.urdf"))
        except output_files.UnsafeTarget as error:
            return f"--export-urdf {error}"
    if args.export_mjcf:
        path = os.fsdecode(args.export_mjcf)
        if not path.lower().endswith(".xml"):
            return f"--export-mjcf '{path}': name an .xml file"
        try:
            output_files.check_target(path)
        except output_files.UnsafeTarget as error:
            return f"--export-mjcf {error}"
        folder = os.path.join(os.path.dirname(os.path.abspath(path)), _mesh_folder(path))
        if os.path.islink(folder) or (os.path.lexists(folder) and not os.path.isdir(folder)):
            return f"--export-mjcf: '{folder}' (for the meshes) is a symbolic link or not a folder"
    return None


def _mesh_folder(path):
    from contactwb.core.mechanism_export import mjcf_mesh_folder
    return mjcf_mesh_folder(path)


def export(args, found, source_path):
    """Writes the formats asked; returns (exit code, the export's JSON summary or None)."""
    from contactwb import core
    from contactwb.core import mechanism_export, output_files
    from contactwb.core.mechanism import DEFAULT_DENSITY
    density = DEFAULT_DENSITY if args.density is None else args.density
    name = os.path.splitext(os.path.basename(source_path))[0]
    try:
        model, written = mechanism_export.export_mechanism(
            found.assembly, found, urdf_dir=os.fsdecode(args.export_urdf) if args.export_urdf else None,
            mjcf_path=os.fsdecode(args.export_mjcf) if args.export_mjcf else None, density=density,
            ground=args.ground, name=name)
    except core.ArgumentError as error:
        print(f"contacts: {error}", file=sys.stderr)
        return EXIT_USAGE, None
    except output_files.UnsafeTarget as error:
        print(f"contacts: {error}", file=sys.stderr)
        return EXIT_USAGE, None
    except core.InputError as error:  # refused before the work (beyond a limit)
        print(f"contacts: export refused: {error} (file '{source_path}')", file=sys.stderr)
        return EXIT_INPUT, None
    except core.ContactsError as error:
        print(f"contacts: export failed: {error} (file '{source_path}')", file=sys.stderr)
        return EXIT_FAILED, None
    except OSError as error:
        where = os.fsdecode(error.filename) if error.filename else "the export"
        print(f"contacts: cannot write '{where}': {error.strerror or error}", file=sys.stderr)
        return EXIT_FAILED, None
    summary = model.to_json()
    summary["files"] = written
    return EXIT_OK, summary


def export_table(summary):
    """The export as text: the tree of links and joints, the notes, the files."""
    lines = [f"Mechanism exported ({len(summary['links'])} links, {len(summary['joints'])} joints, "
             f"density {summary['density']:g} kg/m^3):"]
    links = {link["name"]: link for link in summary["links"]}
    children = {}
    for joint in summary["joints"]:
        children.setdefault(joint["parent"], []).append(joint)

    def show(name, depth, joint):
        link = links[name]
        how = "fixed to the world" if joint is None else joint["type"]
        if joint is not None and joint["elements"]:
            how += ": " + "; ".join(
                ("slides along " if e["kind"] == "prismatic" else "turns about ") +
                "(" + ", ".join(f"{v:.4g}" for v in e["axis"]) + ")" for e in joint["elements"])
        lines.append(f"{'  ' * depth}  {escape_controls(name)} [{how}] {link['mass']:.4g} kg, "
                     f"{len(link['bodies'])} bodies: {escape_controls(', '.join(link['bodies']))}")
        for child in children.get(name, []):
            show(child["child"], depth + 1, child)

    show(summary["ground"], 0, None)
    for joint in children.get("world", []):
        show(joint["child"], 0, joint)
    for note in summary["notes"]:
        lines.append(f"  note: {escape_controls(note)}")
    for path in summary["files"]:
        lines.append(f"  -> {escape_controls(path)}")
    return "\n".join(lines)
