"""`python3 -m contactwb.cli FILE ...` (the installed `contacts` wrapper runs this)."""
import sys

from contactwb.cli.contacts import main

sys.exit(main())
