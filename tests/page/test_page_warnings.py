"""The page's warnings panel in a real browser (headless Chromium through Selenium).

The page of a scene written with a Python run (``page_html(scene, analyze(scene))``, as
``linkage-sym view`` writes it) opens with that run's warnings; after each change the page
lists what its own evaluator finds, worded in JavaScript from its own solution.  The
references are :func:`linkage_sym.analyze` (the numeric solver, which shares no code with
the page's evaluator) of the scene the page's ``scene()`` returns, and the guide-slider of
:mod:`tests.support.parallel_slides`, whose joint ``C`` passes through infinity where the
guide is horizontal:

* as built, the panel shows the run's warning of that passage, and the page's evaluator
  finds the same text; a step exactly at the parallel position is counted as unassemblable;
* after a move of the rod's slide on the guide the passage moves (the page's text is the
  run's for the edited scene), or is gone (and so is the panel), or a step lands on the
  parallel position (and cannot be assembled);
* a crank-rocker whose rocker pivot moves out of reach has steps that cannot be assembled,
  counted and named as the Python run's statuses say;
* a scene without warnings has a hidden, empty panel;
* warnings the page cannot recompute (friction at a standstill) show as from the scene as
  built, and are marked stale after a change and current again when it is undone;
* the driver values are worded as the Python messages word them.
"""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import numpy as np
import pytest

import linkage_sym
from linkage_sym.examples import load_example
from linkage_sym.numeric.results.wording import driver_number
from linkage_sym.page import page_html
from linkage_sym.scene import parse_scene
from tests.support.browser import CHROMEDRIVER, CHROMIUM, open_page
from tests.support.parallel_slides import guide_slider

pytest.importorskip("selenium.webdriver",
                    reason="Selenium is not installed (pip install linkage_sym[page-tests])")

pytestmark = [
    pytest.mark.skipif(not CHROMIUM.exists(), reason=f"no Chromium at {CHROMIUM} "
                       "(apt-get install chromium chromium-driver)"),
    pytest.mark.skipif(not Path(CHROMEDRIVER).exists(), reason="no chromedriver "
                       "(apt-get install chromium-driver)"),
    pytest.mark.slow,
]


def passage(before, after, where):
    """The Python run's wording of the guide-slider's passage (written out here)."""
    return ("dyad PRP (rod, block): the slides of joints A_slide and C_guide become parallel "
            f"between A = {before}° and A = {after}°: joint C passes through infinity there; "
            f"at {where} it is on the far side of its slides")


def built_page(tmp_path, scene, name):
    path = tmp_path / f"{name}.html"
    path.write_text(page_html(scene, linkage_sym.analyze(scene)))
    return path


def warnings(browser):
    return browser.execute_script("return window.linkageSym.warnings()")


def panel(browser):
    """The panel as a reader sees it: shown or not, and its items' texts."""
    el = browser.find_element("id", "warnings")
    items = browser.execute_script(
        "return [...document.querySelectorAll('#warnings-list li > span:first-child')]"
        ".map((s) => s.textContent)")
    return el.is_displayed(), items


def edited(browser):
    """The page's scene, read by the library's loader, and the Python run of it."""
    scene = parse_scene(browser.execute_script("return window.linkageSym.scene()"))
    return scene, linkage_sym.analyze(scene)


@pytest.mark.parametrize("steps, lines", [
    (10, [passage("1.66667", "-1.66667", "step 5 (reached from step 4)")]),
    (11, ["1 step(s) cannot be assembled (steps 5)",
          passage("1.5", "-1.5", "step 6 (reached from step 5)")]),
])
def test_the_panel_opens_with_the_run_s_passage_which_the_page_finds_too(
        browser, tmp_path, steps, lines):
    scene = parse_scene(guide_slider(steps))
    res = linkage_sym.analyze(scene)
    assert res.warnings == lines[-1:]  # the reference run says it
    open_page(browser, built_page(tmp_path, scene, f"gs{steps}"))
    got = warnings(browser)
    assert got["built"] == lines and not got["changed"]
    assert [w["text"] for w in got["shown"]] == lines
    assert all(w["origin"] == "python" and w["recomputed"] for w in got["shown"])
    assert got["page"] == lines  # the page's evaluator words the same, from its own solution
    assert panel(browser) == (True, lines)
    assert browser.get_log("browser") == []


# the rod's slide on the guide, at an angle from the guide's pivot: the rod's line turns
# with the guide at (guide angle + 30° - angle), horizontal where the guide is at angle - 30°
MOVES = [
    (-10.0, []),  # the rod never horizontal over the sweep (30° down to -30°)
    (25.0, [passage("-3.33333", "-6.66667", "step 6 (reached from step 5)")]),
    (40.0, ["1 step(s) cannot be assembled (steps 3)",  # step 3, at 10°, on the parallel
            passage("11.6667", "8.33333", "step 4 (reached from step 3)")]),
]


@pytest.mark.parametrize("angle, lines", MOVES)
def test_after_a_move_the_page_lists_what_its_evaluator_finds(browser, tmp_path, angle, lines):
    open_page(browser, built_page(tmp_path, parse_scene(guide_slider(10)), "gs10"))
    a = math.radians(angle)
    browser.execute_script("window.linkageSym.moveJoint('A_slide', arguments[0], arguments[1])",
                           0.02 * math.cos(a), 0.02 * math.sin(a))
    got = warnings(browser)
    scene, res = edited(browser)
    assert got["changed"]
    # the reference: the Python run of the edited scene, its statuses and its warnings
    assert res.warnings == lines[-1:]
    assert int(np.sum(res.status == "unassemblable")) == len(lines) - len(lines[-1:])
    assert got["page"] == lines
    assert [(w["text"], w["origin"], w["stale"]) for w in got["shown"]] == [
        (t, "page", False) for t in lines]
    assert panel(browser) == (bool(lines), lines)


