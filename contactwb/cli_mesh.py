"""Compatibility shim: this module moved to contactwb.cli.mesh.
The old path stays importable (scripts, saved files); new code imports the new one."""
import sys

from contactwb.cli import mesh as _home

sys.modules[__name__] = _home
