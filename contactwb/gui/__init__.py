"""GUI of the workbench: commands, view providers, task panels (FreeCAD.GuiUp only)."""
