"""make_* functions: create the workbench's document objects, headless."""
from contactwb.make.make_contact_analysis import make_contact_analysis, update_contact_analysis  # noqa: F401
