"""Compatibility shim: this module moved to contactwb.document.export.
The old path stays importable (scripts, saved files); new code imports the new one."""
import sys

from contactwb.document import export as _home

sys.modules[__name__] = _home
