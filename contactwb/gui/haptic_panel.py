"""Compatibility shim: the haptic trial panel moved to
contactwb.gui.panels.haptic_panel, its command to contactwb.gui.commands.haptics."""
from contactwb.gui.commands.haptics import COMMANDS, Contacts_HapticTrial  # noqa: F401
from contactwb.gui.panels import haptic_panel as _panel
from contactwb.gui.panels.haptic_panel import *  # noqa: F401,F403


def __getattr__(name):  # live module state (active_panel) and private names
    return getattr(_panel, name)
