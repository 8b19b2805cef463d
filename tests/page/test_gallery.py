"""The demo's gallery (:mod:`linkage_sym.page.gallery`): one page per shipped example and
one HTML file linking them, self-contained, with relative links that resolve.

The links are read back from the written HTML by the standard library's parser, not by the
code that wrote them.
"""

from __future__ import annotations

from html.parser import HTMLParser

import pytest

from linkage_sym.cli import main
from linkage_sym.examples import example_names, load_example
from linkage_sym.page.gallery import example_descriptions, write_gallery


class _Cards(HTMLParser):
    """Every ``href``, ``src`` and inline ``svg`` of a document, and each card's texts."""

    def __init__(self):
        super().__init__()
        self.hrefs, self.srcs, self.svgs, self.cards = [], [], 0, []
        self._tag = None

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if "href" in a:
            self.hrefs.append(a["href"])
        if "src" in a:
            self.srcs.append(a["src"])
        if tag == "svg":
            self.svgs += 1
        if tag == "a" and a.get("class") == "card":
            self.cards.append({"href": a["href"], "texts": []})
        self._tag = tag

    def handle_data(self, data):
        if self.cards and self._tag in ("h2", "p") and data.strip():
            self.cards[-1]["texts"].append(data.strip())


@pytest.fixture(scope="module")
def gallery(tmp_path_factory):
    """``linkage-sym demo`` as the README's quick start runs it (no ``--example``), its own
    analyses cut to the crank-rocker's: the folder and what it printed."""
    import contextlib
    import io

    import linkage_sym.cli.demo as demo

    folder = tmp_path_factory.mktemp("demo")
    printed = io.StringIO()
    with pytest.MonkeyPatch.context() as mp, contextlib.redirect_stdout(printed):
        mp.setattr(demo, "DEMO_EXAMPLES", ("crank_rocker",))
        assert main(["demo", "-o", str(folder)]) == 0
    return folder, printed.getvalue()


@pytest.mark.slow
def test_the_demo_s_gallery_links_every_example_s_page_and_every_link_resolves(gallery):
    folder, printed = gallery
    assert str(folder / "gallery.html") in printed
    written = [folder / "gallery.html", *(folder / "pages").iterdir()]
    html = written[0].read_text("utf-8")
    parsed = _Cards()
    parsed.feed(html)
    names = example_names()
    assert parsed.hrefs == [f"pages/{n}.html" for n in names]
    for href in parsed.hrefs:  # relative, and a file the demo wrote
        target = folder / href
        assert target.is_file() and target in written
        assert target.read_text("utf-8").startswith("<!DOCTYPE html>")
    assert parsed.srcs == [] and parsed.svgs == len(names)  # thumbnails inline
    descriptions = example_descriptions()
    for card, n in zip(parsed.cards, names):
        assert card["texts"][:2] == [load_example(n).name, descriptions[n]]
    for path in written:
        text = path.read_text("utf-8")
        assert "http://" not in text and "https://" not in text, path.name


def test_every_shipped_example_has_a_one_line_description():
    d = example_descriptions()
    assert sorted(d) == example_names()
    assert d["cam_eccentric_rocker"] == "problem 3-8 of the textbook chapter (cam contact, an extension)"
    assert all(v and "\n" not in v and "*" not in v for v in d.values())


def test_an_example_without_a_description_is_refused_naming_it(tmp_path, monkeypatch):
    import linkage_sym.page.gallery as g

    monkeypatch.setattr(g, "example_descriptions", lambda: {})
    with pytest.raises(KeyError, match="crank_rocker"):
        write_gallery(tmp_path, ["crank_rocker"])
    assert list(tmp_path.iterdir()) == []


@pytest.mark.slow
def test_the_demo_of_named_examples_writes_no_gallery(tmp_path):
    """``--example`` runs those examples' analyses only: every file is named after a scene."""
    assert main(["demo", "-o", str(tmp_path), "--example", "slider_crank_offset"]) == 0
    assert not (tmp_path / "gallery.html").exists() and not (tmp_path / "pages").exists()


def test_write_gallery_writes_the_pages_it_is_given(tmp_path):
    written = write_gallery(tmp_path, ["cam_eccentric_rocker"])
    assert written == [tmp_path / "gallery.html", tmp_path / "pages" / "cam_eccentric_rocker.html"]
    parsed = _Cards()
    parsed.feed(written[0].read_text("utf-8"))
    assert parsed.hrefs == ["pages/cam_eccentric_rocker.html"]


def test_write_gallery_embeds_each_example_s_run_it_is_given(tmp_path):
    """A page with a run opens with its warnings (none for the crank-rocker), one without
    with its evaluator's (``BUILT`` null)."""
    import linkage_sym
    from linkage_sym.examples import load_example

    run = linkage_sym.analyze(load_example("crank_rocker"))
    _, with_run, without = write_gallery(tmp_path, ["crank_rocker", "fivebar"],
                                         {"crank_rocker": run})
    assert "const BUILT = [];" in with_run.read_text("utf-8")
    assert "const BUILT = null;" in without.read_text("utf-8")
