"""The small dialog of Contacts_AnnotateContact: the designer's intent and
ISO 286 fit for the contacts selected, the fit's class shown as it is typed
(at the first cylindrical contact's diameter)."""
from PySide2 import QtWidgets

from contactwb import core
from contactwb.objects.contact_objects import INTENT_CHOICES, check_annotation


class AnnotateDialog(QtWidgets.QDialog):
    """Intent (combo box) and fit (text), with the fit's class below."""

    def __init__(self, contacts, parent=None):
        super().__init__(parent)
        self.setObjectName("ContactsAnnotateDialog")
        self.contacts = list(contacts)
        self.setWindowTitle("Annotate contact" if len(self.contacts) == 1 else
                            f"Annotate {len(self.contacts)} contacts")
        layout = QtWidgets.QFormLayout(self)
        names = ", ".join(c.Label for c in self.contacts[:3]) + (" ..." if len(self.contacts) > 3 else "")
        layout.addRow(QtWidgets.QLabel(names))
        self.intent = QtWidgets.QComboBox()
        self.intent.setObjectName("intent")
        self.intent.addItems(INTENT_CHOICES)
        first = self.contacts[0]
        self.intent.setCurrentText(getattr(first, "Intent", "none"))
        layout.addRow("Intent", self.intent)
        self.fit = QtWidgets.QLineEdit(getattr(first, "Fit", ""))
        self.fit.setObjectName("fit")
        self.fit.setPlaceholderText("ISO 286 fit, e.g. H7/g6 (cylindrical contacts)")
        layout.addRow("Fit", self.fit)
        self.verdict = QtWidgets.QLabel()
        self.verdict.setObjectName("verdict")
        self.verdict.setWordWrap(True)
        layout.addRow(self.verdict)
        buttons = QtWidgets.QDialogButtonBox(QtWidgets.QDialogButtonBox.Ok | QtWidgets.QDialogButtonBox.Cancel)
        buttons.accepted.connect(self.accept)
        buttons.rejected.connect(self.reject)
        layout.addRow(buttons)
        self.ok_button = buttons.button(QtWidgets.QDialogButtonBox.Ok)
        self.intent.currentTextChanged.connect(self.check)
        self.fit.textChanged.connect(self.check)
        self.check()

    def values(self):
        return self.intent.currentText(), self.fit.text().strip()

    def check(self, *_):
        """Shows the fit's class at the first cylindrical contact, or why it is
        refused (OK disabled then)."""
        intent, fit = self.values()
        cylinder = next((c for c in self.contacts if c.ContactType == "CLJ"), None)
        if not fit:
            self.verdict.setText("")
            self.ok_button.setEnabled(True)
            return
        try:
            if cylinder is None:
                raise core.ArgumentError(f"fit {fit} needs a cylindrical contact (CLJ) to give its diameter")
            if intent in ("none", "ignored", "threaded"):
                raise core.ArgumentError(f"a fit needs an intent other than {intent}")
            found = check_annotation(cylinder, intent, fit)
        except core.ArgumentError as error:
            self.verdict.setText(f"<span style='color:#b00020'>{error}</span>")
            self.ok_button.setEnabled(False)
            return
        low, high = found.clearance
        self.verdict.setText(f"{found.fit_class} fit at \u00d8{found.diameter:g} mm: hole {found.hole[0]:+g}/"
                             f"{found.hole[1]:+g} \u00b5m, shaft {found.shaft[0]:+g}/{found.shaft[1]:+g} \u00b5m, "
                             f"clearance {low:g} to {high:g} \u00b5m")
        self.ok_button.setEnabled(True)
