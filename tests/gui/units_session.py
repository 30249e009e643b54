"""Runs inside the FreeCAD GUI (freecad tests/gui/units_session.py under Xvfb)
for tests/gui/test_gui_units.py: issue 21 item 11, units and names. The
Preferences dialog's Contacts group (its icon, its tolerance fields); the
Find contacts panel's tolerances in mm and degrees; one area written alike
in the tree, the property editor and the table; STEP assemblies imported
with Contacts_ImportStep (the bundled motor and inch case, and the shared
files when ../shared/data is there): names from the STEP products, an inch
file's sizes and areas in mm. Screenshots go to $CONTACTS_GUI_OUT."""
import glob
import os
import sys
import re
import traceback

import FreeCAD
import FreeCADGui
from PySide2 import QtCore, QtGui, QtWidgets

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))  # the shared session helpers
import session_helpers  # noqa: E402
from session_helpers import settle  # noqa: E402

out_dir = os.environ["CONTACTS_GUI_OUT"]
repo = os.environ["CONTACTS_REPO"]
shared = os.environ.get("CONTACTS_SHARED_DATA", "")
report = {"errors": {}}
state = {}


step = session_helpers.stepper(report["errors"])


def grab_window(name):
    return session_helpers.grab_window(out_dir, name)


def preferences_dialog():
    """The Contacts group in FreeCAD's Preferences: its icon, its fields."""
    main = FreeCADGui.getMainWindow()
    main.resize(1400, 1000)
    FreeCADGui.activateWorkbench("ContactsWorkbench")
    seen = {}

    def inspect(dialog):
        try:
            groups = {}
            for listing in dialog.findChildren(QtWidgets.QListWidget):
                for row in range(listing.count()):
                    item = listing.item(row)
                    groups[item.text()] = (item, listing)
            item, listing = groups["Contacts"]
            seen["groups"] = sorted(groups)
            seen["icon"] = not item.icon().isNull()
            seen["icon_pixels"] = _opaque_pixels(item.icon().pixmap(48, 48))
            listing.setCurrentItem(item)
            settle()
            page = next(w for w in dialog.findChildren(QtWidgets.QWidget) if w.objectName() == "ContactsPreferences")
            spins = page.findChildren(QtWidgets.QDoubleSpinBox)
            seen["fields"] = [s.text() for s in spins]
            dialog.resize(900, 640)
            settle()
            seen["png"] = os.path.join(out_dir, "gui_preferences.png")
            dialog.grab().save(seen["png"])
        except Exception:
            seen["error"] = traceback.format_exc()
        dialog.reject()

    session_helpers.with_modal_dialog("Std_DlgPreferences", inspect)
    report["preferences"] = seen


def _opaque_pixels(pixmap):
    image = pixmap.toImage()
    return sum(1 for y in range(image.height()) for x in range(image.width())
               if QtGui.QColor.fromRgba(image.pixel(x, y)).alpha() > 0)


def task_panel_units():
    """The motor's Find contacts panel: tolerances in mm and degrees; "0.5 um" typed."""
    from contactwb.gui.panels import task_panel
    FreeCADGui.runCommand("Contacts_OpenSample")
    settle()
    doc = FreeCAD.ActiveDocument
    state["motor"] = doc
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.runCommand("Contacts_FindContacts")
    settle()
    panel = task_panel.current
    result = {"linear_text": panel.linear.text(), "angular_text": panel.angular.text(),
              "linear": panel.linear.value(), "model_linear": panel.model_linear,
              "angular": panel.angular.value(), "model_angular": panel.model_angular}
    editor = panel.linear.lineEdit()
    editor.setText("0.5 um")
    panel.linear.interpretText()
    result["typed_um"] = panel.linear.value()
    result["typed_um_text"] = panel.linear.text()
    panel._set_model_defaults()
    result["accepted"] = panel.accept()
    settle()
    report["panel"] = result


def property_editor_text(obj, name):
    """What FreeCAD's property editor shows for obj.name (the object selected)."""
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(obj)
    # FreeCAD's property view follows the selection on a timer (100 ms by default): let it fire
    import time
    end = time.monotonic() + 0.5
    while time.monotonic() < end:
        settle()
        time.sleep(0.02)
    main = FreeCADGui.getMainWindow()
    for view in main.findChildren(QtWidgets.QTreeView):
        model = view.model()
        if model is None or "PropertyEditor" not in type(view).__name__ + view.metaObject().className():
            continue
        stack = [QtCore.QModelIndex()]
        while stack:
            parent = stack.pop()
            for row in range(model.rowCount(parent)):
                index = model.index(row, 0, parent)
                if model.data(index) == name:
                    return model.data(model.index(row, 1, parent))
                stack.append(index)
    return None


