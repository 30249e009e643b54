"""A STEP assembly into a FreeCAD document through the core's products reader
(contactcore.read_step): each solid becomes a Part::Feature named after its
STEP product (repeated instances '.2', '.3', ...), inside App::Part
containers following the file's assembly tree; shapes in mm whatever the
file's unit. FreeCAD's own import names a compound after the file
("assembly.17") and unnamed occurrences "Undefined015.2"; here every name
comes from the file's products."""
import os

import FreeCAD

from contactwb import core

# Names OCCT's XDE reader gives a product's unnamed solids (its shape types):
# such a part is named after the product holding it instead ("PLATEAU_BAS",
# not "SOLID"), as FreeCAD users name parts after the file's products.
SHAPE_TYPE_NAMES = {"COMPOUND", "COMPSOLID", "SOLID", "SHELL"}


def _base(name):
    head, _, tail = name.rpartition(".")
    return head if head and tail.isdigit() else name


def part_places(bodies):
    """[(container path, part name)] per body: the body's own name (its
    occurrence or product) in the containers of its path; a shape type's
    name replaced by its product's, the part then in that product's place
    (its path's parent); repeats numbered '.2', '.3', ... as the core does."""
    places = []
    for body in bodies:
        levels = body.path.split("/")
        if _base(body.name) in SHAPE_TYPE_NAMES and len(levels) >= 2 and levels[-2]:
            places.append(("/".join(levels[:-2]), levels[-2]))
        else:
            places.append(("/".join(levels[:-1]), body.name))
    names = core.contactcore.unique_names([name for _, name in places])
    return [(container, name) for (container, _), name in zip(places, names)]


def _container(doc, parents, path, label):
    """The App::Part for an assembly path ("Root/Sub"), made on first use."""
    if path not in parents:
        part = doc.addObject("App::Part", "Assembly")
        part.Label = label
        parent_path = path.rpartition("/")[0]
        if parent_path:
            _container(doc, parents, parent_path, parent_path.rpartition("/")[2]).addObject(part)
        parents[path] = part
    return parents[path]


def import_step(doc, path, progress=None):
    """Adds the STEP file's solids to `doc`; returns (the root container,
    [Part::Feature in the file's order], the file's unit). Raises
    contactcore errors (InputError naming the file) for a bad file and
    Cancelled when progress("read", fraction) returns False."""
    import Part
    assembly = core.contactcore.read_step(os.fsencode(os.path.abspath(path)), progress=progress)
    parents = {}
    features = []
    stem = os.path.splitext(os.path.basename(path))[0]
    for body, (container_path, name) in zip(assembly.bodies, part_places(assembly.bodies)):
        # the containers above the part: the products of its path, from the root
        container_path = container_path or stem
        container = _container(doc, parents, container_path, container_path.rpartition("/")[2])
        shape = Part.Shape()
        shape.importBrepFromString(body.brep)
        feature = doc.addObject("Part::Feature", "Part")
        feature.Label = name
        feature.Shape = shape
        container.addObject(feature)
        features.append(feature)
    roots = [p for key, p in parents.items() if "/" not in key]
    root = roots[0] if len(roots) == 1 else None
    for message in assembly.messages:
        FreeCAD.Console.PrintWarning(f"Contacts: {os.path.basename(path)}: {message}\n")
    return root, features, assembly.units
