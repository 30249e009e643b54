"""Contacts workbench: functional contacts between the parts of an assembly,
the kinematic joints they allow, and haptic insertion/extraction trials.

Headless modules (no GUI import): core, bodies, analysis, cli. GUI code lives
in contactwb.gui and is imported only when FreeCAD.GuiUp."""
import os

__version__ = "0.1.0"

PACKAGE_DIR = os.path.dirname(os.path.abspath(__file__))
ROOT_DIR = os.path.dirname(PACKAGE_DIR)
RESOURCES_DIR = os.path.join(ROOT_DIR, "Resources")
ICONS_DIR = os.path.join(RESOURCES_DIR, "icons")
SAMPLES_DIR = os.path.join(RESOURCES_DIR, "samples")


def icon_path(name):
    """Path of an icon of Resources/icons (name without .svg)."""
    return os.path.join(ICONS_DIR, name + ".svg")
