"""Compatibility shim: the haptic trial panel moved to
contactwb.gui.panels.haptic_panel, its command to contactwb.gui.commands.haptics.
Every other name is the panel module's, read live (active_panel changes)."""
from contactwb.gui.commands.haptics import COMMANDS, Contacts_HapticTrial  # noqa: F401
from contactwb.gui.panels import haptic_panel as _panel


def __getattr__(name):
    return getattr(_panel, name)
