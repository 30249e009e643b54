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
import zipfile

from contactwb import cli_process
from contactwb.cli_process import EXIT_OK, EXIT_USAGE, EXIT_INPUT, EXIT_FAILED, EXIT_INTERNAL, EXIT_CANCELLED  # noqa: F401


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


# Limits of an .FCStd archive read (issue 25): beyond them the file is refused
# before FreeCAD unpacks it.
FCSTD_MAX_MEMBER_BYTES = 2 * 1024 ** 3   # one member, uncompressed
FCSTD_MAX_TOTAL_BYTES = 4 * 1024 ** 3    # all members
FCSTD_MAX_MEMBERS = 100_000
FCSTD_MAX_RATIO = 1000                   # uncompressed / compressed, for members above 1 MB


def _check_fcstd(path, core):
    """A clear error for what FreeCAD would half-open or crash on, and an
    "unsupported file" refusal (exit 3) for what it must not be given: members
    encrypted, compressed other than stored or deflated, too large or
    inflating beyond FCSTD_MAX_RATIO, and a Document.xml that declares
    entities (an expansion bomb) or is not well-formed XML. Parsed with
    expat, entity declarations refused, before FreeCAD reads a byte."""
    if not zipfile.is_zipfile(path):
        raise core.InputError(f"not a FreeCAD document (not a zip archive: truncated, or another format) "
                              f"(file '{path}')")

    def unsupported(why):
        return cli_process.InputRefused(f"unsupported file: {why} (file '{path}')")
    try:
        with zipfile.ZipFile(path) as archive:
            members = archive.infolist()
            if "Document.xml" not in archive.namelist():
                raise core.InputError(f"not a FreeCAD document (no Document.xml) (file '{path}')")
            if len(members) > FCSTD_MAX_MEMBERS:
                raise unsupported(f"{len(members)} archive members (at most {FCSTD_MAX_MEMBERS})")
            total = 0
            for member in members:
                if member.flag_bits & 0x1:
                    raise unsupported(f"member '{member.filename}' is encrypted")
                if member.compress_type not in (zipfile.ZIP_STORED, zipfile.ZIP_DEFLATED):
                    raise unsupported(f"member '{member.filename}' uses compression method {member.compress_type} "
                                      "(only stored and deflated are read)")
                if member.file_size > FCSTD_MAX_MEMBER_BYTES:
                    raise unsupported(f"member '{member.filename}' is {member.file_size} bytes uncompressed "
                                      f"(at most {FCSTD_MAX_MEMBER_BYTES})")
                if member.file_size > 1024 ** 2 and member.file_size > FCSTD_MAX_RATIO * max(member.compress_size, 1):
                    raise unsupported(f"member '{member.filename}' inflates {member.compress_size} bytes to "
                                      f"{member.file_size} (more than {FCSTD_MAX_RATIO} times)")
                total += member.file_size
            if total > FCSTD_MAX_TOTAL_BYTES:
                raise unsupported(f"{total} bytes uncompressed in all (at most {FCSTD_MAX_TOTAL_BYTES})")
            damaged = archive.testzip()
            if damaged:
                raise core.InputError(f"damaged FreeCAD document (member '{damaged}' is corrupt) (file '{path}')")
            _check_document_xml(archive, unsupported)
    except zipfile.BadZipFile as error:
        raise core.InputError(f"damaged FreeCAD document ({error}) (file '{path}')")
    except (NotImplementedError, RuntimeError) as error:  # zipfile: unsupported method, encrypted
        raise unsupported(str(error))


def check_input_file(path, core):
    """Before a tool reads `path`: InputError when it is missing, the archive
    checks for an .FCStd (InputRefused: unsupported)."""
    if not os.path.isfile(path):
        raise core.InputError(f"no such file: '{path}'")
    if path.lower().endswith(".fcstd"):
        _check_fcstd(path, core)


