"""Contacts_AnnotateContact: the designer's intent and fit on the contacts
selected (tree, contact table or view), one undoable step."""
import FreeCAD
import FreeCADGui

import contactwb
from contactwb.document.identify import is_contact
from contactwb.gui.dialogs import show_error


def selected_contacts():
    doc = FreeCAD.ActiveDocument
    if doc is None:
        return []
    return [o for o in FreeCADGui.Selection.getSelection(doc.Name) if is_contact(o)]


class Contacts_AnnotateContact:
    """Sets the intent (clearance, transition, interference, bonded, ignored)
    and ISO 286 fit of the selected contacts; joints derived again."""

    def GetResources(self):
        return {
            "Pixmap": contactwb.icon_path("Contacts_AnnotateContact"),
            "MenuText": "Annotate contact...",
            "ToolTip": "Say what the selected contacts are meant to be: a clearance, transition or "
                       "interference fit (with an ISO 286 code such as H7/p6), bonded, or ignored; press "
                       "fits and bonds make their pairs rigid in the joints",
        }

    def IsActive(self):
        return bool(selected_contacts()) and not FreeCADGui.Control.activeDialog()

    def Activated(self):
        from contactwb import core
        from contactwb.gui.panels.annotate_dialog import AnnotateDialog
        from contactwb.make import annotate_contacts
        contacts = selected_contacts()
        dialog = AnnotateDialog(contacts, FreeCADGui.getMainWindow())
        if not dialog.exec_():
            return
        intent, fit = dialog.values()
        try:
            annotate_contacts(contacts, intent, fit)
        except core.ContactsError as error:
            show_error(str(error))
            return
        FreeCAD.Console.PrintMessage(f"Contacts: {len(contacts)} contact(s) annotated {intent}"
                                     f"{' ' + fit if fit else ''}\n")


COMMANDS = {"Contacts_AnnotateContact": Contacts_AnnotateContact}
