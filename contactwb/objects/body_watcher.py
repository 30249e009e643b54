"""The observer keeping live contact analyses in step with their bodies: it
marks an analysis touched as soon as one of its bodies moves, changes shape or
is deleted (FreeCAD itself only recomputes it, silently), so the tree shows it
out of date before the recompute; and it removes the contacts a recompute no
longer found once that recompute is over.

Undo: a recompute that updates a live analysis is recorded as one entry,
RECOMPUTE_TRANSACTION (its contacts found, changed and removed, with the
group's membership), never as FreeCAD's implicit "Delete" of the contacts it
removed. Undoing that entry also undoes the user's action it followed (the
move or the deletion that made the analysis out of date), so one Ctrl+Z
restores the part and its contacts together; redo replays both."""
from contactwb.document.identify import (analyses, is_contact, is_contact_analysis, is_interference,
                                         is_interference_group, is_joint)

RECOMPUTE_TRANSACTION = "Recompute contacts"
# Entries whose own run updates the analyses: a recompute entry right above
# one of them followed no user edit (an undo had made the analysis stale).
OWN_TRANSACTIONS = ("Find contacts", "Derive joints", RECOMPUTE_TRANSACTION)


class BodyWatcher:
    """Marks an analysis touched when a body it depends on moves, changes
    shape or is deleted (FreeCAD itself only recomputes it, silently)."""

    WATCHED = ("Placement", "Shape", "LinkPlacement", "LinkedObject", "Group")

    def __init__(self):
        self.documents = set()
        self.pending = {}  # document name -> contacts to remove once its recompute is over
        self.recording = set()  # documents whose recompute this watcher records as one undo entry
        self.chaining = False  # an undo or redo this watcher runs itself

    def _touch_dependents(self, obj, deleted=False):
        doc = obj.Document
        if doc.Name not in self.documents or is_contact(obj) or is_contact_analysis(obj) or is_joint(obj) \
                or is_interference(obj) or is_interference_group(obj):
            return
        if doc.Transacting:
            # an undo or redo: it restores the analyses with their bodies
            # (the recompute that followed an edit is undone with it)
            return
        for group in analyses(doc):
            if not getattr(group, "UpdateOnRecompute", False):
                continue
            if group.Name == obj.Name or "Touched" in group.State:
                continue
            if obj in group.OutListRecursive:
                if not getattr(group, "OutOfDate", True):
                    group.OutOfDate = True  # recorded with the edit
                group.touch()

    def slotChangedObject(self, obj, prop):
        if prop not in self.WATCHED:
            return
        try:
            self._touch_dependents(obj)
        except Exception:  # an observer must never break an edit
            pass

    def slotCreatedObject(self, obj):
        # a new part (or one brought back by an undo): the document-wide
        # analyses may have missed its contacts
        try:
            doc = obj.Document
            if doc.Recomputing or doc.Transacting or doc.Name not in self.documents:
                return
            if not (hasattr(obj, "Shape") or obj.isDerivedFrom("App::Link") or obj.isDerivedFrom("App::Part")):
                return
            for group in analyses(doc):
                if group.UpdateOnRecompute and group.Scope != "Selection":
                    group.touch()
        except Exception:
            pass

    def slotBeforeRecomputeDocument(self, doc):
        """Opens the recompute's undo entry when a live analysis is out of
        date and no command has its own transaction open."""
        try:
            if doc.Name not in self.documents or not doc.UndoMode or doc.HasPendingTransaction:
                return
            import FreeCAD
            if FreeCAD.getActiveTransaction():
                return
            if any(group.UpdateOnRecompute and "Touched" in group.State for group in analyses(doc)):
                doc.openTransaction(RECOMPUTE_TRANSACTION)
                self.recording.add(doc.Name)
        except Exception:  # an observer must never break a recompute
            pass

    def slotRecomputedDocument(self, doc):
        names = self.pending.pop(doc.Name, [])
        for name in names:
            if doc.getObject(name) is not None:
                doc.removeObject(name)
        if doc.Name in self.recording:
            self.recording.discard(doc.Name)
            import FreeCAD
            active = FreeCAD.getActiveTransaction()
            if active and active[0] == RECOMPUTE_TRANSACTION:
                # closes it also when nothing changed (no entry then): left
                # open, it would take the next edit under its name
                FreeCAD.closeActiveTransaction()
            elif doc.HasPendingTransaction:
                doc.commitTransaction()

    def slotUndoDocument(self, doc):
        # the recompute entry undone: undo the user's action it followed too
        self._undo_or_redo_with_recompute(doc, doc.undo)

    def slotRedoDocument(self, doc):
        # the user's action redone: its recompute entry too
        self._undo_or_redo_with_recompute(doc, doc.redo)

    def _undo_or_redo_with_recompute(self, doc, step):
        """After an undo or redo of a watched document: when our recompute
        entry and the user's action it followed are split by it, `step`
        (doc.undo or doc.redo) once more so they go together."""
        if self.chaining or doc.Name not in self.documents:
            return
        if doc.RedoNames[:1] == [RECOMPUTE_TRANSACTION] and doc.UndoNames \
                and doc.UndoNames[0] not in OWN_TRANSACTIONS:
            self._chain(step)
        self._restore_states(doc)

    @staticmethod
    def _restore_states(doc):
        """An undo or redo brings back the analyses' contacts with their
        bodies, and OutOfDate as it was then: out of date (touched) or
        current (not touched, though FreeCAD touched it relinking bodies)."""
        try:
            for group in analyses(doc):
                if not group.UpdateOnRecompute:
                    continue
                if getattr(group, "OutOfDate", False):
                    group.touch()
                else:
                    group.purgeTouched()
                    # its results brought back by the undo are current too (a
                    # touched one would be saved as needing a recompute)
                    for child in group.Group:
                        if "Touched" in child.State:
                            child.purgeTouched()
                        for grandchild in getattr(child, "Group", []) if is_interference_group(child) else []:
                            if "Touched" in grandchild.State:
                                grandchild.purgeTouched()
        except Exception:
            pass

    def _chain(self, step):
        """Runs the chained undo or redo now, inside the signal of the one
        that asked for it (a deferred one could race with a script's next
        undo)."""
        self.chaining = True
        try:
            step()
        finally:
            self.chaining = False


_watcher = None


def watch_document(doc):
    """Installs (once) the observer marking this document's analyses touched."""
    global _watcher
    import FreeCAD
    if _watcher is None:
        _watcher = BodyWatcher()
        FreeCAD.addDocumentObserver(_watcher)
    _watcher.documents.add(doc.Name)


def pending_removal(doc, names):
    """Contacts to remove once the document's recompute is over."""
    watch_document(doc)
    _watcher.pending.setdefault(doc.Name, []).extend(names)


def remove_after_recompute(doc, objects):
    """Removes contacts no longer found: at once outside a recompute; inside
    one (the group's execute), once it is over, since FreeCAD defers and
    mixes up removals made while recomputing."""
    if not objects:
        return
    if not doc.Recomputing:
        for obj in objects:
            doc.removeObject(obj.Name)
        return
    pending_removal(doc, [obj.Name for obj in objects])
