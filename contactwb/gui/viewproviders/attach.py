"""Gives the workbench's objects their view providers: a new object (the
document objects' code calls contactwb.objects.gui_hooks, which
contactwb.gui.hooks points here), an analysis just found (drawn at once), and
the objects of a document restored without them (made headless, or saved
without the workbench)."""
import FreeCAD

from contactwb.document.identify import (CONTACT, CONTACT_ANALYSIS, INTERFERENCE, INTERFERENCE_GROUP, JOINT,
                                         SIMULATION_MODEL, is_contact, is_contact_analysis, is_joint,
                                         is_simulation_model, proxy_kind)
from contactwb.gui.viewproviders.contact import ViewProviderContact
from contactwb.gui.viewproviders.contact_analysis import ViewProviderContactAnalysis
from contactwb.gui.viewproviders.interference import ViewProviderInterference, ViewProviderInterferenceGroup
from contactwb.gui.viewproviders.joint import ViewProviderJoint
from contactwb.gui.viewproviders.simulation_model import ViewProviderSimulationModel

VIEW_PROVIDERS = {
    CONTACT_ANALYSIS: ViewProviderContactAnalysis,
    CONTACT: ViewProviderContact,
    JOINT: ViewProviderJoint,
    SIMULATION_MODEL: ViewProviderSimulationModel,
    INTERFERENCE: ViewProviderInterference,
    INTERFERENCE_GROUP: ViewProviderInterferenceGroup,
}


def new_view_provider(obj):
    """The view provider of a Contacts object just made (none for another object)."""
    provider_class = VIEW_PROVIDERS.get(proxy_kind(obj))
    if provider_class is not None:
        provider_class(obj.ViewObject)


def attach_analysis(group):
    """Gives a ContactAnalysis group and its contacts their view providers,
    and draws the contacts (unless the drawing shown is of these very
    contacts and regions: a Find contacts again that changed nothing)."""
    provider = group.ViewObject.Proxy
    given = False
    if not isinstance(provider, ViewProviderContactAnalysis):
        provider = ViewProviderContactAnalysis(group.ViewObject)
        given = True
    for child in group.Group:
        if is_contact(child) and not isinstance(child.ViewObject.Proxy, ViewProviderContact):
            ViewProviderContact(child.ViewObject)
            given = True
    if given or provider.drawing_out_of_date():
        provider.rebuild()
    else:
        provider.update_switch()


def give_view_provider(obj, provider_class):
    vobj = obj.ViewObject
    if isinstance(vobj.Proxy, provider_class):
        return False
    provider = provider_class(vobj)
    if getattr(provider, "Object", None) is None:
        # FreeCAD 0.20 calls attach() only for a view provider made with its object
        provider.attach(vobj)
        if hasattr(provider, "getDisplayModes"):  # the modes attach() added, then the first shown
            vobj.DisplayMode = provider.getDisplayModes(vobj)
            vobj.DisplayMode = provider.getDefaultDisplayMode()
    return True


def attach_view_providers(doc_name):
    """View providers for the Contacts objects of a document that has none
    (made headless, or saved without the workbench)."""
    doc = FreeCAD.listDocuments().get(doc_name)
    if doc is None:
        return
    for obj in doc.Objects:
        if getattr(obj, "ViewObject", None) is None or getattr(obj, "Proxy", None) is None:
            continue
        if is_contact_analysis(obj):
            given = give_view_provider(obj, ViewProviderContactAnalysis)
            for child in obj.Group:
                if is_contact(child):
                    given |= give_view_provider(child, ViewProviderContact)
            if given:
                obj.ViewObject.Proxy.rebuild()
        elif proxy_kind(obj) == INTERFERENCE:
            give_view_provider(obj, ViewProviderInterference)
        elif proxy_kind(obj) == INTERFERENCE_GROUP:
            give_view_provider(obj, ViewProviderInterferenceGroup)
        elif is_joint(obj) and give_view_provider(obj, ViewProviderJoint):
            obj.ViewObject.Proxy.redraw()
        elif is_simulation_model(obj) and \
                give_view_provider(obj, ViewProviderSimulationModel):
            obj.ViewObject.Proxy.rebuild()
