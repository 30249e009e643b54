"""A drag handle in the 3D view for the simulated hand (the haptic panel's
mouse-driven hand, beside its sliders): a Coin SoTransformerDragger at the
moving part's centre of mass. Dragging its faces moves the hand's target in
the plane of the face (with Shift: along the face's normal), dragging its
corner knobs turns it; the panel reads the dragger as an offset from the
part's assembled placement (mm, and degrees about global x, then y, then z,
like a trial script's keys) and sends it to the simulated hand. Only Coin
nodes here: the panel owns the session."""
import FreeCAD
from pivy import coin


class HandDragger:
    """`centre`: the part's centre of mass at its assembled placement
    (global, mm); `size`: the handle's half-width (mm); `moved(translate,
    rotate_deg)` is called when the user drags it."""

    def __init__(self, view, centre, size, moved):
        self.view = view
        self.centre = FreeCAD.Vector(*centre)
        self.moved = moved
        self.drags = 0  # value changes from the dragger (the user's drags)
        self._placed = None  # the offset set_offset last put it at (its sensor may report it later)
        self.root = coin.SoSeparator()
        self.root.setName("ContactsHandDragger")
        place = coin.SoTransform()
        place.translation.setValue(self.centre.x, self.centre.y, self.centre.z)
        place.scaleFactor.setValue(size, size, size)
        self.dragger = coin.SoTransformerDragger()
        self.root.addChild(place)
        self.root.addChild(self.dragger)
        self.dragger.addValueChangedCallback(self._changed)
        # First in the view's scene graph: the document's selection node comes
        # later and would take the mouse press (a click on the part selects it).
        view.getSceneGraph().insertChild(self.root, 0)

    def offset(self):
        """The handle's offset from where it started: [x, y, z] mm and
        [rx, ry, rz] degrees (R = Rz Ry Rx, about global axes through the centre)."""
        size = self.root.getChild(0).scaleFactor.getValue()[0]
        t = self.dragger.translation.getValue()
        q = self.dragger.rotation.getValue().getValue()  # x, y, z, w
        yaw, pitch, roll = FreeCAD.Rotation(q[0], q[1], q[2], q[3]).toEuler()  # z, y, x degrees
        # The dragger's translation is in its own (scaled) frame.
        return [t[0] * size, t[1] * size, t[2] * size], [roll, pitch, yaw]

    def set_offset(self, translate, rotate_deg):
        """Puts the handle at an offset (the sliders moved, a script played)
        without driving the hand."""
        size = self.root.getChild(0).scaleFactor.getValue()[0]
        r = FreeCAD.Rotation(rotate_deg[2], rotate_deg[1], rotate_deg[0]).Q  # yaw, pitch, roll
        self._placed = list(translate) + list(rotate_deg)
        self.dragger.translation.setValue(translate[0] / size, translate[1] / size, translate[2] / size)
        self.dragger.rotation.setValue(coin.SbRotation(r[0], r[1], r[2], r[3]))

    def _changed(self, *_):
        translate, rotate = self.offset()
        if self._placed is not None and all(abs(a - b) < 1e-6 for a, b in zip(translate + rotate, self._placed)):
            return  # where set_offset put it: not the user's drag
        self._placed = None
        self.drags += 1
        self.moved(translate, rotate)

    def remove(self):
        """Takes the handle out of the view."""
        if self.root is not None:
            self.view.getSceneGraph().removeChild(self.root)
            self.root = None


def handle_size(shape):
    """Half-width of the handle for a part: a third of its box's diagonal, at least 5 mm."""
    return max(5.0, shape.BoundBox.DiagonalLength / 6.0) if shape.BoundBox.isValid() else 10.0

