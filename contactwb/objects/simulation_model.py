"""Proxy of a body's simulation model: its view model (the B-rep with every
feature, tessellated finely) or its collision model (small features removed
within an envelope, tessellated coarser), every triangle tagged with its
partition, and the partitions switched off for the joint being followed.

Saved files name `contactwb.objects.simulation_model.SimulationModel`: a
permanent name. The mesh is stored in the object (hidden properties), so a
re-opened file shows it without meshing again; the view provider only draws
it (contactwb/gui/viewproviders/simulation_model.py). The model is computed
here (update_simulation_model: the proxy's execute)."""
import math

import FreeCAD

from contactwb import core
from contactwb.core import meshes
from contactwb.document.identify import is_simulation_model  # noqa: F401  (its old home)
from contactwb.document.shapes import assembly_from_shapes
from contactwb.objects.base import VersionedProxy, add_property


MODELS = ["Collision", "View"]


def _properties(obj):
    add_property(obj, "App::PropertyXLinkSub", "Body", "Model", "The body (its top-level object and path)")
    add_property(obj, "App::PropertyEnumeration", "Model", "Model",
         "Collision: small features removed, coarser (what collision queries use); View: every feature")
    if not obj.Model:
        obj.Model = MODELS
        obj.Model = "Collision"
    add_property(obj, "App::PropertyLength", "Deflection", "Model", "Chordal deviation of the view model "
         "(the collision model: twice it)")
    add_property(obj, "App::PropertyAngle", "AngularDeflection", "Model", "Angular deflection of the view model")
    add_property(obj, "App::PropertyLength", "MaxEdgeLength", "Model", "Longest triangle edge of the view model (0: none)")
    add_property(obj, "App::PropertyLength", "FeatureSize", "Model",
         "Collision model: holes, blends and chamfers smaller than this go (0: none)")
    add_property(obj, "App::PropertyLength", "Envelope", "Model",
         "Largest Hausdorff distance of the simplified model to the original (beyond: the original is kept)")
    add_property(obj, "App::PropertyXLinkSub", "FollowedPart", "Switched off",
         "The part of the joint being followed: the partitions in contact with it are switched off")
    add_property(obj, "App::PropertyIntegerList", "UserSwitchedOff", "Switched off",
         "Further partitions switched off (ids)")
    # Results (read-only) and the mesh (hidden)
    add_property(obj, "App::PropertyIntegerList", "SwitchedOff", "Switched off",
         "Partitions switched off: the followed joint's and the user's", 1)
    add_property(obj, "App::PropertyInteger", "Triangles", "Result", "Triangles of the model", 1)
    add_property(obj, "App::PropertyInteger", "Partitions", "Result", "Partitions of the body", 1)
    add_property(obj, "App::PropertyBool", "Watertight", "Result", "Every edge in exactly two triangles", 1)
    add_property(obj, "App::PropertyBool", "Simplified", "Result", "Small features were removed", 1)
    add_property(obj, "App::PropertyLength", "Hausdorff", "Result", "Distance of the model to the original B-rep", 1)
    add_property(obj, "App::PropertyStringList", "RemovedFaces", "Result", "Faces of the small features removed", 1)
    add_property(obj, "App::PropertyString", "Message", "Result", "Why a simplification was refused", 1)
    add_property(obj, "App::PropertyVectorList", "MeshPoints", "Mesh", "Vertices (mm, global)", 2)
    add_property(obj, "App::PropertyIntegerList", "MeshTriangles", "Mesh", "Vertex indices, three per triangle", 2)
    add_property(obj, "App::PropertyIntegerList", "MeshPartitions", "Mesh", "Partition of each triangle", 2)
    add_property(obj, "App::PropertyIntegerList", "MeshFaces", "Mesh", "FaceN of each triangle", 2)


class SimulationModel(VersionedProxy):
    """A body's view or collision model; recomputed when the body or the options change."""
    TYPE = "SimulationModel"  # new in version 2: nothing to migrate yet
    add_properties = staticmethod(_properties)

    def execute(self, obj):
        update_simulation_model(obj)


def shape_of(link):
    """The linked body's shape, placed globally (one solid)."""
    import Part
    root, subnames = link
    subname = subnames[0] if subnames else ""
    shape = Part.getShape(root, subname, needSubElement=False, transform=True)
    if shape.isNull() or not shape.Solids:
        raise core.ContactsError(f"'{root.Label}' has no solid to model")
    return shape.Solids[0] if len(shape.Solids) == 1 else shape


def followed_partitions(shape, partner_shape, linear=None, angular=None):
    """Partition ids of `shape` in contact with `partner_shape` (the joint being followed), with the
    tolerances of the two-body assembly both are modelled in."""
    assembly = assembly_from_shapes([("body", shape), ("partner", partner_shape)])
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
    shape = shape_of(link)
    joint = []
    if obj.FollowedPart and obj.FollowedPart[0] is not None:
        partner = shape_of((obj.FollowedPart[0], list(obj.FollowedPart[1]) or [""]))
        assembly, joint = followed_partitions(shape, partner)
    else:
        assembly = assembly_from_shapes([("body", shape)])
    deflection = max(float(obj.Deflection.Value), 1e-4)
    angle_deg = float(obj.AngularDeflection.Value)  # the property is in degrees, the core takes radians
    angle = math.radians(angle_deg) if angle_deg > 0 else 0.5
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
