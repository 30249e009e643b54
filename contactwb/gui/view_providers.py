"""View providers of the contact objects: icons, and double-click selects the
contact's faces in the 3D view. (They draw nothing of their own: the faces
are shown by selecting them on the bodies.)"""
import FreeCADGui

import contactwb


class _ViewProvider:
    """What both view providers share: the icon and nothing to save."""

    def __init__(self, vobj):
        vobj.Proxy = self

    def attach(self, vobj):
        self.Object = vobj.Object

    def getIcon(self):
        return contactwb.icon_path("Contacts_FindContacts")

    def dumps(self):
        return None

    def loads(self, state):
        return None


class ViewProviderContactAnalysis(_ViewProvider):
    def claimChildren(self):
        return self.Object.Group


class ViewProviderContact(_ViewProvider):
    def doubleClicked(self, vobj):
        select_contact_faces(vobj.Object)
        return True


def select_contact_faces(contact):
    """Selects both sides' faces of a contact in the 3D view."""
    FreeCADGui.Selection.clearSelection()
    for links in (contact.FacesA, contact.FacesB):
        for root, subnames in links:
            for subname in subnames:
                FreeCADGui.Selection.addSelection(root.Document.Name, root.Name, subname)


def attach(group):
    """Gives a ContactAnalysis group and its contacts their view providers."""
    ViewProviderContactAnalysis(group.ViewObject)
    for child in group.Group:
        ViewProviderContact(child.ViewObject)
