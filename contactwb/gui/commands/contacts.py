"""The workbench's analysis commands (one class each, FreeCAD Assembly style):
find contacts, the contact table, isolate, show all, ghost, partitions,
joints, export, the sample."""

import FreeCAD
import FreeCADGui

import contactwb
from contactwb.document.identify import analyses, is_contact, is_contact_analysis, is_joint
from contactwb.gui.dialogs import show_error


class Contacts_FindContacts:
    """Opens the Find contacts task panel (scope, tolerances, types); with an
    analysis selected, finds its contacts again in place."""

    def GetResources(self):
        return {
            "Pixmap": contactwb.icon_path("Contacts_FindContacts"),
            "MenuText": "Find contacts...",
            "ToolTip": "Find the functional contacts (planar fits, cylindrical joints, cones, spheres, "
                       "balls in bores and grooves) of the whole document, the selected parts, or one "
                       "part against the rest; with an analysis selected, find its contacts again",
        }

    def IsActive(self):
        return FreeCAD.ActiveDocument is not None and not FreeCADGui.Control.activeDialog()

    def Activated(self):
        from contactwb.gui.panels import task_panel
        doc = FreeCAD.ActiveDocument
        task_panel.open_panel(doc, task_panel.selected_analysis(doc))


def _selected_contact():
    doc = FreeCAD.ActiveDocument
    if doc is None:
        return None
    return next((o for o in FreeCADGui.Selection.getSelection(doc.Name) if is_contact(o)), None)


# View-only commands (isolate, show all, ghost, partitions, the table and
# panels) change how things look, not the document: FreeCAD must open no undo
# transaction for them (it otherwise records their visibility and
# transparency changes under the command's name).
VIEW_ONLY = {"CmdType": "NoTransaction"}


class Contacts_ShowContactTable:
    """Shows the contact table dock."""

    def GetResources(self):
        return {
            "Pixmap": contactwb.icon_path("Contacts_ShowContactTable"),
            "MenuText": "Contact table",
            "ToolTip": "List every contact in a table: sort and filter by type, part, area or "
                       "partial; a row selects, zooms to or isolates its contact; the counts per "
                       "type and per pair below",
            **VIEW_ONLY,
        }

    def IsActive(self):
        return FreeCAD.ActiveDocument is not None

    def Activated(self):
        from contactwb.gui.panels import contact_table
        contact_table.show()


class Contacts_IsolateContact:
    """Shows only the selected contact and its two parts."""

    def GetResources(self):
        return {
            "Pixmap": contactwb.icon_path("Contacts_IsolateContact"),
            "MenuText": "Isolate contact",
            "ToolTip": "Show only the selected contact with its two parts, and zoom to it",
            **VIEW_ONLY,
        }

    def IsActive(self):
        return _selected_contact() is not None

    def Activated(self):
        from contactwb.gui import actions
        contact = _selected_contact()
        actions.isolate(contact)
        actions.zoom_to(contact)


class Contacts_ShowAll:
    """Undoes isolation and ghosting."""

    def GetResources(self):
        return {
            "Pixmap": contactwb.icon_path("Contacts_ShowAll"),
            "MenuText": "Show all",
            "ToolTip": "Show again the parts and contacts an isolation hid, and undo ghosting",
            **VIEW_ONLY,
        }

    def IsActive(self):
        return bool(analyses(FreeCAD.ActiveDocument))

    def Activated(self):
        from contactwb.gui import actions
        doc = FreeCAD.ActiveDocument
        actions.show_all(doc)


class Contacts_GhostBodies:
    """Makes the parts see-through around the painted contacts (toggles)."""

    def GetResources(self):
        return {
            "Pixmap": contactwb.icon_path("Contacts_GhostBodies"),
            "MenuText": "Ghost parts",
            "ToolTip": "Make the parts' geometry see-through, so the painted contacts (also those "
                       "inside the assembly) stand out (again: make them solid)",
            **VIEW_ONLY,
        }

    def IsActive(self):
        return bool(analyses(FreeCAD.ActiveDocument))

    def Activated(self):
        from contactwb.gui import actions
        doc = FreeCAD.ActiveDocument
        ghosted = not actions.is_ghosted(doc)
        actions.set_ghosted(doc, ghosted)


class Contacts_ShowPartitions:
    """Colours the partitions of the selected parts by surface type (toggles)."""

    def GetResources(self):
        return {
            "Pixmap": contactwb.icon_path("Contacts_ShowPartitions"),
            "MenuText": "Show partitions",
            "ToolTip": "Colour every partition (adjacent faces on one surface) of the selected parts, "
                       "or of all visible parts, by surface type, with a legend (again: hide them)",
            **VIEW_ONLY,
        }

    def IsActive(self):
        return FreeCAD.ActiveDocument is not None

    def Activated(self):
        from contactwb import core
        from contactwb.gui.overlay import partitions as partitions_view
        from contactwb.gui.panels import task_panel
        doc = FreeCAD.ActiveDocument
        if partitions_view.is_shown(doc):
            partitions_view.hide(doc)
            return
        try:
            partitions_view.show(doc, task_panel.selection_entries(doc))
        except core.ContactsError as error:
            show_error(str(error))


