"""Compatibility shim: the headless joints moved to contactwb.core.joints, their
FreeCAD entry points (documents, Part shapes) to contactwb.document.analysis."""
from contactwb.core import joints as _core
from contactwb.core.joints import *  # noqa: F401,F403
from contactwb.document.analysis import joints_in_document, joints_in_shapes  # noqa: F401


def __getattr__(name):  # the rest of the old module's names (private ones too)
    return getattr(_core, name)
