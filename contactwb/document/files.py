"""An assembly from a file, for the file-based tools (`contacts mesh`,
`contacts trial`, `--disassembly`): a STEP file read in C++, or a FreeCAD
document's visible solids."""
import os

from contactwb import core
from contactwb.core import meshes


def load_assembly(path):
    """The bodies of a STEP file (read in C++) or of a FreeCAD document's visible solids."""
    if not os.path.isfile(path):
        raise core.ContactsError(f"no such file: '{path}'")
    if path.lower().endswith(".fcstd"):
        from contactwb.document import bodies as document_bodies
        from contactwb.document import freecad_setup
        doc = freecad_setup.open_document(os.path.abspath(path))
        assembly, _ = document_bodies.assembly_from_document(doc, None, [])
        return assembly
    return meshes.read_step_assembly(path)
