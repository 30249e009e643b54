"""The document of the document tests, built the same way headless
(tests/test_documents.py) and in the GUI (tests/gui/document_gui_session.py,
which FreeCAD runs itself and which puts tests/ on its sys.path): a plate
with a shaft in its bore (CLJ, cylindrical joint) and a block on it (PLF,
planar joint), their contact analysis with joints, and an object of no
workbench. FreeCAD and the workbench are imported only when it is called:
the GUI session imports this module in a step where contactwb must not be
importable."""


def build_contacts_document(name="ContactsDoc"):
    """The document, recomputed and not saved."""
    import FreeCAD
    import Part
    from contactwb.make import make_contact_analysis
    doc = FreeCAD.newDocument(name)
    plate = doc.addObject("Part::Feature", "Plate")
    plate.Shape = Part.makeBox(40, 40, 10, FreeCAD.Vector(-20, -20, 0)).cut(Part.makeCylinder(5, 10))
    shaft = doc.addObject("Part::Feature", "Shaft")
    shaft.Shape = Part.makeCylinder(5, 30, FreeCAD.Vector(0, 0, -10))
    block = doc.addObject("Part::Box", "Block")
    block.Length, block.Width, block.Height = 10, 10, 5
    block.Placement.Base = FreeCAD.Vector(8, 8, 10)
    note = doc.addObject("App::FeaturePython", "Note")
    note.addProperty("App::PropertyString", "Text", "Note", "")
    note.Text = "kept"
    doc.recompute()
    make_contact_analysis(doc, derive_joints=True)
    doc.recompute()
    return doc
