"""The `contacts` command-line tool (`python3 -m contactwb.cli`): contacts.py
is `contacts FILE`, mesh.py `contacts mesh`, trial.py `contacts trial`.
Headless: imports core, document and make, never the GUI."""
from contactwb.cli.contacts import (EXIT_CANCELLED, EXIT_FAILED, EXIT_INPUT, EXIT_INTERNAL,  # noqa: F401
                                    EXIT_OK, EXIT_USAGE, SUBCOMMANDS, main)
