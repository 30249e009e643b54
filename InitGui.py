# Contacts workbench: GUI registration. FreeCAD execs this file, so the class
# is self-contained and imports lazily in Initialize().
import FreeCADGui


class ContactsWorkbench(FreeCADGui.Workbench):
    """Functional contacts between the parts of an assembly."""

    MenuText = "Contacts"
    ToolTip = "Find the functional contacts between parts and the joints they allow"

    def __init__(self):
        import contactwb
        self.__class__.Icon = contactwb.icon_path("ContactsWorkbench")

    def Initialize(self):
        from contactwb.gui import commands, preferences
        # One entry per command module: each registers its commands and
        # returns their names in toolbar order.
        names = []
        names += commands.register()
        from contactwb.gui import simulation_model_view
        names += simulation_model_view.register()
        self.appendToolbar("Contacts", names)
        self.appendMenu("&Contacts", names)
        from contactwb.gui import haptic_panel
        haptic = haptic_panel.register()
        self.appendToolbar("Contacts haptics", haptic)
        self.appendMenu("&Contacts", haptic)
        FreeCADGui.addPreferencePage(preferences.PreferencesPage, "Contacts")

    def ContextMenu(self, recipient):
        if recipient == "View":
            from contactwb.gui import commands
            self.appendContextMenu("Contacts", commands.CONTEXT_COMMANDS)

    def Activated(self):
        pass

    def Deactivated(self):
        pass

    def GetClassName(self):
        return "Gui::PythonWorkbench"


FreeCADGui.addWorkbench(ContactsWorkbench())
