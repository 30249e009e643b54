"""Runs inside the FreeCAD GUI (freecad tests/gui/simulation_model_session.py under Xvfb).

Opens the bundled motor, selects the front cover and then the front bearing,
runs Contacts_ShowSimulationModel, sets the collision model's feature size and
envelope (the small holes go), reads the Coin scene the view provider built
(triangles, per-partition colours, the switched-off bore), saves the 3D view,
undoes, and writes what it saw to $CONTACTS_GUI_RESULT."""
import os
import sys

import FreeCADGui
from pivy import coin

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))  # the shared session helpers
import session_helpers  # noqa: E402
from session_helpers import wait  # noqa: E402

out_dir = os.environ["CONTACTS_GUI_OUT"]
report = {"errors": []}


def named(root, name):
    search = coin.SoSearchAction()
    search.setName(coin.SbName(name))
    search.setInterest(coin.SoSearchAction.FIRST)
    search.setSearchingAll(True)
    search.apply(root)
    path = search.getPath()
    return path.getTail() if path else None


def face_sets(node):
    return [node.getChild(i) for i in range(node.getNumChildren()) if isinstance(node.getChild(i), coin.SoIndexedFaceSet)]


def centre_on_screen(view, model):
    """Where the centre of the model's bounding box (from its MeshPoints, not the scene graph) lands in
    the view: (x, y) with (0, 0) bottom left and (1, 1) top right."""
    points = [(p.x, p.y, p.z) for p in model.MeshPoints]
    centre = [(min(c) + max(c)) / 2 for c in zip(*points)]
    region = view.getViewer().getSoRenderManager().getViewportRegion()
    volume = view.getCameraNode().getViewVolume(region.getViewportAspectRatio())
    screen = volume.projectToScreen(coin.SbVec3f(*centre))
    return list(screen.getValue())[:2]


def run():
    doc = session_helpers.open_sample_in_workbench()
    report["command_listed"] = "Contacts_ShowSimulationModel" in FreeCADGui.listCommands()
    cover = next(o for o in doc.Objects if o.Label == "Front-cover")
    bearing = next(o for o in doc.Objects if o.Label == "Bearing-front")
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(cover)
    FreeCADGui.Selection.addSelection(bearing)
    undo_before = list(doc.UndoNames)
    FreeCADGui.runCommand("Contacts_ShowSimulationModel")
    wait(0.3)
    models = [o for o in doc.Objects if getattr(getattr(o, "Proxy", None), "Type", None) == "SimulationModel"]
    report["models"] = len(models)
    if not models:
        return
    model = models[0]
    report["undo_added"] = [n for n in doc.UndoNames if n not in undo_before]
    report["label"] = model.Label
    report["triangles_coarse"] = model.Triangles
    model.FeatureSize = 2.5
    model.Envelope = 5.0
    doc.recompute()
    wait(0.3)
    report["simplified"] = model.Simplified
    report["hausdorff"] = model.Hausdorff.Value
    report["triangles"] = model.Triangles
    report["switched_off"] = list(model.SwitchedOff)
    report["mesh_partitions"] = sorted(set(model.MeshPartitions))
    # The Coin scene under the object's root node
    root = model.ViewObject.RootNode
    active, off = named(root, "Partitions"), named(root, "SwitchedOff")
    report["layers_found"] = active is not None and off is not None
    if not report["layers_found"]:
        return
    (faces,) = face_sets(active)
    (off_faces,) = face_sets(off)
    indices = list(faces.coordIndex.getValues())
    report["active_triangles"] = len(indices) // 4
    report["off_triangles"] = len(list(off_faces.coordIndex.getValues())) // 4
    report["material_index"] = list(faces.materialIndex.getValues())
    material = active.getChild(0)
    report["colours"] = [list(c.getValue()) for c in material.diffuseColor.getValues()]
    report["off_striped"] = any(isinstance(off.getChild(i), coin.SoTexture2) for i in range(off.getNumChildren()))
    report["legend"] = named(root, "SimulationModelLegend") is not None
    # The mesh partitions of the triangles, in the order drawn
    tri_partitions = list(model.MeshPartitions)
    report["drawn_partitions"] = [p for p in tri_partitions if p not in model.SwitchedOff]
    # Screenshot: the cover's model alone, from the front (the bore of the bearing striped).
    for o in doc.Objects:
        if o is not model and hasattr(o, "Shape"):
            o.ViewObject.Visibility = False
    view = FreeCADGui.activeDocument().activeView()
    wait(0.3)
    view.viewIsometric()
    view.fitAll()
    wait(0.5)
    path = os.path.join(out_dir, "simulation_model_front_cover.png")
    view.saveImage(path, 900, 700, "White")
    report["png"] = path
    report["centre_on_screen"] = centre_on_screen(view, model)
    view.viewTop()
    view.fitAll()
    wait(0.3)
    report["centre_on_screen_top"] = centre_on_screen(view, model)
    path = os.path.join(out_dir, "simulation_model_front_cover_top.png")
    view.saveImage(path, 900, 700, "White")
    report["png_top"] = path
    for o in doc.Objects:
        if hasattr(o, "Shape"):
            o.ViewObject.Visibility = True
    # Hiding the model hides its drawing
    switch = named(root, "SimulationModelSwitch")
    model.ViewObject.Visibility = False
    report["hidden_switch"] = switch.whichChild.getValue()
    model.ViewObject.Visibility = True
    report["shown_switch"] = switch.whichChild.getValue()
    # Undo removes the object (the property changes first, then the command's transaction)
    name = model.Name
    while doc.UndoCount:
        doc.undo()
    report["undone"] = doc.getObject(name) is None


session_helpers.run_and_report(run, report)
