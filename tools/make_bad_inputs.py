#!/usr/bin/python3
"""Writes the bad-input corpus (issue 14) into a folder: damaged STEP, BRep
and FCStd files, each with the outcome the `contacts` CLI must give.

    tools/make_bad_inputs.py --out DIR [--set small|large|all]   # DIR/cases.json lists the cases

Each case: {"file", "args", "exit", "expect"}: the exit code and a piece of
the message (stderr) or of the output. The small set: files made from boxes
and the bundled motor in a few seconds. The large set (a few seconds to
write, tens of seconds to analyse): 5,000 instances of one part, on a grid
and all at one place, and one body of over 100,000 faces."""
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


def freecad():
    sys.path.append("/usr/lib/freecad-python3/lib")
    import FreeCAD  # noqa: F401  (before Part)
    import Part  # noqa: F401
    return FreeCAD


def export_step(path, parts):
    """A STEP file of named parts [(name, shape, placement or None)], as
    FreeCAD writes them (one product per part, so messages name the part)."""
    FreeCAD = freecad()
    import Import
    doc = FreeCAD.newDocument("corpus")
    try:
        objects = []
        for name, shape, placement in parts:
            obj = doc.addObject("Part::Feature", name)
            obj.Shape = shape
            if placement is not None:
                obj.Placement = placement
            objects.append(obj)
        Import.export(objects, path)
    finally:
        FreeCAD.closeDocument(doc.Name)
    return open(path).read()


def base_and_top(scale=1.0, offset=0.0):
    """A 20 x 20 x 10 box with a 10 x 10 x 10 box on it (one PLF of area
    100 * scale^2), scaled and moved by `offset` along x, y and z."""
    FreeCAD = freecad()
    import Part
    corner = FreeCAD.Vector(offset, offset, offset)
    base = Part.makeBox(20 * scale, 20 * scale, 10 * scale, corner)
    top = Part.makeBox(10 * scale, 10 * scale, 10 * scale)  # placed: the STEP file holds its placement
    return [("Base", base, None), ("Top", top, FreeCAD.Placement(corner + FreeCAD.Vector(0, 0, 10 * scale),
                                                                  FreeCAD.Rotation()))]


def odd_solids(out):
    """Open shell, degenerate faces, zero volume, self-intersection: each
    beside a 20 x 20 x 10 base. Returns {case name: path}."""
    FreeCAD = freecad()
    import Part
    V = FreeCAD.Vector
    base = ("Base", Part.makeBox(20, 20, 10), None)
    lid = Part.Shell(Part.makeBox(10, 10, 10, V(0, 0, 10)).Faces[:5])  # a box without its top
    # a cone standing on its base (apex: a degenerated edge) and a ball resting
    # on the base at one point (poles: degenerated edges)
    cone = Part.makeCone(5, 0, 8, V(5, 5, 10))
    ball = Part.makeSphere(3, V(15, 15, 13))
    flatten = FreeCAD.Matrix()
    flatten.scale(1, 1, 0)  # a box of height 0: volume 0, its four sides of area 0
    flat = Part.makeBox(10, 10, 10).transformGeometry(flatten)
    flat.translate(V(0, 0, 10))
    bowtie = Part.Face(Part.makePolygon([V(0, 0, 10), V(10, 10, 10), V(10, 0, 10), V(0, 10, 10), V(0, 0, 10)]))
    # halves of 50/3 and 200/3 mm^2: healed through STEP it encloses 250 mm^3
    unequal = Part.Face(Part.makePolygon([V(0, 0, 10), V(10, 10, 10), V(10, 0, 10), V(0, 20, 10), V(0, 0, 10)]))
    files = {"open_shell": [base, ("Lid", lid, None)],
             "degenerate_faces": [base, ("Cone", cone, None), ("Ball", ball, None)],
             "zero_volume": [base, ("Flat", flat, None)],
             "self_intersecting": [base, ("Bowtie", bowtie.extrude(V(0, 0, 5)), None)],
             "self_intersecting_unequal": [base, ("Bowtie", unequal.extrude(V(0, 0, 5)), None)]}
    paths = {name: (os.path.join(out, name + ".step"), export_step(os.path.join(out, name + ".step"), parts))[0]
             for name, parts in files.items()}
    # A STEP round trip heals the bow-tie into eight valid faces (a solid of
    # volume 0); a document keeps it as it is, self-intersecting faces and all.
    paths["self_intersecting_document"] = save_document(os.path.join(out, "self_intersecting.FCStd"),
                                                        files["self_intersecting"])
    return paths


