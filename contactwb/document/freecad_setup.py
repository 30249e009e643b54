"""FreeCAD as a library in a plain /usr/bin/python3 (Debian 12 paths).

Inside FreeCAD all of this is already done; outside it, FreeCAD must be
imported before Part (the other order segfaults), and a document's PartDesign
and Sketcher objects restore only once those modules are imported."""
import os
import sys

FREECAD_LIB = "/usr/lib/freecad-python3/lib"
FREECAD_MODS = "/usr/share/freecad/Mod"


def import_freecad():
    """Imports FreeCAD and Part, returns the FreeCAD module."""
    if "FreeCAD" not in sys.modules and FREECAD_LIB not in sys.path and os.path.isdir(FREECAD_LIB):
        sys.path.append(FREECAD_LIB)
    import FreeCAD
    import Part  # noqa: F401  (after FreeCAD, always)
    return FreeCAD


def load_document_modules():
    """Registers the object types of common documents (PartDesign, Sketcher)."""
    import_freecad()
    if FREECAD_MODS not in sys.path and os.path.isdir(FREECAD_MODS):
        sys.path.append(FREECAD_MODS)
    for name in ("Sketcher", "PartDesign"):
        try:
            __import__(name)
        except ImportError:
            pass  # a document using them will report its broken objects itself


def open_document(path):
    """Opens an .FCStd headless with its PartDesign/Sketcher objects restored."""
    load_document_modules()
    import FreeCAD
    return FreeCAD.openDocument(path)
