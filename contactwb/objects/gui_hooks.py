"""The GUI's hooks into the document objects. Objects are created and
recomputed headless as well as in the GUI; when the GUI is up, a new object
needs its view provider and a re-found analysis its drawing. The objects (and
the make_* constructors) call these functions; contactwb.gui sets what they do
when it is imported (InitGui.py imports it at start-up), so that nothing
below the GUI imports it. Headless, or before the GUI set them, they do
nothing (contactwb.objects.recovery gives missing view providers back once a
document is restored)."""
import FreeCAD

_hooks = None


def install(hooks):
    """Sets the GUI's hooks: an object with new_object(obj), analysis_found(group)
    and document_restored(doc_name)."""
    global _hooks
    _hooks = hooks


def _call(name, *args):
    if _hooks is not None and FreeCAD.GuiUp:
        getattr(_hooks, name)(*args)


def new_object(obj):
    """`obj` (a ContactAnalysis, Contact, Joint or SimulationModel) was just made:
    give it its view provider."""
    _call("new_object", obj)


def analysis_found(group):
    """A ContactAnalysis's contacts were found (make_contact_analysis): give it
    and its contacts their view providers and draw them now."""
    _call("analysis_found", group)


def document_restored(doc_name):
    """Contacts objects of a document got their proxies back: give them view
    providers once the GUI document has restored its own."""
    _call("document_restored", doc_name)
