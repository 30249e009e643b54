"""annotate_contacts(): the designer's intent (and ISO 286 fit) on some
Contact objects, in one undoable step named "Annotate contact", their
analyses' joints derived again to honour it; headless (the GUI's
Contacts_AnnotateContact calls it)."""
from contactwb import core
from contactwb.document.identify import is_contact, is_contact_analysis
from contactwb.objects.contact_objects import INTENT_CHOICES, check_annotation, update_contact_analysis

TRANSACTION = "Annotate contact"


def annotate_contacts(contacts, intent, fit=""):
    """Sets Intent (one of INTENT_CHOICES; "none" clears it) and Fit (an ISO
    286 code such as H7/p6, "" for none) on each Contact of `contacts`, then
    finds their analyses' contacts and joints again, all in one transaction.
    Raises core.ArgumentError naming the contact for an unknown intent, a fit
    the tables refuse or one contradicting the intent (nothing changed
    then). Returns the analyses updated."""
    contacts = [c for c in contacts if is_contact(c)]
    if not contacts:
        raise core.ArgumentError("no contact to annotate: select contacts in the tree or the contact table")
    if intent not in INTENT_CHOICES:
        raise core.ArgumentError(f"unknown intent '{intent}' (use {', '.join(INTENT_CHOICES)})")
    fit = (fit or "").strip()
    if fit and intent in ("none", "ignored"):
        raise core.ArgumentError(f"a fit ('{fit}') needs an intent other than {intent}")
    if fit:  # every contact checked before anything changes
        from contactwb.core import annotations
        fitted = [c for c in contacts if c.ContactType in annotations.FIT_TYPES]
        if not fitted:
            raise core.ArgumentError(f"fit {fit} needs a cylindrical contact (CLJ) to give its diameter; "
                                     f"the contacts selected are {', '.join(c.Label for c in contacts)}")
        for contact in fitted:
            check_annotation(contact, intent, fit)
    doc = contacts[0].Document
    groups = []
    for contact in contacts:
        for parent in contact.InList:
            if is_contact_analysis(parent) and parent not in groups:
                groups.append(parent)
    doc.openTransaction(TRANSACTION)
    try:
        from contactwb.core import annotations
        for contact in contacts:
            contact.Intent = intent
            contact.Fit = fit if contact.ContactType in annotations.FIT_TYPES else ""
        for group in groups:
            update_contact_analysis(group)
        for contact in contacts:
            contact.purgeTouched()
        for group in groups:
            group.purgeTouched()
    except Exception:
        doc.abortTransaction()
        raise
    doc.commitTransaction()
    return groups
