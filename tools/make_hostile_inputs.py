#!/usr/bin/python3
"""Writes the hostile-input corpus (issue 25) into a folder: inputs outside the
damaged-file corpus of tools/make_bad_inputs.py, as a new user or an attacker
would try them, each with the outcome every `contacts` command must give.

    tools/make_hostile_inputs.py --out DIR      # DIR/cases.json lists the cases

Each case: {"name", "argv", "exit", "expect", "refusal"}: the arguments after
`contacts` (files in DIR), the exit code, a piece of the message (stderr) or
of the output, and whether it is a refusal (bench/bench_bad_inputs.py holds
refusals to 2 s and 300 MB). Written in a few seconds from the bundled motor
and boxes."""
import argparse
import json
import os
import re
import sys
import zipfile

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(REPO, "tools"))
import make_bad_inputs as bad  # noqa: E402

SAMPLES = os.path.join(REPO, "Resources", "samples")
MOTOR = os.path.join(SAMPLES, "motor.step")
MOTOR_FCSTD = os.path.join(SAMPLES, "motor.FCStd")
MOTOR_TOTAL = "Total: 35 contacts (14 PLF, 21 CLJ)"
STEP_HEAD = ("ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION((''),'2;1');\nFILE_NAME('h','2024',(''),(''),'','','');\n"
             "FILE_SCHEMA(('AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }'));\nENDSEC;\nDATA;\n"
             "#1=APPLICATION_CONTEXT('');\n#2=PRODUCT_CONTEXT('',#1,'mechanical');\n"
             "#3=PRODUCT_DEFINITION_CONTEXT('part definition',#1,'design');\n")
STEP_TAIL = "ENDSEC;\nEND-ISO-10303-21;\n"


def doubling_assembly(levels):
    """`levels` + 1 products, each level using the one below twice: 2^levels instances."""
    lines, n, definitions = [], 10, []
    for level in range(levels + 1):
        lines += [f"#{n}=PRODUCT('P{level}','P{level}','',(#2));",
                  f"#{n + 1}=PRODUCT_DEFINITION_FORMATION('','',#{n});",
                  f"#{n + 2}=PRODUCT_DEFINITION('design','',#{n + 1},#3);"]
        definitions.append(n + 2)
        n += 3
    for level in range(levels):
        for _ in range(2):
            lines.append(f"#{n}=NEXT_ASSEMBLY_USAGE_OCCURRENCE('{n}','','',#{definitions[level]},"
                         f"#{definitions[level + 1]},$);")
            n += 1
    return STEP_HEAD + "\n".join(lines) + "\n" + STEP_TAIL


def grid_assembly(levels):
    """A grid-shaped DAG: level k has k + 1 products, product (k, i) uses (k + 1, i) and
    (k + 1, i + 1): 2^levels instances from a few hundred entities."""
    lines, n, definition = [], 10, {}
    for k in range(levels + 1):
        for i in range(k + 1):
            lines += [f"#{n}=PRODUCT('G{k}_{i}','G{k}_{i}','',(#2));",
                      f"#{n + 1}=PRODUCT_DEFINITION_FORMATION('','',#{n});",
                      f"#{n + 2}=PRODUCT_DEFINITION('design','',#{n + 1},#3);"]
            definition[k, i] = n + 2
            n += 3
    for k in range(levels):
        for i in range(k + 1):
            for j in (i, i + 1):
                lines.append(f"#{n}=NEXT_ASSEMBLY_USAGE_OCCURRENCE('{n}','','',#{definition[k, i]},"
                             f"#{definition[k + 1, j]},$);")
                n += 1
    return STEP_HEAD + "\n".join(lines) + "\n" + STEP_TAIL


