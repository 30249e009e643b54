"""The session's one selection and document observer for the contact
overlays: highlights the selected contacts and follows the bodies' Visibility,
moves and deletions."""
import weakref

import FreeCAD
import FreeCADGui


# Bodies a haptic trial is moving: (document name, object name). Their
# Placement changes at display rate while the trial panel is open; the
# overlays do not redraw their contacts for each frame (the panel asks for
# one redraw when it closes: follow_body_again).
moving_bodies = set()


def follow_body_again(doc_name, obj_name):
    """Ends a trial's pause on a body: its overlays redraw once."""
    moving_bodies.discard((doc_name, obj_name))
    for overlay in list(OverlayWatcher.overlays):
        if overlay.doc_name == doc_name and obj_name in overlay.path_names:
            method = overlay.on_body_changed
            rebuild = method() if method is not None else None
            if rebuild is not None:
                rebuild()



def _redraw_faces(overlay):
    """Redraws an overlay's faces after one of its bodies changed (on_body_changed
    gives the rebuild to run, or None when there is nothing to redraw)."""
    method = overlay.on_body_changed
    rebuild = method() if method is not None else None
    if rebuild is not None:
        rebuild()

class OverlayWatcher:
    """The session's one selection and document observer: highlights the
    selected contacts and follows the bodies' Visibility, for every overlay
    alive (a weak set: closed documents drop out)."""

    overlays = weakref.WeakSet()
    _installed = None

    @classmethod
    def register(cls, overlay):
        cls.overlays.add(overlay)
        if cls._installed is None:
            cls._installed = cls()
            FreeCADGui.Selection.addObserver(cls._installed)
            FreeCAD.addDocumentObserver(cls._installed)

    @classmethod
    def refresh_highlight(cls, doc_name):
        overlays = [o for o in list(cls.overlays) if o.doc_name == doc_name]
        if not overlays:
            return
        objects, faces = set(), set()
        for selected in FreeCADGui.Selection.getSelectionEx(doc_name, 0):
            if not selected.SubElementNames:
                objects.add(selected.ObjectName)
            for subname in selected.SubElementNames:
                faces.add((selected.ObjectName, subname))
        for overlay in overlays:
            overlay.highlight(objects, faces)

    def _selection_changed(self, doc_name):
        try:
            self.refresh_highlight(doc_name)
        except Exception as error:  # an observer must never break the selection
            FreeCAD.Console.PrintWarning(f"Contacts: highlight failed: {error}\n")

    def addSelection(self, doc, obj, sub, pnt):
        self._selection_changed(doc)

    def removeSelection(self, doc, obj, sub):
        self._selection_changed(doc)

    def setSelection(self, doc):
        self._selection_changed(doc)

    def clearSelection(self, doc):
        for name in [doc] if doc else FreeCAD.listDocuments():
            self._selection_changed(name)

    def _document_settled(self, doc):
        # a recompute (which may change nothing, leaving the analysis up to
        # date), an undo or a redo: the paint's shown-while-current switch
        try:
            for overlay in list(self.overlays):
                if overlay.doc_name == doc.Name and overlay.on_recomputed is not None:
                    method = overlay.on_recomputed()
                    if method is not None:
                        method()
        except Exception as error:
            FreeCAD.Console.PrintWarning(f"Contacts: cannot follow the recompute: {error}\n")

    def slotRecomputedDocument(self, doc):
        self._document_settled(doc)

    def slotUndoDocument(self, doc):
        self._forget_regions(doc)
        self._document_settled(doc)

    def slotRedoDocument(self, doc):
        self._forget_regions(doc)
        self._document_settled(doc)

    @staticmethod
    def _forget_regions(doc):
        # the bodies are back where the undo put them, without a recompute:
        # the cached regions may be those of a later placement
        from contactwb.objects import regions
        regions.forget_document(doc.Name)

    def slotDeletedDocument(self, doc):
        self._forget_regions(doc)

    def slotDeletedObject(self, obj):
        # a body deleted: its contacts lose their links; redraw without them
        try:
            for overlay in list(self.overlays):
                if overlay.doc_name == obj.Document.Name and obj.Name in overlay.path_names:
                    _redraw_faces(overlay)
        except Exception as error:
            FreeCAD.Console.PrintWarning(f"Contacts: cannot follow the bodies: {error}\n")

    def slotChangedObject(self, obj, prop):
        if prop not in ("Visibility", "Placement", "Shape") or not self.overlays:
            return
        try:
            doc_name = obj.Document.Name
            if prop != "Visibility" and (doc_name, obj.Name) in moving_bodies:
                return  # a haptic trial moves it at display rate: no redraw per frame
            for overlay in list(self.overlays):
                if overlay.doc_name != doc_name or obj.Name not in overlay.path_names:
                    continue
                if prop == "Visibility":
                    overlay.update_bodies()
                else:  # a body moved or changed: redraw its faces
                    _redraw_faces(overlay)
        except Exception as error:
            FreeCAD.Console.PrintWarning(f"Contacts: cannot follow the bodies: {error}\n")
