"""Show partitions: every maximal partition (adjacent faces on one surface,
contactcore.partition_brep) of the selected bodies coloured by surface type,
as in the paper's Fig. 3c, with a legend in the view. Drawn in the 3D view's
scene graph, beside the document (nothing is saved); the command toggles it."""
import FreeCAD
import FreeCADGui
import numpy
from pivy import coin

from contactwb.gui.overlay.coin_nodes import legend_node, material, polygon_offset
from contactwb.gui.overlay.colours import rgb
from contactwb.gui.overlay.faces import pushed_out

SURFACE_COLOURS = {  # Fig. 3c's idea: one colour per surface type
    "Plane": "#4f81bd",
    "Cylinder": "#f2a33a",
    "Cone": "#8e44ad",
    "Sphere": "#e0457b",
    "Torus": "#2ca58d",
    "Other": "#9a9a9a",
}
NODE_NAME = "ContactsPartitions"


def surface_kind(partition):
    return getattr(partition.params.kind, "name", str(partition.params.kind).rpartition(".")[2])


class PartitionsView:
    """The drawing of one document's partitions (one per document)."""

    def __init__(self, doc, bodies):
        from contactwb import core
        self.doc_name = doc.Name
        self.root = coin.SoSeparator()
        self.root.setName(NODE_NAME)
        pick = coin.SoPickStyle()
        pick.style.setValue(coin.SoPickStyle.UNPICKABLE)
        hints = coin.SoShapeHints()
        hints.vertexOrdering.setValue(coin.SoShapeHints.COUNTERCLOCKWISE)
        hints.shapeType.setValue(coin.SoShapeHints.UNKNOWN_SHAPE_TYPE)
        for node in (pick, hints, polygon_offset(0.0, -1.0)):
            self.root.addChild(node)
        self.counts = {kind: 0 for kind in SURFACE_COLOURS}
        self.bodies = [b.name for b in bodies]
        meshes = {kind: [] for kind in SURFACE_COLOURS}
        for body in bodies:
            partitions = core.contactcore.partition_brep(body.shape.exportBrepToString())
            box = body.shape.BoundBox
            deflection = max((box.XLength + box.YLength + box.ZLength) / 300.0 * 0.5, 1e-4)
            faces = body.shape.Faces
            for partition in partitions.partitions:
                kind = surface_kind(partition)
                kind = kind if kind in SURFACE_COLOURS else "Other"
                self.counts[kind] += 1
                for index in partition.faces:
                    points, triangles = faces[index - 1].tessellate(deflection)
                    if triangles:
                        points = numpy.array([(p.x, p.y, p.z) for p in points], dtype=float)
                        triangles = numpy.array(triangles, dtype=numpy.int64).reshape(-1, 3)
                        meshes[kind].append((pushed_out(points, triangles, deflection),
                                             triangles))
        for kind, parts in meshes.items():
            if not parts:
                continue
            layer = coin.SoSeparator()
            layer.setName(f"Partitions_{kind}")
            layer.addChild(material(rgb(SURFACE_COLOURS[kind])))
            coordinates = coin.SoCoordinate3()
            offset, rows = 0, []
            all_points = []
            for points, triangles in parts:
                row = numpy.full((len(triangles), 4), -1, dtype=numpy.int32)
                row[:, :3] = triangles + offset
                rows.append(row)
                all_points.append(points)
                offset += len(points)
            stacked = numpy.vstack(all_points)
            coordinates.point.setValues(0, len(stacked), stacked)
            indices = numpy.vstack(rows).ravel()
            face_set = coin.SoIndexedFaceSet()
            face_set.coordIndex.setValues(0, len(indices), indices)
            layer.addChild(coordinates)
            layer.addChild(face_set)
            self.root.addChild(layer)
        self.legend = legend_node(
            [(f"{kind}: {count} partition{'s' if count > 1 else ''}", rgb(SURFACE_COLOURS[kind]))
             for kind, count in self.counts.items() if count], "PartitionsLegend")
        self.root.addChild(self.legend)


_views = {}  # document name -> (PartitionsView, the scene graph it is in)


def is_shown(doc):
    return doc is not None and doc.Name in _views


def show(doc, entries):
    """Draws the partitions of the bodies the selection entries pick (every
    visible body when there is none); returns the PartitionsView."""
    from contactwb.document import bodies as document_bodies
    hide(doc)
    everything = document_bodies.document_bodies(doc)
    chosen = document_bodies.bodies_of_selection(everything, entries) if entries else everything
    view = PartitionsView(doc, chosen)
    graph = FreeCADGui.getDocument(doc.Name).activeView().getSceneGraph()
    graph.addChild(view.root)
    _views[doc.Name] = (view, graph)
    FreeCAD.Console.PrintMessage(
        f"Contacts: partitions of {len(chosen)} bodies: "
        + ", ".join(f"{count} {kind.lower()}" for kind, count in view.counts.items() if count) + "\n")
    return view


def hide(doc):
    view, graph = _views.pop(doc.Name, (None, None))
    if view is not None:
        graph.removeChild(view.root)
