"""View provider of an Interference (two bodies' overlapping material): FreeCAD's
Part view provider draws the overlapping solid (the object's Shape); this one
colours it red, as interference checkers show overlaps. (A Python Part
feature's view provider attaches only once it has a Python proxy: without one,
nothing is drawn.)

Saved files name ViewProviderInterference by this module: a permanent name."""
from contactwb.gui.viewproviders.base import ViewProvider

INTERFERENCE_COLOUR = (0.9, 0.05, 0.05)


class ViewProviderInterference(ViewProvider):
    """The overlapping solid, red and opaque."""

    def __init__(self, vobj):
        super().__init__(vobj)
        vobj.ShapeColor = INTERFERENCE_COLOUR
        vobj.LineColor = INTERFERENCE_COLOUR
        vobj.PointColor = INTERFERENCE_COLOUR
        vobj.Transparency = 0

    def getDefaultDisplayMode(self):
        return "Flat Lines"