def contact_readings(contact, widget, row):
    """A contact's area, span and radius: its values, and the texts the property
    editor and the contact table's row `row` write for them."""
    return {"label2": contact.Label2, "partial": contact.Partial,
            "area": contact.Area.Value, "span": contact.Span.Value, "radius": contact.Radius.Value,
            "editor": {n: property_editor_text(contact, n) for n in ("Area", "Span", "Radius")},
            "table": {"Area": widget.table.item(row, 4).text(), "Span": widget.table.item(row, 5).text(),
                      "Radius": widget.table.item(row, 6).text()}}


def areas_alike():
    """One contact's area in the tree's description, the property editor and the table."""
    from contactwb.document.identify import analyses, is_contact
    from contactwb.gui.panels import contact_table
    doc = state["motor"]
    (group,) = analyses(doc)
    contacts = [c for c in group.Group if is_contact(c)]
    FreeCADGui.runCommand("Contacts_ShowContactTable")
    settle()
    widget = contact_table.dock().widget()
    rows = {widget.contact_of_row(r).Name: r for r in range(widget.table.rowCount())}
    result = []
    # the largest (cm^2 under the Standard schema) and the smallest contact
    for contact in sorted(contacts, key=lambda c: c.Area.Value)[::len(contacts) - 1]:
        result.append({"label": contact.Label, "area": contact.Area.Value, "label2": contact.Label2,
                       "editor": property_editor_text(contact, "Area"),
                       "table": widget.table.item(rows[contact.Name], 4).text(),
                       "type_id": contact.getTypeIdOfProperty("Area")})
    report["areas"] = result
    FreeCADGui.Selection.clearSelection()
    widget.parent().hide()


def quantities_alike():
    """Every quantity the workbench shows, as the property editor, the task
    panel, the tree's description column and the table write it: the
    analysis' tolerances (used and set), a partial contact's area and span, a
    cylinder contact's radius."""
    from contactwb.document.identify import analyses, is_contact
    from contactwb.gui.panels import contact_table, task_panel
    doc = state["motor"]
    (group,) = analyses(doc)
    result = {"schema": FreeCAD.Units.getSchema(),
              "decimals": FreeCAD.ParamGet("User parameter:BaseApp/Preferences/Units").GetInt("Decimals", 2)}
    # the tolerances: the property editor and the panel the analysis opens in (double-click, Find contacts
    # with the analysis selected)
    names = ("Linear Tolerance", "Angular Tolerance", "Linear Tolerance Setting", "Angular Tolerance Setting")
    result["editor"] = {name: property_editor_text(group, name) for name in names}
    result["used"] = [group.LinearToleranceValue.Value, group.AngularToleranceValue.Value]
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(group)
    FreeCADGui.runCommand("Contacts_FindContacts")
    settle()
    panel = task_panel.current
    result["panel"] = [panel.linear.text(), panel.angular.text()]
    FreeCADGui.Control.closeDialog()
    settle()
    # a setting typed in another unit, as the editor shows it then
    group.LinearToleranceSetting = "0.5 um"
    result["typed_setting"] = property_editor_text(group, "Linear Tolerance Setting")
    group.LinearToleranceSetting = ""
    result["default_setting"] = property_editor_text(group, "Linear Tolerance Setting")
    doc.recompute()  # the setting back as it was: the analysis current again
    # the contacts' quantities: tree (Label2), property editor, table
    contacts = [c for c in group.Group if is_contact(c)]
    FreeCADGui.runCommand("Contacts_ShowContactTable")
    settle()
    widget = contact_table.dock().widget()
    rows = {widget.contact_of_row(r).Name: r for r in range(widget.table.rowCount())
            if widget.contact_of_row(r) is not None}
    # the motor's cylinder contacts of the smallest and the largest radius (full turns: no partial one)
    cylinders = sorted((c for c in contacts if c.ContactType == "CLJ"), key=lambda c: (c.Radius.Value, c.Number))
    seen = []
    for contact in (cylinders[0], cylinders[-1]):
        row = rows[contact.Name]
        seen.append(dict(contact_readings(contact, widget, row), name=contact.Name))
    result["contacts"] = seen
    # the picture: the analysis selected (its tolerances in the property editor) beside the table
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(group)
    property_editor_text(group, "Linear Tolerance")
    main = FreeCADGui.getMainWindow()
    tree = next(t for t in main.findChildren(QtWidgets.QTreeWidget))
    tree.expandAll()
    widget.table.scrollToItem(widget.table.item(rows[cylinders[0].Name], 0))
    # wide enough to read the properties' names and the table's Span and Radius
    combo = next(d for d in main.findChildren(QtWidgets.QDockWidget) if d.objectName() == "Combo View")
    main.resizeDocks([combo, widget.parent()], [440, 640], QtCore.Qt.Horizontal)
    for view in main.findChildren(QtWidgets.QTreeView):
        if "PropertyEditor" in type(view).__name__ + view.metaObject().className():
            view.header().resizeSection(0, 210)
    result["png"] = grab_window("gui_units_alike.png")
    FreeCADGui.Selection.clearSelection()
    widget.parent().hide()
    report["quantities"] = result