def _check_document_xml(archive, unsupported):
    """Document.xml parsed in a stream by expat with no entity declarations
    allowed (none in a real document): an expansion bomb is refused before
    any expansion."""
    from xml.parsers import expat
    parser = expat.ParserCreate()

    def refuse_entity(name, *_):
        raise unsupported(f"Document.xml declares the entity '{name}' (entity declarations are refused)")
    parser.EntityDeclHandler = refuse_entity
    parser.UnparsedEntityDeclHandler = refuse_entity
    parser.SetParamEntityParsing(expat.XML_PARAM_ENTITY_PARSING_NEVER)
    try:
        with archive.open("Document.xml") as stream:
            while True:
                chunk = stream.read(1 << 20)
                parser.Parse(chunk, not chunk)
                if not chunk:
                    break
    except expat.ExpatError as error:
        raise unsupported(f"Document.xml is not well-formed XML ({error})")


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
    """The command; called without argv (the process's command line) it also
    takes SIGINT/SIGTERM and checks standard output (cli_process.run)."""
    own_process = argv is None
    argv = sys.argv[1:] if argv is None else list(argv)
    if argv and argv[0] in SUBCOMMANDS:
        import importlib
        return importlib.import_module(SUBCOMMANDS[argv[0]]).main(argv[1:], own_process=own_process)
    return cli_process.run("contacts", lambda: _contacts(argv), own_process)


