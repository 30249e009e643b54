"""What several headless test files build the same way: the bundled motor's
bodies as FreeCAD shapes, and the three-box document of the live-analysis
tests. (Imported by name: pytest puts tests/ on sys.path, conftest.py first.)"""
import os

import FreeCAD

MOTOR = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "Resources", "samples", "motor.step")


def motor_shapes():
    """[(body name, Part.Shape)] of the motor as the core reads it."""
    import Part
    from contactwb import core
    shapes = []
    for body in core.contactcore.read_step(MOTOR).bodies:
        shape = Part.Shape()
        shape.importBrepFromString(body.brep)
        shapes.append((body.name, shape))
    return shapes


def three_boxes(name, undo=False, labels=False):
    """A generator for a pytest fixture: document `name` with Base 10x10x10;
    Top 6x4x5 on it (PLF 24 mm2); Side 10x10x10 beside Base (PLF 100 mm2,
    x = 10); recomputed. undo: undo on, as in the GUI; labels: the labels
    set to the names explicitly. Closes the document after the test."""
    doc = FreeCAD.newDocument(name)
    if undo:
        doc.UndoMode = 1
    base = doc.addObject("Part::Box", "Base")
    top = doc.addObject("Part::Box", "Top")
    top.Length, top.Width, top.Height = 6, 4, 5
    top.Placement.Base = FreeCAD.Vector(2, 3, 10)
    side = doc.addObject("Part::Box", "Side")
    side.Placement.Base = FreeCAD.Vector(10, 0, 0)
    if labels:
        base.Label, top.Label, side.Label = "Base", "Top", "Side"
    doc.recompute()
    name = doc.Name
    yield doc
    if name in FreeCAD.listDocuments():
        FreeCAD.closeDocument(name)
