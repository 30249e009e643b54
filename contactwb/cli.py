"""`contacts FILE` — the functional contacts of an assembly (STEP or FCStd).

Prints the paper's table (per contact type, the body pairs and counts, with
totals), or JSON with --json."""
import argparse
import json
import os
import sys
import time


def _progress_printer(stream):
    last = {"stage": None, "shown": -1}

    def report(stage, fraction):
        step = int(fraction * 10)
        if stage != last["stage"] or step != last["shown"]:
            stream.write(f"\r{stage}: {int(fraction * 100):3d}%")
            stream.flush()
            last.update(stage=stage, shown=step)
        if fraction >= 1.0:
            stream.write("\n")
        return True
    return report


# `contacts NAME ...` runs another tool: NAME -> module with main(argv) -> exit code.
SUBCOMMANDS = {
    "mesh": "contactwb.cli_mesh",
    "trial": "contactwb.cli_trial",
}


def main(argv=None):
    argv = sys.argv[1:] if argv is None else list(argv)
    if argv and argv[0] in SUBCOMMANDS:
        import importlib
        return importlib.import_module(SUBCOMMANDS[argv[0]]).main(argv[1:])
    parser = argparse.ArgumentParser(prog="contacts", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("file", help="a STEP (.step/.stp) or FreeCAD (.FCStd) assembly")
    parser.add_argument("--json", action="store_true", help="print JSON instead of the table")
    parser.add_argument("--linear", type=float, help="linear tolerance, mm (default: scales with the model)")
    parser.add_argument("--angular", type=float, help="angular tolerance, radians (default 1e-4)")
    parser.add_argument("--progress", action="store_true", help="show progress on stderr")
    parser.add_argument("--max-pairs", type=int, default=None, metavar="N",
                        help="stop when more than N body pairs have meeting boxes (default 2000000): "
                             "heavily overlapping input")
    parser.add_argument("--joints", action="store_true", help="also print joints, mobility and rigid groups")
    parser.add_argument("--graph", metavar="FILE", help="write the liaison graph (.svg, .png or .dot)")
    parser.add_argument("--ground", metavar="NAME", help="body held still (default: the largest by volume)")
    parser.add_argument("--clearance-gap", type=float, default=0.0, metavar="MM",
                        help="with --joints: also list clearance fits with a gap below MM")
    parser.add_argument("--disassembly", action="store_true",
                        help="print the removal sequence (with --json: {\"disassembly\": [{\"parts\", \"direction\"}]})")
    args = parser.parse_args(argv)
    if args.disassembly:
        from contactwb import cli_mesh
        return cli_mesh.print_disassembly(args.file, args.json, args.linear, args.angular)

    from contactwb import analysis, core
    from contactwb import joints as joints_api
    progress = _progress_printer(sys.stderr) if args.progress else None
    start = time.perf_counter()
    found = None
    wants_joints = args.joints or args.graph
    try:
        if args.file.lower().endswith(".fcstd"):
            from contactwb import freecad_setup
            if not os.path.isfile(args.file):
                raise core.ContactsError(f"no such file: '{args.file}'")
            doc = freecad_setup.open_document(os.path.abspath(args.file))
            if wants_joints:
                result, found, _ = joints_api.joints_in_document(
                    doc, linear=args.linear, angular=args.angular, progress=progress, ground=args.ground,
                    clearance_gap=args.clearance_gap, max_pairs=args.max_pairs)
            else:
                result, _ = analysis.find_contacts_in_document(doc, linear=args.linear, angular=args.angular,
                                                               progress=progress, max_pairs=args.max_pairs)
        elif wants_joints:
            result, found = joints_api.joints_in_step(args.file, args.linear, args.angular, progress,
                                                      ground=args.ground, clearance_gap=args.clearance_gap,
                                                      max_pairs=args.max_pairs)
        else:
            result = analysis.find_contacts_in_step(args.file, args.linear, args.angular, progress,
                                                    max_pairs=args.max_pairs)
        if args.graph:
            found.write_graph(args.graph)
    except core.Cancelled:
        print("contacts: cancelled", file=sys.stderr)
        return 130
    except core.ContactsError as error:
        print(f"contacts: {error}", file=sys.stderr)
        return 1
    elapsed = time.perf_counter() - start
    if args.json:
        document = result.to_json()
        if args.joints:
            document.update(found.to_json())
            if args.clearance_gap > 0:
                document["clearances"] = found.clearances
        json.dump(document, sys.stdout, indent=2)
        sys.stdout.write("\n")
    else:
        print(result.table())
        if args.joints:
            print()
            print(found.table())
        t = result.times
        print(f"Time: {elapsed * 1000:.1f} ms in all (partitions {t['partitions'] * 1000:.1f} ms, "
              f"broad phase {t['broad_phase'] * 1000:.2f} ms, candidates {t['candidates'] * 1000:.2f} ms, "
              f"common areas {t['area'] * 1000:.1f} ms); {result.body_pairs} body pairs with meeting boxes, "
              f"{result.candidates} candidate partition pairs")
    return 0


if __name__ == "__main__":
    sys.exit(main())
