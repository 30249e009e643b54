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
            _show_error(str(error))
            return
        finally:
            progress.close()
        doc.commitTransaction()
        doc.recompute()
        FreeCAD.Console.PrintMessage(
            f"Contacts: {len(group.Group)} contacts between {group.BodyCount} bodies "
            f"({', '.join(group.Summary) or 'none'})\n")


def _show_error(message):
    """An error in the Console and in a message box."""
    from PySide2 import QtWidgets
    FreeCAD.Console.PrintError(f"Contacts: {message}\n")
    QtWidgets.QMessageBox.warning(FreeCADGui.getMainWindow(), "Contacts", message)


def _analysis_to_export(doc):
    """The selected ContactAnalysis (or the one holding a selected contact),
    else the document's only one; None when that is ambiguous."""
    from contactwb import export
    from contactwb.objects.contact_objects import is_contact_analysis
    chosen = []
    for obj in FreeCADGui.Selection.getSelection(doc.Name):
        for candidate in [obj] + list(obj.InList):
            if is_contact_analysis(candidate) and candidate not in chosen:
                chosen.append(candidate)
    if not chosen:
        chosen = export.analyses(doc)
    return chosen[0] if len(chosen) == 1 else None


class Contacts_ExportContacts:
    """Writes a contact analysis to a JSON or CSV file."""

    FILTERS = {"JSON (*.json)": ".json", "CSV (*.csv)": ".csv"}

    def GetResources(self):
        return {
            "Pixmap": contactwb.icon_path("Contacts_ExportContacts"),
            "MenuText": "Export contacts...",
            "ToolTip": "Write the contacts of the selected analysis (or of the only one) to a "
                       "JSON or CSV file",
        }

    def IsActive(self):
        from contactwb import export
        return bool(export.analyses(FreeCAD.ActiveDocument))

    def Activated(self):
        import os
        from PySide2 import QtWidgets
        from contactwb import export
        doc = FreeCAD.ActiveDocument
        group = _analysis_to_export(doc)
        if group is None:
            _show_error("Select the contact analysis to export (the document holds several).")
            return
        folder = os.path.dirname(doc.FileName) if doc.FileName else os.path.expanduser("~")
        suggestion = os.path.join(folder, f"{doc.Label}_{group.Label}.json")
        path, chosen_filter = QtWidgets.QFileDialog.getSaveFileName(
            FreeCADGui.getMainWindow(), "Export contacts", suggestion, ";;".join(self.FILTERS))
        if not path:
            return
        if os.path.splitext(path)[1].lower() not in export.FORMATS:
            path += self.FILTERS.get(chosen_filter, ".json")
        try:
            count = export.export_contacts(group, path)
        except (OSError, ValueError) as error:
            _show_error(f"cannot export '{group.Label}': {error}")
            return
        noun = "contact" if count == 1 else "contacts"
        FreeCAD.Console.PrintMessage(f"Contacts: {count} {noun} of '{group.Label}' written to {path}\n")


COMMANDS = {
    "Contacts_FindContacts": Contacts_FindContacts,
    "Contacts_ExportContacts": Contacts_ExportContacts,
}


def register():
    """Adds the commands to FreeCAD; returns their names in toolbar order."""
    for name, command in COMMANDS.items():
        FreeCADGui.addCommand(name, command())
    return list(COMMANDS)