def _analysis_for_joints():
    """The selected analysis (or the one holding a selected contact or
    joint), else the document's only one."""
    doc = FreeCAD.ActiveDocument
    if doc is None:
        return None
    for obj in FreeCADGui.Selection.getSelection(doc.Name):
        if is_contact_analysis(obj):
            return obj
        if is_contact(obj) or is_joint(obj):
            return next((p for p in obj.InList if is_contact_analysis(p)), None)
    found = analyses(doc)
    return found[0] if len(found) == 1 else None


class Contacts_DeriveJoints:
    """Derives the joints of an analysis (Joint objects drawn as axis glyphs)."""

    def GetResources(self):
        return {
            "Pixmap": contactwb.icon_path("Contacts_DeriveJoints"),
            "MenuText": "Derive joints",
            "ToolTip": "Derive the kinematic joint each body pair's contacts allow (type, degrees of "
                       "freedom, axes, free directions) as Joint objects of the selected analysis, "
                       "drawn as axis glyphs; kept up to date with the contacts",
        }

    def IsActive(self):
        return _analysis_for_joints() is not None

    def Activated(self):
        from contactwb import core
        from contactwb.make import make_contact_analysis
        group = _analysis_for_joints()
        doc = group.Document
        doc.openTransaction("Derive joints")
        try:
            from contactwb.document.units import tolerance_settings
            linear, angular = tolerance_settings(group)
            make_contact_analysis(doc, list(group.Sources) or None, linear, angular, scope=group.Scope,
                                  types=list(group.ContactTypes) or None,
                                  clearance_gap=group.ClearanceGap.Value, group=group, derive_joints=True)
        except (core.ContactsError, ValueError) as error:
            doc.abortTransaction()
            show_error(str(error))
            return
        doc.commitTransaction()
        FreeCAD.Console.PrintMessage(f"Contacts: {'; '.join(group.Mobility[:2])}\n")
        from contactwb.gui.panels import joints_panel
        joints_panel.open_joints_panel(group)


class Contacts_ShowJoints:
    """The mobility, rigid groups and liaison graph of an analysis, in a panel."""

    def GetResources(self):
        return {
            "Pixmap": contactwb.icon_path("Contacts_ShowJoints"),
            "MenuText": "Joints and liaison graph",
            "ToolTip": "Show the assembly's degrees of freedom, its rigid groups and the liaison graph "
                       "of the selected analysis (after Derive joints)",
            **VIEW_ONLY,
        }

    def IsActive(self):
        group = _analysis_for_joints()
        return group is not None and bool(getattr(group, "LiaisonGraph", ""))

    def Activated(self):
        from contactwb.gui.panels import joints_panel
        joints_panel.open_joints_panel(_analysis_for_joints())


class Contacts_OpenSample:
    """Opens the bundled motor."""

    def GetResources(self):
        return {
            "Pixmap": contactwb.icon_path("Contacts_OpenSample"),
            "MenuText": "Open sample motor",
            "ToolTip": "Open the bundled 18-part electric motor (the paper's example) to try the workbench",
        }

    def IsActive(self):
        return True

    def Activated(self):
        import os
        doc = FreeCAD.openDocument(os.path.join(contactwb.SAMPLES_DIR, "motor.FCStd"))
        FreeCADGui.activeDocument().activeView().viewIsometric()
        FreeCADGui.SendMsgToActiveView("ViewFit")
        return doc


class Contacts_ImportStep:
    """Imports a STEP assembly with its product names (the core's reader)."""

    def GetResources(self):
        return {
            "Pixmap": contactwb.icon_path("Contacts_ImportStep"),
            "MenuText": "Import STEP assembly...",
            "ToolTip": "Import a STEP assembly into the active document (or a new one): one part per solid, "
                       "named after its STEP product, in containers following the file's assembly tree; "
                       "shapes in mm whatever the file's unit",
        }

    def IsActive(self):
        return True

    def Activated(self):
        import os
        from PySide2 import QtWidgets
        folder = os.path.dirname(FreeCAD.ActiveDocument.FileName) if FreeCAD.ActiveDocument and \
            FreeCAD.ActiveDocument.FileName else os.path.expanduser("~")
        path, _ = QtWidgets.QFileDialog.getOpenFileName(FreeCADGui.getMainWindow(), "Import STEP assembly",
                                                        folder, "STEP (*.step *.stp *.STEP *.STP)")
        if path:
            import_step_file(path)


