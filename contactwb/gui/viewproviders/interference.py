"""View providers of the interferences (two bodies' overlapping material):
ViewProviderInterference colours an Interference's solid (its Shape, drawn by
FreeCAD's Part view provider) red, as interference checkers show overlaps (a
Python Part feature's view provider attaches only once it has a Python
proxy: without one, nothing is drawn); ViewProviderInterferenceGroup shows
the analysis' Interferences group with its children in the tree.

Saved files name ViewProviderInterference and ViewProviderInterferenceGroup by
this module: permanent names."""
import contactwb
from contactwb.gui.palette import INTERFERENCE_COLOUR, rgb
from contactwb.gui.viewproviders.base import ViewProvider



class ViewProviderInterference(ViewProvider):
    """The overlapping solid, red and opaque."""

    def __init__(self, vobj):
        super().__init__(vobj)
        vobj.ShapeColor = rgb(INTERFERENCE_COLOUR)
        vobj.LineColor = rgb(INTERFERENCE_COLOUR)
        vobj.PointColor = rgb(INTERFERENCE_COLOUR)
        vobj.Transparency = 0

    def getIcon(self):
        return contactwb.icon_path("Contacts_Interference")

    def getDefaultDisplayMode(self):
        return "Flat Lines"


class ViewProviderInterferenceGroup(ViewProvider):
    """The Interferences group: its Interference children in the tree (hiding
    the group hides their solids, as any group)."""

    def getIcon(self):
        return contactwb.icon_path("Contacts_Interference")

    def claimChildren(self):
        return self.Object.Group