def save_document(path, parts):
    """An .FCStd of Part::Features (name, shape, placement or None). Returns the path."""
    FreeCAD = freecad()
    doc = FreeCAD.newDocument("corpus")
    try:
        for name, shape, placement in parts:
            obj = doc.addObject("Part::Feature", name)
            obj.Shape = shape
            if placement is not None:
                obj.Placement = placement
        doc.saveAs(path)
    finally:
        FreeCAD.closeDocument(doc.Name)
    return path


def non_finite_steps(text):
    """Two boxes (Base, Top placed 10 mm up) with one number made infinite or
    NaN: the placement's point and direction, a vertex's point. Returns
    {name: (text, entity)}, entity the damaged one ("#20 (CARTESIAN_POINT)")."""
    top = re.search(r"^(#\d+) = CARTESIAN_POINT\('',\(0\.,0\.,10\.\)\);", text, re.M)  # Top's placement
    axis = re.search(r"^(#\d+) = AXIS2_PLACEMENT_3D\('',%s,(#\d+)," % re.escape(top.group(1)), text, re.M)
    direction = re.search(r"^%s = DIRECTION\('',\(0\.,0\.,1\.\)\);" % re.escape(axis.group(2)), text, re.M)
    vertex = [m for m in re.finditer(r"^(#\d+) = CARTESIAN_POINT\('',\(([^,)]*),([^,)]*),([^,)]*)\)\);",
                                     text, re.M)][-1]  # a point of Top's edges
    cases = {}
    for value, tag in (("1.E+400", "inf"), ("NAN", "nan")):
        cases[f"placement_{tag}"] = (text.replace(top.group(0), f"{top.group(1)} = CARTESIAN_POINT('',(0.,0.,{value}));"),
                                     f"{top.group(1)} (CARTESIAN_POINT)")
        cases[f"vertex_{tag}"] = (text[:vertex.start(2)] + value + text[vertex.end(2):],
                                  f"{vertex.group(1)} (CARTESIAN_POINT)")
    cases["direction_inf"] = (text.replace(direction.group(0), f"{axis.group(2)} = DIRECTION('',(0.,0.,1.E+400));"),
                              f"{axis.group(2)} (DIRECTION)")
    return cases


def placed_document(path, value):
    """An .FCStd of Base and Top with Top's placement x set to `value` (NaN, inf)."""
    FreeCAD = freecad()
    doc = FreeCAD.newDocument("corpus")
    try:
        for name, shape, placement in base_and_top():
            obj = doc.addObject("Part::Feature", name)
            obj.Shape = shape
            if placement is not None:
                obj.Placement = placement
        doc.Top.Placement = FreeCAD.Placement(FreeCAD.Vector(value, 0, 10), FreeCAD.Rotation())
        doc.saveAs(path)
    finally:
        FreeCAD.closeDocument(doc.Name)


