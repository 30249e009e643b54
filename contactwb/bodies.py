"""Compatibility shim: this module moved to contactwb.document.bodies.
The old path stays importable (scripts, saved files); new code imports the new one."""
import sys

from contactwb.document import bodies as _home

sys.modules[__name__] = _home
