"""Compatibility shim: this module moved to contactwb.gui.panels.task_panel.
The old path stays importable (scripts, saved files); new code imports the new one."""
import sys

from contactwb.gui.panels import task_panel as _home

sys.modules[__name__] = _home
