"""The workbench's core: no FreeCAD import at all (as freecad.gears keeps its
math). The C++ extension and its exceptions, the contact kinds, and the
results of each stage (contacts, joints, meshes, trials) with their text,
JSON and CSV forms. FreeCAD adapters are in contactwb.document.

    from contactwb import core
    core.contactcore.read_step(...)     # the extension
    core.ContactsError, core.Cancelled, core.InputError, core.ArgumentError, core.InternalError"""
from contactwb.core.extension import (ArgumentError, Cancelled, ContactsError, InputError,  # noqa: F401
                                      InternalError, contactcore)
