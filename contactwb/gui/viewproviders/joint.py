"""View provider of a Joint: its axis glyphs (contactwb.gui.overlay.joint_glyphs)
over the bodies, labelled and pickable (a click on a glyph selects the
joint); a selected joint (tree, view or joints panel) is drawn in the
selection colour; double-click selects the faces of its contacts.

Saved files name ViewProviderJoint (also by its old module,
contactwb.gui.joint_view): a permanent name."""
import FreeCAD
import FreeCADGui
from pivy import coin

import contactwb
from contactwb.gui.overlay.joint_glyphs import joint_glyphs
from contactwb.gui.viewproviders.base import ViewProvider


class _SelectionHighlight:
    """One selection observer for every joint: redraws the joints whose
    selected state changed, in the selection colour or their own."""

    def __init__(self):
        self.highlighted = set()  # (document name, joint name)

    def _update(self, *_):
        try:
            from contactwb.document.identify import is_joint
            selected = {(o.Document.Name, o.Name) for o in FreeCADGui.Selection.getSelection("*") if is_joint(o)}
            for doc_name, name in selected ^ self.highlighted:
                doc = FreeCAD.listDocuments().get(doc_name)
                joint = doc.getObject(name) if doc else None
                proxy = getattr(getattr(joint, "ViewObject", None), "Proxy", None)
                if isinstance(proxy, ViewProviderJoint):
                    proxy.highlighted = (doc_name, name) in selected
                    proxy.redraw()
            self.highlighted = selected
        except Exception as error:  # an observer must never break the selection
            FreeCAD.Console.PrintWarning(f"Contacts: joint highlight failed: {error}\n")

    addSelection = removeSelection = setSelection = clearSelection = _update


class _GlyphClicks:
    """A left click in a 3D view whose picked object is a Joint selects that
    joint (with Ctrl: adds it): FreeCAD's selection ignores a Python view
    provider's own Coin nodes. One event callback per view."""

    def __init__(self):
        self.views = {}  # id(view) -> (view, callback)

    def watch(self, doc_name):
        gui_doc = FreeCADGui.getDocument(doc_name)
        if gui_doc is None:
            return
        for view in gui_doc.mdiViewsOfType("Gui::View3DInventor"):
            if id(view) in self.views:
                continue
            callback = view.addEventCallbackPivy(coin.SoMouseButtonEvent.getClassTypeId(),
                                                 lambda cb, v=view: self.clicked(v, cb))
            self.views[id(view)] = (view, callback)

    def clicked(self, view, callback):
        try:
            event = callback.getEvent()
            if event.getButton() != coin.SoMouseButtonEvent.BUTTON1 or event.getState() != coin.SoButtonEvent.UP:
                return
            position = event.getPosition().getValue()
            info = view.getObjectInfo((int(position[0]), int(position[1])))
            doc = FreeCAD.listDocuments().get(info["Document"]) if info else None
            joint = doc.getObject(info["Object"]) if doc else None
            proxy = getattr(getattr(joint, "ViewObject", None), "Proxy", None)
            if not isinstance(proxy, ViewProviderJoint):
                return
            add = event.wasCtrlDown()
            doc_name, name = joint.Document.Name, joint.Name

            def select():  # after FreeCAD's own handling of the click, which clears the selection
                target = FreeCAD.listDocuments().get(doc_name)
                target = target.getObject(name) if target else None
                if target is not None:
                    if not add:
                        FreeCADGui.Selection.clearSelection()
                    FreeCADGui.Selection.addSelection(target)
            from PySide2 import QtCore
            QtCore.QTimer.singleShot(0, select)
        except Exception as error:  # a click must never raise into the view
            FreeCAD.Console.PrintWarning(f"Contacts: joint pick failed: {error}\n")


_highlight = None
_clicks = _GlyphClicks()


def _install_highlight():
    global _highlight
    if _highlight is None:
        _highlight = _SelectionHighlight()
        FreeCADGui.Selection.addObserver(_highlight)


class ViewProviderJoint(ViewProvider):
    """Draws its Joint's glyphs (over the bodies: an annotation)."""

    def attach(self, vobj):
        super().attach(vobj)
        self.glyphs = coin.SoAnnotation()
        self.glyphs.setName("JointGlyphs")
        self.axes = self.arrows = 0
        self.highlighted = False
        vobj.addDisplayMode(self.glyphs, "Glyphs")
        _install_highlight()

    def getDisplayModes(self, vobj):
        return ["Glyphs"]

    def getDefaultDisplayMode(self):
        return "Glyphs"

    def setDisplayMode(self, mode):
        return mode

    def updateData(self, obj, prop):
        if prop in ("AxisPoints", "AxisDirections", "Translations", "Centre", "GlyphLength", "Label", "JointType"):
            self.redraw()

    def redraw(self):
        glyphs = getattr(self, "glyphs", None)
        if glyphs is None:
            return
        glyphs.removeAllChildren()
        try:
            from contactwb.gui.overlay.colours import selection_colour
            node, self.axes, self.arrows = joint_glyphs(self.Object, getattr(self, "highlighted", False),
                                                        selection_colour())
        except Exception as error:  # drawing only
            FreeCAD.Console.PrintWarning(f"Contacts: cannot draw joint '{self.Object.Label}': {error}\n")
            return
        glyphs.addChild(node)
        try:
            _clicks.watch(self.Object.Document.Name)
        except Exception:  # no view yet (a document opened without the GUI): the next redraw
            pass

    def getIcon(self):
        return contactwb.icon_path("Contacts_DeriveJoints")

    # FreeCAD's unified selection picks the glyph's path and asks which
    # element it is (the whole joint); _GlyphClicks selects it on a click.
    def useNewSelectionModel(self):
        return True

    def getElementPicked(self, picked_point):
        return ""

    def doubleClicked(self, vobj):
        """Selects the faces of the joint's contacts."""
        FreeCADGui.Selection.clearSelection()
        for contact in vobj.Object.Contacts:
            for links in (contact.FacesA, contact.FacesB):
                for root, subnames in links:
                    for subname in subnames:
                        FreeCADGui.Selection.addSelection(root.Document.Name, root.Name, subname)
        return True
