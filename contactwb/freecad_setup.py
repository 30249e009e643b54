"""Compatibility shim: this module moved to contactwb.document.freecad_setup.
The old path stays importable (scripts, saved files); new code imports the new one."""
import sys

from contactwb.document import freecad_setup as _home

sys.modules[__name__] = _home
