"""Compatibility shim: this module moved to contactwb.cli.trial.
The old path stays importable (scripts, saved files); new code imports the new one."""
import sys

from contactwb.cli import trial as _home

sys.modules[__name__] = _home
