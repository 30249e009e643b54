"""The workbench's commands, one module per group (analysis, simulation
model, haptics); register() adds them all to FreeCAD for InitGui.py."""
import FreeCADGui

from contactwb.gui.commands import annotate, contacts, haptics, mechanism, simulation_model
from contactwb.gui.commands.contacts import (CONTEXT_COMMANDS, Contacts_DeriveJoints,  # noqa: F401
                                             Contacts_ExportContacts, Contacts_FindContacts,
                                             Contacts_GhostBodies, Contacts_IsolateContact,
                                             Contacts_OpenSample, Contacts_ShowAll, Contacts_ShowContactTable,
                                             Contacts_ShowJoints, Contacts_ShowPartitions)
from contactwb.gui.commands.annotate import Contacts_AnnotateContact  # noqa: F401
from contactwb.gui.commands.haptics import Contacts_HapticTrial  # noqa: F401
from contactwb.gui.commands.mechanism import Contacts_ExportMechanism  # noqa: F401
from contactwb.gui.commands.simulation_model import Contacts_ShowSimulationModel  # noqa: F401

# Toolbars (and menu sections) in order: name -> {command name: class}.
TOOLBARS = {
    "Contacts": {**contacts.COMMANDS, **mechanism.COMMANDS, **simulation_model.COMMANDS, **annotate.COMMANDS},
    "Contacts haptics": haptics.COMMANDS,
}


def register():
    """Adds every command to FreeCAD; returns {toolbar name: [command names]} in order."""
    toolbars = {}
    for toolbar, commands in TOOLBARS.items():
        for name, command in commands.items():
            FreeCADGui.addCommand(name, command())
        toolbars[toolbar] = list(commands)
    return toolbars
