"""The `contacts` command-line tool (`python3 -m contactwb.cli`): contacts.py
is `contacts FILE`, mesh.py `contacts mesh`, trial.py `contacts trial`.
Headless: imports core, document and make, never the GUI."""
import signal as _signal
import sys as _sys

if _sys.argv == ["-m"]:
    # `python3 -m contactwb.cli` is starting (the `contacts` command; argv is ["-m"] only while
    # Python imports the package to run): hold SIGINT and SIGTERM from here on, so that Ctrl+C
    # during the second of imports before the command's own handler (cli.process) is in place is
    # taken by that handler (exit 130), not raised as a KeyboardInterrupt inside an import.
    _signal.pthread_sigmask(_signal.SIG_BLOCK, {_signal.SIGINT, _signal.SIGTERM})

from contactwb.cli.contacts import (EXIT_CANCELLED, EXIT_FAILED, EXIT_INPUT, EXIT_INTERNAL,  # noqa: F401
                                    EXIT_OK, EXIT_USAGE, SUBCOMMANDS, main)
