"""Loads the C++ extension `contactcore` and moves shapes between FreeCAD and it.

The extension sits beside the workbench once installed; in a source checkout
it is found in $CONTACTS_PYTHON_DIR or <repo>/build/python."""
import os
import sys

from contactwb import ROOT_DIR


def _load():
    # An explicit build folder first: FreeCAD puts installed workbenches at the
    # front of sys.path, so a plain import could load another (older) build.
    explicit = os.environ.get("CONTACTS_PYTHON_DIR")
    if explicit and os.path.isdir(explicit) and "contactcore" not in sys.modules:
        if explicit in sys.path:
            sys.path.remove(explicit)
        sys.path.insert(0, explicit)
    try:
        import contactcore  # installed beside the workbench, or already on sys.path
        return contactcore
    except ImportError:
        pass
    candidates = [os.environ.get("CONTACTS_PYTHON_DIR"), os.path.join(ROOT_DIR, "build", "python")]
    for folder in filter(None, candidates):
        if os.path.isdir(folder) and folder not in sys.path:
            sys.path.insert(0, folder)
            try:
                import contactcore
                return contactcore
            except ImportError:
                sys.path.remove(folder)
    raise ImportError(
        "The Contacts C++ extension (contactcore) is not built or not installed: "
        "run `make build` (or `make install`) in the workbench's source folder, "
        "or set CONTACTS_PYTHON_DIR to the folder holding contactcore*.so")


contactcore = _load()
ContactsError = contactcore.ContactsError
Cancelled = contactcore.Cancelled
InputError = contactcore.InputError        # a file or shape that cannot be read or used (a ContactsError)
ArgumentError = contactcore.ArgumentError  # an option out of range (a ContactsError and a ValueError)


def shape_to_brep(shape):
    """BRep text of a Part.Shape (with its placement)."""
    return shape.exportBrepToString()


def shape_from_brep(text):
    """A Part.Shape from BRep text (needs FreeCAD's Part module)."""
    import Part
    shape = Part.Shape()
    shape.importBrepFromString(text)
    return shape


def assembly_from_shapes(named_shapes):
    """A contactcore.Assembly from (name, Part.Shape) pairs, shapes already
    placed globally. They cross into C++ as one compound (instances share
    geometry in the BRep stream, so this is cheap even for thousands)."""
    import Part
    named_shapes = list(named_shapes)
    if not named_shapes:
        raise ContactsError("no bodies given")
    compound = Part.makeCompound([shape for _, shape in named_shapes])
    return contactcore.bodies_from_brep(compound.exportBrepToString(), [name for name, _ in named_shapes])
