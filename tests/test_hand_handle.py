"""The haptic panel's hand handle (contactwb/gui/panels/hand_handle.py)
without a GUI: its pose read as the trial's offset convention (translate,
then Rz Ry Rx about the centre: pose_math.h rotation_xyz), its box, its
place first in the scene graph, and that only a drag (the dragger active)
moves the hand. The drag with the mouse in FreeCAD's 3D view is
tests/gui/test_haptic_hand.py."""
import math

import FreeCAD
import numpy
import pytest
from pivy import coin

from contactwb.gui.panels import hand_handle


def rotation_xyz(rx, ry, rz):
    """Rz Ry Rx from the angles in degrees, written out by hand (pose_math.h's convention)."""
    a, b, c = (math.radians(v) for v in (rx, ry, rz))
    rot_x = numpy.array([[1, 0, 0], [0, math.cos(a), -math.sin(a)], [0, math.sin(a), math.cos(a)]])
    rot_y = numpy.array([[math.cos(b), 0, math.sin(b)], [0, 1, 0], [-math.sin(b), 0, math.cos(b)]])
    rot_z = numpy.array([[math.cos(c), -math.sin(c), 0], [math.sin(c), math.cos(c), 0], [0, 0, 1]])
    return rot_z @ rot_y @ rot_x


def matrix_of(rotation):
    m = rotation.toMatrix()
    return numpy.array([[m.A11, m.A12, m.A13], [m.A21, m.A22, m.A23], [m.A31, m.A32, m.A33]])


class FakeView:
    """What the handle asks of a 3D view: its scene graph (here with a node already in it)."""

    def __init__(self):
        self.graph = coin.SoSeparator()
        self.graph.addChild(coin.SoSeparator())

    def getSceneGraph(self):
        return self.graph


@pytest.mark.parametrize("angles", [(10, 20, 30), (-35, 5, 170), (0, -60, 0), (90, 0, -90)])
def test_the_handle_turns_as_the_trial_offsets(angles):
    assert matrix_of(hand_handle.rotation_of(angles)) == pytest.approx(rotation_xyz(*angles), abs=1e-12)
    assert hand_handle.angles_of(hand_handle.rotation_of(angles)) == pytest.approx(list(angles), abs=1e-9)


def make_handle():
    box = FreeCAD.BoundBox(-4, -5, 2, 4, 5, 72)  # a shaft 70 long, centre off the box's middle
    view = FakeView()
    return view, hand_handle.HandHandle(view, (0.0, 0.0, 30.0), box)


def test_the_handle_is_the_parts_box_plus_a_margin_first_in_the_scene():
    view, handle = make_handle()
    # about the centre z 30: 28 below, 42 above; the larger side and 1 mm each way
    assert list(handle.half_size) == pytest.approx([5.0, 6.0, 43.0])
    assert view.graph.findChild(handle.root) == 0  # before any legend camera (see hand_handle)
    assert handle.root.getName().getString() == hand_handle.NODE_NAME
    handle.remove()
    assert view.graph.findChild(handle.root) == -1
    assert view.graph.getNumChildren() == 1


def test_only_a_drag_moves_the_hand():
    _, handle = make_handle()
    assert handle.poll() is None
    # A set (a slider, a script) and the dragger's own rewrite of its fields: not a drag.
    handle.set([1.0, 2.0, 3.0], [0.0, 0.0, 45.0])
    assert handle.poll() is None
    handle.dragger.translation.setValue(1.0, 2.0, 3.5)
    assert handle.poll() is None
    # The designer holds it and moves it: the hand's offset, once.
    handle.dragger.isActive.setValue(True)
    handle.dragger.translation.setValue(1.0, 2.0, 9.0)
    handle.dragger.rotation.setValue(*hand_handle.rotation_of([0.0, 0.0, 60.0]).Q)
    translate, rotate = handle.poll()
    assert translate == pytest.approx([1.0, 2.0, 9.0], abs=1e-6)
    assert rotate == pytest.approx([0.0, 0.0, 60.0], abs=1e-4)  # single-precision quaternion
    assert handle.poll() is None
    # Its last move may come with the release: still read at the next poll, then no more.
    handle.dragger.translation.setValue(1.0, 2.0, 10.0)
    handle.dragger.isActive.setValue(False)
    assert handle.poll()[0] == pytest.approx([1.0, 2.0, 10.0], abs=1e-6)
    handle.dragger.translation.setValue(1.0, 2.0, 11.0)
    assert handle.poll() is None


def test_a_scale_drag_is_undone():
    _, handle = make_handle()
    handle.dragger.scaleFactor.setValue(9.0, 9.0, 9.0)
    handle.poll()
    assert list(handle.dragger.scaleFactor.getValue().getValue()) == pytest.approx([5.0, 6.0, 43.0])
