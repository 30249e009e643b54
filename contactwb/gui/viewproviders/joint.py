"""View provider of a Joint: its axis glyphs (contactwb.gui.overlay.joint_glyphs)
over the bodies; double-click selects the faces of its contacts.

Saved files name ViewProviderJoint (also by its old module,
contactwb.gui.joint_view): a permanent name."""
import FreeCAD
import FreeCADGui
from pivy import coin

import contactwb
from contactwb.gui.overlay.joint_glyphs import joint_glyphs
from contactwb.gui.viewproviders.base import OneDisplayMode, ViewProvider


class ViewProviderJoint(OneDisplayMode, ViewProvider):
    """Draws its Joint's glyphs (over the bodies: an annotation)."""
    DISPLAY_MODE = "Glyphs"

    def attach(self, vobj):
        super().attach(vobj)
        self.glyphs = coin.SoAnnotation()
        self.glyphs.setName("JointGlyphs")
        self.axes = self.arrows = 0
        vobj.addDisplayMode(self.glyphs, "Glyphs")

    def updateData(self, obj, prop):
        if prop in ("AxisPoints", "AxisDirections", "Translations", "Centre", "GlyphLength"):
            self.redraw()

    def redraw(self):
        glyphs = getattr(self, "glyphs", None)
        if glyphs is None:
            return
        glyphs.removeAllChildren()
        try:
            node, self.axes, self.arrows = joint_glyphs(self.Object)
        except Exception as error:  # drawing only
            FreeCAD.Console.PrintWarning(f"Contacts: cannot draw joint '{self.Object.Label}': {error}\n")
            return
        glyphs.addChild(node)

    def getIcon(self):
        return contactwb.icon_path("Contacts_DeriveJoints")

    def doubleClicked(self, vobj):
        """Selects the faces of the joint's contacts."""
        FreeCADGui.Selection.clearSelection()
        for contact in vobj.Object.Contacts:
            for links in (contact.FacesA, contact.FacesB):
                for root, subnames in links:
                    for subname in subnames:
                        FreeCADGui.Selection.addSelection(root.Document.Name, root.Name, subname)
        return True
