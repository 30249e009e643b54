"""The Find contacts task panel: scope, tolerances (with units, defaults from
the model), contact types, clearance gap; progress and Cancel in the panel.
Run on an existing analysis (selected, or double-clicked) it updates that one
in place."""
import time
from math import degrees, radians

import FreeCAD
import FreeCADGui
from PySide2 import QtCore, QtWidgets

from contactwb.core.kinds import CONTACT_TYPES, SCOPES, TYPE_NAMES
from contactwb.document.identify import is_alive, is_contact, is_contact_analysis
from contactwb.gui import settings

PROGRESS_PERIOD_S = 0.1  # the search's progress shown (and Cancel heard) at most ten times a second,
PROGRESS_COST_RATIO = 9.0  # and after an update that took t, not before 9 t (at most a tenth of the time)
PROGRESS_FIRST_S = 0.3  # and not before the search has run this long: a shorter one needs no progress shown
SCOPE_TEXTS = {"Document": "Whole document", "Selection": "Selected parts only",
               "PartAgainstRest": "Selected part against the rest"}


def selection_entries(doc):
    """The selection as (top-level object, [subnames]) entries, unresolved
    (links and their placements kept), without analyses and contacts."""
    entries = []
    for selected in FreeCADGui.Selection.getSelectionEx(doc.Name, 0):
        obj = selected.Object
        subnames = list(selected.SubElementNames) or [""]
        kept = [s for s in subnames
                if not (is_contact(obj.getSubObject(s, retType=1) if s else obj)
                        or is_contact_analysis(obj.getSubObject(s, retType=1) if s else obj))]
        if kept and not (is_contact(obj) or is_contact_analysis(obj)):
            entries.append((obj, kept))
    return entries


def selected_analysis(doc):
    """The analysis selected (or holding a selected contact), if one. (A
    selected part is no analysis, though analyses link to it.)"""
    for obj in FreeCADGui.Selection.getSelection(doc.Name):
        if is_contact_analysis(obj):
            return obj
        if is_contact(obj):
            return next((p for p in obj.InList if is_contact_analysis(p)), None)
    return None


def model_tolerances(doc, entries=None, scope="Document"):
    """(linear mm, angular rad) the core would choose for the bodies the scope
    analyses (the document's visible solids; the selection `entries` for
    scope "Selection") and report as used: each body's defaults are scaled to
    its own box (contactcore.find_contacts), the coarsest body's linear one is
    the analysis' LinearTolerance."""
    from contactwb import core
    from contactwb.document import bodies
    linear, angular = None, 1e-4
    analysed = bodies.document_bodies(doc)
    if scope == "Selection" and entries:
        analysed = bodies.bodies_of_selection(analysed, entries)
    for body in analysed:
        box = body.shape.BoundBox
        if not box.isValid():
            continue
        tolerances = core.contactcore.default_tolerances(box.XMin, box.YMin, box.ZMin,
                                                         box.XMax, box.YMax, box.ZMax)
        linear = tolerances.linear if linear is None else max(linear, tolerances.linear)
        angular = tolerances.angular
    return (1e-3 if linear is None else linear), angular


def _quantity_box(unit, value):
    """A tolerance field in mm or degrees (contactwb.gui.units.MeasureBox)."""
    from contactwb.gui.units import MeasureBox
    return MeasureBox("mm" if unit == "mm" else "\u00b0", value)


