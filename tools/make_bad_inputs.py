#!/usr/bin/python3
"""Writes the bad-input corpus (issue 14) into a folder: damaged STEP, BRep
and FCStd files, each with the outcome the `contacts` CLI must give.

    tools/make_bad_inputs.py --out DIR   # prints nothing; DIR/cases.json lists the cases

Each case: {"file", "args", "exit", "expect"}: the exit code and a piece of
the message (stderr) or of the output. Small files, made from a box and the
bundled motor in a few milliseconds."""
import argparse
import json
import os
import re
import sys

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MOTOR = os.path.join(REPO, "Resources", "samples", "motor.step")


def box_step():
    sys.path.append("/usr/lib/freecad-python3/lib")
    import FreeCAD  # noqa: F401  (before Part)
    import Part
    import tempfile
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "box.step")
        Part.makeBox(10, 10, 10).exportStep(path)
        return open(path).read()


def nested_step(depth, cyclic=False):
    """An assembly `depth` levels deep (NEXT_ASSEMBLY_USAGE_OCCURRENCE chain);
    cyclic: the last level contains the first."""
    lines = ["ISO-10303-21;", "HEADER;", "FILE_DESCRIPTION((''),'2;1');",
             "FILE_NAME('n','2024',(''),(''),'','','');",
             "FILE_SCHEMA(('AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }'));", "ENDSEC;", "DATA;",
             "#1=APPLICATION_CONTEXT('');", "#2=PRODUCT_CONTEXT('',#1,'mechanical');",
             "#3=PRODUCT_DEFINITION_CONTEXT('part definition',#1,'design');"]
    n = 10
    pds = []
    for level in range(depth):
        lines.append(f"#{n}=PRODUCT('P{level}','P{level}','',(#2));")
        lines.append(f"#{n + 1}=PRODUCT_DEFINITION_FORMATION('','',#{n});")
        lines.append(f"#{n + 2}=PRODUCT_DEFINITION('design','',#{n + 1},#3);")
        pds.append(n + 2)
        n += 3
    for parent, child in zip(pds, pds[1:] + ([pds[0]] if cyclic else [])):
        lines.append(f"#{n}=NEXT_ASSEMBLY_USAGE_OCCURRENCE('','','',#{parent},#{child},$);")
        n += 1
    lines += ["ENDSEC;", "END-ISO-10303-21;"]
    return "\n".join(lines) + "\n"


def write(out, name, data):
    path = os.path.join(out, name)
    with open(path, "wb") as f:
        f.write(data.encode() if isinstance(data, str) else data)
    return path


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--out", required=True)
    out = parser.parse_args().out
    os.makedirs(out, exist_ok=True)
    box = box_step()
    motor = open(MOTOR, "rb").read()
    cases = []

    def case(name, data, exit_code, expect, args=()):
        path = write(out, name, data) if data is not None else os.path.join(out, name)
        cases.append({"file": path, "args": list(args), "exit": exit_code, "expect": expect})

    case("empty.step", b"", 3, "empty file")
    for fraction in (0.1, 0.5, 0.9):
        case(f"motor_cut_{int(fraction * 100)}.step", motor[:int(len(motor) * fraction)], None, "")
    case("garbage.step", os.urandom(2000), 3, "not a STEP file")
    case("image.step", b"\x89PNG\r\n\x1a\n" + os.urandom(200), 3, "PNG image")
    case("image.FCStd", b"\x89PNG\r\n\x1a\n" + os.urandom(200), 3, "not a FreeCAD document")
    case("step_renamed.FCStd", box, 3, "not a FreeCAD document")
    fcstd = open(os.path.join(REPO, "Resources", "samples", "motor.FCStd"), "rb").read()
    case("motor_half.FCStd", fcstd[:len(fcstd) // 2], 3, "not a FreeCAD document")
    case("no_solid.step", nested_step(1), 3, "no solid")
    case("deep.step", nested_step(30000), 3, "levels deep")
    case("cyclic.step", nested_step(5, cyclic=True), 3, "cyclic assembly reference")
    # One damaged entity at a time: unknown type and a garbage line (these crashed OCCT 7.6).
    entities = [m.start() for m in re.finditer(r"^#\d+ = ", box, re.M)]
    for k in (11, 17, 18, 22, 24, 27, 33, 40):
        start = entities[k]
        end = box.index(";", start) + 1
        ident = box[start:box.index("=", start)].strip()
        case(f"unknown_type_{k}.step", box[:start] + f"{ident} = NOT_A_TYPE('');" + box[end:], None, "")
        case(f"garbage_line_{k}.step", box[:start] + f"{ident} = garbage (((;" + box[end:], None, "")
    case("box.step", box, 0, "Total: 0 contacts")
    for value in ("nan", "-1", "-inf", "inf", "0"):
        case(f"box.step", None, 2, "--linear", args=["--linear", value])
        case(f"box.step", None, 2, "--angular", args=["--angular", value])
    case("box.step", None, 2, "too large", args=["--linear", "100"])
    case("box.step", None, 2, "too large", args=["--linear", "1e300"])
    case("box.step", None, 2, "too large", args=["--angular", "1"])
    case("missing.step", None, 3, "no such file")
    case("folder.step", None, 3, "directory")
    os.makedirs(os.path.join(out, "folder.step"), exist_ok=True)
    case(os.fsdecode(b"\xff\xfe-not-utf8.step"), box, 0, "Total: 0 contacts")
    with open(os.path.join(out, "cases.json"), "w") as f:
        json.dump(cases, f, indent=1)


if __name__ == "__main__":
    main()
