"""A Joint drawn as axis glyphs at the centre of its contacts: each rotation
axis a dark red line through its point with a ring around it, each free
translation a teal arrow (far from FreeCAD's selection green); a rigid joint
a small grey ball; its label ("J3 revolute") beside it. The glyphs are
pickable: a click selects the joint. A selected joint is drawn in FreeCAD's
selection colour, thicker."""
import math

import FreeCAD
from pivy import coin

# the one palette (teal translations, far from the selection green)
from contactwb.gui.palette import JOINT_RIGID as RIGID_COLOUR
from contactwb.gui.palette import JOINT_ROTATION as ROTATION_COLOUR
from contactwb.gui.palette import JOINT_TRANSLATION as TRANSLATION_COLOUR

GLYPH_WIDTH = 4
LABEL_SIZE = 14  # points


def _line(points, colour, width=GLYPH_WIDTH):
    node = coin.SoSeparator()
    material = coin.SoMaterial()
    material.diffuseColor.setValue(*colour)
    style = coin.SoDrawStyle()
    style.lineWidth.setValue(width)
    light = coin.SoLightModel()
    light.model.setValue(coin.SoLightModel.BASE_COLOR)
    coordinates = coin.SoCoordinate3()
    coordinates.point.setValues(0, len(points), points)
    lines = coin.SoLineSet()
    lines.numVertices.setValue(len(points))
    for child in (material, style, light, coordinates, lines):
        node.addChild(child)
    return node


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


def _label(text, position, colour):
    node = coin.SoSeparator()
    material = coin.SoMaterial()
    material.diffuseColor.setValue(*colour)
    light = coin.SoLightModel()
    light.model.setValue(coin.SoLightModel.BASE_COLOR)
    translation = coin.SoTranslation()
    translation.translation.setValue(*tuple(position))
    font = coin.SoFont()
    font.size.setValue(LABEL_SIZE)
    label = coin.SoText2()
    label.string.setValue(text)
    for child in (material, light, translation, font, label):
        node.addChild(child)
    return node


def joint_glyphs(joint, highlighted=False, highlight_colour=(0.11, 0.68, 0.11)):
    """Coin nodes drawing a Joint; (node, rotation axes, translation arrows).
    highlighted: every glyph in `highlight_colour` (FreeCAD's selection
    colour), wider."""
    root = coin.SoSeparator()
    length = max(float(joint.GlyphLength.Value), 1e-3)
    rotation_colour = highlight_colour if highlighted else ROTATION_COLOUR
    translation_colour = highlight_colour if highlighted else TRANSLATION_COLOUR
    width = GLYPH_WIDTH + (3 if highlighted else 0)
    axes = arrows = 0
    label_at = FreeCAD.Vector(joint.Centre)
    for point, direction in zip(joint.AxisPoints, joint.AxisDirections):
        if direction.Length < 1e-12:
            continue
        direction = FreeCAD.Vector(direction).normalize()
        # the axis line through the point nearest the contacts' centre
        foot = point + direction * (joint.Centre - point).dot(direction)
        ends = [tuple(foot - direction * (length / 2)), tuple(foot + direction * (length / 2))]
        root.addChild(_line(ends, rotation_colour, width))
        root.addChild(_line(_ring(foot + direction * (length * 0.3), direction, length * 0.12),
                            rotation_colour, width - 1))
        if not axes:
            label_at = foot + direction * (length / 2)
        axes += 1
    for direction in joint.Translations:
        if direction.Length < 1e-12:
            continue
        direction = FreeCAD.Vector(direction).normalize()
        tip = joint.Centre + direction * (length * 0.45)
        root.addChild(_line([tuple(joint.Centre), tuple(tip - direction * (length * 0.08))], translation_colour,
                            width))
        root.addChild(_cone(tip, direction, length * 0.1, translation_colour))
        if not axes and not arrows:
            label_at = tip
        arrows += 1
    if not axes and not arrows:  # rigid: a ball where the contacts hold
        node = coin.SoSeparator()
        material = coin.SoMaterial()
        material.diffuseColor.setValue(*(highlight_colour if highlighted else RIGID_COLOUR))
        translation = coin.SoTranslation()
        translation.translation.setValue(*tuple(joint.Centre))
        sphere = coin.SoSphere()
        sphere.radius.setValue(length * 0.04)
        for child in (material, translation, sphere):
            node.addChild(child)
        root.addChild(node)
    # the label: "J3 revolute" (the joint's number and type) at the end of its first glyph
    number = joint.Label.split(" ", 1)[0]
    root.addChild(_label(f"{number} {joint.JointType}", label_at,
                         highlight_colour if highlighted else (rotation_colour if axes else translation_colour)))
    return root, axes, arrows
