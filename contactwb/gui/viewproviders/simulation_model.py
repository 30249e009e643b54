"""View provider of a SimulationModel: draws the model's mesh from its
properties (contactwb.gui.overlay.simulation_model; nothing is meshed here)
with a legend naming the model, its size, its distance to the original and
the switched-off partitions.

Saved files name ViewProviderSimulationModel (also by its old module,
contactwb.gui.simulation_model_view): a permanent name."""
import numpy
from pivy import coin

import contactwb
from contactwb.gui.overlay.coin_nodes import legend_node
from contactwb.gui.overlay.simulation_model import STRIPE_COLOUR, model_nodes
from contactwb.gui.viewproviders.base import OneDisplayMode, ViewProvider


class ViewProviderSimulationModel(OneDisplayMode, ViewProvider):
    """Draws a SimulationModel's mesh from its properties (nothing is meshed here)."""
    DISPLAY_MODE = "Mesh"

    def attach(self, vobj):
        super().attach(vobj)
        self.switch = coin.SoSwitch()
        self.switch.setName("SimulationModelSwitch")
        vobj.RootNode.addChild(self.switch)
        self.root = None
        self.counts = {"active": 0, "switched_off": 0}
        self.rebuild()

    def getIcon(self):
        return contactwb.icon_path("Contacts_ShowSimulationModel")

    def onChanged(self, vobj, prop):
        if prop == "Visibility":
            self._update_switch()

    def _update_switch(self):
        obj = getattr(self, "Object", None)
        shown = obj is not None and obj.ViewObject.Visibility
        self.switch.whichChild.setValue(coin.SO_SWITCH_ALL if shown else coin.SO_SWITCH_NONE)

    def updateData(self, obj, prop):
        if prop in ("MeshTriangles", "SwitchedOff") and hasattr(self, "switch"):
            self.rebuild()

    def rebuild(self):
        obj = self.Object
        self.switch.removeAllChildren()
        self.root = None
        if not obj.MeshTriangles or not obj.MeshPoints:
            return
        points = numpy.array([(p.x, p.y, p.z) for p in obj.MeshPoints], dtype=float)
        triangles = numpy.array(obj.MeshTriangles, dtype=numpy.int32).reshape(-1, 3)
        partitions = numpy.array(obj.MeshPartitions, dtype=numpy.int32)
        if len(partitions) != len(triangles):  # a property being written: wait for the last one
            return
        self.root, self.counts = model_nodes(points, triangles, partitions, set(obj.SwitchedOff))
        distance = f", Hausdorff {obj.Hausdorff.Value:.3f} mm" if obj.Model == "Collision" else \
            f", deviation {obj.Hausdorff.Value:.3f} mm"
        entries = [(f"{obj.Label}: {obj.Triangles} triangles, {obj.Partitions} partitions{distance}",
                    (0.1, 0.1, 0.1))]
        if obj.Simplified and obj.RemovedFaces:
            entries.append((f"{len(obj.RemovedFaces)} faces of small features removed", (0.1, 0.1, 0.1)))
        if obj.Message:
            entries.append((obj.Message, (0.7, 0.1, 0.1)))
        if obj.SwitchedOff:
            entries.append((f"switched off (striped): partitions {', '.join(map(str, obj.SwitchedOff))}",
                            STRIPE_COLOUR))
        self.root.addChild(legend_node(entries, "SimulationModelLegend"))
        self.switch.addChild(self.root)
        self._update_switch()

    def claimChildren(self):
        return []
