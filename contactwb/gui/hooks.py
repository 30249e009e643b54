"""What the document objects' GUI hooks (contactwb.objects.gui_hooks) do in
the GUI: view providers for new objects, the drawing of an analysis just
found, view providers for a restored document's objects. Installed when
contactwb.gui is imported (InitGui.py does at start-up)."""
from contactwb.objects import gui_hooks


class GuiHooks:
    """The view-provider modules are imported at the first call (pivy and
    the drawings load only once there is something to draw)."""

    def new_object(self, obj):
        from contactwb.gui.viewproviders import attach
        attach.new_view_provider(obj)

    def analysis_found(self, group):
        from contactwb.gui.viewproviders import attach
        attach.attach_analysis(group)

    def document_restored(self, doc_name):
        attach_when_restored(doc_name)


RETRY_MS = 50


def attach_when_restored(doc_name):
    """View providers for the document's Contacts objects that have none, once
    the GUI document has restored its own: FreeCAD processes events while it
    opens a document, and an object given a view provider before the GUI
    restores the saved one would end with the saved one unattached."""
    from PySide2 import QtCore

    def attach_now():
        import FreeCAD
        from contactwb.gui.viewproviders import attach
        doc = FreeCAD.listDocuments().get(doc_name)
        if doc is None:
            return
        if doc.Restoring:  # still loading (its GUI part too): later
            QtCore.QTimer.singleShot(RETRY_MS, attach_now)
            return
        attach.attach_view_providers(doc_name)

    QtCore.QTimer.singleShot(0, attach_now)


def install():
    gui_hooks.install(GuiHooks())
