"""Coin helpers shared by the drawings: materials, polygon offsets, stripes
and the legend drawn over the view's corner."""
import math

from pivy import coin


def material(colour, transparency=0.0):
    # Mostly emissive: the type colour reads the same on every side of a
    # cylinder, while the diffuse part keeps a hint of the shape.
    material = coin.SoMaterial()
    material.diffuseColor.setValue(*(0.5 * c for c in colour))
    material.emissiveColor.setValue(*(0.6 * c for c in colour))
    material.ambientColor.setValue(0, 0, 0)
    material.specularColor.setValue(0, 0, 0)
    material.transparency.setValue(transparency)
    return material


def line_material(colour):
    """Opaque flat colour (lines drawn with the BASE_COLOR light model)."""
    material = coin.SoMaterial()
    material.diffuseColor.setValue(*colour)
    material.transparency.setValue(0.0)
    return material


def polygon_offset(factor, units):
    offset = coin.SoPolygonOffset()
    offset.factor.setValue(factor)
    offset.units.setValue(units)
    return offset


def stripes():
    """Nodes striping what follows: a two-texel texture repeated along a
    fixed world direction (independent of the tessellation); the last one
    sets the period (set_stripe_period)."""
    complexity = coin.SoComplexity()
    complexity.textureQuality.setValue(0.1)  # nearest texel: sharp stripes
    texture = coin.SoTexture2()
    texture.image.setValue(coin.SbVec2s(2, 1), 1, bytes([255, 150]))
    texture.model.setValue(coin.SoTexture2.MODULATE)
    texture.wrapS.setValue(coin.SoTexture2.REPEAT)
    texture.wrapT.setValue(coin.SoTexture2.REPEAT)
    coordinates = coin.SoTextureCoordinatePlane()
    coordinates.directionT.setValue(0, 0, 0)
    set_stripe_period(coordinates, 1.0)
    return [complexity, texture, coordinates]


def set_stripe_period(coordinates, period):
    """One light and one dark stripe every `period` mm along (1, 1, 1)."""
    step = 1.0 / (period * math.sqrt(3.0))
    coordinates.directionS.setValue(step, step, step)


def left_out_of_fit_all():
    """An empty group that FreeCAD's View > Fit all leaves out: its own
    SoSkipBoundingGroup, which View3DInventorViewer::viewAll switches to
    EXCLUDE_BBOX while it fits. Held by Python as pivy holds the nodes it
    makes (one reference, dropped with the Python object)."""
    kind = coin.SoType.fromName(coin.SbName("SoSkipBoundingGroup"))
    if kind.isBad():  # pivy without FreeCAD's GUI loaded: no view to fit
        return coin.SoGroup()
    group = kind.createInstance()
    group.ref()
    group.thisown = True
    return group


def legend_node(entries, name="ContactsLegend", stack=None):
    """A legend drawn over the view's top-left corner: one line of text per
    (text, (r, g, b)) entry, in its colour. An annotation (named `name`) with
    its own camera, so it stays put whatever the view's camera does;
    unpickable. Its text would count at the legend camera's coordinates (near
    the origin) in the scene's bounding box and pull Fit all off the model:
    it is wrapped in a group Fit all leaves out, which is returned.
    stack=(document name, key): placed below the document's other legends
    (legend_stack), never over them."""
    legend = coin.SoAnnotation()
    legend.setName(name)
    pick = coin.SoPickStyle()
    pick.style.setValue(coin.SoPickStyle.UNPICKABLE)
    camera = coin.SoOrthographicCamera()
    camera.viewportMapping.setValue(coin.SoCamera.LEAVE_ALONE)  # x, y in -1..1 across the view
    camera.height.setValue(2.0)
    camera.position.setValue(0, 0, 5)
    light = coin.SoLightModel()
    light.model.setValue(coin.SoLightModel.BASE_COLOR)
    font = coin.SoFont()
    font.size.setValue(16)
    font.name.setValue("sans:bold")
    for node in (pick, camera, light, font):
        legend.addChild(node)
    start = coin.SoTranslation()
    start.translation.setValue(-0.96, 0.9, 0)
    legend.addChild(start)
    if stack is not None:
        from contactwb.gui.overlay import legend_stack
        if entries:
            legend_stack.register(stack[0], stack[1], start, len(entries))
        else:
            legend_stack.unregister(stack[0], stack[1])
    for text, colour in entries:
        base = coin.SoBaseColor()
        base.rgb.setValue(*colour)
        label = coin.SoText2()
        label.string.setValue(text)
        step = coin.SoTranslation()
        step.translation.setValue(0, -0.055, 0)
        for node in (base, label, step):
            legend.addChild(node)
    left_out = left_out_of_fit_all()
    left_out.addChild(legend)
    return left_out
