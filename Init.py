# Contacts workbench: application (non-GUI) initialisation. No GUI import here:
# FreeCAD runs this in freecadcmd too. The workbench's code is in contactwb/.
import FreeCAD

FreeCAD.__unit_test__ += ["contactwb.freecad_tests"]
