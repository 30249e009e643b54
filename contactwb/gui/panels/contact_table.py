"""The contact table: a dock listing every contact of the active document's
analyses, sortable and filterable (text, type, partial), with the paper's
summary (counts per type and per body pair). Selection goes both ways: a row
selects its contact (zoom and isolate on demand); selecting a part, a painted
face or a contact in the view or the tree selects its rows."""
import FreeCAD
import FreeCADGui
from PySide2 import QtCore, QtGui, QtWidgets

from contactwb.core.kinds import CONTACT_TYPES
from contactwb.document import units
from contactwb.document.identify import interferences_of, is_contact, is_joint
from contactwb.gui.overlay.colours import legend_colours
from contactwb.gui.palette import INTERFERENCE_COLOUR
from contactwb.gui.panels import contact_extent

# Quantities written as the property editor writes them (contactwb.document.units)
COLUMNS = ["#", "Type", "Part A", "Part B", "Area", "Span / DOF", "Radius", "Extent", "Partial", "Analysis"]
NUMERIC = {0, 4, 5, 6}
PARTIAL_COLUMN = 8
DOCK_NAME = "ContactsTable"
SORT_KEY = QtCore.Qt.UserRole + 2  # the Type column's key: type, then pair, then number
# The dock's share of the main window's width at most: the 3D view keeps the rest.
DOCK_WIDTH_SHARE = 0.3
DOCK_MIN_WIDTH = 360
# Types with an angular span and a radius (revolution contacts); the others show none.
REVOLUTION_TYPES = ("CLJ", "CJU", "SPF", "LAF", "SPT", "TRF")


class _Item(QtWidgets.QTableWidgetItem):
    """A cell sorting by its number when it has one."""

    def __lt__(self, other):
        mine, theirs = self.data(SORT_KEY), other.data(SORT_KEY)
        if mine is not None and theirs is not None:
            return mine < theirs
        mine, theirs = self.data(QtCore.Qt.UserRole + 1), other.data(QtCore.Qt.UserRole + 1)
        if mine is not None and theirs is not None:
            return mine < theirs
        return super().__lt__(other)


def _sort_key(kind, a, b, number):
    """Type, then pair (the two parts in name order), then number."""
    rank = CONTACT_TYPES.index(kind) if kind in CONTACT_TYPES else len(CONTACT_TYPES)
    return "\t".join((f"{rank:02d}{kind}", *sorted((a, b)), f"{number:09d}"))  # (no NUL: Qt cuts there)


def _cell(text, number=None, colour=None):
    item = _Item(text)
    item.setFlags(QtCore.Qt.ItemIsSelectable | QtCore.Qt.ItemIsEnabled)
    if number is not None:
        item.setData(QtCore.Qt.UserRole + 1, float(number))
        item.setTextAlignment(QtCore.Qt.AlignRight | QtCore.Qt.AlignVCenter)
    if colour is not None:
        item.setData(QtCore.Qt.DecorationRole, QtGui.QColor(colour))
    return item


