"""Compatibility shim: haptic trials moved to contactwb.core.trial, load_assembly
(STEP or FreeCAD document) to contactwb.document.files."""
from contactwb.core import trial as _core
from contactwb.core.trial import *  # noqa: F401,F403
from contactwb.document.files import load_assembly  # noqa: F401


def __getattr__(name):  # the rest of the old module's names (private ones too)
    return getattr(_core, name)
