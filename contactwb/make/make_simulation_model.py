"""make_simulation_model(): a body's view or collision model as a document
object (headless; the GUI command wraps it in a transaction)."""
import FreeCAD

from contactwb import core, meshes


def _link(obj):
    """XLinkSub value of a body given as an object or (root, subname)."""
    if isinstance(obj, tuple):
        root, subname = obj
        return (root, [subname or ""])
    return (obj, [""])


def _shape_of(link):
    """The linked body's shape, placed globally (one solid)."""
    import Part
    root, subnames = link
    subname = subnames[0] if subnames else ""
    shape = Part.getShape(root, subname, needSubElement=False, transform=True)
    if shape.isNull() or not shape.Solids:
        raise core.ContactsError(f"'{root.Label}' has no solid to model")
    return shape.Solids[0] if len(shape.Solids) == 1 else shape


def make_simulation_model(doc, body, model="Collision", followed=None, switched_off=(), deflection=0.1,
                          angle=0.5, max_edge=0.0, feature_size=0.0, envelope=0.0, name="SimulationModel"):
    """A SimulationModel object for `body` (an object, or (top-level object, subname)), computed at once.
    `followed`: the other part of the joint being followed (its contact partitions switched off);
    `switched_off`: further partition ids."""
    from contactwb.objects.simulation_model import SimulationModel
    obj = doc.addObject("App::FeaturePython", name)
    SimulationModel(obj)
    obj.Body = _link(body)
    if followed is not None:
        obj.FollowedPart = _link(followed)
    obj.Model = model
    obj.Deflection = deflection
    obj.AngularDeflection = angle * 180 / 3.141592653589793
    obj.MaxEdgeLength = max_edge
    obj.FeatureSize = feature_size
    obj.Envelope = envelope
    obj.UserSwitchedOff = sorted(set(int(p) for p in switched_off))
    root = obj.Body[0]
    obj.Label = f"{model} model of {root.Label}"
    if FreeCAD.GuiUp:
        from contactwb.gui.simulation_model_view import ViewProviderSimulationModel
        ViewProviderSimulationModel(obj.ViewObject)
    update_simulation_model(obj)
    obj.purgeTouched()
    return obj


def followed_partitions(shape, partner_shape, linear=None, angular=None):
    """Partition ids of `shape` in contact with `partner_shape` (the joint being followed), with the
    tolerances of the two-body assembly both are modelled in."""
    assembly = core.assembly_from_shapes([("body", shape), ("partner", partner_shape)])
    result = core.contactcore.find_contacts(assembly, linear=linear, angular=angular)
    ids = set()
    for contact in result.contacts:
        ids.add(contact.partition_a if contact.body_a == 0 else contact.partition_b)
    return assembly, sorted(ids)


def update_simulation_model(obj):
    """(Re)computes the model of obj's body into its properties."""
    if not obj.Body or obj.Body[0] is None:
        raise core.ContactsError(f"'{obj.Label}' has no body")
    link = (obj.Body[0], list(obj.Body[1]) or [""])
    shape = _shape_of(link)
    joint = []
    if obj.FollowedPart and obj.FollowedPart[0] is not None:
        partner = _shape_of((obj.FollowedPart[0], list(obj.FollowedPart[1]) or [""]))
        assembly, joint = followed_partitions(shape, partner)
    else:
        assembly = core.assembly_from_shapes([("body", shape)])
    deflection = max(float(obj.Deflection.Value), 1e-4)
    angle_degrees = float(obj.AngularDeflection.Value)
    angle = angle_degrees * 3.141592653589793 / 180 if angle_degrees > 0 else 0.5
    feature_size = float(obj.FeatureSize.Value)
    envelope = float(obj.Envelope.Value)
    (models,) = meshes.simulation_models(assembly, deflection, angle, float(obj.MaxEdgeLength.Value),
                                         feature_size if envelope > 0 else 0.0, envelope, bodies=[0])
    result = models.collision if obj.Model == "Collision" else models.view
    mesh = result.mesh
    obj.MeshPoints = [FreeCAD.Vector(*v) for v in mesh.vertices]
    obj.MeshTriangles = [i for t in mesh.triangles for i in t]
    obj.MeshPartitions = list(mesh.triangle_partition)
    obj.MeshFaces = list(mesh.triangle_face)
    obj.Triangles = result.quality.triangles
    obj.Partitions = mesh.partition_count
    obj.Watertight = result.quality.watertight
    collision = obj.Model == "Collision"
    obj.Simplified = collision and models.simplified
    obj.Hausdorff = models.collision_hausdorff if collision else models.view_deviation
    obj.RemovedFaces = [f"Face{f}" for f in models.removed_faces] if collision else []
    obj.Message = models.message if collision else ""
    valid = set(range(mesh.partition_count))
    obj.SwitchedOff = sorted((set(joint) | set(obj.UserSwitchedOff)) & valid)
