"""Compatibility shim: this module moved to contactwb.gui.overlay.partitions.
The old path stays importable (scripts, saved files); new code imports the new one."""
import sys

from contactwb.gui.overlay import partitions as _home

sys.modules[__name__] = _home
