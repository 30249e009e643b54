#!/usr/bin/python3
"""Writes the fuzz targets' seed corpus (committed in fuzz/corpus/<target>/):
small STEP and BRep assemblies that have contacts (so the fuzzer starts
inside partitions and contacts), a few damaged files from the bad-input
corpus, and HID input reports of both SpaceMouse report formats.

    fuzz/make_seeds.py            # rewrites fuzz/corpus/{fuzz_step,fuzz_brep,fuzz_hid}/seed_*
"""
import os
import re
import struct
import sys
import tempfile

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CORPUS = os.path.join(REPO, "fuzz", "corpus")
sys.path.append("/usr/lib/freecad-python3/lib")
sys.path.append(os.path.join(REPO, "tools"))


def write(target, name, data):
    folder = os.path.join(CORPUS, target)
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, "seed_" + name), "wb") as f:
        f.write(data.encode() if isinstance(data, str) else data)


def shapes():
    import FreeCAD  # noqa: F401  (before Part)
    import Part
    from FreeCAD import Vector
    boxes = [Part.makeBox(10, 10, 10), Part.makeBox(10, 10, 5, Vector(0, 0, 10))]
    block = Part.makeBox(20, 20, 10).cut(Part.makeCylinder(3, 10, Vector(10, 10, 0)))
    shaft = Part.makeCylinder(3, 16, Vector(10, 10, -3))
    ball = Part.makeSphere(2, Vector(0, 0, 0))
    cup = Part.makeBox(6, 6, 3, Vector(-3, -3, -3)).cut(Part.makeSphere(2, Vector(0, 0, 0)))
    return {"boxes": boxes, "shaft_in_bore": [block, shaft], "ball_in_cup": [ball, cup]}


def step_text(solids):
    import Part
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "seed.step")
        Part.makeCompound(solids).exportStep(path)
        return open(path).read()


def hid_reports(model, reports):
    """Byte 0 model, byte 1 mode 0 (reports), then length-prefixed reports."""
    out = bytes([model, 0])
    for report in reports:
        out += bytes([len(report)]) + report
    return out


def main():
    import make_bad_inputs
    import FreeCAD  # noqa: F401  (before Part)
    import Part
    for name, solids in shapes().items():
        text = step_text(solids)
        write("fuzz_step", name + ".step", text)
        write("fuzz_brep", name + ".brep", Part.makeCompound(solids).exportBrepToString())
    boxes = step_text(shapes()["boxes"])
    entities = [m.start() for m in re.finditer(r"^#\d+ = ", boxes, re.M)]
    start = entities[17]
    ident = boxes[start:boxes.index("=", start)].strip()
    write("fuzz_step", "unknown_type.step", boxes[:start] + f"{ident} = NOT_A_TYPE('');" + boxes[boxes.index(";", start) + 1:])
    write("fuzz_step", "cyclic.step", make_bad_inputs.nested_step(3, cyclic=True))
    write("fuzz_step", "no_solid.step", make_bad_inputs.nested_step(2))
    brep = shapes()["boxes"][0].exportBrepToString()
    write("fuzz_brep", "cut_short.brep", brep[:len(brep) // 2])

    axes = struct.pack("<hhh", 120, -350, 7)
    rotation = struct.pack("<hhh", -5, 300, -120)
    # SpaceNavigator (two reports), SpaceMouse Wireless (six axes), a generic entry; buttons; short and unknown reports.
    write("fuzz_hid", "two_reports.bin", hid_reports(6, [b"\x01" + axes, b"\x02" + rotation, b"\x03\x01\x00"]))
    write("fuzz_hid", "six_axes.bin", hid_reports(11, [b"\x01" + axes + rotation, b"\x03\x02", b"\x01" + axes]))
    write("fuzz_hid", "generic.bin", hid_reports(21, [b"\x01" + axes, b"\x04\x00", b"\x02\x01", b"\x03\xff\xff\xff\xff\xff"]))
    # A report descriptor with the PID page (usage page 0x0F) after a long item.
    write("fuzz_hid", "descriptor.bin", bytes([3, 1]) + bytes([0x05, 0x01, 0x09, 0x08, 0xA1, 0x01, 0xFE, 0x02, 0x10, 0xAA, 0xBB,
                                                             0x06, 0x0F, 0x00, 0xC0]))


if __name__ == "__main__":
    main()