def schema_changed():
    """Preferences -> General -> Units set to "Metric small parts & CNC" as the
    dialog does (the parameter written, then the schema set): the largest
    contact's area in the tree, the property editor and the table after it,
    then back to the Standard schema."""
    from contactwb.document.identify import analyses, is_contact
    from contactwb.gui.panels import contact_table
    doc = state["motor"]
    (group,) = analyses(doc)
    largest = max((c for c in group.Group if is_contact(c)), key=lambda c: c.Area.Value)
    FreeCADGui.runCommand("Contacts_ShowContactTable")
    settle()
    widget = contact_table.dock().widget()
    params = FreeCAD.ParamGet("User parameter:BaseApp/Preferences/Units")
    result = {"area": largest.Area.Value, "undo": list(doc.UndoNames)}

    def seen():
        session_helpers.wait(0.3)
        row = next(r for r in range(widget.table.rowCount()) if widget.contact_of_row(r) == largest)
        return {"label2": largest.Label2, "editor": property_editor_text(largest, "Area"),
                "table": widget.table.item(row, 4).text()}

    for schema in (6, 0):
        params.SetInt("UserSchema", schema)
        FreeCAD.Units.setSchema(schema)
        result[str(schema)] = seen()
    result["undo_after"] = list(doc.UndoNames)
    result["touched"] = [o.Name for o in doc.Objects if "Touched" in o.State]
    FreeCADGui.Selection.clearSelection()
    widget.parent().hide()
    report["schema"] = result


def selection_tolerance_alike():
    """Find contacts on two parts of the motor (Screw-1 and Back-cover
    selected: scope Selection): the linear tolerance the panel shows is the
    one the new analysis reports in the property editor (the coarsest of the
    two parts', not the document's)."""
    from contactwb.document.identify import analyses
    from contactwb.gui.panels import task_panel
    doc = state["motor"]
    before = {g.Name for g in analyses(doc)}
    (whole,) = [g for g in analyses(doc)]
    FreeCADGui.Selection.clearSelection()
    for label in ("Screw-1", "Back-cover"):
        FreeCADGui.Selection.addSelection(doc.getObjectsByLabel(label)[0])
    FreeCADGui.runCommand("Contacts_FindContacts")
    settle()
    panel = task_panel.current
    result = {"scope": panel.scope_value(), "panel": panel.linear.text(), "document": whole.LinearTolerance}
    result["accepted"] = panel.accept()
    settle()
    (group,) = [g for g in analyses(doc) if g.Name not in before]
    result["editor"] = property_editor_text(group, "Linear Tolerance")
    result["used"] = group.LinearToleranceValue.Value
    # the panel the new analysis opens in shows its figure too
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(group)
    FreeCADGui.runCommand("Contacts_FindContacts")
    settle()
    result["reopened"] = task_panel.current.linear.text()
    FreeCADGui.Control.closeDialog()
    settle()
    report["selection_tolerance"] = result


def cases_alike():
    """The bundled cases with a partial contact (cradle_120: a 120° cradle) and
    a circle contact (ball_in_bore): each contact's area, span and radius in
    the tree's description, the property editor and the table."""
    from contactwb.document.identify import is_contact
    from contactwb.gui.panels import contact_table
    from contactwb.make import make_contact_analysis
    result = {}
    for name in ("cradle_120", "ball_in_bore"):
        doc = FreeCAD.openDocument(os.path.join(repo, "Resources", "samples", "cases", name + ".FCStd"))
        FreeCAD.setActiveDocument(doc.Name)
        FreeCADGui.activateWorkbench("ContactsWorkbench")
        group = make_contact_analysis(doc)
        doc.recompute()
        settle()
        FreeCADGui.runCommand("Contacts_ShowContactTable")
        settle()
        widget = contact_table.dock().widget()
        widget.fill(doc)
        settle()
        rows = {widget.contact_of_row(r).Name: r for r in range(widget.table.rowCount())
                if widget.contact_of_row(r) is not None}
        seen = []
        for contact in (c for c in group.Group if is_contact(c)):
            row = rows[contact.Name]
            seen.append(dict(contact_readings(contact, widget, row), type=contact.ContactType))
        result[name] = seen
        FreeCADGui.Selection.clearSelection()
        widget.parent().hide()
        FreeCAD.closeDocument(doc.Name)
        settle()
    report["cases"] = result


