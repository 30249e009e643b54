"""View provider of a ContactAnalysis group: draws its contacts over the
bodies (contactwb.gui.overlay.contact_overlay). The drawing follows the
group's Visibility, and each side of a contact its body's; it is rebuilt from
the document when the view provider attaches (also on re-opening a file),
when contacts are added or deleted and when a body moves.

Saved files name ViewProviderContactAnalysis (also by its old module,
contactwb.gui.view_providers): a permanent name."""
import weakref

import FreeCAD
import FreeCADGui
from pivy import coin

from contactwb.document.identify import is_contact
from contactwb.gui import actions
from contactwb.gui.overlay.contact_overlay import ContactOverlay
from contactwb.gui.overlay.watcher import OverlayWatcher
from contactwb.gui.panels import task_panel
from contactwb.gui.viewproviders.base import ViewProvider, add_action

RESTORE_RETRY_MS = 50  # a drawing asked for while the document is opening waits this long, again


class ViewProviderContactAnalysis(ViewProvider):
    """Draws the group's contacts (ContactOverlay) under a switch of its own
    that follows the group's Visibility. (Not as a display mode: a group with
    display modes shows again any child one hides.)"""

    def attach(self, vobj):
        super().attach(vobj)
        self._stale, self._scheduled = False, False
        self.overlay = ContactOverlay(vobj.Object.Document.Name)
        # weak: the overlay must not keep a closed document's view provider alive
        self.overlay.on_body_changed = weakref.WeakMethod(self.schedule_rebuild)
        self.overlay.on_recomputed = weakref.WeakMethod(self.after_recompute)
        self.switch = coin.SoSwitch()
        self.switch.setName("ContactsSwitch")
        self.switch.addChild(self.overlay.root)
        vobj.RootNode.addChild(self.switch)
        self.onChanged(vobj, "Visibility")
        OverlayWatcher.register(self.overlay)
        # Drawn once the document is loaded (on restore the bodies are meshed
        # by then, and their triangulation is reused); a new analysis is drawn
        # at once by attach() below.
        self.schedule_rebuild()

    def onChanged(self, vobj, prop):
        if prop == "Visibility":
            self.update_switch()

    def is_stale(self):
        """Whether the analysis waits for a recompute after its bodies
        changed: its paint would show contacts that may no longer exist."""
        obj = getattr(self, "Object", None)
        try:
            return bool(getattr(obj, "UpdateOnRecompute", False)) and "Touched" in obj.State
        except Exception:
            return False

    def update_switch(self):
        switch = getattr(self, "switch", None)
        if switch is None:
            return
        shown = self.Object.ViewObject.Visibility and not self.is_stale()
        switch.whichChild.setValue(coin.SO_SWITCH_ALL if shown else coin.SO_SWITCH_NONE)

    def drawing_out_of_date(self):
        """Whether the drawing shown is not that of the group as it is: other
        contacts, other regions (contactwb.objects.regions), another count of
        interferences in the legend, other preferences, or a rebuild asked for."""
        from contactwb.document.identify import interferences_of
        from contactwb.gui.overlay.contact_overlay import drawing_settings
        from contactwb.objects import regions
        overlay = getattr(self, "overlay", None)
        if overlay is None or self._stale:
            return True
        group = self.Object
        contacts = tuple(c.Name for c in group.Group if is_contact(c) and c.FacesA and c.FacesB)
        # (no regions cached: an undo dropped them; the bodies' own moves redraw then)
        return (contacts != overlay.names or regions.generation(group) not in (None, overlay.region_generation)
                or len(interferences_of(group)) != overlay.interferences
                or overlay.drawn_with != drawing_settings())

    def after_recompute(self):
        """After a recompute, an undo or a redo: the paint shown while the
        analysis is current, and drawn again if the core's regions changed
        since it was drawn (a part moved, its contacts kept) or a drawing
        waited for the recompute."""
        self.update_switch()
        overlay = getattr(self, "overlay", None)
        if overlay is None or self.is_stale():
            return
        try:
            # other regions, contacts or interferences, or the preferences' paint style or colours
            changed = self.drawing_out_of_date()
        except Exception:  # the group deleted
            return
        if changed:
            self.schedule_rebuild()

    def updateData(self, obj, prop):
        # Contacts deleted, added or found again (Bodies is set by every run):
        # redraw, unless the drawing is of the very same contacts and regions
        # (a Find contacts again that changed nothing). (Group alone is also
        # announced after every attach.)
        overlay = getattr(self, "overlay", None)
        if overlay is None:
            return
        if (prop == "Bodies" and self.drawing_out_of_date()) or (
                prop == "Group" and tuple(c.Name for c in obj.Group if is_contact(c)) != overlay.names):
            self.schedule_rebuild()

    def schedule_rebuild(self):
        """Rebuilds once the current operation (loading, a recompute, a move
        of many bodies) is over."""
        self._stale = True
        if not self._scheduled:
            from PySide2 import QtCore
            self._scheduled = True
            QtCore.QTimer.singleShot(0, self._deferred_rebuild)

    def _deferred_rebuild(self):
        self._scheduled = False
        if not self._stale:
            return
        try:
            self.Object.ViewObject.Visibility  # raises once the group is deleted
            document = self.Object.Document
            busy = document.Restoring or document.Recomputing or document.Transacting
        except Exception:
            return
        if busy:
            # FreeCAD processes events while it opens a document, and the
            # search's progress while it recomputes: the bodies' visibility,
            # the contacts and the group's state are not final yet (drawing
            # now would draw again for every change: once per recompute)
            from PySide2 import QtCore
            self._scheduled = True
            QtCore.QTimer.singleShot(RESTORE_RETRY_MS, self._deferred_rebuild)
            return
        self.rebuild()

    def rebuild(self):
        """Draws the group's contacts now."""
        self._stale = False
        contacts = [c for c in self.Object.Group if is_contact(c) and c.FacesA and c.FacesB]
        self.update_switch()
        from contactwb.document.units import tolerances_used
        fuzzy = max(10 * tolerances_used(self.Object)[0], 1e-4)
        try:
            self.overlay.build(contacts, fuzzy=fuzzy, group=self.Object)
        except Exception as error:  # a drawing problem must not break the document
            FreeCAD.Console.PrintError(f"Contacts: cannot draw '{self.Object.Label}': {error}\n")
            return
        if self.overlay.failures:
            FreeCAD.Console.PrintWarning(
                f"Contacts: {len(self.overlay.failures)} faces of '{self.Object.Label}' not drawn, "
                f"first: {self.overlay.failures[0]}\n")
        OverlayWatcher.refresh_highlight(self.Object.Document.Name)

    def claimChildren(self):
        return self.Object.Group

    def setEdit(self, vobj, mode=0):
        """Double-click or Edit: the task panel, to find the contacts again."""
        if mode != 0:
            return None
        task_panel.open_panel(vobj.Object.Document, vobj.Object)
        return True

    def unsetEdit(self, vobj, mode=0):
        return None

    def doubleClicked(self, vobj):
        task_panel.open_panel(vobj.Object.Document, vobj.Object)
        return True

    def setupContextMenu(self, vobj, menu):
        group = vobj.Object
        add_action(menu, "Find contacts again...", lambda: task_panel.open_panel(group.Document, group))
        add_action(menu, "Contact table", lambda: FreeCADGui.runCommand("Contacts_ShowContactTable"))
        add_action(menu, "Export contacts...", lambda: actions.export_analysis(group))
