"""GUI of the workbench (FreeCAD.GuiUp only), by job: viewproviders/ (one
module per view provider), overlay/ (Coin drawings, legends, colours),
commands/ (command classes and their registration), panels/ (task panels and
docks), dialogs (message boxes), actions (what commands do to the view),
settings and preferences. InitGui.py calls contactwb.gui.hooks.install() at
start-up: it sets the hooks through which the document objects get their view
providers. This file imports nothing, so importing any gui module never runs
the others (no cycle through the package)."""
