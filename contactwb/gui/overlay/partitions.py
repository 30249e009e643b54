"""Show partitions: every maximal partition (adjacent faces on one surface,
contactcore.partition_brep) of the selected bodies coloured by surface type,
as in the paper's Fig. 3c, with a legend in the view. The colours are the
contact types' families (contactwb.gui.palette: planes in the planar fit's
orange, cylinders in the cylindrical joint's blue, ...), and two adjacent
partitions of one type get different shades. The legend sits below the
contacts' legends (legend_stack). Drawn in the 3D view's scene graph, beside
the document (nothing is saved); the command toggles it."""
import FreeCAD
import FreeCADGui
import numpy
from pivy import coin

from contactwb.gui.overlay.coin_nodes import legend_node, material, polygon_offset
from contactwb.gui import palette
from contactwb.gui.overlay import legend_stack
from contactwb.gui.overlay.colours import legend_colours
from contactwb.gui.overlay.faces import pushed_out

SURFACE_KINDS = ("Plane", "Cylinder", "Cone", "Sphere", "Torus", "Other")
NODE_NAME = "ContactsPartitions"
LEGEND_KEY = "partitions"


def _adjacent_partitions(faces, partition_of_face):
    """{partition: {partitions sharing an edge with it}} of one body."""
    faces_of_edge = {}
    for index, face in enumerate(faces, start=1):
        for edge in face.Edges:
            faces_of_edge.setdefault(edge.hashCode(), set()).add(index)
    neighbours = {}
    for sharing in faces_of_edge.values():
        partitions = {partition_of_face[f] for f in sharing if f in partition_of_face}
        for p in partitions:
            neighbours.setdefault(p, set()).update(partitions - {p})
    return neighbours


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
        self.counts = {kind: 0 for kind in SURFACE_KINDS}
        self.bodies = [b.name for b in bodies]
        self.type_colours = legend_colours()
        self.shades = []          # per body: [(kind, shade index)] per partition
        self.adjacent_same = []   # (body, partition, partition) of one kind sharing an edge
        meshes = {}               # (kind, shade) -> [(points, triangles)]
        for body in bodies:
            partitions = core.contactcore.partition_brep(body.shape.exportBrepToString()).partitions
            box = body.shape.BoundBox
            deflection = max((box.XLength + box.YLength + box.ZLength) / 300.0 * 0.5, 1e-4)
            faces = body.shape.Faces
            kinds = [surface_kind(p) if surface_kind(p) in SURFACE_KINDS else "Other" for p in partitions]
            partition_of_face = {f: k for k, p in enumerate(partitions) for f in p.faces}
            touching = _adjacent_partitions(faces, partition_of_face)
            same = {k: {n for n in touching.get(k, ()) if kinds[n] == kinds[k]} for k in range(len(partitions))}
            shades = palette.greedy_shades(len(partitions), same)
            self.shades.append(list(zip(kinds, shades)))
            self.adjacent_same += [(body.name, k, n) for k in same for n in same[k] if k < n]
            for k, partition in enumerate(partitions):
                self.counts[kinds[k]] += 1
                for index in partition.faces:
                    points, triangles = faces[index - 1].tessellate(deflection)
                    if triangles:
                        points = numpy.array([(p.x, p.y, p.z) for p in points], dtype=float)
                        triangles = numpy.array(triangles, dtype=numpy.int64).reshape(-1, 3)
                        meshes.setdefault((kinds[k], shades[k]), []).append(
                            (pushed_out(points, triangles, deflection), triangles))
        for (kind, shade), parts in sorted(meshes.items()):
            layer = coin.SoSeparator()
            layer.setName(f"Partitions_{kind}_{shade}")
            layer.addChild(material(self.colour(kind, shade)))
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
            [(f"{kind}: {count} partition{'s' if count > 1 else ''}"
              + (f" ({palette.SURFACE_FAMILY[kind]} colours)" if kind in palette.SURFACE_FAMILY else ""),
              self.colour(kind, 0))
             for kind, count in self.counts.items() if count], "PartitionsLegend", stack=(doc.Name, LEGEND_KEY))
        self.root.addChild(self.legend)

    def colour(self, kind, shade):
        """(r, g, b) of a partition: its contact type's family, this shade."""
        return palette.surface_colour(kind, shade, self.type_colours)


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
        legend_stack.unregister(doc.Name, LEGEND_KEY)