def import_step_file(path, doc=None):
    """Contacts_ImportStep's work on a chosen file: into `doc` (default the
    active document, else a new one named after the file), one undo entry,
    the view fitted. Returns the features made ([] after an error, shown)."""
    import os
    from contactwb import core
    from contactwb.document import step_import
    doc = doc or FreeCAD.ActiveDocument or FreeCAD.newDocument(
        "".join(c if c.isalnum() else "_" for c in os.path.splitext(os.path.basename(path))[0]) or "Assembly")
    doc.openTransaction("Import STEP")
    try:
        root, features, unit = step_import.import_step(doc, path)
    except (core.ContactsError, OSError) as error:
        doc.abortTransaction()
        show_error(f"cannot import '{path}': {error}")
        return []
    doc.recompute()
    doc.commitTransaction()
    converted = "" if unit == "mm" else f" (file unit {unit}, converted to mm)"
    FreeCAD.Console.PrintMessage(f"Contacts: {len(features)} parts imported from {path}{converted}\n")
    gui_doc = FreeCADGui.getDocument(doc.Name)
    if gui_doc is not None:
        FreeCADGui.setActiveDocument(doc.Name)
        view = gui_doc.activeView()
        if view is not None and hasattr(view, "viewIsometric"):
            view.viewIsometric()
            view.fitAll()
    return features


def _analysis_to_export(doc):
    """The selected ContactAnalysis (or the one holding a selected contact),
    else the document's only one; None when that is ambiguous."""
    chosen = []
    for obj in FreeCADGui.Selection.getSelection(doc.Name):
        # the analysis itself, or the one holding a selected contact (a
        # selected part is linked by analyses but chooses none)
        candidates = [obj] if is_contact_analysis(obj) else list(obj.InList) if is_contact(obj) else []
        for candidate in candidates:
            if is_contact_analysis(candidate) and candidate not in chosen:
                chosen.append(candidate)
    if not chosen:
        chosen = analyses(doc)
    return chosen[0] if len(chosen) == 1 else None


class Contacts_ExportContacts:
    """Writes a contact analysis to a JSON or CSV file."""

    FILTERS = {"JSON (*.json)": ".json", "CSV (*.csv)": ".csv"}

    def GetResources(self):
        return {
            "Pixmap": contactwb.icon_path("Contacts_ExportContacts"),
            "MenuText": "Export contacts...",
            "ToolTip": "Write the contacts of the selected analysis (or of the only one) to a "
                       "JSON or CSV file",
        }

    def IsActive(self):
        return bool(analyses(FreeCAD.ActiveDocument))

    def Activated(self):
        import os
        from PySide2 import QtWidgets
        from contactwb.document import export
        doc = FreeCAD.ActiveDocument
        group = _analysis_to_export(doc)
        if group is None:
            show_error("Select the contact analysis to export (the document holds several).")
            return
        folder = os.path.dirname(doc.FileName) if doc.FileName else os.path.expanduser("~")
        suggestion = os.path.join(folder, f"{doc.Label}_{group.Label}.json")
        path, chosen_filter = QtWidgets.QFileDialog.getSaveFileName(
            FreeCADGui.getMainWindow(), "Export contacts", suggestion, ";;".join(self.FILTERS))
        if not path:
            return
        if os.path.splitext(path)[1].lower() not in export.FORMATS:
            path += self.FILTERS.get(chosen_filter, ".json")
        try:
            count = export.export_contacts(group, path)
        except (OSError, ValueError) as error:
            show_error(f"cannot export '{group.Label}': {error}")
            return
        noun = "contact" if count == 1 else "contacts"
        FreeCAD.Console.PrintMessage(f"Contacts: {count} {noun} of '{group.Label}' written to {path}\n")


# Toolbar and menu order (contactwb.gui.commands registers them with the others).
COMMANDS = {
    "Contacts_FindContacts": Contacts_FindContacts,
    "Contacts_ShowContactTable": Contacts_ShowContactTable,
    "Contacts_IsolateContact": Contacts_IsolateContact,
    "Contacts_ShowAll": Contacts_ShowAll,
    "Contacts_GhostBodies": Contacts_GhostBodies,
    "Contacts_ShowPartitions": Contacts_ShowPartitions,
    "Contacts_DeriveJoints": Contacts_DeriveJoints,
    "Contacts_ShowJoints": Contacts_ShowJoints,
    "Contacts_ExportContacts": Contacts_ExportContacts,
    "Contacts_OpenSample": Contacts_OpenSample,
    "Contacts_ImportStep": Contacts_ImportStep,
}

# In the 3D view's context menu (a contact's own menu: its view provider).
CONTEXT_COMMANDS = ["Contacts_FindContacts", "Contacts_IsolateContact", "Contacts_ShowAll",
                    "Contacts_ShowContactTable", "Contacts_AnnotateContact"]