def step_names(path):
    """Every name the file declares (its quoted strings: products, occurrences
    (NEXT_ASSEMBLY_USAGE_OCCURRENCE), solids), read as text."""
    with open(path, "rb") as stream:
        text = stream.read().decode("latin-1")
    return set(re.findall(r"'([^']*)'", text))


def import_file(path):
    """Contacts_ImportStep's work on `path`, into a new document."""
    from contactwb.gui.commands.contacts import import_step_file
    doc = FreeCAD.newDocument(re.sub(r"\W", "_", os.path.splitext(os.path.basename(path))[0]))
    doc.UndoMode = 1
    features = import_step_file(path, doc)
    settle()
    return doc, features


def imports():
    """The bundled motor and inch case through Contacts_ImportStep."""
    import Part
    result = {}
    samples = os.path.join(repo, "Resources", "samples")
    # the motor: the parts named as in motor.FCStd, which the STEP file was written from
    motor = state["motor"]
    fcstd_labels = sorted(o.Label for o in motor.Objects if o.TypeId == "Part::Feature")
    FreeCAD.closeDocument(motor.Name)  # the picture: the imported tree alone
    settle()
    doc, features = import_file(os.path.join(samples, "motor.step"))
    result["motor"] = {"labels": sorted(f.Label for f in features), "fcstd_labels": fcstd_labels,
                       "containers": sorted(o.Label for o in doc.Objects if o.TypeId == "App::Part"),
                       "undo": list(doc.UndoNames)}
    view = FreeCADGui.activeDocument().activeView()
    view.viewIsometric()
    view.fitAll()
    tree = next(t for t in FreeCADGui.getMainWindow().findChildren(QtWidgets.QTreeWidget))
    tree.expandAll()
    result["motor"]["png"] = grab_window("gui_import_step.png")
    # the inch case: sizes in mm (as FreeCAD's own reader converts them, and as the inch.FCStd it was written from)
    inch_path = os.path.join(samples, "cases", "inch.step")
    doc, features = import_file(inch_path)
    read = Part.read(inch_path)
    reference = FreeCAD.openDocument(os.path.join(samples, "cases", "inch.FCStd"))
    by_label = {o.Label: o for o in reference.Objects if o.TypeId == "Part::Feature"}
    result["inch"] = {"labels": [f.Label for f in features],
                      "volumes": [f.Shape.Volume for f in features],
                      "part_read_volumes": [s.Volume for s in read.Solids],
                      "fcstd_volumes": [by_label[f.Label].Shape.Volume if f.Label in by_label else None
                                        for f in features]}
    FreeCAD.setActiveDocument(doc.Name)
    from contactwb.make import make_contact_analysis
    group = make_contact_analysis(doc)
    doc.recompute()
    contacts = []
    for contact in group.Group:
        if not hasattr(contact, "FacesA"):
            continue
        brute = 0.0  # the two sides' common area by OCCT's Boolean
        for root_a, subs_a in contact.FacesA:
            for sub_a in subs_a:
                for root_b, subs_b in contact.FacesB:
                    for sub_b in subs_b:
                        face_a = Part.getShape(root_a, sub_a, needSubElement=True, transform=True)
                        face_b = Part.getShape(root_b, sub_b, needSubElement=True, transform=True)
                        brute += face_a.common(face_b, 1e-4).Area
        contacts.append([contact.ContactType, contact.BodyA, contact.BodyB, contact.Area.Value, brute,
                         contact.Label2, contact.Area.UserString])
    group_reference = make_contact_analysis(reference)
    reference.recompute()
    result["inch"]["contacts"] = sorted(contacts)
    result["inch"]["fcstd_contacts"] = sorted([c.ContactType, c.BodyA, c.BodyB, c.Area.Value]
                                              for c in group_reference.Group if hasattr(c, "FacesA"))
    FreeCAD.closeDocument(reference.Name)
    report["imports"] = result


def shared_imports():
    """Every shared STEP file: names from its products, none after the file or 'Undefined'."""
    if not shared or not os.path.isdir(os.path.join(shared, "step")):
        report["shared"] = None
        return
    result = {}
    for path in sorted(glob.glob(os.path.join(shared, "step", "*.st*p"))):
        doc, features = import_file(path)
        result[os.path.basename(path)] = {
            "labels": [f.Label for f in features], "products": sorted(step_names(path)),
            "stem": os.path.splitext(os.path.basename(path))[0],
            "containers": [o.Label for o in doc.Objects if o.TypeId == "App::Part"],
            "solids": [len(f.Shape.Solids) for f in features]}
        FreeCAD.closeDocument(doc.Name)
        settle()
    report["shared"] = result


for function in (preferences_dialog, task_panel_units, areas_alike, quantities_alike, schema_changed,
                 selection_tolerance_alike, imports,
                 cases_alike,
                 shared_imports):
    step(function)
session_helpers.write_report_and_exit(report)
