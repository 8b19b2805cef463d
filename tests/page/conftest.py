"""Fixtures of the page's browser tests: one headless Chromium per module and the pages
each module writes once (:mod:`tests.support.browser` starts the browser)."""

from __future__ import annotations

import pytest

from tests.support import browser as support


@pytest.fixture(scope="module")
def browser():
    """A headless Chromium for the module's tests (quit at the module's end)."""
    driver = support.chromium()
    yield driver
    driver.quit()


@pytest.fixture(scope="module")
def pages(tmp_path_factory):
    """``page(name, scene=None)``: the path of the page of the shipped example ``name`` (or
    of ``scene``, under that name), written once per module."""
    from linkage_sym.examples import load_example
    from linkage_sym.page import page_html

    folder = tmp_path_factory.mktemp("pages")
    made = {}

    def page(name, scene=None):
        if name not in made:
            path = folder / f"{name}.html"
            path.write_text(page_html(scene if scene is not None else load_example(name)))
            made[name] = path
        return made[name]

    return page
