"""``python -m linkage_sym``: the same program as ``linkage-sym``."""

import sys

from linkage_sym.cli import main

sys.exit(main())
