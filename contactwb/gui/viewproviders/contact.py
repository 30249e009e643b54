"""View provider of one Contact: drawn by its group's overlay, its
Visibility switches its part of that drawing; its icon is its type's.

Saved files name ViewProviderContact (also by its old module,
contactwb.gui.view_providers): a permanent name."""
import os

from pivy import coin

import contactwb
from contactwb.gui import actions
from contactwb.gui.viewproviders.base import OneDisplayMode, ViewProvider, add_action


def contact_icon_path(kind):
    path = contactwb.icon_path(f"Contacts_{kind}")
    return path if os.path.isfile(path) else contactwb.icon_path("Contacts_FindContacts")


def overlays_of(contact):
    """The overlays drawing a Contact (its groups')."""
    for parent in contact.InList:
        proxy = getattr(getattr(parent, "ViewObject", None), "Proxy", None)
        overlay = getattr(proxy, "overlay", None)
        if overlay is not None:
            yield overlay


def _annotate(contact):
    """The context menu's Annotate: the command on the selected contacts (this
    one selected if it is not)."""
    import FreeCADGui
    if contact not in FreeCADGui.Selection.getSelection(contact.Document.Name):
        FreeCADGui.Selection.clearSelection()
        FreeCADGui.Selection.addSelection(contact)
    FreeCADGui.runCommand("Contacts_AnnotateContact")


class ViewProviderContact(OneDisplayMode, ViewProvider):
    """A contact: drawn by its group's overlay; its Visibility switches its
    part of that drawing."""
    DISPLAY_MODE = "Overlay"

    def attach(self, vobj):
        super().attach(vobj)
        # An empty display mode: without one the tree greys the contact out
        # as if it were hidden.
        vobj.addDisplayMode(coin.SoGroup(), "Overlay")

    def getIcon(self):
        return contact_icon_path(getattr(getattr(self, "Object", None), "ContactType", ""))

    def doubleClicked(self, vobj):
        actions.select_contact_faces(vobj.Object)
        return True

    def setupContextMenu(self, vobj, menu):
        contact = vobj.Object
        add_action(menu, "Select faces", lambda: actions.select_contact_faces(contact))
        add_action(menu, "Zoom to contact", lambda: actions.zoom_to(contact))
        add_action(menu, "Isolate with its parts", lambda: actions.run_isolate(contact))
        add_action(menu, "Annotate (intent, fit)...", lambda: _annotate(contact))
        add_action(menu, "Export contacts...", lambda: actions.export_analysis(actions.analysis_of(contact)))

    def onChanged(self, vobj, prop):
        if prop != "Visibility":
            return
        for overlay in overlays_of(vobj.Object):
            overlay.set_visible(vobj.Object.Name, vobj.Visibility)
