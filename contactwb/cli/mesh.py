"""`contacts mesh FILE --out DIR` — one PLY per body (triangles tagged with
their FaceN and partition, vertices shared) and DIR/meshes.json (per body:
triangles, watertight, minimum angle, aspect ratio percentiles). With
--simplify S --envelope E, also each body's collision model (NAME.collision.ply):
the B-rep without its holes, blends and chamfers smaller than S, tessellated
twice as coarse, kept within the Hausdorff distance E of the original (else the
original is kept and the output says so)."""
import argparse
import json
import sys


def main(argv):
    parser = argparse.ArgumentParser(prog="contacts mesh", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("file", help="a STEP (.step/.stp) or FreeCAD (.FCStd) assembly")
    parser.add_argument("--out", required=True, metavar="DIR", help="folder for the PLY files and meshes.json")
    parser.add_argument("--deflection", type=float, default=0.1, metavar="D", help="chordal deviation, mm (0.1)")
    parser.add_argument("--angle", type=float, default=0.5, metavar="A", help="angular deflection, radians (0.5)")
    parser.add_argument("--max-edge", type=float, default=0.0, metavar="L",
                        help="maximum triangle edge length, mm (default: no bound)")
    parser.add_argument("--simplify", type=float, default=0.0, metavar="S",
                        help="collision models without the holes, blends and chamfers smaller than S mm")
    parser.add_argument("--envelope", type=float, metavar="E",
                        help="largest Hausdorff distance (mm) of a simplified model to the original (with --simplify)")
    parser.add_argument("--linear", type=float, help="linear tolerance of partitions, mm (default: scaled)")
    parser.add_argument("--angular", type=float, help="angular tolerance of partitions, radians")
    args = parser.parse_args(argv)
    if args.deflection <= 0 or args.angle <= 0 or args.max_edge < 0:
        parser.error("--deflection and --angle must be positive, --max-edge not negative")
    if args.simplify < 0 or (args.simplify > 0 and not (args.envelope or 0) > 0):
        parser.error("--simplify S needs a positive S and --envelope E (mm)")
    if args.envelope is not None and not args.simplify > 0:
        parser.error("--envelope goes with --simplify")

    from contactwb import core
    from contactwb.core import meshes
    from contactwb.document.files import load_assembly
    try:
        assembly = load_assembly(args.file)
        document = meshes.write_meshes(assembly, args.out, args.deflection, args.angle, args.max_edge,
                                       args.linear, args.angular, args.simplify, args.envelope or 0.0)
    except core.ContactsError as error:
        print(f"contacts mesh: {error}", file=sys.stderr)
        return 1
    except OSError as error:
        print(f"contacts mesh: {error}", file=sys.stderr)
        return 1
    for body in document["bodies"]:
        print(f"{body['name']}: {body['triangles']} triangles, "
              f"{'watertight' if body['watertight'] else 'NOT watertight'}, "
              f"min angle {body['min_angle']:.1f} deg, aspect p50 {body['aspect_ratio']['p50']:.2f} "
              f"p99 {body['aspect_ratio']['p99']:.2f} -> {body['file']}")
        collision = body.get("collision")
        if collision is None:
            continue
        if collision["simplified"]:
            change = (f"{len(collision['removed_faces'])} faces of small features removed"
                      if collision["removed_faces"] else "no small feature")
            print(f"  collision model: {collision['triangles']} triangles, {change}, "
                  f"Hausdorff {collision['hausdorff']:.3f} mm <= {args.envelope:g} -> {collision['file']}")
        else:
            print(f"  collision model: {collision['triangles']} triangles, {collision['message']} "
                  f"-> {collision['file']}")
    return 0



def print_disassembly(path, as_json=False, linear=None, angular=None):
    """`contacts FILE --disassembly [--json]`: the removal sequence; exit code 0, or 2 when the parts interlock."""
    from contactwb import core
    from contactwb.core import meshes
    from contactwb.document.files import load_assembly
    try:
        assembly = load_assembly(path)
        document = meshes.disassembly_json(assembly, meshes.disassemble(assembly, linear=linear, angular=angular))
    except core.ContactsError as error:
        print(f"contacts: {error}", file=sys.stderr)
        return 1
    if as_json:
        json.dump(document, sys.stdout, indent=2)
        sys.stdout.write("\n")
    else:
        print(meshes.disassembly_table(document))
    return 0 if document["complete"] else 2


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
