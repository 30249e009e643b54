"""The `contacts` command-line tool (`python3 -m contactwb.cli`): contacts.py
is `contacts FILE`, mesh.py `contacts mesh`, trial.py `contacts trial`.
Headless: imports core, document and make, never the GUI."""
import os as _os
import signal as _signal
import sys as _sys


def _cancelled_while_starting(signum, frame):
    _os.write(2, f"contacts: cancelled ({_signal.Signals(signum).name})\n".encode())
    _os._exit(130)


if _sys.argv == ["-m"]:
    # `python3 -m contactwb.cli` is starting (the `contacts` command; argv is ["-m"] only while
    # Python imports the package to run it): Ctrl+C or SIGTERM during the imports, before the
    # command's own handler (cli.process) is in place, ends it at once with exit 130 (nothing
    # has been written yet), not as a KeyboardInterrupt traceback inside an import.
    _signal.signal(_signal.SIGINT, _cancelled_while_starting)
    _signal.signal(_signal.SIGTERM, _cancelled_while_starting)

from contactwb.cli.contacts import (EXIT_CANCELLED, EXIT_FAILED, EXIT_INPUT, EXIT_INTERNAL,  # noqa: F401
                                    EXIT_OK, EXIT_USAGE, SUBCOMMANDS, main)
