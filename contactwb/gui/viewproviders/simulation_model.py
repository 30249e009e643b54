"""Contacts_ShowSimulationModel and the view provider of a SimulationModel.

The model's triangles are drawn with one colour per partition (a fixed
palette, so a partition keeps its colour between the view and the collision
model), the mesh edges in a thin dark line over them, and the switched-off
partitions (the joint being followed, or the user's) in light grey with red
stripes: the paper's Fig. 4c. A legend names the model, its size, its
distance to the original and the switched-off partitions.

Saved files name ViewProviderSimulationModel: a permanent name."""
import colorsys

import FreeCAD
import FreeCADGui
import numpy
from pivy import coin

import contactwb
from contactwb.gui.view_providers import _ViewProvider, _polygon_offset, legend_node

SWITCHED_OFF_COLOUR = (0.85, 0.85, 0.85)
STRIPE_COLOUR = (0.85, 0.1, 0.1)
EDGE_COLOUR = (0.15, 0.15, 0.15)


def partition_colour(partition):
    """A colour of its own for each partition id: hues spread by the golden ratio, saturated, never
    grey (the switched-off colour)."""
    hue = (partition * 0.618033988749895) % 1.0
    value = 0.95 if partition % 2 == 0 else 0.75
    return colorsys.hsv_to_rgb(hue, 0.75, value)


def _red_stripes():
    """Nodes striping what follows in red over its own colour (a two-texel texture repeated along
    (1, 1, 1), 1 mm period: independent of the triangles)."""
    complexity = coin.SoComplexity()
    complexity.textureQuality.setValue(0.1)
    texture = coin.SoTexture2()
    texture.image.setValue(coin.SbVec2s(2, 1), 3, bytes([255, 255, 255, 217, 26, 26]))
    texture.model.setValue(coin.SoTexture2.MODULATE)
    texture.wrapS.setValue(coin.SoTexture2.REPEAT)
    coordinates = coin.SoTextureCoordinatePlane()
    step = 1.0 / (1.0 * 3 ** 0.5)
    coordinates.directionS.setValue(step, step, step)
    coordinates.directionT.setValue(0, 0, 0)
    return [complexity, texture, coordinates]


def model_nodes(points, triangles, partitions, switched_off, name="SimulationModel"):
    """(root, counts): Coin nodes drawing a tagged mesh. `points` (n, 3), `triangles` (m, 3),
    `partitions` (m,) arrays; the triangles of `switched_off` partitions go to their own striped layer.
    counts: {"active": triangles, "switched_off": triangles}."""
    root = coin.SoSeparator()
    root.setName(name)
    hints = coin.SoShapeHints()
    hints.vertexOrdering.setValue(coin.SoShapeHints.COUNTERCLOCKWISE)
    hints.shapeType.setValue(coin.SoShapeHints.SOLID)
    coordinates = coin.SoCoordinate3()
    coordinates.point.setValues(0, len(points), points.tolist())
    root.addChild(hints)
    root.addChild(coordinates)
    off = numpy.isin(partitions, sorted(switched_off)) if len(switched_off) else numpy.zeros(len(partitions), bool)
    counts = {"active": int((~off).sum()), "switched_off": int(off.sum())}

    def face_set(rows):
        indices = numpy.full((len(rows), 4), -1, dtype=numpy.int32)
        indices[:, :3] = rows
        node = coin.SoIndexedFaceSet()
        flat = indices.ravel().tolist()
        node.coordIndex.setValues(0, len(flat), flat)
        return node

    active = coin.SoSeparator()
    active.setName("Partitions")
    if counts["active"]:
        count = int(partitions.max()) + 1 if len(partitions) else 0
        material = coin.SoMaterial()
        colours = [partition_colour(p) for p in range(count)]
        material.diffuseColor.setValues(0, count, colours)
        material.ambientColor.setValue(0.2, 0.2, 0.2)
        binding = coin.SoMaterialBinding()
        binding.value.setValue(coin.SoMaterialBinding.PER_FACE_INDEXED)
        faces = face_set(triangles[~off])
        chosen = partitions[~off].astype(numpy.int32).tolist()
        faces.materialIndex.setValues(0, len(chosen), chosen)
        for node in (material, binding, faces):
            active.addChild(node)
    root.addChild(active)
    layer = coin.SoSeparator()
    layer.setName("SwitchedOff")
    if counts["switched_off"]:
        material = coin.SoMaterial()
        material.diffuseColor.setValue(*SWITCHED_OFF_COLOUR)
        material.emissiveColor.setValue(0.25, 0.25, 0.25)
        for node in [material, *_red_stripes(), face_set(triangles[off])]:
            layer.addChild(node)
    root.addChild(layer)
    # The mesh's edges: the triangles again, drawn as lines (polygons in line mode, so a polygon
    # offset applies to them), pulled further towards the viewer than the faces.
    edges = coin.SoSeparator()
    edges.setName("Edges")
    light = coin.SoLightModel()
    light.model.setValue(coin.SoLightModel.BASE_COLOR)
    colour = coin.SoBaseColor()
    colour.rgb.setValue(*EDGE_COLOUR)
    style = coin.SoDrawStyle()
    style.style.setValue(coin.SoDrawStyle.LINES)
    style.lineWidth.setValue(1)
    line_offset = _polygon_offset(-2.0, -4.0)
    line_offset.styles.setValue(coin.SoPolygonOffset.LINES)
    for node in (light, colour, style, line_offset, face_set(triangles)):
        edges.addChild(node)
    # The model is drawn where its body is (the body stays shown, and in any analysis): its faces
    # pulled towards the viewer win over the body's coincident ones.
    root.insertChild(_polygon_offset(-1.0, -2.0), 2)
    root.addChild(edges)
    return root, counts


