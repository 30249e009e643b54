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
        from PySide2 import QtCore
        from contactwb.gui.viewproviders import attach
        # after the GUI document has restored its own view providers
        QtCore.QTimer.singleShot(0, lambda name=doc_name: attach.attach_view_providers(name))


def install():
    gui_hooks.install(GuiHooks())