class FindContactsPanel:
    """Task panel of Contacts_FindContacts."""

    def __init__(self, doc, entries=None, group=None):
        self.doc = doc
        self.group = group
        self.entries = list(entries or [])
        if group is not None and not self.entries:
            self.entries = [(o, list(s)) for o, s in group.Sources]
        self.running = False
        self.cancel_requested = False
        self.result = None
        self.form = self._build()
        self._load()

    # --- widgets ---------------------------------------------------------
    def _build(self):
        form = QtWidgets.QWidget()
        form.setObjectName("ContactsFindPanel")
        form.setWindowTitle("Find contacts" if self.group is None else f"Find contacts again: {self.group.Label}")
        layout = QtWidgets.QVBoxLayout(form)

        scope_box = QtWidgets.QGroupBox("Scope")
        scope_layout = QtWidgets.QVBoxLayout(scope_box)
        self.scope = QtWidgets.QComboBox()
        for scope in SCOPES:
            self.scope.addItem(SCOPE_TEXTS[scope], scope)
        self.parts = QtWidgets.QLabel()
        self.parts.setWordWrap(True)
        scope_layout.addWidget(self.scope)
        scope_layout.addWidget(self.parts)
        layout.addWidget(scope_box)

        tolerance_box = QtWidgets.QGroupBox("Tolerances")
        grid = QtWidgets.QFormLayout(tolerance_box)
        linear, angular = model_tolerances(self.doc)
        self.model_linear, self.model_angular = linear, angular
        self.linear = _quantity_box("mm", linear)
        self.angular = _quantity_box("deg", degrees(angular))
        self.gap = _quantity_box("mm", 0.0)
        grid.addRow("Linear:", self.linear)
        grid.addRow("Angular:", self.angular)
        grid.addRow("Clearance gap:", self.gap)
        self.defaults = QtWidgets.QPushButton("Model defaults")
        self.defaults.setToolTip(f"Scaled to the model: {linear:.3g} mm, {degrees(angular):.3g}\u00b0")
        self.defaults.clicked.connect(self._set_model_defaults)
        grid.addRow("", self.defaults)
        layout.addWidget(tolerance_box)

        types_box = QtWidgets.QGroupBox("Contact types to look for")
        types_layout = QtWidgets.QGridLayout(types_box)
        self.types = {}
        for index, kind in enumerate(CONTACT_TYPES):
            check = QtWidgets.QCheckBox(f"{kind} {TYPE_NAMES[kind]}")
            check.setChecked(True)
            self.types[kind] = check
            types_layout.addWidget(check, index // 2, index % 2)
        layout.addWidget(types_box)

        run_box = QtWidgets.QGroupBox("Progress")
        run_layout = QtWidgets.QVBoxLayout(run_box)
        self.status = QtWidgets.QLabel("Press OK to find the contacts.")
        self.status.setWordWrap(True)
        self.progress_bar = QtWidgets.QProgressBar()
        self.progress_bar.setRange(0, 1000)
        self.progress_bar.setValue(0)
        self.cancel = QtWidgets.QPushButton("Cancel search")
        self.cancel.setEnabled(False)
        self.cancel.clicked.connect(self.request_cancel)
        for widget in (self.status, self.progress_bar, self.cancel):
            run_layout.addWidget(widget)
        layout.addWidget(run_box)
        layout.addStretch(1)
        self.scope.currentIndexChanged.connect(self._show_parts)
        self.scope.currentIndexChanged.connect(self._follow_model_defaults)
        return form

    def _load(self):
        group = self.group
        if group is not None:
            self.scope.setCurrentIndex(SCOPES.index(group.Scope))
            from contactwb.document.units import tolerance_settings
            try:
                linear, angular = tolerance_settings(group)
            except Exception:  # a setting typed wrong in the property editor: the model's shown, to correct
                linear, angular = None, None
            if linear:
                self.linear.setValue(linear)
            if angular:
                self.angular.setValue(degrees(angular))
            self.gap.setValue(group.ClearanceGap.Value)
            for kind, check in self.types.items():
                check.setChecked(not group.ContactTypes or kind in group.ContactTypes)
        else:
            params = settings.params()
            if params.GetFloat("LinearTolerance", 0.0) > 0:
                self.linear.setValue(params.GetFloat("LinearTolerance"))
            if params.GetFloat("AngularTolerance", 0.0) > 0:
                self.angular.setValue(params.GetFloat("AngularTolerance"))
            parts = len(self.entries)
            self.scope.setCurrentIndex(SCOPES.index(
                "Document" if not parts else "PartAgainstRest" if parts == 1 and len(self.entries[0][1]) == 1
                else "Selection"))
        self._show_parts()

    def _show_parts(self, *_):
        names = []
        for obj, subnames in self.entries:
            for subname in subnames:
                target = obj.getSubObject(subname, retType=1) if subname else obj
                names.append(getattr(target, "Label", obj.Label))
        if self.scope_value() == "Document":
            self.parts.setText("Every visible solid of the document.")
        elif names:
            self.parts.setText("Parts: " + ", ".join(names))
        else:
            self.parts.setText("Select the parts in the tree or the 3D view first.")

    def _follow_model_defaults(self, *_):
        """The model's defaults for the scope chosen (a selection's coarsest body
        may be smaller than the document's); a field left at the old default
        follows, so that the panel shows what the analysis will report."""
        linear, angular = model_tolerances(self.doc, self.entries, self.scope_value())
        if abs(self.linear.value() - self.model_linear) <= 1e-12:
            self.linear.setValue(linear)
        if abs(radians(self.angular.value()) - self.model_angular) <= 1e-12:
            self.angular.setValue(degrees(angular))
        self.model_linear, self.model_angular = linear, angular
        self.defaults.setToolTip(f"Scaled to the model: {linear:.3g} mm, {degrees(angular):.3g}\u00b0")

    def _set_model_defaults(self):
        self.linear.setValue(self.model_linear)
        self.angular.setValue(degrees(self.model_angular))

    # --- values --------------------------------------------------------
    def scope_value(self):
        return self.scope.currentData()

    def settings(self):
        """(linear mm or None, angular rad or None, types, gap mm) as chosen;
        the model's defaults are passed as None (so they follow the model)."""
        linear = self.linear.value()
        angular = radians(self.angular.value())
        linear = None if abs(linear - self.model_linear) <= 1e-12 or linear <= 0 else linear
        angular = None if abs(angular - self.model_angular) <= 1e-12 or angular <= 0 else angular
        types = [k for k, check in self.types.items() if check.isChecked()]
        return linear, angular, types, self.gap.value()

    # --- running -------------------------------------------------------
    def request_cancel(self):
        self.cancel_requested = True

    def _set_progress(self, value):
        """The bar's value, painted with the next events processed (not at
        once: QProgressBar.setValue repaints, which flushes the window)."""
        self.progress_bar.setUpdatesEnabled(False)
        self.progress_bar.setValue(value)
        self.progress_bar.setUpdatesEnabled(True)  # schedules its paint

    def progress(self, stage, fraction):
        """The core's progress: shown, and Cancel heard, from PROGRESS_FIRST_S
        into the search, at most every PROGRESS_PERIOD_S, and never more than
        a tenth of the search's time
        (a QProgressBar repaints at once on each value, and processing the
        events may draw the window and its 3D view: done at each of the
        core's calls, on a busy machine, they took most of a search). The bar
        and the text are painted together, by the events processed: a paint
        of a widget flushes the whole window, composed through OpenGL beside
        the 3D view (software rendering under Xvfb: 0.1 s and more each)."""
        now = time.monotonic()
        if now >= self._next_progress:
            self._set_progress(int(fraction * 1000))
            self.status.setText(f"{stage.capitalize()}...")
            QtWidgets.QApplication.processEvents()
            done = time.monotonic()
            self._next_progress = done + max(PROGRESS_PERIOD_S, PROGRESS_COST_RATIO * (done - now))
        return not self.cancel_requested

    def run(self):
        """Finds the contacts; True when done (the panel may close)."""
        from contactwb import core
        from contactwb.make import analysis_of_scope, make_contact_analysis
        linear, angular, types, gap = self.settings()
        if not types:
            self.status.setText("Tick at least one contact type.")
            return False
        scope = self.scope_value()
        if scope != "Document" and not self.entries:
            self.status.setText("This scope needs parts: select them, then run Find contacts.")
            return False
        self.running, self.cancel_requested = True, False
        # a repaint of the window (and the events it lets in) per update: none for a search that ends soon
        self._next_progress = time.monotonic() + PROGRESS_FIRST_S
        self.cancel.setEnabled(True)
        # the same scope again: that analysis, updated in place (not a second one)
        target = self.group if is_alive(self.doc, self.group) else analysis_of_scope(self.doc, scope, self.entries)
        self.doc.openTransaction("Find contacts")
        try:
            group = make_contact_analysis(self.doc, self.entries if scope != "Document" else None,
                                          linear, angular, self.progress, scope=scope,
                                          types=types if len(types) < len(CONTACT_TYPES) else None,
                                          clearance_gap=gap, group=target)
        except core.Cancelled:
            self.doc.abortTransaction()
            self.status.setText("Cancelled: nothing changed.")
            self.progress_bar.setValue(0)
            FreeCAD.Console.PrintWarning("Contacts: cancelled\n")
            return False
        except (core.ContactsError, ValueError) as error:
            self.doc.abortTransaction()
            self.status.setText(f"Error: {error}")
            FreeCAD.Console.PrintError(f"Contacts: {error}\n")
            return False
        finally:
            self.running = False
            self.cancel.setEnabled(False)
        self.doc.commitTransaction()
        self.group = self.result = group
        self._set_progress(1000)  # painted if the panel stays open (OK closes it)
        message = (f"{group.ContactCount} contacts between {group.BodyCount} bodies "
                   f"({', '.join(group.Summary) or 'none'})")
        if group.InterferenceCount:
            message += (f"; {group.InterferenceCount} interference{'s' if group.InterferenceCount > 1 else ''} "
                        f"(overlapping material): " + "; ".join(group.Interferences))
        self.status.setText(message)
        FreeCAD.Console.PrintMessage(f"Contacts: {message}\n")
        from contactwb.gui.panels import contact_table
        contact_table.refresh()
        return True

    # --- FreeCAD task dialog -------------------------------------------
    def getStandardButtons(self):
        return int(QtWidgets.QDialogButtonBox.Ok | QtWidgets.QDialogButtonBox.Close)

    def accept(self):
        if self.running:
            return False
        if self.run():
            FreeCADGui.Control.closeDialog()
            return True
        return False

    def reject(self):
        if self.running:
            self.request_cancel()
            return False
        FreeCADGui.Control.closeDialog()
        return True


current = None  # the panel last opened (scripts and tests drive it)


def open_panel(doc, group=None):
    """Shows the panel (for `group`: to find its contacts again)."""
    if FreeCADGui.Control.activeDialog():
        FreeCADGui.Control.closeDialog()
    entries = selection_entries(doc) if group is None else None
    global current
    panel = current = FindContactsPanel(doc, entries, group)
    FreeCADGui.Control.showDialog(panel)
    QtCore.QCoreApplication.processEvents()
    return panel
