"""A Joint drawn as axis glyphs at the centre of its contacts: each rotation
axis a dark red line through its point with a ring around it, each free
translation a green arrow; a rigid joint a small grey ball."""
import math

import FreeCAD
from pivy import coin

from contactwb.gui.overlay.coin_nodes import unlit_polyline

ROTATION_COLOUR = (0.75, 0.05, 0.1)
TRANSLATION_COLOUR = (0.1, 0.6, 0.15)
RIGID_COLOUR = (0.45, 0.45, 0.45)
GLYPH_WIDTH = 4


def _line(points, colour, width=GLYPH_WIDTH):
    node = coin.SoSeparator()
    material = coin.SoMaterial()
    material.diffuseColor.setValue(*colour)
    node.addChild(material)
    return unlit_polyline(points, width, node)


def _ring(centre, axis, radius, segments=48):
    axis = FreeCAD.Vector(axis).normalize()
    helper = FreeCAD.Vector(1, 0, 0) if abs(axis.x) < 0.9 else FreeCAD.Vector(0, 1, 0)
    u = axis.cross(helper).normalize()
    v = axis.cross(u)
    return [tuple(centre + u * (radius * math.cos(2 * math.pi * k / segments))
                  + v * (radius * math.sin(2 * math.pi * k / segments))) for k in range(segments + 1)]


def _cone(tip, direction, length, colour):
    """A cone of `length` pointing along `direction`, its tip at `tip`."""
    node = coin.SoSeparator()
    material = coin.SoMaterial()
    material.diffuseColor.setValue(*colour)
    transform = coin.SoTransform()
    centre = tip - direction * (length / 2)
    transform.translation.setValue(centre.x, centre.y, centre.z)
    # SoCone points along +y
    rotation = FreeCAD.Rotation(FreeCAD.Vector(0, 1, 0), direction)
    transform.rotation.setValue(*rotation.Q)
    cone = coin.SoCone()
    cone.height.setValue(length)
    cone.bottomRadius.setValue(length * 0.35)
    for child in (material, transform, cone):
        node.addChild(child)
    return node


def joint_glyphs(joint):
    """Coin nodes drawing a Joint; (node, rotation axes, translation arrows)."""
    root = coin.SoSeparator()
    pick = coin.SoPickStyle()
    pick.style.setValue(coin.SoPickStyle.UNPICKABLE)
    root.addChild(pick)
    length = max(float(joint.GlyphLength.Value), 1e-3)
    axes = arrows = 0
    for point, direction in zip(joint.AxisPoints, joint.AxisDirections):
        if direction.Length < 1e-12:
            continue
        direction = FreeCAD.Vector(direction).normalize()
        # the axis line through the point nearest the contacts' centre
        foot = point + direction * (joint.Centre - point).dot(direction)
        ends = [tuple(foot - direction * (length / 2)), tuple(foot + direction * (length / 2))]
        root.addChild(_line(ends, ROTATION_COLOUR))
        root.addChild(_line(_ring(foot + direction * (length * 0.3), direction, length * 0.12),
                            ROTATION_COLOUR, GLYPH_WIDTH - 1))
        axes += 1
    for direction in joint.Translations:
        if direction.Length < 1e-12:
            continue
        direction = FreeCAD.Vector(direction).normalize()
        tip = joint.Centre + direction * (length * 0.45)
        root.addChild(_line([tuple(joint.Centre), tuple(tip - direction * (length * 0.08))], TRANSLATION_COLOUR))
        root.addChild(_cone(tip, direction, length * 0.1, TRANSLATION_COLOUR))
        arrows += 1
    if not axes and not arrows:  # rigid: a ball where the contacts hold
        node = coin.SoSeparator()
        material = coin.SoMaterial()
        material.diffuseColor.setValue(*RIGID_COLOUR)
        translation = coin.SoTranslation()
        translation.translation.setValue(*tuple(joint.Centre))
        sphere = coin.SoSphere()
        sphere.radius.setValue(length * 0.04)
        for child in (material, translation, sphere):
            node.addChild(child)
        root.addChild(node)
    return root, axes, arrows
