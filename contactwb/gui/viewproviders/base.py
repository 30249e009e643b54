"""The base of the workbench's view providers (nothing to save: every drawing
is rebuilt from the document) and their context-menu helper."""
import contactwb


class ViewProvider:
    """What every view provider here shares: nothing to save."""

    def __init__(self, vobj):
        vobj.Proxy = self

    def attach(self, vobj):
        self.Object = vobj.Object

    def getIcon(self):
        return contactwb.icon_path("Contacts_FindContacts")

    # Nothing to save (the drawing is rebuilt from the document). FreeCAD 0.20
    # under Python 3.11 asks __getstate__ before dumps: both must say so.
    def __getstate__(self):
        return None

    def __setstate__(self, state):
        return None

    def dumps(self):
        return None

    def loads(self, state):
        return None


class OneDisplayMode:
    """A view provider drawing in one display mode of its own, DISPLAY_MODE
    (added by its attach()): FreeCAD lists, defaults to and keeps that mode."""
    DISPLAY_MODE = None

    def getDisplayModes(self, vobj):
        return [self.DISPLAY_MODE]

    def getDefaultDisplayMode(self):
        return self.DISPLAY_MODE

    def setDisplayMode(self, mode):
        return mode


def add_action(menu, text, slot):
    """A context-menu entry running slot()."""
    action = menu.addAction(text)
    action.triggered.connect(slot)
    return action
