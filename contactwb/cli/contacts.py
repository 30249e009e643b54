"""`contacts FILE` — the functional contacts of an assembly (STEP or FCStd).

Prints the paper's table (per contact type, the body pairs and counts, with
totals), or JSON with --json.

Exit codes (every subcommand): 0 done; 2 usage error (bad option or
tolerance); 3 the input cannot be read, holds no usable solid or is refused
(beyond a limit); 4 the analysis failed (OCCT error, out of memory, parts
interlocked) or the output could not be written; 5 internal error (a bug:
please report it); 130 cancelled (Ctrl+C, SIGTERM); 141 standard output
closed by its reader."""
import argparse
import contextlib
import json
import math
import os
import sys
import time

from contactwb.cli.process import finite_number, internal_error, naming_the_file, nonnegative_count, run as run_command
from contactwb.cli.process import out_of_memory_message, unsafe_output, working_on
from contactwb.cli.process import EXIT_OK, EXIT_USAGE, EXIT_INPUT, EXIT_FAILED, EXIT_INTERNAL, EXIT_CANCELLED  # noqa: F401


def _tolerance(text):
    """argparse type: a positive, finite number."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a number: {text!r}")
    if not math.isfinite(value) or value <= 0:
        raise argparse.ArgumentTypeError(f"must be a positive, finite number, got {text}")
    return value


@contextlib.contextmanager
def _stdout_to_stderr():
    """OCCT and FreeCAD print to the C-level stdout: keep it for our output."""
    sys.stdout.flush()
    saved = os.dup(1)
    try:
        os.dup2(2, 1)
        yield
    finally:
        sys.stdout.flush()
        os.dup2(saved, 1)
        os.close(saved)


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
    "mesh": "contactwb.cli.mesh",
    "trial": "contactwb.cli.trial",
}


def main(argv=None):
    """The command; called without argv (the process's command line) it also
    takes SIGINT/SIGTERM and checks standard output (run)."""
    own_process = argv is None
    argv = sys.argv[1:] if argv is None else list(argv)
    if argv and argv[0] in SUBCOMMANDS:
        import importlib
        return importlib.import_module(SUBCOMMANDS[argv[0]]).main(argv[1:], own_process=own_process)
    return run_command("contacts", lambda: _contacts(argv), own_process)


def _contacts(argv):
    parser = argparse.ArgumentParser(prog="contacts", description=__doc__,  # exit codes in __doc__
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("file", help="a STEP (.step/.stp) or FreeCAD (.FCStd) assembly")
    parser.add_argument("--json", action="store_true", help="print JSON instead of the table")
    parser.add_argument("--linear", type=_tolerance, help="linear tolerance, mm (default: scales with the model)")
    parser.add_argument("--angular", type=_tolerance, help="angular tolerance, radians (default 1e-4)")
    parser.add_argument("--progress", action="store_true", help="show progress on stderr")
    parser.add_argument("--max-pairs", type=nonnegative_count, default=None, metavar="N",
                        help="stop when more than N body pairs have meeting boxes (default 2000000): "
                             "heavily overlapping input")
    parser.add_argument("--max-bodies", type=nonnegative_count, default=None, metavar="N",
                        help="refuse a STEP assembly expanding to more than N instances, counted before it is "
                             "expanded (default 1000000)")
    parser.add_argument("--joints", action="store_true", help="also print joints, mobility and rigid groups")
    parser.add_argument("--graph", metavar="FILE", help="write the liaison graph (.svg, .png or .dot)")
    parser.add_argument("--ground", metavar="NAME", help="body held still (default: the largest by volume)")
    parser.add_argument("--annotations", metavar="FILE.json",
                        help="the designer's fits and bonds (docs/joints.md): a JSON list of {\"a\", \"b\", "
                             "\"type\" (optional), \"intent\": clearance|transition|interference|bonded|ignored, "
                             "\"fit\" (optional)}; press fits and bonds make their pairs rigid (implies --joints)")
    parser.add_argument("--clearance-gap", type=finite_number(low=0), default=0.0, metavar="MM",
                        help="with --joints: also list clearance fits with a gap below MM (\"proposed_intent\": "
                             "\"clearance\") and coaxial overlaps below MM (a press fit drawn oversize: a negative "
                             "gap, \"proposed_intent\": \"interference\")")
    parser.add_argument("--disassembly", action="store_true",
                        help="print the removal sequence (with --json: {\"disassembly\": [{\"parts\", \"direction\", "
                             "\"blocked_before\", \"why_free\", \"released\"}]}); with --annotations, fitted and bonded "
                             "parts come out as sub-assemblies")
    parser.add_argument("--check-solids", choices=("quick", "full"), default="quick",
                        help="solid checks: quick (default: self-intersecting wires, open or misoriented shells, "
                             "edges off their faces, zero or negative volume) or full (also OCCT's whole "
                             "BRepCheck_Analyzer and faces crossing each other: seconds on a large "
                             "model); see docs/reliability.md")
    parser.add_argument("--export-urdf", metavar="DIR",
                        help="write the derived mechanism as URDF: DIR/NAME.urdf and DIR/meshes/*.stl, one link "
                             "per rigid group (docs/mechanism.md; implies --joints)")
    parser.add_argument("--export-mjcf", metavar="FILE.xml",
                        help="write the derived mechanism as MuJoCo MJCF: FILE.xml and FILE_meshes/*.stl beside it "
                             "(implies --joints)")
    parser.add_argument("--density", type=finite_number(low=0, low_open=True), default=None, metavar="KG_PER_M3",
                        help="with --export-urdf/--export-mjcf: density of every body, kg/m^3 (default 7850, steel)")
    args = parser.parse_args(argv)
    working_on(os.fsdecode(args.file))
    if args.export_urdf or args.export_mjcf or args.density is not None:
        from contactwb.cli.export_mechanism import check_export_arguments
        problem = check_export_arguments(args)
        if problem:
            print(f"contacts: {problem}", file=sys.stderr)
            return EXIT_USAGE
    if args.graph and unsafe_output("contacts", "--graph", args.graph):
        return EXIT_USAGE
    if args.disassembly:
        from contactwb.cli.mesh import print_disassembly  # the module, not the package: no cycle through cli/__init__
        return print_disassembly(os.fsdecode(args.file), args.json, args.linear, args.angular,
                                 max_bodies=args.max_bodies, annotations=args.annotations)

    try:
        from contactwb import core
        from contactwb.core import analysis
        from contactwb.core import joints as joints_api
    except MemoryError as error:  # the extension cannot even be loaded under a memory limit
        print(f"contacts: {naming_the_file(str(error) or 'out of memory', os.fsdecode(args.file))}", file=sys.stderr)
        return EXIT_FAILED
    progress = _progress_printer(sys.stderr) if args.progress else None
    start = time.perf_counter()
    found = None
    if args.annotations:
        args.joints = True
    exporting = bool(args.export_urdf or args.export_mjcf)
    if exporting:
        args.joints = True
    wants_joints = args.joints or args.graph
    # Paths go to C++ as bytes: a file name that is not UTF-8 still works.
    path = os.fsdecode(args.file)
    try:
        with _stdout_to_stderr():
            if path.lower().endswith(".fcstd"):
                from contactwb.document import analysis as document_analysis
                from contactwb.document import files, freecad_setup
                if not os.path.isfile(path):
                    raise core.InputError(f"no such file: '{path}'")
                files.check_fcstd(path)
                doc = freecad_setup.open_document(os.path.abspath(path))
                if wants_joints:
                    result, found, _ = document_analysis.joints_in_document(
                        doc, linear=args.linear, angular=args.angular, progress=progress, ground=args.ground,
                        clearance_gap=args.clearance_gap, max_pairs=args.max_pairs, check_solids=args.check_solids,
                        annotations=args.annotations)
                else:
                    result, _ = document_analysis.find_contacts_in_document(
                        doc, linear=args.linear, angular=args.angular, progress=progress,
                        max_pairs=args.max_pairs, check_solids=args.check_solids)
            elif wants_joints:
                result, found = joints_api.joints_in_step(path, args.linear, args.angular, progress,
                                                          ground=args.ground, clearance_gap=args.clearance_gap,
                                                          max_pairs=args.max_pairs, check_solids=args.check_solids,
                                                          max_bodies=args.max_bodies,
                                                          annotations=args.annotations)
            else:
                result = analysis.find_contacts_in_step(path, args.linear, args.angular, progress,
                                                        max_pairs=args.max_pairs, check_solids=args.check_solids,
                                                        max_bodies=args.max_bodies)
            if args.graph:
                found.write_graph(args.graph)
    except (core.Cancelled, KeyboardInterrupt):
        print("contacts: cancelled", file=sys.stderr)
        return EXIT_CANCELLED
    except core.ArgumentError as error:
        print(f"contacts: {error}", file=sys.stderr)
        return EXIT_USAGE
    except core.InputError as error:
        print(f"contacts: {naming_the_file(str(error), path)}", file=sys.stderr)
        return EXIT_INPUT
    except MemoryError as error:
        print(f"contacts: {out_of_memory_message(error, path)}", file=sys.stderr)
        return EXIT_FAILED
    except core.InternalError as error:  # a bug in the core
        print(f"contacts: internal error ({error}); please report it", file=sys.stderr)
        return EXIT_INTERNAL
    except core.ContactsError as error:
        print(f"contacts: {error}", file=sys.stderr)
        return EXIT_FAILED
    except (OSError, UnicodeError, ValueError, OverflowError) as error:
        if args.graph and isinstance(error, OSError) and error.filename and \
                os.fsdecode(error.filename) == os.fsdecode(args.graph):
            print(f"contacts: cannot write '{args.graph}': {error.strerror}", file=sys.stderr)
            return EXIT_FAILED
        print(f"contacts: cannot read '{path}': {error}", file=sys.stderr)
        return EXIT_INPUT
    except Exception as error:  # a bug: say so, without a traceback unless asked
        return internal_error("contacts", error)
    exported = None
    if exporting:
        from contactwb.cli.export_mechanism import export
        code, exported = export(args, found, path)
        if code != EXIT_OK:
            return code
    elapsed = time.perf_counter() - start
    if args.json:
        document = result.to_json()
        if args.joints:
            document.update(found.to_json())
            if args.clearance_gap > 0:
                document["clearances"] = found.clearances
        if exported is not None:
            document["export"] = exported
        json.dump(document, sys.stdout, indent=2)
        sys.stdout.write("\n")
    else:
        print(result.table())
        if args.joints:
            print()
            print(found.table(interferences=False))  # the contact table above lists them
        if exported is not None:
            from contactwb.cli.export_mechanism import export_table
            print()
            print(export_table(exported))
        t = result.times
        print(f"Time: {elapsed * 1000:.1f} ms in all (partitions {t['partitions'] * 1000:.1f} ms, "
              f"broad phase {t['broad_phase'] * 1000:.2f} ms, candidates {t['candidates'] * 1000:.2f} ms, "
              f"common areas {t['area'] * 1000:.1f} ms); {result.body_pairs} body pairs with meeting boxes, "
              f"{result.candidates} candidate partition pairs")
    return 0


if __name__ == "__main__":
    sys.exit(main())
