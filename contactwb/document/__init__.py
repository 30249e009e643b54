"""FreeCAD adapters: a document's visible solids as bodies (bodies), Part
shapes into the extension (shapes), contacts and joints of a document
(analysis), files opened as assemblies (files), a document's analyses as
results (export), what our objects are (identify), FreeCAD as a library
(freecad_setup). Imports contactwb.core only."""
