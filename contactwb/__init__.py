"""Contacts workbench: functional contacts between the parts of an assembly,
the kinematic joints they allow, and haptic insertion/extraction trials.

Layers, imports going one way (docs/architecture.md, "Python layers"):
core (no FreeCAD) -> document (FreeCAD adapters) -> objects (document object
proxies and their recompute) -> make (constructors) -> gui; cli beside gui.
The other modules at this level are compatibility shims for the paths of
earlier releases (tests/test_import_layers.py lists them), and freecad_tests
(FreeCAD's own test runner's entry)."""
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
