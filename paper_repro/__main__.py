"""``python -m paper_repro``: every source's table of reproduced items (see run_all.py)."""

import sys

from paper_repro.run_all import main

sys.exit(main())
