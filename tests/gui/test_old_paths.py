"""Issue 23: the module paths of earlier releases still give the same classes
and functions (saved documents name the proxies' and view providers' modules;
scripts and the README the others). Imported headless, as test_overlay.py does."""
import importlib

import pytest

pytest.importorskip("pivy.coin")

# (old module, name) -> new module defining it
MOVED = {
    ("contactwb.gui.view_providers", "ViewProviderContactAnalysis"): "contactwb.gui.viewproviders.contact_analysis",
    ("contactwb.gui.view_providers", "ViewProviderContact"): "contactwb.gui.viewproviders.contact",
    ("contactwb.gui.joint_view", "ViewProviderJoint"): "contactwb.gui.viewproviders.joint",
    ("contactwb.gui.simulation_model_view", "ViewProviderSimulationModel"):
        "contactwb.gui.viewproviders.simulation_model",
    ("contactwb.gui.view_providers", "ContactOverlay"): "contactwb.gui.overlay.contact_overlay",
    ("contactwb.gui.task_panel", "FindContactsPanel"): "contactwb.gui.panels.task_panel",
    ("contactwb.gui.contact_table", "ContactTable"): "contactwb.gui.panels.contact_table",
    ("contactwb.gui.haptic_panel", "HapticTrialPanel"): "contactwb.gui.panels.haptic_panel",
    ("contactwb.gui.haptic_panel", "Contacts_HapticTrial"): "contactwb.gui.commands.haptics",
    ("contactwb.gui.joint_view", "JointsPanel"): "contactwb.gui.panels.joints_panel",
    ("contactwb.gui.partitions_view", "PartitionsView"): "contactwb.gui.overlay.partitions",
    ("contactwb.gui.commands", "Contacts_ExportContacts"): "contactwb.gui.commands.contacts",
    ("contactwb.objects.contact_objects", "ContactAnalysis"): "contactwb.objects.contact_objects",
    ("contactwb.objects.contact_objects", "Contact"): "contactwb.objects.contact_objects",
    ("contactwb.objects.contact_objects", "Joint"): "contactwb.objects.contact_objects",
    ("contactwb.objects.simulation_model", "SimulationModel"): "contactwb.objects.simulation_model",
    ("contactwb.analysis", "Analysis"): "contactwb.core.analysis",
    ("contactwb.analysis", "find_contacts_in_step"): "contactwb.core.analysis",
    ("contactwb.analysis", "find_contacts_in_document"): "contactwb.document.analysis",
    ("contactwb.joints", "joints_in_document"): "contactwb.document.analysis",
    ("contactwb.meshes", "load_assembly"): "contactwb.document.files",
    ("contactwb.trial", "check_script"): "contactwb.core.trial",
    ("contactwb.export", "export_contacts"): "contactwb.document.export",
    ("contactwb.bodies", "document_bodies"): "contactwb.document.bodies",
    ("contactwb.freecad_setup", "open_document"): "contactwb.document.freecad_setup",
    ("contactwb.cli_mesh", "main"): "contactwb.cli.mesh",
    ("contactwb.make", "make_contact_analysis"): "contactwb.make.make_contact_analysis",
}


@pytest.mark.parametrize("old, name", sorted(MOVED))
def test_old_path_gives_the_same_object(old, name):
    new = MOVED[(old, name)]
    assert getattr(importlib.import_module(old), name) is getattr(importlib.import_module(new), name)
    assert getattr(importlib.import_module(new), name).__module__ == new


def test_old_paths_read_module_state_live():
    from contactwb.gui import haptic_panel, joint_view, task_panel
    from contactwb.gui.panels import haptic_panel as new_haptic, joints_panel, task_panel as new_task
    marker = object()
    for old, new, name in ((haptic_panel, new_haptic, "active_panel"), (joint_view, joints_panel, "current_panel"),
                           (task_panel, new_task, "current")):
        saved = getattr(new, name)
        setattr(new, name, marker)
        try:
            assert getattr(old, name) is marker, name
        finally:
            setattr(new, name, saved)
