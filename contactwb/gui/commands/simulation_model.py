"""Contacts_ShowSimulationModel: the collision model of the selected part as
a document object (its partitions coloured, those of the followed joint
switched off)."""
import FreeCAD
import FreeCADGui

import contactwb
from contactwb import core
from contactwb.document.bodies import object_path
from contactwb.gui.dialogs import show_error
from contactwb.make import make_simulation_model
from contactwb.objects.simulation_model import shape_of


def _selected():
    """(body, followed, partitions switched off) from the selection: the first selected part is modelled
    (its selected faces' partitions switched off), a second one is the part of the joint being followed."""
    selection = FreeCADGui.Selection.getSelectionEx("", 0)  # unresolved: top-level object and path
    entries = []
    for item in selection:
        subnames = list(item.SubElementNames) or [""]
        entries.append((item.Object, subnames))
    if not entries:
        return None, None, []
    root, subnames = entries[0]
    path = object_path(subnames[0])
    faces = [s.rpartition(".")[2] for s in subnames if s.rpartition(".")[2].startswith("Face")]
    followed = None
    if len(entries) > 1:
        other_root, other_subnames = entries[1]
        followed = (other_root, object_path(other_subnames[0]))
    return (root, path), followed, faces


class Contacts_ShowSimulationModel:
    """Adds the collision model of the selected part (partitions coloured, those of the followed joint
    switched off) as a document object."""

    def GetResources(self):
        return {
            "Pixmap": contactwb.icon_path("Contacts_ShowSimulationModel"),
            "MenuText": "Show simulation model",
            "ToolTip": "Show the collision model of the selected part (its Model property: the view model), "
                       "each partition in its own colour. Select a second part to switch off the partitions "
                       "of the joint between them (striped), or faces of the part to switch off theirs",
        }

    def IsActive(self):
        return FreeCAD.ActiveDocument is not None and bool(FreeCADGui.Selection.getSelection())

    def Activated(self):
        body, followed, faces = _selected()
        if body is None:
            return
        doc = FreeCAD.ActiveDocument
        doc.openTransaction("Show simulation model")
        try:
            switched = []
            if faces:
                switched = _partitions_of_faces(body, faces)
            obj = make_simulation_model(doc, body, "Collision", followed=followed, switched_off=switched)
        except core.ContactsError as error:
            doc.abortTransaction()
            show_error(str(error))
            return
        doc.commitTransaction()
        FreeCADGui.Selection.clearSelection()
        FreeCAD.Console.PrintMessage(f"Contacts: {obj.Label}: {obj.Triangles} triangles, {obj.Partitions} "
                                     f"partitions, switched off {list(obj.SwitchedOff) or 'none'}\n")
        return obj


def _partitions_of_faces(body, faces):
    """Partition ids of the body's faces named "FaceN"."""
    root, path = body
    shape = shape_of((root, [path]))
    partitions = core.contactcore.partition_brep(shape.exportBrepToString())
    wanted = {int(f[4:]) for f in faces}
    return sorted({p.id for p in partitions.partitions if wanted & set(p.faces)})


COMMANDS = {"Contacts_ShowSimulationModel": Contacts_ShowSimulationModel}

