"""The SimulationModel document object (make_simulation_model, headless) and
its Coin drawing (simulation_model_view.model_nodes): the motor's front cover,
its collision model without the small holes, the bore of the bearing it holds
switched off. (tests/gui/test_simulation_model_gui.py runs the command.)"""
import pytest

import FreeCAD

from contactwb import analysis, bodies, core
from contactwb.make import make_simulation_model
from contactwb.objects.simulation_model import is_simulation_model

coin = pytest.importorskip("pivy.coin")
view = pytest.importorskip("contactwb.gui.simulation_model_view")


@pytest.fixture(scope="module")
def motor(sample):
    doc = FreeCAD.openDocument(sample("motor.FCStd"))
    yield doc
    FreeCAD.closeDocument(doc.Name)


def part(doc, label):
    return next(o for o in doc.Objects if o.Label == label)


def test_collision_model_of_the_front_cover_with_the_bearing_joint_switched_off(motor, tmp_path):
    cover, bearing = part(motor, "Front-cover"), part(motor, "Bearing-front")
    model = make_simulation_model(motor, cover, "Collision", followed=bearing, feature_size=2.5, envelope=5)
    try:
        assert model.Triangles == len(model.MeshTriangles) // 3 == len(model.MeshPartitions) > 0
        assert model.Watertight and model.Simplified and model.Message == ""
        assert model.Hausdorff.Value == pytest.approx(4.0, abs=1e-6)  # half the cover's thickness
        # Switched off: the cover's partitions in contact with the bearing, as the whole motor's
        # analysis names them (its faces).
        result = analysis.find_contacts_in_document(motor)[0]
        partitions = core.contactcore.partition_brep(cover.Shape.exportBrepToString())
        face_partition = {f"Face{f}": p.id for p in partitions.partitions for f in p.faces}
        expected = sorted({face_partition[f] for c in result.contacts for side, faces in
                           (("a", c.faces_a), ("b", c.faces_b)) if getattr(c, side) == "Front-cover"
                           and {c.a, c.b} == {"Front-cover", "Bearing-front"} for f in faces})
        assert expected and list(model.SwitchedOff) == expected
        small = {p.id for p in partitions.partitions if p.params.kind.name == "Cylinder"
                 and abs(p.params.radius - 1.2) < 1e-9}
        assert len(small) == 4 and not small & set(model.MeshPartitions)
        # The cover is still a body of the document (a model is not a part).
        assert "Front-cover" in [b.name for b in bodies.document_bodies(motor)]
        assert len(bodies.document_bodies(motor)) == 18
        # Saved and re-opened: the proxy and the stored mesh come back (nothing is meshed again).
        path = str(tmp_path / "motor_with_model.FCStd")
        motor.saveCopy(path)
        copy = FreeCAD.openDocument(path)
        try:
            (restored,) = [o for o in copy.Objects if is_simulation_model(o)]
            assert restored.Label == "Collision model of Front-cover"
            assert list(restored.MeshTriangles) == list(model.MeshTriangles)
            assert list(restored.SwitchedOff) == list(model.SwitchedOff)
            assert restored.Body[0].Label == "Front-cover" and restored.FollowedPart[0].Label == "Bearing-front"
            assert (restored.ProxyType, restored.ProxyVersion) == ("SimulationModel", 2)
            # As a FreeCAD without the workbench leaves it (proxy gone, properties kept):
            # the workbench gives it its proxy back.
            from contactwb.objects import recovery
            restored.Proxy = None
            assert recovery.restore_proxies(copy) == [restored.Name]
            assert is_simulation_model(restored) and list(restored.MeshTriangles) == list(model.MeshTriangles)
        finally:
            FreeCAD.closeDocument(copy.Name)
        # The view model: every feature, finer.
        model.Model = "View"
        motor.recompute()
        assert model.Triangles == 3000 and small <= set(model.MeshPartitions)  # finer than the collision model's 1,170
        assert 0 < model.Hausdorff.Value <= 0.1 and not model.Simplified
    finally:
        motor.removeObject(model.Name)


def test_model_nodes_colour_each_partition_and_stripe_the_switched_off():
    import numpy
    # Two triangles of partition 0, one of 1, one of 2 (switched off).
    points = numpy.array([(0, 0, 0), (1, 0, 0), (0, 1, 0), (1, 1, 0), (0, 0, 1)], dtype=float)
    triangles = numpy.array([(0, 1, 2), (1, 3, 2), (0, 4, 1), (0, 2, 4)], dtype=numpy.int32)
    partitions = numpy.array([0, 0, 1, 2], dtype=numpy.int32)
    root, counts = view.model_nodes(points, triangles, partitions, {2})
    assert counts == {"active": 3, "switched_off": 1}
    layers = {root.getChild(i).getName().getString(): root.getChild(i) for i in range(root.getNumChildren())}
    active = layers["Partitions"]
    faces = next(active.getChild(i) for i in range(active.getNumChildren())
                 if isinstance(active.getChild(i), coin.SoIndexedFaceSet))
    assert list(faces.coordIndex.getValues()) == [0, 1, 2, -1, 1, 3, 2, -1, 0, 4, 1, -1]
    assert list(faces.materialIndex.getValues()) == [0, 0, 1]
    material = active.getChild(0)
    colours = [tuple(c.getValue()) for c in material.diffuseColor.getValues()]
    assert colours[0] == pytest.approx(view.partition_colour(0)) and colours[1] == pytest.approx(view.partition_colour(1))
    assert colours[0] != pytest.approx(colours[1])
    off = layers["SwitchedOff"]
    kinds = [type(off.getChild(i)).__name__ for i in range(off.getNumChildren())]
    assert "SoTexture2" in kinds  # striped
    (off_faces,) = [off.getChild(i) for i in range(off.getNumChildren())
                    if isinstance(off.getChild(i), coin.SoIndexedFaceSet)]
    assert list(off_faces.coordIndex.getValues()) == [0, 2, 4, -1]


def test_partition_colours_are_distinct_and_never_the_switched_off_grey():
    colours = [view.partition_colour(p) for p in range(40)]
    for i, a in enumerate(colours):
        assert max(a) - min(a) > 0.3  # saturated: not grey
        for b in colours[i + 1:]:
            assert max(abs(x - y) for x, y in zip(a, b)) > 0.02
