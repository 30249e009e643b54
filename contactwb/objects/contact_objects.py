"""Proxies of the contact analysis (a group) and of each contact (a child).

Saved files refer to `contactwb.objects.contact_objects.ContactAnalysis` and
`...Contact`: these names are permanent."""


def is_contact_analysis(obj):
    """Whether a document object is a ContactAnalysis group (also once re-opened)."""
    return getattr(getattr(obj, "Proxy", None), "Type", None) == "ContactAnalysis"


def is_contact(obj):
    """Whether a document object is one Contact of an analysis."""
    return getattr(getattr(obj, "Proxy", None), "Type", None) == "Contact"


class ContactAnalysis:
    """A group holding the contacts found among some objects (a snapshot:
    run Contacts_FindContacts again after moving parts)."""

    def __init__(self, obj):
        obj.Proxy = self
        self.Type = "ContactAnalysis"
        obj.addProperty("App::PropertyLinkList", "Sources", "Contacts",
                        "Objects analysed (empty: every visible solid of the document)")
        obj.addProperty("App::PropertyLength", "LinearTolerance", "Contacts", "Linear tolerance used")
        obj.addProperty("App::PropertyAngle", "AngularTolerance", "Contacts", "Angular tolerance used")
        obj.addProperty("App::PropertyInteger", "BodyCount", "Contacts", "Bodies analysed")
        obj.addProperty("App::PropertyStringList", "Summary", "Contacts", "Counts by contact type")
        obj.addProperty("App::PropertyStringList", "Messages", "Contacts", "What was skipped and why")
        for name in ("LinearTolerance", "AngularTolerance", "BodyCount", "Summary", "Messages"):
            obj.setEditorMode(name, 1)  # read-only: results, not inputs

    def onDocumentRestored(self, obj):
        obj.Proxy = self

    def dumps(self):
        return None

    def loads(self, state):
        self.Type = "ContactAnalysis"


class Contact:
    """One functional contact: its type, the two bodies and their faces."""

    def __init__(self, obj):
        obj.Proxy = self
        self.Type = "Contact"
        obj.addProperty("App::PropertyString", "ContactType", "Contact", "PLF, CLJ, CJU, SPF, LAF, SPT or TRF")
        obj.addProperty("App::PropertyString", "BodyA", "Contact", "First body")
        obj.addProperty("App::PropertyString", "BodyB", "Contact", "Second body")
        obj.addProperty("App::PropertyXLinkSubList", "FacesA", "Contact", "Faces of the first body in contact")
        obj.addProperty("App::PropertyXLinkSubList", "FacesB", "Contact", "Faces of the second body in contact")
        obj.addProperty("App::PropertyArea", "Area", "Contact", "Common area (0 for circle contacts)")
        obj.addProperty("App::PropertyBool", "Partial", "Contact", "Revolution contact spanning under 180 degrees")
        obj.addProperty("App::PropertyAngle", "Span", "Contact", "Common angular span")
        obj.addProperty("App::PropertyLength", "Radius", "Contact", "Radius (cylinder, sphere, ball)")
        obj.addProperty("App::PropertyVector", "Point", "Contact", "A point of the contact (axis point, centre)")
        obj.addProperty("App::PropertyVector", "Direction", "Contact", "Normal of the first body, or axis")
        for name in obj.PropertiesList:
            if obj.getGroupOfProperty(name) == "Contact":
                obj.setEditorMode(name, 1)

    def onDocumentRestored(self, obj):
        obj.Proxy = self

    def dumps(self):
        return None

    def loads(self, state):
        self.Type = "Contact"