class ContactTable(QtWidgets.QWidget):
    """The dock's widget."""

    def __init__(self, parent=None):
        super().__init__(parent)
        self.setObjectName("ContactsTableWidget")
        self.doc_name = None
        self.contacts = []       # Contact objects, in row-insertion order (row -> via UserRole)
        self._syncing = False
        layout = QtWidgets.QVBoxLayout(self)
        filters = QtWidgets.QHBoxLayout()
        self.filter_text = QtWidgets.QLineEdit()
        self.filter_text.setPlaceholderText("Filter by part or type...")
        self.filter_type = QtWidgets.QComboBox()
        self.filter_type.addItem("All types", "")
        for kind in CONTACT_TYPES:
            self.filter_type.addItem(kind, kind)
        self.filter_type.addItem("Joints", "joint")
        self.filter_partial = QtWidgets.QCheckBox("Partial only")
        self.min_area = QtWidgets.QDoubleSpinBox()
        self.min_area.setRange(0, 1e12)
        self.min_area.setDecimals(3)
        self.min_area.setPrefix("area \u2265 ")
        self.min_area.setSuffix(" mm\u00b2")
        for widget in (self.filter_text, self.filter_type, self.min_area, self.filter_partial):
            filters.addWidget(widget)
        layout.addLayout(filters)
        self.table = QtWidgets.QTableWidget(0, len(COLUMNS))
        self.table.setHorizontalHeaderLabels(COLUMNS)
        self.table.setSelectionBehavior(QtWidgets.QAbstractItemView.SelectRows)
        self.table.setSelectionMode(QtWidgets.QAbstractItemView.ExtendedSelection)
        self.table.verticalHeader().setVisible(False)
        self.table.horizontalHeader().setStretchLastSection(True)
        self.table.horizontalHeader().setSortIndicator(1, QtCore.Qt.AscendingOrder)  # type, then pair
        self.table.setHorizontalScrollBarPolicy(QtCore.Qt.ScrollBarAsNeeded)
        self.table.setWordWrap(False)
        # The summary has its own pane under the table, collapsible and
        # scrolling: a long "By pair" list never takes the table's rows.
        self.splitter = QtWidgets.QSplitter(QtCore.Qt.Vertical)
        self.splitter.addWidget(self.table)
        summary_pane = QtWidgets.QWidget()
        summary_layout = QtWidgets.QVBoxLayout(summary_pane)
        summary_layout.setContentsMargins(0, 0, 0, 0)
        self.summary_toggle = QtWidgets.QToolButton()
        self.summary_toggle.setText("Summary")
        self.summary_toggle.setCheckable(True)
        self.summary_toggle.setChecked(True)
        self.summary_toggle.setToolButtonStyle(QtCore.Qt.ToolButtonTextBesideIcon)
        self.summary_toggle.setArrowType(QtCore.Qt.DownArrow)
        self.summary_toggle.setAutoRaise(True)
        summary_layout.addWidget(self.summary_toggle)
        self.summary = QtWidgets.QTextBrowser()
        self.summary.setObjectName("ContactsSummary")
        summary_layout.addWidget(self.summary, 1)
        self.summary_pane = summary_pane
        self.splitter.addWidget(summary_pane)
        self.splitter.setStretchFactor(0, 4)
        self.splitter.setStretchFactor(1, 1)
        self.splitter.setCollapsible(0, False)
        self.splitter.setSizes([400, 110])
        layout.addWidget(self.splitter, 1)
        self.summary_toggle.toggled.connect(self.set_summary_shown)
        buttons = QtWidgets.QHBoxLayout()
        self.zoom_button = QtWidgets.QPushButton("Zoom to")
        self.isolate_button = QtWidgets.QPushButton("Isolate")
        self.show_all_button = QtWidgets.QPushButton("Show all")
        for widget in (self.zoom_button, self.isolate_button, self.show_all_button):
            buttons.addWidget(widget)
        buttons.addStretch(1)
        layout.addLayout(buttons)
        self.filter_text.textChanged.connect(self.apply_filter)
        self.filter_type.currentIndexChanged.connect(self.apply_filter)
        self.filter_partial.toggled.connect(self.apply_filter)
        self.min_area.valueChanged.connect(self.apply_filter)
        self.table.itemSelectionChanged.connect(self._rows_selected)
        self.zoom_button.clicked.connect(self.zoom)
        self.isolate_button.clicked.connect(self.isolate)
        self.show_all_button.clicked.connect(self.show_all)
        self.table.setContextMenuPolicy(QtCore.Qt.CustomContextMenu)
        self.table.customContextMenuRequested.connect(self._context_menu)

    def sizeHint(self):
        # What the dock asks for: the columns scroll, the 3D view keeps its room.
        return QtCore.QSize(DOCK_MIN_WIDTH + 60, 480)

    def minimumSizeHint(self):
        return QtCore.QSize(240, 200)

    def set_summary_shown(self, shown):
        """Folds the summary pane to its header (or opens it again)."""
        self.summary.setVisible(shown)
        self.summary_toggle.setArrowType(QtCore.Qt.DownArrow if shown else QtCore.Qt.RightArrow)
        self.summary_pane.setMaximumHeight(16777215 if shown else self.summary_toggle.sizeHint().height())
        if shown:
            total = sum(self.splitter.sizes())
            self.splitter.setSizes([total - 110, 110])

    # --- filling -------------------------------------------------------
    def fill(self, doc=None):
        """Lists the contacts of `doc` (default: the active document)."""
        from contactwb.document import export
        doc = doc or FreeCAD.ActiveDocument
        self.doc_name = doc.Name if doc else None
        groups = export.analyses(doc) if doc else []
        self.contacts = [c for g in groups for c in export.live_contacts(g)]
        joints = [j for g in groups for j in g.Group if is_joint(j)]
        colours = legend_colours()
        self._syncing = True
        self.table.setSortingEnabled(False)
        interferences = [i for g in groups for i in interferences_of(g)]
        self.table.setRowCount(len(self.contacts) + len(joints) + len(interferences))
        for row, contact in enumerate(self.contacts):
            group = next((p for p in contact.InList if p in groups), None)
            kind = contact.ContactType
            revolution = kind in REVOLUTION_TYPES
            type_cell = _cell(kind, colour=colours.get(kind))
            type_cell.setData(SORT_KEY, _sort_key(kind, contact.BodyA, contact.BodyB, contact.Number))
            cells = [
                _cell(str(contact.Number), contact.Number),
                type_cell,
                _cell(contact.BodyA), _cell(contact.BodyB),
                _cell(units.area_text(contact.Area.Value), contact.Area.Value),
                _cell(units.angle_text(contact.Span.Value) if revolution else "", contact.Span.Value),
                _cell(units.length_text(contact.Radius.Value) if revolution else "", contact.Radius.Value),
                _cell(contact_extent.extent_text(contact)),
                _cell("yes" if contact.Partial else ""),
                _cell(group.Label if group else ""),
            ]
            for column, item in enumerate(cells):
                item.setData(QtCore.Qt.UserRole, contact.Name)
                self.table.setItem(row, column, item)
        for row, joint in enumerate(joints, start=len(self.contacts)):
            group = next((p for p in joint.InList if p in groups), None)
            number = joint.Label.split(" ", 1)[0]  # "J3"
            type_cell = _cell(f"joint: {joint.JointType}")
            type_cell.setData(SORT_KEY, _sort_key("joint " + joint.JointType, joint.BodyA, joint.BodyB,
                                                  int(number[1:]) if number[1:].isdigit() else 0))
            cells = [_cell(number), type_cell, _cell(joint.BodyA), _cell(joint.BodyB),
                     _cell("", 0.0), _cell(f"{joint.DOF} DOF", joint.DOF), _cell(""), _cell(""), _cell(""),
                     _cell(group.Label if group else "")]
            for column, item in enumerate(cells):
                item.setData(QtCore.Qt.UserRole, joint.Name)
                self.table.setItem(row, column, item)
        # overlapping material: its common volume in the area column
        analysis_of = {o.Name: g for g in groups for o in interferences_of(g)}  # under its Interferences group
        for row, overlap in enumerate(interferences, start=len(self.contacts) + len(joints)):
            group = analysis_of.get(overlap.Name)
            volume = overlap.Volume.Value
            number = f"I{overlap.Number}" if getattr(overlap, "Number", 0) else overlap.Label.split(":", 1)[0]  # "I2"
            type_cell = _cell("Interference", colour=INTERFERENCE_COLOUR)
            type_cell.setData(SORT_KEY, _sort_key("Interference", overlap.BodyA, overlap.BodyB,
                                                  int(number[1:]) if number[1:].isdigit() else 0))
            cells = [_cell(number), type_cell, _cell(overlap.BodyA), _cell(overlap.BodyB),
                     _cell(units.volume_text(volume), volume), _cell(""), _cell(""), _cell(""), _cell(""),
                     _cell(group.Label if group else "")]
            for column, item in enumerate(cells):
                item.setData(QtCore.Qt.UserRole, overlap.Name)
                self.table.setItem(row, column, item)
        self.table.setSortingEnabled(True)  # sorts by the header's column: type then pair at first
        self.table.resizeColumnsToContents()
        self._syncing = False
        self.summary.setText(self._summary(groups))
        self.apply_filter()
        self.sync_from_selection()

    @staticmethod
    def _summary(groups):
        lines = []
        for group in groups:
            contacts = sum(1 for c in group.Group if is_contact(c))
            joints = sum(1 for c in group.Group if is_joint(c))
            lines.append(f"<b>{group.Label}</b>: {contacts} contacts between {group.BodyCount} bodies"
                         + (f", {joints} joints" if joints else "")
                         + (" <i>(out of date: recompute)</i>" if "Touched" in group.State else ""))
            lines.append("By type: " + (", ".join(group.Summary) or "none"))
            if getattr(group, "InterferenceCount", 0):
                lines.append(f"Interferences: {group.InterferenceCount} (overlapping material)")
            if group.PairSummary:
                lines.append("By pair: " + "; ".join(group.PairSummary))
            if getattr(group, "Mobility", None):
                lines.append("; ".join(group.Mobility[:2]))
        return "<br>".join(lines) or "No contact analysis in this document: run Find contacts."

    def contact_of_row(self, row):
        item = self.table.item(row, 0)
        name = item.data(QtCore.Qt.UserRole) if item else None
        doc = FreeCAD.getDocument(self.doc_name) if self.doc_name else None
        return doc.getObject(name) if doc and name else None

    def row_of(self, name):
        for row in range(self.table.rowCount()):
            if self.table.item(row, 0).data(QtCore.Qt.UserRole) == name:
                return row
        return -1

    def apply_filter(self, *_):
        text = self.filter_text.text().strip().lower()
        kind = self.filter_type.currentData()
        partial_only = self.filter_partial.isChecked()
        least = self.min_area.value()
        for row in range(self.table.rowCount()):
            values = [self.table.item(row, c).text() for c in (1, 2, 3)]
            hidden = bool(text) and not any(text in v.lower() for v in values)
            hidden |= bool(kind) and values[0] != kind and not (kind == "joint" and values[0].startswith("joint"))
            hidden |= partial_only and self.table.item(row, PARTIAL_COLUMN).text() != "yes"
            hidden |= self.table.item(row, 4).data(QtCore.Qt.UserRole + 1) < least
            self.table.setRowHidden(row, hidden)

    def _context_menu(self, position):
        """Right-click on rows: annotate their contacts (the selection follows the rows)."""
        if not [c for c in self.selected_contacts() if not is_joint(c)]:
            return
        menu = QtWidgets.QMenu(self.table)
        menu.addAction("Annotate (intent, fit)...", lambda: FreeCADGui.runCommand("Contacts_AnnotateContact"))
        menu.exec_(self.table.viewport().mapToGlobal(position))

    def visible_rows(self):
        return [r for r in range(self.table.rowCount()) if not self.table.isRowHidden(r)]

    # --- selection, both ways -------------------------------------------
    def selected_contacts(self):
        rows = sorted({index.row() for index in self.table.selectionModel().selectedRows()})
        return [c for c in (self.contact_of_row(r) for r in rows) if c is not None]

    def _first_contact(self):
        """The first selected row's contact (a joint's first contact)."""
        for obj in self.selected_contacts():
            if is_joint(obj):
                if obj.Contacts:
                    return obj.Contacts[0]
            elif is_contact(obj):  # (an interference has no faces to zoom to)
                return obj
        return None

    def _rows_selected(self):
        if self._syncing:
            return
        contacts = self.selected_contacts()
        self._syncing = True
        try:
            FreeCADGui.Selection.clearSelection()
            for contact in contacts:
                FreeCADGui.Selection.addSelection(contact)
        finally:
            self._syncing = False

    def sync_from_selection(self):
        """Selects the rows of the contacts selected, or touching a selected
        part or face, in the tree or the view."""
        if self._syncing or not self.doc_name:
            return
        from contactwb.gui import actions
        faces, bodies = {}, {}
        for contact in self.contacts:
            try:
                for links in (contact.FacesA, contact.FacesB):
                    for root, subnames in links:
                        for subname in subnames:
                            faces.setdefault((root.Name, subname), set()).add(contact.Name)
                bodies[contact.Name] = actions.contact_bodies(contact)
            except Exception:  # a contact deleted meanwhile
                continue
        wanted = set()
        for selected in FreeCADGui.Selection.getSelectionEx(self.doc_name, 0):
            obj = selected.Object
            for subname in selected.SubElementNames or [""]:
                target = obj.getSubObject(subname, retType=1) if subname else obj
                if is_contact(target) or is_joint(target):
                    wanted.add(target.Name)
                    continue
                if (obj.Name, subname) in faces:  # a painted face: its contacts
                    wanted |= faces[(obj.Name, subname)]
                    continue
                # a part (or one of its other faces): every contact it has
                element = subname.rpartition(".")[2]
                path = subname[:len(subname) - len(element)] if element else subname
                for name, paths in bodies.items():
                    for root, body_path in paths:
                        if root is obj and (body_path.startswith(path) if not element
                                            else path.startswith(body_path)):
                            wanted.add(name)
        self._syncing = True
        try:
            self.table.clearSelection()
            model = self.table.selectionModel()
            for name in wanted:
                row = self.row_of(name)
                if row >= 0:
                    model.select(self.table.model().index(row, 0),
                                 QtCore.QItemSelectionModel.Select | QtCore.QItemSelectionModel.Rows)
            if wanted:
                row = self.row_of(sorted(wanted)[0])
                if row >= 0:
                    self.table.scrollToItem(self.table.item(row, 0))
        finally:
            self._syncing = False

    # --- buttons -------------------------------------------------------
    def zoom(self):
        from contactwb.gui import actions
        contact = self._first_contact()
        if contact is not None:
            actions.zoom_to(contact)

    def isolate(self):
        from contactwb.gui import actions
        contact = self._first_contact()
        if contact is not None:
            actions.isolate(contact)
            actions.zoom_to(contact)

    def show_all(self):
        from contactwb.gui import actions
        if self.doc_name:
            actions.show_all(FreeCAD.getDocument(self.doc_name))


