"""The haptic panel's hand handle (contactwb/gui/panels/hand_handle.py)
without a GUI: its pose read as the trial's offset convention (translate,
then Rz Ry Rx about the centre: pose_math.h rotation_xyz), its box, its
place first in the scene graph, that it is picked where a body hides it
(the rest of the scene unpickable while it is shown, Coin's ray pick), and
that only a drag (the dragger active) moves the hand. The drag with the mouse in FreeCAD's 3D view is
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
    # Right after it, the rest of the scene made unpickable while it is shown.
    assert view.graph.findChild(handle.others) == 1
    assert handle.others.getName().getString() == hand_handle.OTHERS_NODE_NAME
    assert not handle.others_pickable()
    handle.show(False)
    assert handle.others_pickable()
    handle.show(True)
    assert not handle.others_pickable()
    handle.remove()
    assert view.graph.findChild(handle.root) == -1
    assert view.graph.findChild(handle.others) == -1
    assert view.graph.getNumChildren() == 1


def picked_under_the_centre(root):
    """The nodes on the path of the nearest surface under the middle of a 100 x 100 view (Coin's
    ray pick, as a dragger's press is picked)."""
    pick = coin.SoRayPickAction(coin.SbViewportRegion(100, 100))
    pick.setPoint(coin.SbVec2s(50, 50))
    pick.apply(root)
    point = pick.getPickedPoint()
    if point is None:
        return []
    path = point.getPath()
    return [path.getNode(i) for i in range(path.getLength())]


def test_the_handle_is_picked_where_a_body_hides_it():
    # A camera looking down -z at the handle (the shaft's box, z 2..72) with a plate over it: a
    # body in front, as the motor's Body is in front of its Axis.
    view, handle = make_handle()
    plate = coin.SoSeparator()
    place = coin.SoTranslation()
    place.translation.setValue(0.0, 0.0, 100.0)
    cube = coin.SoCube()
    cube.width.setValue(50.0)
    cube.height.setValue(50.0)
    cube.depth.setValue(2.0)
    plate.addChild(place)
    plate.addChild(cube)
    view.graph.addChild(plate)
    root = coin.SoSeparator()
    camera = coin.SoOrthographicCamera()
    camera.position.setValue(0.0, 0.0, 200.0)
    camera.height.setValue(120.0)
    camera.nearDistance.setValue(1.0)
    camera.farDistance.setValue(400.0)
    root.addChild(camera)
    root.addChild(view.graph)
    # Shown: the handle (its dragger), not the plate in front of it, nor its outline drawn over all.
    path = picked_under_the_centre(root)
    assert handle.dragger in path and handle.outline not in path
    # Hidden (a hardware device drives the hand): the plate again, as without the handle.
    handle.show(False)
    path = picked_under_the_centre(root)
    assert cube in path and handle.dragger not in path
    handle.remove()
    assert cube in picked_under_the_centre(root)


def test_the_outline_follows_the_handle():
    # Its box as lines over the whole scene: an annotation in the handle's switch, scaled to the
    # handle's box, moved and turned with the dragger by field connections.
    view, handle = make_handle()
    assert handle.outline.isOfType(coin.SoAnnotation.getClassTypeId())
    assert handle.switch.findChild(handle.outline) == 2  # after the centre's translation and the dragger
    search = coin.SoSearchAction()
    search.setType(coin.SoScale.getClassTypeId())
    search.apply(handle.outline)
    assert list(search.getPath().getTail().scaleFactor.getValue().getValue()) == pytest.approx([5.0, 6.0, 43.0])
    handle.dragger.translation.setValue(1.0, 2.0, 3.0)
    handle.dragger.rotation.setValue(*hand_handle.rotation_of([0.0, 0.0, 30.0]).Q)
    assert list(handle.follow.translation.getValue().getValue()) == pytest.approx([1.0, 2.0, 3.0])
    assert list(handle.follow.rotation.getValue().getValue()) == pytest.approx(
        list(hand_handle.rotation_of([0.0, 0.0, 30.0]).Q), abs=1e-6)
    handle.set([4.0, 5.0, 6.0], [10.0, 0.0, 0.0])  # a slider: the outline follows too
    assert list(handle.follow.translation.getValue().getValue()) == pytest.approx([4.0, 5.0, 6.0])
    handle.show(False)  # hidden with the handle (the same switch)
    assert handle.switch.whichChild.getValue() == coin.SO_SWITCH_NONE
    handle.remove()


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