def instances_step(template, count, spacing, columns=100):
    """`count` instances of the part of a one-instance assembly STEP
    (`template`, as FreeCAD exports an App::Part holding one App::Link):
    columns of cubes `spacing` apart (0: all at one place)."""
    last = max(int(n) for n in re.findall(r"^#(\d+) =", template, re.M))
    shape_rep = re.search(r"^#(\d+) = SHAPE_REPRESENTATION\('',\((#\d+),(#\d+)\),(#\d+)\);", template, re.M)
    relation = re.search(r"REPRESENTATION_RELATIONSHIP\('','',(#\d+),(#\d+)\)", template)
    usage = re.search(r"NEXT_ASSEMBLY_USAGE_OCCURRENCE\('1','Cube_0','',(#\d+),(#\d+),\$\);", template)
    origin = shape_rep.group(2)
    axes, lines, n = [shape_rep.group(3)], [], last + 1
    for k in range(1, count):
        x, y = spacing * (k % columns), spacing * (k // columns)
        lines += [f"#{n} = AXIS2_PLACEMENT_3D('',#{n + 1},#{n + 2},#{n + 3});",
                  f"#{n + 1} = CARTESIAN_POINT('',({x:.1f},{y:.1f},0.));",
                  f"#{n + 2} = DIRECTION('',(0.,0.,1.));", f"#{n + 3} = DIRECTION('',(1.,0.,0.));",
                  f"#{n + 4} = CONTEXT_DEPENDENT_SHAPE_REPRESENTATION(#{n + 5},#{n + 7});",
                  f"#{n + 5} = ( REPRESENTATION_RELATIONSHIP('','',{relation.group(1)},{relation.group(2)}) "
                  f"REPRESENTATION_RELATIONSHIP_WITH_TRANSFORMATION(#{n + 6}) SHAPE_REPRESENTATION_RELATIONSHIP() );",
                  f"#{n + 6} = ITEM_DEFINED_TRANSFORMATION('','',{origin},#{n});",
                  f"#{n + 7} = PRODUCT_DEFINITION_SHAPE('Placement','Placement of an item',#{n + 8});",
                  f"#{n + 8} = NEXT_ASSEMBLY_USAGE_OCCURRENCE('{k + 1}','Cube_{k}','',"
                  f"{usage.group(1)},{usage.group(2)},$);"]
        axes.append(f"#{n}")
        n += 9
    head = template[:template.rindex("ENDSEC;")].replace(
        shape_rep.group(0), f"#{shape_rep.group(1)} = SHAPE_REPRESENTATION('',({origin},{','.join(axes)}),"
                            f"{shape_rep.group(4)});")
    return head + "\n".join(lines) + "\nENDSEC;\nEND-ISO-10303-21;\n"


def one_instance_template(path):
    FreeCAD = freecad()
    import Import
    import Part
    doc = FreeCAD.newDocument("corpus")
    try:
        grid = doc.addObject("App::Part", "Grid")
        cube = doc.addObject("Part::Feature", "Cube")
        cube.Shape = Part.makeBox(10, 10, 10)
        link = doc.addObject("App::Link", "Cube_0")
        link.LinkedObject = cube
        grid.addObject(link)
        doc.recompute()
        Import.export([grid], path)
    finally:
        FreeCAD.closeDocument(doc.Name)
    return open(path).read()


HOLES_PER_SIDE = 159  # 159^2 square holes, 4 faces each: 101,130 faces
HOLE_PITCH, HOLE_SIZE = 2.0, 1.0


def many_faces_document(path):
    """A 318 x 318 x 1 plate with 159 x 159 square through-holes of 1 mm (one
    solid of 101,130 faces, built as one face with holes extruded) lying on a
    318 x 318 x 10 base: one PLF of 318^2 - 159^2 = 75,843 mm^2."""
    FreeCAD = freecad()
    import Part
    V = FreeCAD.Vector
    side = HOLES_PER_SIDE * HOLE_PITCH
    wires = [Part.makePolygon([V(0, 0, 0), V(side, 0, 0), V(side, side, 0), V(0, side, 0), V(0, 0, 0)])]
    for i in range(HOLES_PER_SIDE):
        for j in range(HOLES_PER_SIDE):
            x, y = i * HOLE_PITCH + 0.5, j * HOLE_PITCH + 0.5
            wires.append(Part.makePolygon([V(x, y, 0), V(x, y + HOLE_SIZE, 0), V(x + HOLE_SIZE, y + HOLE_SIZE, 0),
                                           V(x + HOLE_SIZE, y, 0), V(x, y, 0)]))
    plate = Part.Face(Part.Plane(), wires).extrude(V(0, 0, 1))
    plate.translate(V(0, 0, 10))
    doc = FreeCAD.newDocument("corpus")
    try:
        doc.addObject("Part::Feature", "Base").Shape = Part.makeBox(side, side, 10)
        doc.addObject("Part::Feature", "Plate").Shape = plate
        doc.saveAs(path)
    finally:
        FreeCAD.closeDocument(doc.Name)
    return len(plate.Faces)


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
    parser.add_argument("--set", choices=("small", "large", "all"), default="small")
    args = parser.parse_args()
    out = args.out
    os.makedirs(out, exist_ok=True)
    cases = []

    def case(name, data, exit_code, expect, args=(), **facts):
        path = write(out, name, data) if data is not None else os.path.join(out, name)
        cases.append({"file": path, "args": list(args), "exit": exit_code, "expect": expect, **facts})

    if args.set in ("large", "all"):
        large_cases(out, case)
    if args.set in ("small", "all"):
        small_cases(out, case)
    with open(os.path.join(out, "cases.json"), "w") as f:
        json.dump(cases, f, indent=1)


def large_cases(out, case):
    template = one_instance_template(os.path.join(out, "one_instance.step"))
    # 100 x 50 cubes side by side: 99 * 50 + 100 * 49 faces touching
    case("instances_5000_grid.step", instances_step(template, 5000, 10.0), 0, "Total: 9850 contacts (9850 PLF)")
    # all at one place: 12,497,500 overlapping pairs, beyond the default --max-pairs
    case("instances_5000_same_place.step", instances_step(template, 5000, 0.0), 3, "--max-pairs")
    faces = many_faces_document(os.path.join(out, "faces_100k.FCStd"))
    case("faces_100k.FCStd", None, 0, "Total: 1 contacts (1 PLF)", plate_faces=faces)


def small_cases(out, case):
    box = box_step()
    motor = open(MOTOR, "rb").read()

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

    odd = odd_solids(out)
    case(odd["open_shell"], None, 0, "Lid': 1 open shell(s)")
    case(odd["degenerate_faces"], None, 0, "Total: 1 contacts (1 PLF)")  # the cone's base; the ball touches at a point
    case(odd["zero_volume"], None, 0, "body 'Flat' has no volume")
    case(odd["self_intersecting"], None, 0, "Bowtie")  # healed by the STEP reader: named in its contact
    case(odd["self_intersecting_document"], None, 0, "'Bowtie' is not a valid solid")
    case(odd["self_intersecting_unequal"], None, 0, "Bowtie  faces crossing each other",
         args=["--check-solids", "full"])
    two_boxes = export_step(os.path.join(out, "two_boxes.step"), base_and_top())
    case("two_boxes.step", None, 0, "Total: 1 contacts (1 PLF)")
    for name, (text, entity) in non_finite_steps(two_boxes).items():
        case(f"{name}.step", text, 3, entity)
    for value, tag in ((float("nan"), "nan"), (float("inf"), "inf"), (-float("inf"), "minus_inf")):
        placed_document(os.path.join(out, f"{tag}_placement.FCStd"), value)
        case(f"{tag}_placement.FCStd", None, 3, "(body 'Top')")
    # coordinates from 1e-6 to 1e6 mm: tiny and huge parts, small parts far from the origin
    for name, scale, offset in (("tiny_1e-6", 1e-6, 0.0), ("huge_1e5", 1e5, 0.0), ("far_1e6", 1.0, 1e6)):
        export_step(os.path.join(out, f"{name}.step"), base_and_top(scale, offset))
        case(f"{name}.step", None, 0, "Total: 1 contacts (1 PLF)")


if __name__ == "__main__":
    main()
