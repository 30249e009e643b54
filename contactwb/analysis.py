"""Compatibility shim (and the README's `from contactwb import analysis`): the
headless analysis moved to contactwb.core.analysis, its FreeCAD entry points
(documents, Part shapes) to contactwb.document.analysis."""
from contactwb.core import analysis as _core
from contactwb.core.analysis import *  # noqa: F401,F403
from contactwb.core.analysis import analysis_of_result as _analysis  # noqa: F401  (its old name)
from contactwb.document.analysis import find_contacts_in_document, find_contacts_in_shapes  # noqa: F401


def __getattr__(name):  # the rest of the old module's names (private ones too)
    return getattr(_core, name)
