"""``python -m ccopt.cli``: the ``ccopt`` command."""
import sys

from ccopt.cli import main

sys.exit(main())
