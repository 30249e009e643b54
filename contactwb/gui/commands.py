"""Workbench commands (one class each, FreeCAD Assembly style)."""
import FreeCAD
import FreeCADGui

import contactwb


class ProgressDialog:
    """A cancellable progress dialog fed by the core's progress callback."""

    def __init__(self, title):
        from PySide2 import QtCore, QtWidgets
        self._qt = QtWidgets
        self.dialog = QtWidgets.QProgressDialog(title, "Cancel", 0, 1000, FreeCADGui.getMainWindow())
        self.dialog.setWindowModality(QtCore.Qt.WindowModal)
        self.dialog.setMinimumDuration(300)

    def __call__(self, stage, fraction):
        self.dialog.setLabelText(f"{stage.capitalize()}...")
        self.dialog.setValue(int(fraction * 1000))
        self._qt.QApplication.processEvents()
        return not self.dialog.wasCanceled()

    def close(self):
        self.dialog.reset()


class Contacts_FindContacts:
    """Finds the contacts of the selected objects, or of every visible solid."""

    def GetResources(self):
        return {
            "Pixmap": contactwb.icon_path("Contacts_FindContacts"),
            "MenuText": "Find contacts",
            "ToolTip": "Find the functional contacts (planar fits, cylindrical joints, cones, spheres, "
                       "balls in bores and grooves) between the selected parts, or all visible parts",
        }

    def IsActive(self):
        return FreeCAD.ActiveDocument is not None

    def Activated(self):
        from contactwb import core
        from contactwb.make import make_contact_analysis
        doc = FreeCAD.ActiveDocument
        selection = FreeCADGui.Selection.getSelection(doc.Name) or None
        progress = ProgressDialog("Finding contacts")
        doc.openTransaction("Find contacts")
        try:
            group = make_contact_analysis(doc, selection, progress=progress)
        except core.Cancelled:
            doc.abortTransaction()
            FreeCAD.Console.PrintWarning("Contacts: cancelled\n")
            return
        except (core.ContactsError, ValueError) as error:
            doc.abortTransaction()
            FreeCAD.Console.PrintError(f"Contacts: {error}\n")
            from PySide2 import QtWidgets
            QtWidgets.QMessageBox.warning(FreeCADGui.getMainWindow(), "Contacts", str(error))
            return
        finally:
            progress.close()
        doc.commitTransaction()
        doc.recompute()
        FreeCAD.Console.PrintMessage(
            f"Contacts: {len(group.Group)} contacts between {group.BodyCount} bodies "
            f"({', '.join(group.Summary) or 'none'})\n")


COMMANDS = {
    "Contacts_FindContacts": Contacts_FindContacts,
}


def register():
    """Adds the commands to FreeCAD; returns their names in toolbar order."""
    for name, command in COMMANDS.items():
        FreeCADGui.addCommand(name, command())
    return list(COMMANDS)
