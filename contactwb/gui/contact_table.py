"""Compatibility shim: this module moved to contactwb.gui.panels.contact_table.
The old path stays importable (scripts, saved files); new code imports the new one."""
import sys

from contactwb.gui.panels import contact_table as _home

sys.modules[__name__] = _home