def test_a_pivot_moved_out_of_reach_counts_the_steps_that_cannot_be_assembled(browser, tmp_path):
    scene = load_example("crank_rocker")
    open_page(browser, built_page(tmp_path, scene, "crank_rocker"))
    assert warnings(browser)["shown"] == []
    # the rocker's pivot 42 mm further out: near 180° the coupler and rocker cannot reach
    browser.execute_script("window.linkageSym.moveJoint('D', 0.12, 0.0)")
    scene, res = edited(browser)
    bad = np.flatnonzero(res.status == "unassemblable")
    assert 0 < len(bad) < len(res.status) and res.warnings == []
    first = ", ".join(str(k) for k in bad[:5])
    line = f"{len(bad)} step(s) cannot be assembled (steps {first} and {len(bad) - 5} more)"
    assert warnings(browser)["page"] == [line]
    assert panel(browser) == (True, [line])


@pytest.mark.parametrize("name", ["crank_rocker", "cam_eccentric_rocker"])
def test_a_scene_without_warnings_has_a_hidden_empty_panel(browser, tmp_path, name):
    open_page(browser, built_page(tmp_path, load_example(name), name))
    got = warnings(browser)
    assert got["built"] == [] and got["shown"] == [] and got["page"] == []
    assert panel(browser) == (False, [])


def test_warnings_the_page_cannot_recompute_are_from_the_scene_as_built(browser, tmp_path):
    """Friction at a standstill (the driver at speed 0): the run's friction warnings, which
    the page does not compute, are shown as built, greyed once a pivot moves, and current
    again when it moves back."""
    base = load_example("slider_crank_press_friction")
    still = dataclasses.replace(base.drivers[0], speed=0.0, acceleration=0.0)
    scene = dataclasses.replace(base, drivers=(still,))
    lines = linkage_sym.analyze(scene).warnings
    assert len(lines) == 4 and all("is taken as zero there" in t for t in lines)
    open_page(browser, built_page(tmp_path, scene, "standstill"))
    got = warnings(browser)
    assert got["page"] == []
    assert [(w["text"], w["origin"], w["recomputed"], w["stale"]) for w in got["shown"]] == [
        (t, "python", False, False) for t in lines]
    assert panel(browser) == (True, lines)
    A = scene.joint("A").at
    browser.execute_script("window.linkageSym.moveJoint('A', arguments[0], arguments[1])",
                           A[0] + 0.002, A[1])
    got = warnings(browser)
    assert [(w["text"], w["stale"]) for w in got["shown"]] == [(t, True) for t in lines]
    assert browser.execute_script(
        "return [...document.querySelectorAll('#warnings-list li')].map((li) => li.className)"
    ) == ["stale"] * 4
    assert "cannot recompute" in browser.find_element("id", "warnings-source").text
    browser.execute_script("window.linkageSym.moveJoint('A', arguments[0], arguments[1])", *A)
    got = warnings(browser)
    assert not got["changed"] and not any(w["stale"] for w in got["shown"])


def test_a_page_written_without_a_run_opens_with_its_evaluator_s_warnings(browser, tmp_path):
    path = tmp_path / "gs11.html"
    path.write_text(page_html(parse_scene(guide_slider(11))))
    open_page(browser, path)
    got = warnings(browser)
    lines = ["1 step(s) cannot be assembled (steps 5)",
             passage("1.5", "-1.5", "step 6 (reached from step 5)")]
    assert got["built"] is None and got["page"] == lines
    assert [(w["text"], w["origin"]) for w in got["shown"]] == [(t, "page") for t in lines]


VALUES = [0.0, -1e-17, 1e-9, 2.5e-4, -0.0123456789, 0.5, 1.0 / 3.0, 123.4565, 98765.4321,
          1234567.0, -3.0e7, 6.283185307179586, -2.617993877991494]


def test_the_page_words_driver_values_as_the_python_messages(browser, pages):
    open_page(browser, pages("crank_rocker"))
    for kind in ("R", "P"):
        got = browser.execute_script(
            "return arguments[0].map((v) => PageWarnings.driverNumber(v, arguments[1]))",
            VALUES, kind)
        assert got == [driver_number(v, kind) for v in VALUES], kind


def test_a_step_on_the_parallel_position_is_worded_as_the_python_run_words_it(browser, tmp_path):
    # the guide-slider of 11 steps has step 5 (the guide at 0 deg) exactly on the parallel
    # position; the page's message was "its closed form has no real solution"
    scene = parse_scene(guide_slider(11))
    res = linkage_sym.analyze(scene)
    assert res.status[5] == "unassemblable"
    open_page(browser, built_page(tmp_path, scene, "gs11"))
    got = browser.execute_script("return window.linkageSym.solve(0.0)")
    assert got["status"] == "unassemblable"
    assert got["message"] == res.messages[5] == (
        "dyad PRP (rod, block): the slides of joints A_slide and C_guide are parallel")
    assert browser.get_log("browser") == []
