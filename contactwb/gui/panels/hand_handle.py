"""The simulated hand's handle in the 3D view (the haptic panel's, issue 20
item 6): a Coin transformer dragger around the part that the designer drags
(a face moves it in that face's plane, an edge's knob turns it) and the hand
follows. Nothing calls back into Python from Coin: pivy's value-changed
callback ran without the GIL and crashed FreeCAD, so the panel's display
timer polls the dragger's fields each frame instead. The handle is a node of
the view's scene graph only (no document object: nothing in the undo
stack), removed when the panel closes.

Its box is also drawn as dashed lines over the whole scene (an
annotation), so it is seen where bodies hide it. While it is shown the rest
of the scene is unpickable (an SoPickStyle right
after it in the scene graph): Coin's draggers start only on the nearest
picked surface, so a handle around a part inside others (the motor's Axis
in its Body) could otherwise be grabbed only where nothing hides it. The
bodies cannot be selected in the view meanwhile; the style is switched back
when the handle is hidden and removed with it.

Its pose is the hand's offset in the trial's convention (contactwb.core.trial,
pose_math.h offset_pose): translate in mm, then turned by R = Rz Ry Rx about
global axes through the scene's centre; the dragger sits at that centre, so
its translation and rotation fields are that offset."""
import FreeCAD
from pivy import coin

NODE_NAME = "ContactsHandHandle"
OTHERS_NODE_NAME = "ContactsHandHandleOthersUnpickable"
OUTLINE_NODE_NAME = "ContactsHandHandleOutline"
MARGIN_MM = 1.0  # the handle's box clears the part's box by this much on each side


def rotation_of(rotate_deg):
    """FreeCAD.Rotation of the offset's angles (rx, ry, rz) in degrees: Rz Ry Rx."""
    rx, ry, rz = rotate_deg
    return FreeCAD.Rotation(rz, ry, rx)  # yaw (z), pitch (y), roll (x)


def angles_of(rotation):
    """The offset's (rx, ry, rz) in degrees of a FreeCAD.Rotation (rotation_of's inverse)."""
    yaw, pitch, roll = rotation.toEuler()
    return [roll, pitch, yaw]


class HandHandle:
    """The dragger in `view`'s scene graph, centred on `centre` (the scene's
    centre, global mm), its box the part's `box` (FreeCAD.BoundBox) plus
    MARGIN_MM each side."""

    def __init__(self, view, centre, box):
        self.scene = view.getSceneGraph()
        self.root = coin.SoSeparator()
        self.root.setName(NODE_NAME)
        place = coin.SoTranslation()
        place.translation.setValue(*centre)
        self.dragger = coin.SoTransformerDragger()
        # The dragger's box spans -1..1: half the part's box (about the
        # centre, which need not be the box's middle) and the margin.
        self.half_size = [max(abs(hi - c), abs(c - lo)) + MARGIN_MM
                          for lo, hi, c in ((box.XMin, box.XMax, centre[0]), (box.YMin, box.YMax, centre[1]),
                                            (box.ZMin, box.ZMax, centre[2]))]
        self.dragger.scaleFactor.setValue(*self.half_size)
        self.half_size = self.dragger.scaleFactor.getValue().getValue()  # as stored (single precision)
        self.switch = coin.SoSwitch()  # shown while the simulated hand is the device
        self.switch.whichChild.setValue(coin.SO_SWITCH_ALL)
        self.switch.addChild(place)
        self.switch.addChild(self.dragger)
        self.switch.addChild(self._outline())
        self.root.addChild(self.switch)
        # First in the graph: a camera met before it by Coin's ray pick (the
        # contacts' legend has its own) leaves the pick with that camera's
        # ray, and the press would land on the wrong face of the handle.
        self.scene.insertChild(self.root, 0)
        self.others = coin.SoPickStyle()  # the rest of the scene, while the handle is shown
        self.others.setName(OTHERS_NODE_NAME)
        self.others.style.setValue(coin.SoPickStyle.UNPICKABLE)
        self.scene.insertChild(self.others, 1)
        self.seen = self._fields()
        self.was_dragging = False

    def _outline(self):
        """The handle's box as dashed lines drawn over the whole scene (an
        annotation: after it, without the depth test), so that it is seen
        where bodies hide it. It follows the dragger through field
        connections (Coin's own: no Python callback) and is not pickable
        (the dragger takes the presses)."""
        self.outline = coin.SoAnnotation()
        self.outline.setName(OUTLINE_NODE_NAME)
        unpickable = coin.SoPickStyle()
        unpickable.style.setValue(coin.SoPickStyle.UNPICKABLE)
        self.follow = coin.SoTransform()
        self.follow.translation.connectFrom(self.dragger.translation)
        self.follow.rotation.connectFrom(self.dragger.rotation)
        size = coin.SoScale()
        size.scaleFactor.setValue(*self.half_size)
        flat = coin.SoLightModel()
        flat.model.setValue(coin.SoLightModel.BASE_COLOR)
        colour = coin.SoBaseColor()
        colour.rgb.setValue(1.0, 0.75, 0.0)
        lines = coin.SoDrawStyle()
        lines.style.setValue(coin.SoDrawStyle.LINES)
        lines.linePattern.setValue(0xF0F0)
        lines.lineWidth.setValue(1.0)
        for node in (unpickable, self.follow, size, flat, colour, lines, coin.SoCube()):  # the cube spans -1..1
            self.outline.addChild(node)
        return self.outline

    def show(self, on):
        self.switch.whichChild.setValue(coin.SO_SWITCH_ALL if on else coin.SO_SWITCH_NONE)
        self.others.style.setValue(coin.SoPickStyle.UNPICKABLE if on else coin.SoPickStyle.SHAPE)

    def others_pickable(self):
        """Whether the rest of the scene can be picked (the handle hidden)."""
        return self.others.style.getValue() == coin.SoPickStyle.SHAPE

    def _fields(self):
        translation = tuple(self.dragger.translation.getValue().getValue())
        quaternion = tuple(self.dragger.rotation.getValue().getValue())  # x, y, z, w
        return translation, quaternion

    def dragging(self):
        """Whether the designer holds the handle (a mouse button down on it)."""
        return bool(self.dragger.isActive.getValue())

    def poll(self):
        """The hand offset ([x, y, z] mm, [rx, ry, rz] degrees) the handle was
        dragged to since the last poll or set, or None when it was not. Only
        a drag counts (the dragger active now or at the last poll: its last
        move may come with the release): the dragger rewrites its own fields
        a little after a set (its motion matrix read back in single
        precision), which must not take the hand from a playing script."""
        # The handle moves the hand, it does not resize anything: a corner knob's scale is undone.
        if self.dragger.scaleFactor.getValue().getValue() != self.half_size:
            self.dragger.scaleFactor.setValue(*self.half_size)
        dragging = self.dragging()
        was_dragging, self.was_dragging = self.was_dragging, dragging
        fields = self._fields()
        if not (dragging or was_dragging) or fields == self.seen:
            self.seen = fields
            return None
        self.seen = fields
        translation, quaternion = fields
        return list(translation), angles_of(FreeCAD.Rotation(*quaternion))

    def set(self, translate, rotate_deg):
        """Shows the hand at an offset set elsewhere (the sliders, a script)."""
        self.dragger.translation.setValue(*translate)
        self.dragger.rotation.setValue(*rotation_of(rotate_deg).Q)
        self.seen = self._fields()

    def remove(self):
        self.scene.removeChild(self.others)
        self.scene.removeChild(self.root)
