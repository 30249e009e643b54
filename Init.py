# Contacts workbench: application (non-GUI) initialisation. No GUI import here:
# FreeCAD runs this in freecadcmd too. The workbench's code is in contactwb/.
import FreeCAD

FreeCAD.__unit_test__ += ["contactwb.freecad_tests"]

# Contacts objects of documents saved without the workbench get their proxies back.
try:
    from contactwb.objects import recovery
    recovery.watch_restores()
except Exception as error:  # a broken install must not stop FreeCAD
    FreeCAD.Console.PrintError(f"Contacts: {error}\n")
