"""Reproductions of the sources' printed numbers (README, "Sources" [1]-[4]).

Each script in this folder runs on its own (``python3 paper_repro/<script>.py``) and exposes
``items()``, its comparisons as :class:`paper_repro.items.Item` rows; ``python -m paper_repro``
(or ``python paper_repro/run_all.py``) prints them all as one table per source and exits
non-zero if any drifted.
"""
