"""What the document objects' GUI hooks (contactwb.objects.gui_hooks) do in
the GUI: view providers for new objects, the drawing of an analysis just
found, view providers for a restored document's objects; and the watch on
the unit preferences that keeps the tree's quantities as the property editor
writes them. Installed when contactwb.gui is imported (InitGui.py does at
start-up)."""
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


class UnitPreferencesObserver:
    """Watches Preferences -> General -> Units (FreeCAD's parameter observer):
    a new unit schema or number of decimals rewrites the quantities' texts the
    recomputes wrote (the tree's description column) and refills the contact
    table, so that they keep saying what the property editor says."""
    PATH = "User parameter:BaseApp/Preferences/Units"

    def onChange(self, group, name):
        if name in ("UserSchema", "Decimals"):
            from PySide2 import QtCore
            # the dialog sets the schema after writing the parameters: relabel once it has
            QtCore.QTimer.singleShot(0, relabel_documents)


def relabel_documents():
    import FreeCAD
    try:
        from contactwb.objects.contact_objects import relabel_quantities
        for doc in FreeCAD.listDocuments().values():
            relabel_quantities(doc)
        from contactwb.gui.panels import contact_table
        contact_table.refresh()
    except Exception as error:  # a label left as it was must not break the preferences dialog
        FreeCAD.Console.PrintError(f"Contacts: the quantities' texts were not rewritten: {error}\n")


_unit_observer = None  # (the parameter group, the observer): FreeCAD detaches a group's observers
                      # when its Python handle goes, so both are held


def watch_unit_preferences():
    global _unit_observer
    if _unit_observer is None:
        import FreeCAD
        group, observer = FreeCAD.ParamGet(UnitPreferencesObserver.PATH), UnitPreferencesObserver()
        group.Attach(observer)
        _unit_observer = (group, observer)


def install():
    gui_hooks.install(GuiHooks())
    watch_unit_preferences()