def _contacts(argv):
    parser = argparse.ArgumentParser(prog="contacts", description=__doc__,  # exit codes in __doc__
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("file", help="a STEP (.step/.stp) or FreeCAD (.FCStd) assembly")
    parser.add_argument("--json", action="store_true", help="print JSON instead of the table")
    parser.add_argument("--linear", type=_tolerance, help="linear tolerance, mm (default: scales with the model)")
    parser.add_argument("--angular", type=_tolerance, help="angular tolerance, radians (default 1e-4)")
    parser.add_argument("--progress", action="store_true", help="show progress on stderr")
    parser.add_argument("--max-pairs", type=cli_process.nonnegative_count, default=None, metavar="N",
                        help="stop when more than N body pairs have meeting boxes (default 2000000): "
                             "heavily overlapping input")
    parser.add_argument("--max-bodies", type=cli_process.nonnegative_count, default=None, metavar="N",
                        help="refuse a STEP assembly expanding to more than N instances, counted before it is "
                             "expanded (default 1000000)")
    parser.add_argument("--joints", action="store_true", help="also print joints, mobility and rigid groups")
    parser.add_argument("--graph", metavar="FILE", help="write the liaison graph (.svg, .png or .dot)")
    parser.add_argument("--ground", metavar="NAME", help="body held still (default: the largest by volume)")
    parser.add_argument("--clearance-gap", type=cli_process.finite_number(low=0), default=0.0, metavar="MM",
                        help="with --joints: also list clearance fits with a gap below MM")
    parser.add_argument("--disassembly", action="store_true",
                        help="print the removal sequence (with --json: {\"disassembly\": [{\"parts\", \"direction\"}]})")
    parser.add_argument("--check-solids", choices=("quick", "full"), default="quick",
                        help="solid checks: quick (default: self-intersecting wires, open or misoriented shells, "
                             "edges off their faces, zero or negative volume) or full (also OCCT's whole "
                             "BRepCheck_Analyzer and faces crossing each other: seconds on a large "
                             "model); see docs/reliability.md")
    args = parser.parse_args(argv)
    if args.graph:
        from contactwb import output_files
        try:
            output_files.check_target(args.graph)
        except output_files.UnsafeTarget as error:
            print(f"contacts: --graph {error}", file=sys.stderr)
            return EXIT_USAGE
    if args.disassembly:
        from contactwb import cli_mesh
        return cli_mesh.print_disassembly(os.fsdecode(args.file), args.json, args.linear, args.angular,
                                          max_bodies=args.max_bodies)

    try:
        from contactwb import analysis, core
        from contactwb import joints as joints_api
    except MemoryError as error:  # the extension cannot even be loaded under a memory limit
        print(f"contacts: {error} (file '{os.fsdecode(args.file)}')", file=sys.stderr)
        return EXIT_FAILED
    progress = _progress_printer(sys.stderr) if args.progress else None
    start = time.perf_counter()
    found = None
    wants_joints = args.joints or args.graph
    # Paths go to C++ as bytes: a file name that is not UTF-8 still works.
    path = os.fsdecode(args.file)
    try:
        with _stdout_to_stderr():
            if path.lower().endswith(".fcstd"):
                from contactwb import freecad_setup
                if not os.path.isfile(path):
                    raise core.InputError(f"no such file: '{path}'")
                _check_fcstd(path, core)
                doc = freecad_setup.open_document(os.path.abspath(path))
                if wants_joints:
                    result, found, _ = joints_api.joints_in_document(
                        doc, linear=args.linear, angular=args.angular, progress=progress, ground=args.ground,
                        clearance_gap=args.clearance_gap, max_pairs=args.max_pairs, check_solids=args.check_solids)
                else:
                    result, _ = analysis.find_contacts_in_document(doc, linear=args.linear, angular=args.angular,
                                                                   progress=progress, max_pairs=args.max_pairs,
                                                                   check_solids=args.check_solids)
            elif wants_joints:
                result, found = joints_api.joints_in_step(path, args.linear, args.angular, progress,
                                                          ground=args.ground, clearance_gap=args.clearance_gap,
                                                          max_pairs=args.max_pairs, check_solids=args.check_solids,
                                                          max_bodies=args.max_bodies)
            else:
                result = analysis.find_contacts_in_step(path, args.linear, args.angular, progress,
                                                        max_pairs=args.max_pairs, check_solids=args.check_solids,
                                                        max_bodies=args.max_bodies)
            if args.graph:
                found.write_graph(args.graph)
    except cli_process.InputRefused as error:
        print(f"contacts: {error}", file=sys.stderr)
        return EXIT_INPUT
    except (core.Cancelled, KeyboardInterrupt):
        print("contacts: cancelled", file=sys.stderr)
        return EXIT_CANCELLED
    except core.ArgumentError as error:
        print(f"contacts: {error}", file=sys.stderr)
        return EXIT_USAGE
    except core.InputError as error:
        where = "" if os.path.basename(path) in str(error) else f" (file '{path}')"  # a document's body errors
        print(f"contacts: {error}{where}", file=sys.stderr)
        return EXIT_INPUT
    except core.ContactsError as error:
        print(f"contacts: {error}", file=sys.stderr)
        return EXIT_FAILED
    except MemoryError as error:  # the core's (naming the file) or Python's own (no text)
        text = str(error) if "out of memory" in str(error) else "out of memory"
        where = "" if os.path.basename(path) in text else f" (file '{path}')"
        print(f"contacts: {text}{where}", file=sys.stderr)
        return EXIT_FAILED
    except (OSError, UnicodeError, ValueError, OverflowError) as error:
        if args.graph and isinstance(error, OSError) and error.filename and \
                os.fsdecode(error.filename) == os.fsdecode(args.graph):
            print(f"contacts: cannot write '{args.graph}': {error.strerror}", file=sys.stderr)
            return EXIT_FAILED
        print(f"contacts: cannot read '{path}': {error}", file=sys.stderr)
        return EXIT_INPUT
    except Exception as error:  # a bug: say so, without a traceback unless asked
        if os.environ.get("CONTACTS_DEBUG"):
            raise
        print(f"contacts: internal error ({type(error).__name__}: {error}); "
              "set CONTACTS_DEBUG=1 for the traceback and please report it", file=sys.stderr)
        return EXIT_INTERNAL
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
            print(found.table(interferences=False))  # the contact table above lists them
        t = result.times
        print(f"Time: {elapsed * 1000:.1f} ms in all (partitions {t['partitions'] * 1000:.1f} ms, "
              f"broad phase {t['broad_phase'] * 1000:.2f} ms, candidates {t['candidates'] * 1000:.2f} ms, "
              f"common areas {t['area'] * 1000:.1f} ms); {result.body_pairs} body pairs with meeting boxes, "
              f"{result.candidates} candidate partition pairs")
    return 0


if __name__ == "__main__":
    sys.exit(main())
