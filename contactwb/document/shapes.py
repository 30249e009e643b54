"""Part shapes into the extension and back (BRep text)."""
from contactwb import core


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
        raise core.ContactsError("no bodies given")
    compound = Part.makeCompound([shape for _, shape in named_shapes])
    try:
        return core.contactcore.bodies_from_brep(compound.exportBrepToString(), [name for name, _ in named_shapes])
    except core.InputError as error:
        # FreeCAD wrote this text into memory just now: cut short, it ran out
        # of memory writing it (it does not say so).
        if "text cut short" in str(error):
            raise MemoryError(f"out of memory (FreeCAD's BRep export of the shapes came back cut short: {error})") \
                from error
        raise
