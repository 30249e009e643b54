"""Loads the C++ extension `contactcore` (no FreeCAD import: moving FreeCAD
shapes into it is contactwb.document.shapes).

The extension sits beside the workbench once installed; in a source checkout
it is found in $CONTACTS_PYTHON_DIR or <repo>/build/python."""
import os
import sys

from contactwb import ROOT_DIR


def _load():
    # An explicit $CONTACTS_PYTHON_DIR wins over an installed copy: FreeCAD puts
    # every Mod folder on sys.path, so a workbench installed earlier would
    # otherwise shadow the build that the tests and benchmarks mean to run.
    explicit = os.environ.get("CONTACTS_PYTHON_DIR")
    if explicit and os.path.isdir(explicit):
        module = _import_from(explicit)
        if module is not None:
            return module
    try:
        import contactcore  # installed beside the workbench, or already on sys.path
        return contactcore
    except ImportError as error:
        _raise_if_out_of_memory(error)
    module = _import_from(os.path.join(ROOT_DIR, "build", "python"))
    if module is not None:
        return module
    raise ImportError(
        "The Contacts C++ extension (contactcore) is not built or not installed: "
        "run `make build` (or `make install`) in the workbench's source folder, "
        "or set CONTACTS_PYTHON_DIR to the folder holding contactcore*.so")


def _raise_if_out_of_memory(error):
    """An extension that exists but cannot be mapped under a memory limit is
    not "not built": say what it is."""
    text = str(error).lower()
    if "cannot allocate memory" in text or "failed to map segment" in text:
        raise MemoryError(f"out of memory loading the Contacts extension ({error})") from error


def _import_from(folder):
    """contactcore from `folder`, ahead of any other copy on sys.path; None if absent there."""
    if not os.path.isdir(folder):
        return None
    if folder in sys.path:
        sys.path.remove(folder)
    sys.path.insert(0, folder)
    try:
        import contactcore
    except ImportError as error:
        sys.path.remove(folder)
        _raise_if_out_of_memory(error)
        return None
    if os.path.dirname(os.path.realpath(contactcore.__file__)) != os.path.realpath(folder):
        # Imported earlier from somewhere else; the caller asked for this folder's copy.
        raise ImportError(f"contactcore was already loaded from {contactcore.__file__}, "
                          f"not from {folder}")
    return contactcore


contactcore = _load()
ContactsError = contactcore.ContactsError
Cancelled = contactcore.Cancelled
InputError = contactcore.InputError        # a file or shape that cannot be read or used (a ContactsError)
ArgumentError = contactcore.ArgumentError  # an option out of range (a ContactsError and a ValueError)
InternalError = contactcore.InternalError  # a bug in the core (the CLI's exit 5; a ContactsError)