def diamond_sets(levels):
    """GEOMETRIC_SETs in a diamond: two sets a level, each holding both sets of the level
    below (2^levels points when expanded), inside a shape representation."""
    lines = ["#20=CARTESIAN_POINT('',(0.,0.,0.));", "#21=CARTESIAN_POINT('',(1.,0.,0.));"]
    below, n = (20, 21), 30
    for _ in range(levels):
        lines += [f"#{n}=GEOMETRIC_SET('',(#{below[0]},#{below[1]}));",
                  f"#{n + 1}=GEOMETRIC_SET('',(#{below[1]},#{below[0]}));"]
        below, n = (n, n + 1), n + 2
    lines += ["#4=( GEOMETRIC_REPRESENTATION_CONTEXT(3) GLOBAL_UNIT_ASSIGNED_CONTEXT((#5)) "
              "REPRESENTATION_CONTEXT('',''));", "#5=( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.) );",
              f"#{n}=GEOMETRICALLY_BOUNDED_WIREFRAME_SHAPE_REPRESENTATION('',(#{below[0]}),#4);"]
    return STEP_HEAD + "\n".join(lines) + "\n" + STEP_TAIL


def motor_with_far_cube(path, distance):
    """The motor's parts and a 1 mm cube `distance` mm away along x, as FreeCAD exports them."""
    FreeCAD = bad.freecad()
    import Part
    sys.path.insert(0, REPO)
    from contactwb import core
    parts = []
    for body in core.contactcore.read_step(MOTOR).bodies:
        shape = Part.Shape()
        shape.importBrepFromString(body.brep)
        parts.append((body.name, shape, None))
    parts.append(("Stray", Part.makeBox(1, 1, 1, FreeCAD.Vector(distance, 0, 0)), None))
    return bad.export_step(path, parts)


def renamed_step(text, old, new):
    """`text` with the part named `old` renamed: its PRODUCT's name and id and the name of the
    occurrence placing it (which names the body)."""
    pattern = re.compile(r"PRODUCT\('%s','%s'" % (re.escape(old), re.escape(old)))
    assert pattern.search(text), old
    text = pattern.sub(lambda _: f"PRODUCT('{new}','{new}'", text)
    usage = re.compile(r"(NEXT_ASSEMBLY_USAGE_OCCURRENCE\('[^']*',)'%s'" % re.escape(old))
    assert usage.search(text), old
    return usage.sub(lambda m: m.group(1) + f"'{new}'", text)


def patched_zip(source, target, member, flags=None, method=None):
    """A copy of the archive with `member`'s flag bits or compression method
    changed in its local and central headers (zipfile cannot write those)."""
    data = bytearray(open(source, "rb").read())
    with zipfile.ZipFile(source) as archive:
        info = archive.getinfo(member)
        if info.compress_type != zipfile.ZIP_STORED and method is not None:
            raise ValueError("store the member first")
    local = info.header_offset
    assert data[local:local + 4] == b"PK\x03\x04"
    # This member's entry in the central directory, found by its name.
    name = member.encode()
    position = 0
    while True:
        position = data.index(b"PK\x01\x02", position)
        name_length = int.from_bytes(data[position + 28:position + 30], "little")
        if data[position + 46:position + 46 + name_length] == name:
            central = position
            break
        position += 4
    if flags is not None:
        for offset in (local + 6, central + 8):
            data[offset:offset + 2] = (int.from_bytes(data[offset:offset + 2], "little") | flags).to_bytes(2, "little")
    if method is not None:
        for offset in (local + 8, central + 10):
            data[offset:offset + 2] = method.to_bytes(2, "little")
    open(target, "wb").write(bytes(data))
    return target


def stored_copy(source, target):
    """The archive rewritten with every member stored (uncompressed)."""
    with zipfile.ZipFile(source) as archive, zipfile.ZipFile(target, "w", zipfile.ZIP_STORED) as out:
        for info in archive.infolist():
            out.writestr(info.filename, archive.read(info.filename), zipfile.ZIP_STORED)
    return target


def with_document_xml(source, target, document_xml):
    with zipfile.ZipFile(source) as archive, zipfile.ZipFile(target, "w", zipfile.ZIP_DEFLATED) as out:
        for info in archive.infolist():
            data = document_xml if info.filename == "Document.xml" else archive.read(info.filename)
            out.writestr(info.filename, data)
    return target


