"""The documentation site (docs/): it builds with warnings as errors, its command-line reference
lists every command and option of the parser, every gallery and tutorial page has its figures,
and every internal link resolves (a file of the build, and the anchor in it).

The build reuses the pictures of the gallery (docs/gallery/_files, made again when a scene
changes) and the notebooks' execution cache (docs/_build/.jupyter_cache): the first build on a
fresh checkout takes minutes, a later one seconds plus what changed.
"""

from __future__ import annotations

import argparse
import subprocess
import sys
from html.parser import HTMLParser
from pathlib import Path
from urllib.parse import unquote, urlsplit

import pytest

from linkage_sym.cli import build_parser
from linkage_sym.examples import example_names

ROOT = Path(__file__).resolve().parents[2]

pytestmark = pytest.mark.slow


class _Page(HTMLParser):
    """The text, the ids, the links and the images of one HTML page."""

    def __init__(self):
        super().__init__()
        self.text: list[str] = []
        self.ids: set[str] = set()
        self.links: list[str] = []
        self.images: list[str] = []

    def handle_starttag(self, tag, attrs):
        attrs = dict(attrs)
        if "id" in attrs:
            self.ids.add(attrs["id"])
        if tag == "a" and attrs.get("href"):
            self.links.append(attrs["href"])
        if tag == "img":
            self.images.append(attrs["src"])

    def handle_data(self, data):
        self.text.append(data)


def _read(path: Path) -> _Page:
    page = _Page()
    page.feed(path.read_text())
    page.text = " ".join("".join(page.text).split())
    return page


@pytest.fixture(scope="module")
def site(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("html")
    run = subprocess.run(
        [sys.executable, "-m", "sphinx", "-W", "--keep-going", "-q", "-b", "html",
         "-d", str(out / ".doctrees"), "docs", str(out)],
        cwd=ROOT, capture_output=True, text=True, check=False)
    assert run.returncode == 0, run.stdout + run.stderr
    return out


def _commands(parser, path=("linkage-sym",)):
    """(command words, sub-parser) of every command and sub-command, depth first."""
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            for name, sub in action.choices.items():
                yield (*path, name), sub
                yield from _commands(sub, (*path, name))


def test_cli_reference_lists_every_command_and_option(site):
    page = _read(site / "reference" / "cli.html")
    commands = list(_commands(build_parser()))
    assert len(commands) >= 12
    for words, sub in commands:
        command = " ".join(words)
        assert command in page.text, command
        for action in sub._actions:
            for option in action.option_strings:
                assert option in page.text, (command, option)


def test_every_example_has_its_gallery_page_with_figures(site):
    names = example_names()
    index = _read(site / "gallery" / "index.html")
    for name in names:
        assert f"{name}.html" in index.links, name
        page = _read(site / "gallery" / f"{name}.html")
        gifs = [s for s in page.images if s.endswith(".gif")]
        pngs = [s for s in page.images if s.endswith(".png")]
        assert len(gifs) == 1 and len(pngs) >= 2, (name, page.images)
        for src in page.images:
            assert (site / "gallery" / src).resolve().is_file(), (name, src)


def test_every_tutorial_has_its_figures(site):
    notebooks = sorted(p.stem for p in (ROOT / "notebooks").glob("*.py")
                       if p.read_text().startswith("# ---\n# jupyter:"))
    assert notebooks
    for name in notebooks:
        page = _read(site / "tutorials" / f"{name}.html")
        assert page.images, name
        for src in page.images:
            assert src.startswith("data:") or (site / "tutorials" / src).resolve().is_file()


def test_internal_links_resolve(site):
    pages = {p.resolve(): _read(p) for p in site.rglob("*.html")
             if "_static" not in p.parts and ".doctrees" not in p.parts}
    checked = 0
    for path, page in pages.items():
        for href in page.links:
            parts = urlsplit(href)
            if parts.scheme or parts.netloc or href.startswith("mailto:"):
                continue
            target = (path.parent / unquote(parts.path)).resolve() if parts.path else path
            assert target.exists(), (path.relative_to(site), href)
            if parts.fragment and target.suffix == ".html":
                assert parts.fragment in pages[target].ids, (path.relative_to(site), href)
            checked += 1
    assert checked > 500
