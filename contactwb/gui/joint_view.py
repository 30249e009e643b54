"""Compatibility shim (saved files name contactwb.gui.joint_view.ViewProviderJoint):
the view provider moved to contactwb.gui.viewproviders.joint, the glyphs to
contactwb.gui.overlay.joint_glyphs, the joints panel to
contactwb.gui.panels.joints_panel."""
from contactwb.gui.overlay.joint_glyphs import *  # noqa: F401,F403
from contactwb.gui.panels import joints_panel as _panel
from contactwb.gui.panels.joints_panel import JointsPanel, open_joints_panel, render_graph  # noqa: F401
from contactwb.gui.viewproviders.joint import ViewProviderJoint  # noqa: F401


def __getattr__(name):  # live module state (current_panel)
    return getattr(_panel, name)
