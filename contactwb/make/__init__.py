"""make_* functions: create the workbench's document objects, headless.
(update_* are the objects' recomputes, contactwb.objects; kept here as the
public API has always named them.)"""
from contactwb.make.make_contact_analysis import (analysis_of_scope, make_contact_analysis,  # noqa: F401
                                                 update_contact_analysis)
from contactwb.make.annotate_contacts import annotate_contacts  # noqa: F401
from contactwb.make.make_simulation_model import make_simulation_model, update_simulation_model  # noqa: F401
