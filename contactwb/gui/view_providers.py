"""Compatibility shim (saved files name
contactwb.gui.view_providers.ViewProviderContactAnalysis and
...ViewProviderContact): the module was split by job. View providers:
contactwb.gui.viewproviders.contact_analysis and .contact; the overlay, its
faces, Coin helpers, colours and observer: contactwb.gui.overlay; selecting a
contact's faces: contactwb.gui.actions; preferences: contactwb.gui.settings."""
from contactwb.core.kinds import CIRCLE_TYPES, TYPE_NAMES  # noqa: F401
from contactwb.gui.actions import select_contact_faces  # noqa: F401
from contactwb.gui.overlay.coin_nodes import *  # noqa: F401,F403
from contactwb.gui.overlay.coin_nodes import material as _material, polygon_offset as _polygon_offset  # noqa: F401
from contactwb.gui.overlay.colours import *  # noqa: F401,F403
from contactwb.gui.overlay.contact_overlay import (CIRCLE_FACE_TRANSPARENCY, CIRCLE_WIDTH,  # noqa: F401
                                                   ContactOverlay, path_visible)
from contactwb.gui.overlay.faces import CIRCLE_SEGMENTS, FaceSource, circle_points  # noqa: F401
from contactwb.gui.overlay.faces import pushed_out as _pushed_out  # noqa: F401
from contactwb.gui.settings import PREFERENCES, paint_style  # noqa: F401
from contactwb.gui.viewproviders.attach import attach_analysis as attach  # noqa: F401
from contactwb.gui.viewproviders.base import ViewProvider as _ViewProvider  # noqa: F401
from contactwb.gui.viewproviders.contact import ViewProviderContact, contact_icon_path  # noqa: F401
from contactwb.gui.viewproviders.contact_analysis import ViewProviderContactAnalysis  # noqa: F401
