"""make_simulation_model(): a body's view or collision model as a document
object (headless; the GUI command wraps it in a transaction). The model is
computed by the object's recompute (contactwb.objects.simulation_model)."""
import math

from contactwb.objects import gui_hooks
from contactwb.objects.simulation_model import (SimulationModel, followed_partitions,  # noqa: F401
                                                shape_of, update_simulation_model)


def _link(obj):
    """XLinkSub value of a body given as an object or (root, subname)."""
    if isinstance(obj, tuple):
        root, subname = obj
        return (root, [subname or ""])
    return (obj, [""])


def make_simulation_model(doc, body, model="Collision", followed=None, switched_off=(), deflection=0.1,
                          angle=0.5, max_edge=0.0, feature_size=0.0, envelope=0.0, name="SimulationModel"):
    """A SimulationModel object for `body` (an object, or (top-level object, subname)), computed at once.
    `followed`: the other part of the joint being followed (its contact partitions switched off);
    `switched_off`: further partition ids; `deflection` mm, `angle` radians (shown in degrees)."""
    obj = doc.addObject("App::FeaturePython", name)
    SimulationModel(obj)
    obj.Body = _link(body)
    if followed is not None:
        obj.FollowedPart = _link(followed)
    obj.Model = model
    obj.Deflection = deflection
    obj.AngularDeflection = math.degrees(angle)  # `angle` in radians, the property in degrees
    obj.MaxEdgeLength = max_edge
    obj.FeatureSize = feature_size
    obj.Envelope = envelope
    obj.UserSwitchedOff = sorted(set(int(p) for p in switched_off))
    root = obj.Body[0]
    obj.Label = f"{model} model of {root.Label}"
    gui_hooks.new_object(obj)
    update_simulation_model(obj)
    obj.purgeTouched()
    return obj
