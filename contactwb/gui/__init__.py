"""GUI of the workbench (FreeCAD.GuiUp only), by job: viewproviders/ (one
module per view provider), overlay/ (Coin drawings, legends, colours),
commands/ (command classes and their registration), panels/ (task panels and
docks), dialogs (message boxes), actions (what commands do to the view),
settings and preferences. Importing it sets the hooks through which the
document objects get their view providers (contactwb.gui.hooks)."""
from contactwb.gui import hooks

hooks.install()
