"""Contacts_HapticTrial: the haptic trial panel on the selected part."""
import FreeCAD
import FreeCADGui

import contactwb
from contactwb import core
from contactwb.gui.dialogs import show_error
from contactwb.gui.panels import haptic_panel

TITLE = "Haptic trial"


def selected_part():
    """The one selected object, with the path it was picked by (a part inside an
    App::Part or through a link): (object, subname) or None."""
    selection = FreeCADGui.Selection.getSelectionEx("", 0)  # unresolved: top-level object and path
    if len(selection) != 1:
        return None
    entry = selection[0]
    subnames = [s for s in entry.SubElementNames] or [""]
    if len(subnames) != 1:
        return None
    return entry.Object, subnames[0]


class Contacts_HapticTrial:
    """Opens the haptic trial panel on the selected part."""

    def GetResources(self):
        return {
            "Pixmap": contactwb.icon_path("Contacts_HapticTrial"),
            "MenuText": "Haptic trial",
            "ToolTip": "Grab the selected part with a 3D mouse or the simulated hand and insert or extract it: "
                       "the part follows the joints its contacts allow and stops at collisions",
        }

    def IsActive(self):
        return FreeCAD.ActiveDocument is not None and FreeCADGui.Control.activeDialog() is False

    def Activated(self):
        picked = selected_part()
        if picked is None:
            show_error("Select one part (a solid) to move.", TITLE)
            return
        try:
            panel = haptic_panel.HapticTrialPanel(FreeCAD.ActiveDocument, picked)
        except core.ContactsError as error:
            show_error(str(error), TITLE)
            return
        FreeCADGui.Control.showDialog(panel)


COMMANDS = {"Contacts_HapticTrial": Contacts_HapticTrial}
