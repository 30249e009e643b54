"""Compatibility shim (saved files name
contactwb.gui.simulation_model_view.ViewProviderSimulationModel): the view
provider moved to contactwb.gui.viewproviders.simulation_model, the drawing to
contactwb.gui.overlay.simulation_model, the command to
contactwb.gui.commands.simulation_model."""
from contactwb.gui.commands.simulation_model import COMMANDS, Contacts_ShowSimulationModel  # noqa: F401
from contactwb.gui.overlay.simulation_model import *  # noqa: F401,F403
from contactwb.gui.viewproviders.simulation_model import ViewProviderSimulationModel  # noqa: F401