ENTITY_BOMB = ('<?xml version="1.0" encoding="utf-8"?>\n<!DOCTYPE Document [\n <!ENTITY a0 "lol">\n'
               + "".join(f' <!ENTITY a{k} "{("&a%d;" % (k - 1)) * 10}">\n' for k in range(1, 10))
               + ']>\n<Document SchemaVersion="4" ProgramVersion="0.20" FileVersion="1">&a9;</Document>\n')


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--out", required=True)
    args = parser.parse_args()
    out = os.path.abspath(args.out)
    os.makedirs(out, exist_ok=True)
    cases = []

    def path(name):
        return os.path.join(out, name)

    def write(name, data):
        with open(path(name), "wb") as stream:
            stream.write(data.encode("utf-8") if isinstance(data, str) else data)
        return path(name)

    def case(name, argv, exit_code, expect, refusal=False, **facts):
        cases.append({"name": name, "argv": [os.fsdecode(a) for a in argv], "exit": exit_code, "expect": expect,
                      "refusal": refusal, **facts})

    motor = open(MOTOR, encoding="utf-8").read()

    # 1. A stray part does not skew the tolerances of the others.
    for distance, tag in ((1e5, "100m"), (1e6, "1km"), (1e9, "1e9mm")):
        motor_with_far_cube(path(f"motor_far_cube_{tag}.step"), distance)
        case(f"far cube {tag}", [path(f"motor_far_cube_{tag}.step")], 0, MOTOR_TOTAL, absent="not a valid solid")

    # 2. Bounds before work: instances counted before they are expanded, numbers checked.
    case("doubling assembly 2^30", [write("doubling_30.step", doubling_assembly(30))], 3,
         "expands to 1.07374e+09 instances", refusal=True)
    case("grid assembly 2^24", [write("grid_24.step", grid_assembly(24))], 3, "expands to 1.67772e+07 instances",
         refusal=True)
    case("--max-bodies 1000 on 2^10", [write("doubling_10.step", doubling_assembly(10)), "--max-bodies", "1000"], 3,
         "more than the limit of 1000 bodies", refusal=True)
    case("diamond of geometric sets", [write("diamond_sets_30.step", diamond_sets(30))], 3,
         "expands to 1.07374e+09 items", refusal=True)
    line = "#115 = VECTOR('',#116,1.);"
    assert line in motor
    case("VECTOR 1e400", [write("motor_vector_inf.step", motor.replace(line, "#115 = VECTOR('',#116,1.E+400);"))],
         3, "#115 (VECTOR)", refusal=True)
    unit = "#88 = ( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.) );"
    assert unit in motor
    case("infinite unit factor", [write("motor_unit_inf.step", motor.replace(unit, (
        "#88 = ( CONVERSION_BASED_UNIT('INCH',#99990) LENGTH_UNIT() NAMED_UNIT(#99991) );\n"
        "#99990 = LENGTH_MEASURE_WITH_UNIT(LENGTH_MEASURE(1.E+400),#99992);\n"
        "#99991 = DIMENSIONAL_EXPONENTS(1.,0.,0.,0.,0.,0.,0.);\n"
        "#99992 = ( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.) );")))], 3, "#99990 (MEASURE_WITH_UNIT)",
        refusal=True)
    circle = re.search(r"^(#\d+) = CIRCLE\('',(#\d+),([^)]*)\);", motor, re.M)
    case("circle of infinite radius --json",
         [write("motor_circle_inf.step", motor.replace(circle.group(0), f"{circle.group(1)} = CIRCLE('',"
                                                                         f"{circle.group(2)},1.E+400);")), "--json"],
         3, f"{circle.group(1)} (CIRCLE)", refusal=True)

    # Meshes: sizes checked, the triangle count estimated before meshing.
    mesh_out = path("mesh_out")
    case("--max-edge 0.001", ["mesh", MOTOR, "--out", mesh_out, "--max-edge", "0.001"], 3, "--max-triangles",
         refusal=True)
    case("--deflection 1e-6", ["mesh", MOTOR, "--out", mesh_out, "--deflection", "1e-6"], 3, "--max-triangles",
         refusal=True)
    case("--max-triangles 1000", ["mesh", MOTOR, "--out", mesh_out, "--max-triangles", "1000"], 3,
         "more than the limit of 1000 ", refusal=True)
    for option, value in (("--deflection", "inf"), ("--max-edge", "nan"), ("--angle", "nan"), ("--deflection", "-1")):
        case(f"mesh {option} {value}", ["mesh", MOTOR, "--out", mesh_out, option, value], 2, option, refusal=True)
    write("a_file", "not a folder")
    case("--out an existing file", ["mesh", MOTOR, "--out", path("a_file")], 2, "exists and is not a folder",
         refusal=True)

    # Trial scripts, checked before the loop starts.
    scripts = {
        "nan_time": ('{"hand": [{"t": NaN}]}', "NaN is not a number a script may hold"),
        "long_time": ('{"hand": [{"t": 0}, {"t": 10000}]}', "the script lasts at most 600 s"),
        "infinite_time": ('{"hand": [{"t": 1e400}]}', "is not finite"),
        "huge_list": (json.dumps({"hand": [{"t": i * 1e-3, "translate": [0, 0, 0]} for i in range(100000)]}),
                      "larger than 1000000 bytes"),
        "many_keys": (json.dumps({"hand": [{"t": 0}] * 10001}), "10001 hand keys (at most 10000)"),
        "digits_400": ('{"hand": [{"t": %s}]}' % ("9" * 400), "more than 30 digits"),
        "nested_200000": ('{"hand": ' + "[" * 200000 + "]" * 200000 + "}", "nested deeper than 16 levels"),
        "translate_nan": ('{"hand": [{"t": 0, "translate": [0, NaN, 0]}]}', "NaN is not a number"),
        "decreasing": ('{"hand": [{"t": 1}, {"t": 0.5}]}', "must be >= 0 and not decrease"),
        "time_1e300": ('{"hand": [{"t": 0}, {"t": 1e300}]}', "the script lasts at most 600 s"),
    }
    for name, (text, expect) in scripts.items():
        case(f"trial script {name}", ["trial", MOTOR, "--part", "Axis", "--script", write(f"{name}.json", text)], 3,
             expect, refusal=True)
    case("trial script latin-1", ["trial", MOTOR, "--part", "Axis", "--script",
                                  write("latin1.json", '{"hand": [{"t": 0}], "note": "caf\xe9"}'.encode("latin-1"))],
         3, "not UTF-8 text", refusal=True)
    case("trial --stiffness nan", ["trial", MOTOR, "--part", "Axis", "--script", path("decreasing.json"),
                                   "--stiffness", "nan"], 2, "--stiffness", refusal=True)

    # .FCStd archives checked before FreeCAD reads them.
    case("entity bomb", [with_document_xml(MOTOR_FCSTD, path("entity_bomb.FCStd"), ENTITY_BOMB)], 3,
         "unsupported file: Document.xml declares the entity 'a0'", refusal=True)
    stored = stored_copy(MOTOR_FCSTD, path("motor_stored.FCStd"))
    case("encrypted member", [patched_zip(stored, path("encrypted.FCStd"), "Document.xml", flags=0x1)], 3,
         "unsupported file: member 'Document.xml' is encrypted", refusal=True)
    case("deflate64 member", [patched_zip(stored, path("deflate64.FCStd"), "Document.xml", method=9)], 3,
         "unsupported file: member 'Document.xml' uses compression method 9", refusal=True)
    case("stored archive reads", [stored], 0, MOTOR_TOTAL)

    # One exit-code contract.
    for value in ("-5", str(2 ** 64), "x"):
        case(f"--max-pairs {value}", [MOTOR, "--max-pairs", value], 2, "--max-pairs", refusal=True)
    missing = path("missing.step")
    for argv in ([missing], [missing, "--joints"], [missing, "--disassembly"], ["mesh", missing, "--out", mesh_out],
                 ["trial", missing, "--part", "Axis", "--script", os.path.join(REPO, "Resources", "trials",
                                                                                 "motor_axis_insertion.json")]):
        case(f"missing file: {' '.join(a for a in argv if a != missing)}", argv, 3, "no such file", refusal=True)
    for option, target in (("--export-urdf", path("urdf_out")), ("--export-mjcf", path("mjcf_out.xml"))):
        case(f"missing file: {option}", [missing, option, target], 3, "no such file", refusal=True)
    case("interlocked parts", [os.path.join(SAMPLES, "cases", "ball_bearing.step"), "--disassembly"], 4,
         "Stopped: no part or group")
    # Outputs never created in /dev, /proc or /sys (as root they would be): usage errors.
    taper_step = os.path.join(SAMPLES, "cases", "taper_pin.step")
    for option, target in (("--graph", "/dev/contacts_graph.svg"), ("--export-mjcf", "/dev/contacts_model.xml"),
                           ("--export-urdf", "/proc/contacts_urdf")):
        case(f"{option} in a system folder", [taper_step, option, target], 2, "is in the system folder", refusal=True)
    case("trial --record in /dev", ["trial", MOTOR, "--part", "Axis", "--script",
                                    os.path.join(REPO, "Resources", "trials", "motor_axis_insertion.json"),
                                    "--record", "/dev/contacts_record.json"], 2, "is in the system folder",
         refusal=True)
    taper = open(os.path.join(SAMPLES, "cases", "taper_pin.step"), "rb").read()
    odd_name = os.path.join(os.fsencode(out), b"taper_\xff\xfe.step")
    with open(odd_name, "wb") as stream:
        stream.write(taper)
    case("non-UTF-8 name --joints", [odd_name, "--joints"], 0, "Total: 1 contacts")
    case("non-UTF-8 name --disassembly", [odd_name, "--disassembly"], 0, "Taper-pin along (0, 0, 1)")
    case("non-UTF-8 name mesh", ["mesh", odd_name, "--out", path("mesh_odd")], 0, "Taper-pin:")
    odd_motor = os.path.join(os.fsencode(out), b"motor_\xff.step")
    with open(odd_motor, "wb") as stream:
        stream.write(open(MOTOR, "rb").read())
    case("non-UTF-8 name trial", ["trial", odd_motor, "--part", "Axis", "--script",
                                  os.path.join(REPO, "Resources", "trials", "motor_axis_insertion.json")], 0,
         "Trial of 'Axis'")

    # Names: control characters escaped in the table; every STEP string encoding decoded;
    # an occurrence without a name takes its product's.
    two_boxes = bad.export_step(path("two_boxes.step"), bad.base_and_top())
    case("control characters in a name",
         [write("escape_name.step", renamed_step(two_boxes, "Top", "Top\x1b]0;pwned\x07"))], 0, "Top\\x1b]0;pwned\\x07",
         absent="\x1b")
    for tag, encoded, decoded in (("x2", "\\X2\\041F0438043D\\X0\\", "\u041f\u0438\u043d"),
                                  ("x4", "\\X4\\0001F642\\X0\\", "\U0001F642"),
                                  ("s", "Gr\\S\\|n", "Gr\u00fcn"),
                                  ("x", "Gr\\X\\FCn", "Gr\u00fcn")):
        case(f"name encoded {tag}", [write(f"name_{tag}.step", renamed_step(two_boxes, "Top", encoded))], 0,
             f"<->  {decoded}", absent="\\X")
    template = bad.one_instance_template(path("one_instance.step"))
    unnamed = re.sub(r"NEXT_ASSEMBLY_USAGE_OCCURRENCE\('(\d+)','Cube_0',", r"NEXT_ASSEMBLY_USAGE_OCCURRENCE('\1','',",
                     template)
    assert unnamed != template
    case("unnamed occurrence", [write("unnamed_occurrence.step", unnamed), "--json"], 0, '"name": "Cube"')

    with open(os.path.join(out, "cases.json"), "w") as stream:
        json.dump(cases, stream, indent=1)


if __name__ == "__main__":
    main()
