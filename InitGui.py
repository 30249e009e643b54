# Contacts workbench: GUI registration. FreeCAD execs this file, so the class
# is self-contained and imports lazily in Initialize(). contactwb.gui.hooks
# (light: no Coin, no Qt) sets the hooks through which objects made or restored
# before the workbench is activated get their view providers.
import FreeCADGui

try:
    from contactwb.gui import hooks as contacts_gui_hooks
    contacts_gui_hooks.install()
except Exception as error:  # a broken install must not stop FreeCAD
    import FreeCAD
    FreeCAD.Console.PrintError(f"Contacts: {error}\n")


class ContactsWorkbench(FreeCADGui.Workbench):
    """Functional contacts between the parts of an assembly."""

    MenuText = "Contacts"
    ToolTip = "Find the functional contacts between parts and the joints they allow"

    def __init__(self):
        import contactwb
        self.__class__.Icon = contactwb.icon_path("ContactsWorkbench")

    def Initialize(self):
        from contactwb.gui import commands, preferences
        # Every command, by toolbar; the menu lists them all in that order.
        for toolbar, names in commands.register().items():
            self.appendToolbar(toolbar, names)
            self.appendMenu("&Contacts", names)
        import contactwb
        # The Preferences dialog shows the group "Contacts" with the icon "preferences-contacts"
        FreeCADGui.addIconPath(contactwb.ICONS_DIR)
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
