"""pytest configuration shared by the doctests and the test suite."""

import pytest

# running __main__ would call the command line and exit
collect_ignore = ["linkage_sym/__main__.py"]

SLOW_DOCTESTS = {
    "linkage_sym.synthesis.equations",  # each derives a mechanism's equations with SymPy
    "linkage_sym.synthesis.equations.latex_document",
    "linkage_sym.synthesis.equations.plain_text",
    "linkage_sym.plotting.centres.centres_figure",  # each draws a figure of every centre
    "linkage_sym.plotting.centres.polygons_figure",
}
"""Doctests over 3 s on a loaded 2-core machine: marked ``slow`` like the tests (a doctest
takes no decorator), so that ``pytest -m "not slow"`` leaves them out."""


def pytest_collection_modifyitems(config, items):
    for item in items:
        if isinstance(item, pytest.DoctestItem) and item.name in SLOW_DOCTESTS:
            item.add_marker(pytest.mark.slow)
