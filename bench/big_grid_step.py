#!/usr/bin/python3
"""A bolted grid of N parts (tools/samples_families.py's bolted_grid: the same
parts, names and placements) written as STEP text from the 100-part grid that
FreeCAD exports, without FreeCAD's export: Import.export takes 99 s for 10,000
parts on this machine and grows faster than linearly, so 100,000 parts
(issue 24's read-scaling target) would take hours. The template's two part
products (plate, bolt) and their geometry are kept; its occurrences (one
NEXT_ASSEMBLY_USAGE_OCCURRENCE, CONTEXT_DEPENDENT_SHAPE_REPRESENTATION,
REPRESENTATION_RELATIONSHIP_WITH_TRANSFORMATION, ITEM_DEFINED_TRANSFORMATION
and AXIS2_PLACEMENT_3D per part, as FreeCAD writes them) are written anew
for the N parts.

  bench/big_grid_step.py N OUT.step [--template bolted_grid_100.step]
"""
import argparse
import os
import re
import subprocess
import sys

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(REPO, "tools"))
sys.path.insert(0, REPO)

ENTITY = re.compile(r"^#(\d+)\s*=\s*(.*)$", re.S)


def entities(text):
    """{id: body} of the DATA section, and the header up to it."""
    header, data = text.split("DATA;", 1)
    data = data.rsplit("ENDSEC;", 1)[0]
    out = {}
    for chunk in data.split(";\n"):
        chunk = chunk.strip()
        if not chunk:
            continue
        match = ENTITY.match(chunk)
        if not match:
            raise SystemExit(f"unexpected STEP text: {chunk[:80]}")
        out[int(match.group(1))] = " ".join(match.group(2).split())
    return header + "DATA;\n", out


def refs(body):
    return [int(r) for r in re.findall(r"#(\d+)", body)]


def layout(n):
    """(name, (x, y, z)) of the grid's parts, in order."""
    from contactwb import freecad_setup
    freecad_setup.import_freecad()
    import samples_families as sf
    parts, _, _ = sf.bolted_grid(n)
    out = []
    for part in parts:
        base = part.placement.Base
        if not part.placement.Rotation.isIdentity():
            raise SystemExit(f"{part.label}: rotated parts are not supported by this writer")
        out.append((part.label, (base.x, base.y, base.z)))
    return out


def write_grid(template_path, n, out_path):
    with open(template_path) as f:
        header, body = entities(f.read())
    nauos = {i: b for i, b in body.items() if b.startswith("NEXT_ASSEMBLY_USAGE_OCCURRENCE(")}
    cdsrs = {i: b for i, b in body.items() if b.startswith("CONTEXT_DEPENDENT_SHAPE_REPRESENTATION(")}
    # The assembly: the relating product definition of the occurrences, its shape representation.
    assembly_pd = refs(next(iter(nauos.values())))[0]
    pds_of = {i: refs(b)[0] for i, b in body.items() if b.startswith("PRODUCT_DEFINITION_SHAPE(")}
    assembly_sr = None
    for i, b in body.items():
        if b.startswith("SHAPE_DEFINITION_REPRESENTATION("):
            pds, sr = refs(b)[:2]
            if pds_of.get(pds) == assembly_pd:
                assembly_sr = sr
    sr_refs = refs(body[assembly_sr])
    origin_axis, context = sr_refs[0], sr_refs[-1]
    # Per kind of part (its name up to the first '-'): related product definition and shape representation.
    kinds, dropped = {}, set()
    for cdsr_id, cdsr in cdsrs.items():
        rr, pds = refs(cdsr)[:2]
        nauo = pds_of[pds]
        name = re.match(r"NEXT_ASSEMBLY_USAGE_OCCURRENCE\('[^']*','([^']*)'", nauos[nauo]).group(1)
        child_pd = refs(nauos[nauo])[1]
        rr_refs = refs(body[rr])
        child_sr, idt = rr_refs[0], rr_refs[2]
        axis = refs(body[idt])[1]
        kinds.setdefault(name.split("-")[0], (child_pd, child_sr))
        dropped |= {cdsr_id, rr, pds, nauo, idt, axis, *refs(body[axis])}
    next_id = max(body) + 1
    lines = [header]
    for i in sorted(body):
        if i in dropped:
            continue
        if i == assembly_sr:
            continue  # rewritten below with the new placements
        lines.append(f"#{i} = {body[i]};\n")
    z_dir, x_dir = next_id, next_id + 1
    lines.append(f"#{z_dir} = DIRECTION('',(0.,0.,1.));\n#{x_dir} = DIRECTION('',(1.,0.,0.));\n")
    next_id += 2
    axes = []
    for k, (name, (x, y, z)) in enumerate(layout(n)):
        kind = name.split("-")[0]
        if kind not in kinds:
            raise SystemExit(f"the template has no part of kind {kind}")
        child_pd, child_sr = kinds[kind]
        point, axis, idt, rr, cdsr, pds, nauo = range(next_id, next_id + 7)
        next_id += 7
        axes.append(axis)
        lines.append(
            f"#{point} = CARTESIAN_POINT('',({x!r},{y!r},{z!r}));\n"
            f"#{axis} = AXIS2_PLACEMENT_3D('',#{point},#{z_dir},#{x_dir});\n"
            f"#{idt} = ITEM_DEFINED_TRANSFORMATION('','',#{origin_axis},#{axis});\n"
            f"#{rr} = ( REPRESENTATION_RELATIONSHIP('','',#{child_sr},#{assembly_sr}) "
            f"REPRESENTATION_RELATIONSHIP_WITH_TRANSFORMATION(#{idt}) SHAPE_REPRESENTATION_RELATIONSHIP() );\n"
            f"#{cdsr} = CONTEXT_DEPENDENT_SHAPE_REPRESENTATION(#{rr},#{pds});\n"
            f"#{pds} = PRODUCT_DEFINITION_SHAPE('Placement','Placement of an item',#{nauo});\n"
            f"#{nauo} = NEXT_ASSEMBLY_USAGE_OCCURRENCE('{k + 1}','{name}','',#{assembly_pd},#{child_pd},$);\n")
    items = ",".join(f"#{a}" for a in [origin_axis] + axes)
    lines.append(f"#{assembly_sr} = SHAPE_REPRESENTATION('',({items}),#{context});\n")
    lines.append("ENDSEC;\nEND-ISO-10303-21;\n")
    with open(out_path, "w") as f:
        f.writelines(lines)
    return out_path


def template_file(data_dir):
    path = os.path.join(data_dir, "bolted_grid_100.step")
    if not os.path.isfile(path):
        subprocess.run([sys.executable, os.path.join(REPO, "tools", "make_samples.py"), "--grid", "100",
                        "--no-fcstd", "--out", data_dir], check=True, stdout=subprocess.DEVNULL)
    return path


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("n", type=int)
    parser.add_argument("out")
    parser.add_argument("--template", help="a bolted grid exported by tools/make_samples.py --grid (100 parts)")
    args = parser.parse_args()
    template = args.template or template_file(os.path.dirname(os.path.abspath(args.out)))
    write_grid(template, args.n, args.out)


if __name__ == "__main__":
    main()