class ViewProviderSimulationModel(_ViewProvider):
    """Draws a SimulationModel's mesh from its properties (nothing is meshed here)."""

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

    def getDisplayModes(self, vobj):
        return ["Mesh"]

    def getDefaultDisplayMode(self):
        return "Mesh"

    def setDisplayMode(self, mode):
        return mode

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


def _selected():
    """(body, followed, partitions switched off) from the selection: the first selected part is modelled
    (its selected faces' partitions switched off), a second one is the part of the joint being followed."""
    selection = FreeCADGui.Selection.getSelectionEx("", 0)  # unresolved: top-level object and path
    entries = []
    for item in selection:
        subnames = list(item.SubElementNames) or [""]
        entries.append((item.Object, subnames))
    if not entries:
        return None, None, []
    from contactwb.bodies import _object_path
    root, subnames = entries[0]
    path = _object_path(subnames[0])
    faces = [s.rpartition(".")[2] for s in subnames if s.rpartition(".")[2].startswith("Face")]
    followed = None
    if len(entries) > 1:
        other_root, other_subnames = entries[1]
        followed = (other_root, _object_path(other_subnames[0]))
    return (root, path), followed, faces


class Contacts_ShowSimulationModel:
    """Adds the collision model of the selected part (partitions coloured, those of the followed joint
    switched off) as a document object."""

    def GetResources(self):
        return {
            "Pixmap": contactwb.icon_path("Contacts_ShowSimulationModel"),
            "MenuText": "Show simulation model",
            "ToolTip": "Show the collision model of the selected part (its Model property: the view model), "
                       "each partition in its own colour. Select a second part to switch off the partitions "
                       "of the joint between them (striped), or faces of the part to switch off theirs",
        }

    def IsActive(self):
        return FreeCAD.ActiveDocument is not None and bool(FreeCADGui.Selection.getSelection())

    def Activated(self):
        from contactwb import core
        from contactwb.make import make_simulation_model
        body, followed, faces = _selected()
        if body is None:
            return
        doc = FreeCAD.ActiveDocument
        doc.openTransaction("Show simulation model")
        try:
            switched = []
            if faces:
                switched = _partitions_of_faces(body, faces)
            obj = make_simulation_model(doc, body, "Collision", followed=followed, switched_off=switched)
        except core.ContactsError as error:
            doc.abortTransaction()
            from contactwb.gui.commands import _show_error
            _show_error(str(error))
            return
        doc.commitTransaction()
        FreeCADGui.Selection.clearSelection()
        FreeCAD.Console.PrintMessage(f"Contacts: {obj.Label}: {obj.Triangles} triangles, {obj.Partitions} "
                                     f"partitions, switched off {list(obj.SwitchedOff) or 'none'}\n")
        return obj


def _partitions_of_faces(body, faces):
    """Partition ids of the body's faces named "FaceN"."""
    from contactwb import core
    from contactwb.make.make_simulation_model import _shape_of
    root, path = body
    shape = _shape_of((root, [path]))
    partitions = core.contactcore.partition_brep(shape.exportBrepToString())
    wanted = {int(f[4:]) for f in faces}
    return sorted({p.id for p in partitions.partitions if wanted & set(p.faces)})


COMMANDS = {"Contacts_ShowSimulationModel": Contacts_ShowSimulationModel}


def register():
    """Adds the command to FreeCAD; returns its name."""
    for name, command in COMMANDS.items():
        FreeCADGui.addCommand(name, command())
    return list(COMMANDS)