class _Observer:
    """Keeps the table in step with the selection and the documents."""

    def __init__(self, table):
        self.table = table
        self._scheduled = False

    def _sync(self, *_):
        try:
            if self.table.doc_name:
                self.table.sync_from_selection()
        except Exception as error:  # an observer must never break the selection
            FreeCAD.Console.PrintWarning(f"Contacts: table selection failed: {error}\n")

    addSelection = removeSelection = setSelection = clearSelection = _sync

    def _schedule(self):
        if not self._scheduled:
            self._scheduled = True
            QtCore.QTimer.singleShot(0, self._refill)

    def _refill(self):
        self._scheduled = False
        try:
            self.table.fill()
        except Exception as error:
            FreeCAD.Console.PrintWarning(f"Contacts: table refresh failed: {error}\n")

    def slotRecomputedDocument(self, doc):
        self._schedule()

    def slotDeletedObject(self, obj):
        if is_contact(obj):
            self._schedule()

    def slotActivateDocument(self, doc):
        self._schedule()

    def slotDeletedDocument(self, doc):
        self._schedule()


_dock = None


def dock():
    """The dock (created once, tabbed on the right)."""
    global _dock
    if _dock is None:
        main = FreeCADGui.getMainWindow()
        _dock = QtWidgets.QDockWidget("Contacts", main)
        _dock.setObjectName(DOCK_NAME)
        widget = ContactTable(_dock)
        _dock.setWidget(widget)
        main.addDockWidget(QtCore.Qt.RightDockWidgetArea, _dock)
        fit_dock_width(_dock)
        observer = _Observer(widget)
        _dock.observer = observer
        FreeCADGui.Selection.addObserver(observer)
        FreeCAD.addDocumentObserver(observer)
    return _dock


def fit_dock_width(dock_widget):
    """Gives the dock at most DOCK_WIDTH_SHARE of the main window's width
    (never under DOCK_MIN_WIDTH): the table's columns scroll instead of
    squeezing the 3D view."""
    main = dock_widget.parentWidget()
    if main is None or dock_widget.isFloating():
        return
    width = max(DOCK_MIN_WIDTH, int(main.width() * DOCK_WIDTH_SHARE))
    if dock_widget.width() > width or not dock_widget.isVisible():
        main.resizeDocks([dock_widget], [width], QtCore.Qt.Horizontal)


def show():
    """Shows the table with the active document's contacts."""
    widget = dock()
    widget.widget().fill()
    widget.show()
    widget.raise_()
    fit_dock_width(widget)
    return widget.widget()


def refresh():
    """Refills the table if it was opened."""
    if _dock is not None and _dock.isVisible():
        _dock.widget().fill()
