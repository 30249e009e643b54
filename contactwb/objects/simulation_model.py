"""Proxy of a body's simulation model: its view model (the B-rep with every
feature, tessellated finely) or its collision model (small features removed
within an envelope, tessellated coarser), every triangle tagged with its
partition, and the partitions switched off for the joint being followed.

Saved files name `contactwb.objects.simulation_model.SimulationModel`: a
permanent name. The mesh is stored in the object (hidden properties), so a
re-opened file shows it without meshing again; the view provider only draws
it (contactwb/gui/simulation_model_view.py)."""
from contactwb.objects.contact_objects import _add, _VersionedProxy


MODELS = ["Collision", "View"]


def is_simulation_model(obj):
    """Whether a document object is a SimulationModel (also once re-opened)."""
    return getattr(getattr(obj, "Proxy", None), "Type", None) == "SimulationModel"


def _properties(obj):
    _add(obj, "App::PropertyXLinkSub", "Body", "Model", "The body (its top-level object and path)")
    _add(obj, "App::PropertyEnumeration", "Model", "Model",
         "Collision: small features removed, coarser (what collision queries use); View: every feature")
    if not obj.Model:
        obj.Model = MODELS
        obj.Model = "Collision"
    _add(obj, "App::PropertyLength", "Deflection", "Model", "Chordal deviation of the view model "
         "(the collision model: twice it)")
    _add(obj, "App::PropertyAngle", "AngularDeflection", "Model", "Angular deflection of the view model")
    _add(obj, "App::PropertyLength", "MaxEdgeLength", "Model", "Longest triangle edge of the view model (0: none)")
    _add(obj, "App::PropertyLength", "FeatureSize", "Model",
         "Collision model: holes, blends and chamfers smaller than this go (0: none)")
    _add(obj, "App::PropertyLength", "Envelope", "Model",
         "Largest Hausdorff distance of the simplified model to the original (beyond: the original is kept)")
    _add(obj, "App::PropertyXLinkSub", "FollowedPart", "Switched off",
         "The part of the joint being followed: the partitions in contact with it are switched off")
    _add(obj, "App::PropertyIntegerList", "UserSwitchedOff", "Switched off",
         "Further partitions switched off (ids)")
    # Results (read-only) and the mesh (hidden)
    _add(obj, "App::PropertyIntegerList", "SwitchedOff", "Switched off",
         "Partitions switched off: the followed joint's and the user's", 1)
    _add(obj, "App::PropertyInteger", "Triangles", "Result", "Triangles of the model", 1)
    _add(obj, "App::PropertyInteger", "Partitions", "Result", "Partitions of the body", 1)
    _add(obj, "App::PropertyBool", "Watertight", "Result", "Every edge in exactly two triangles", 1)
    _add(obj, "App::PropertyBool", "Simplified", "Result", "Small features were removed", 1)
    _add(obj, "App::PropertyLength", "Hausdorff", "Result", "Distance of the model to the original B-rep", 1)
    _add(obj, "App::PropertyStringList", "RemovedFaces", "Result", "Faces of the small features removed", 1)
    _add(obj, "App::PropertyString", "Message", "Result", "Why a simplification was refused", 1)
    _add(obj, "App::PropertyVectorList", "MeshPoints", "Mesh", "Vertices (mm, global)", 2)
    _add(obj, "App::PropertyIntegerList", "MeshTriangles", "Mesh", "Vertex indices, three per triangle", 2)
    _add(obj, "App::PropertyIntegerList", "MeshPartitions", "Mesh", "Partition of each triangle", 2)
    _add(obj, "App::PropertyIntegerList", "MeshFaces", "Mesh", "FaceN of each triangle", 2)


class SimulationModel(_VersionedProxy):
    """A body's view or collision model; recomputed when the body or the options change."""
    TYPE = "SimulationModel"  # new in version 2: nothing to migrate yet
    add_properties = staticmethod(_properties)

    def execute(self, obj):
        from contactwb.make.make_simulation_model import update_simulation_model
        update_simulation_model(obj)
