"""`contacts mesh FILE --out DIR` — one PLY per body (triangles tagged with
their FaceN and partition, vertices shared) and DIR/meshes.json (per body:
triangles, watertight, minimum angle, aspect ratio percentiles). With
--simplify S --envelope E, also each body's collision model (NAME.collision.ply):
the B-rep without its holes, blends and chamfers smaller than S, tessellated
twice as coarse, kept within the Hausdorff distance E of the original (else the
original is kept and the output says so)."""
import argparse
import json
import os
import sys

from contactwb.cli.process import escape_controls, finite_number, naming_the_file, nonnegative_count, run as run_command
from contactwb.cli.process import out_of_memory_message, working_on
from contactwb.cli.process import EXIT_CANCELLED, EXIT_FAILED, EXIT_INPUT, EXIT_OK, EXIT_USAGE

_finite = finite_number


def main(argv, own_process=False):
    return run_command("contacts mesh", lambda: _mesh(argv), own_process)


def _error_code(core, error):
    """The exit code of a core exception (cli_process's contract)."""
    if isinstance(error, core.Cancelled):
        return EXIT_CANCELLED
    if isinstance(error, core.ArgumentError):
        return EXIT_USAGE
    if isinstance(error, core.InputError):
        return EXIT_INPUT
    return EXIT_FAILED


def _mesh(argv):
    parser = argparse.ArgumentParser(prog="contacts mesh", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("file", help="a STEP (.step/.stp) or FreeCAD (.FCStd) assembly")
    parser.add_argument("--out", required=True, metavar="DIR", help="folder for the PLY files and meshes.json")
    parser.add_argument("--deflection", type=_finite(), default=0.1, metavar="D", help="chordal deviation, mm (0.1)")
    parser.add_argument("--angle", type=_finite(), default=0.5, metavar="A", help="angular deflection, radians (0.5)")
    parser.add_argument("--max-edge", type=_finite(), default=0.0, metavar="L",
                        help="maximum triangle edge length, mm (default: no bound)")
    parser.add_argument("--max-triangles", type=nonnegative_count, default=None, metavar="N",
                        help="refuse, before meshing, when the sizes asked need more than N triangles "
                             "(estimated from the bodies' areas; default 20000000)")
    parser.add_argument("--max-bodies", type=nonnegative_count, default=None, metavar="N",
                        help="refuse a STEP assembly expanding to more than N instances (default 1000000)")
    parser.add_argument("--simplify", type=_finite(), default=0.0, metavar="S",
                        help="collision models without the holes, blends and chamfers smaller than S mm")
    parser.add_argument("--envelope", type=_finite(), metavar="E",
                        help="largest Hausdorff distance (mm) of a simplified model to the original (with --simplify)")
    parser.add_argument("--linear", type=_finite(low=0, low_open=True),
                        help="linear tolerance of partitions, mm (default: scaled)")
    parser.add_argument("--angular", type=_finite(low=0, low_open=True), help="angular tolerance of partitions, radians")
    args = parser.parse_args(argv)
    if args.deflection <= 0 or args.angle <= 0 or args.max_edge < 0:
        parser.error("--deflection and --angle must be positive, --max-edge not negative")
    if args.simplify < 0 or (args.simplify > 0 and not (args.envelope or 0) > 0):
        parser.error("--simplify S needs a positive S and --envelope E (mm)")
    if args.envelope is not None and not args.simplify > 0:
        parser.error("--envelope goes with --simplify")

    out = os.fsdecode(args.out)
    if os.path.lexists(out) and not os.path.isdir(out):
        print(f"contacts mesh: --out '{out}' exists and is not a folder: name a folder (new or existing) "
              "for the PLY files and meshes.json", file=sys.stderr)
        return EXIT_USAGE

    from contactwb import core
    from contactwb.core import meshes
    from contactwb.document.files import load_assembly
    path = os.fsdecode(args.file)
    working_on(path)
    try:
        assembly = load_assembly(path, args.max_bodies)
        document = meshes.write_meshes(assembly, out, args.deflection, args.angle, args.max_edge,
                                       args.linear, args.angular, args.simplify, args.envelope or 0.0,
                                       max_triangles=args.max_triangles)
    except core.ContactsError as error:
        print(f"contacts mesh: {naming_the_file(str(error), path)}", file=sys.stderr)
        return _error_code(core, error)
    except MemoryError as error:
        print(f"contacts mesh: {out_of_memory_message(error, path)}", file=sys.stderr)
        return EXIT_FAILED
    except OSError as error:
        where = os.fsdecode(error.filename) if error.filename else out
        print(f"contacts mesh: cannot write '{where}': {error.strerror or error}", file=sys.stderr)
        return EXIT_FAILED
    for body in document["bodies"]:
        if body.get("failed"):
            print(f"{escape_controls(body['name'])}: NOT meshed: {body['failed']}")
            continue
        print(f"{escape_controls(body['name'])}: {body['triangles']} triangles, "
              f"{'watertight' if body['watertight'] else 'NOT watertight'}, "
              f"min angle {body['min_angle']:.1f} deg, aspect p50 {body['aspect_ratio']['p50']:.2f} "
              f"p99 {body['aspect_ratio']['p99']:.2f} -> {body['file']}")
        collision = body.get("collision")
        if collision is not None and collision["simplified"]:
            change = (f"{len(collision['removed_faces'])} faces of small features removed"
                      if collision["removed_faces"] else "no small feature")
            print(f"  collision model: {collision['triangles']} triangles, {change}, "
                  f"Hausdorff {collision['hausdorff']:.3f} mm <= {args.envelope:g} -> {collision['file']}")
        elif collision is not None:
            print(f"  collision model: {collision['triangles']} triangles, {collision['message']} "
                  f"-> {collision['file']}")
        if body.get("invalid"):
            print(f"  not a valid solid: {body['invalid']['reason']} "
                  f"({', '.join(body['invalid']['faces']) or 'whole solid'})")
        for face in body.get("failed_faces", []):
            print(f"  {face['face']} not meshed: {face['message']}")
    return EXIT_OK



def print_disassembly(path, as_json=False, linear=None, angular=None, max_bodies=None, annotations=None):
    """`contacts FILE --disassembly [--json] [--annotations FILE.json]`: the removal sequence (fitted
    and bonded parts as sub-assemblies); exit code 0, or 4 (the analysis failed) when the parts
    interlock; 3 unreadable input; 2 a bad annotations file."""
    from contactwb import core
    from contactwb.core import meshes
    from contactwb.document.files import load_assembly
    try:
        assembly = load_assembly(path, max_bodies)
        document = meshes.disassembly_json(assembly, meshes.disassemble(assembly, linear=linear, angular=angular,
                                                                        annotations=annotations))
    except core.ContactsError as error:
        print(f"contacts: {naming_the_file(str(error), path)}", file=sys.stderr)
        return _error_code(core, error)
    except MemoryError as error:
        print(f"contacts: {out_of_memory_message(error, path)}", file=sys.stderr)
        return EXIT_FAILED
    if as_json:
        json.dump(document, sys.stdout, indent=2)
        sys.stdout.write("\n")
    else:
        print(meshes.disassembly_table(document))
    return EXIT_OK if document["complete"] else EXIT_FAILED


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
