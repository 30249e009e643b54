"""A simulation model's mesh drawn in Coin: one colour per partition (a fixed
palette, so a partition keeps its colour between the view and the collision
model), the mesh edges in a thin dark line over them, and the switched-off
partitions in light grey with red stripes (the paper's Fig. 4c)."""
import colorsys

import numpy
from pivy import coin

from contactwb.gui.overlay.coin_nodes import polygon_offset

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
    line_offset = polygon_offset(-2.0, -4.0)
    line_offset.styles.setValue(coin.SoPolygonOffset.LINES)
    for node in (light, colour, style, line_offset, face_set(triangles)):
        edges.addChild(node)
    # The model is drawn where its body is (the body stays shown, and in any analysis): its faces
    # pulled towards the viewer win over the body's coincident ones.
    root.insertChild(polygon_offset(-1.0, -2.0), 2)
    root.addChild(edges)
    return root, counts
