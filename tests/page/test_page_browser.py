"""The page of ``linkage-sym view`` in a real browser (headless Chromium through Selenium).

For every shipped example (those with cam contacts solved by ``cams.js``, the others by the
symbolic layer's generated functions), the page written by
:func:`linkage_sym.page.page_html` is opened from a file, and:

* ``window.linkageSym.solve(q)`` at 12 driver values across the sweep equals the numeric
  solver's joint positions (:func:`linkage_sym.numeric.plan.compile_plan`, which shares no
  code with the generated functions or the page's evaluator) to ``1e-9`` of the mechanism's
  size, statuses equal;
* after ``moveJoint`` of a ground pivot by 1 % of the size, ``solve`` equals
  :func:`linkage_sym.analyze` of the scene ``scene()`` returns (read by the library's own
  loader, as ``linkage-sym analyze`` reads a file), at the same 12 values;
* the page loads with no console message of level ``SEVERE`` (Selenium's browser log), its
  HTML names no ``http(s)://`` address and the browser fetched nothing but the file itself
  (``performance.getEntries()``);
* its screenshot is not blank (distinct pixel colours counted).

One browser for the module.  Skipped, saying why, where Chromium, its driver or Selenium
is missing (``apt-get install chromium chromium-driver``; the ``page-tests`` extra).
"""

from __future__ import annotations

import io
import json
import math
from pathlib import Path

import numpy as np
import pytest

from linkage_sym.examples import example_names

from tests.support.browser import CHROMEDRIVER, CHROMIUM, open_page, twelve
TOL = 1e-9

webdriver = pytest.importorskip(
    "selenium.webdriver", reason="Selenium is not installed (pip install linkage_sym[page-tests])")

from selenium.common.exceptions import JavascriptException  # noqa: E402

pytestmark = [
    pytest.mark.skipif(not CHROMIUM.exists(), reason=f"no Chromium at {CHROMIUM} "
                       "(apt-get install chromium chromium-driver)"),
    pytest.mark.skipif(not Path(CHROMEDRIVER).exists(), reason="no chromedriver "
                       "(apt-get install chromium-driver)"),
    pytest.mark.slow,
]

import linkage_sym  # noqa: E402
from linkage_sym.examples import load_example  # noqa: E402
from linkage_sym.numeric.plan import compile_plan  # noqa: E402
from linkage_sym.page import page_html  # noqa: E402
from linkage_sym.scene import parse_scene  # noqa: E402


def page_solve(browser, qs):
    return browser.execute_script(
        "return arguments[0].map((q) => window.linkageSym.solve(q));", qs)


def assert_positions(got, res, scene, what, idx=None):
    """The page's steps ``got`` against the result ``res`` (at its steps ``idx``)."""
    L = scene.characteristic_length()
    idx = np.arange(len(got)) if idx is None else idx
    assert [g["status"] for g in got] == [str(res.status[i]) for i in idx], what
    for g, k in zip(got, idx):
        if g["status"] == "unassemblable":
            continue
        for j in scene.joints:
            err = np.max(np.abs(np.array(g["joints"][j.name]) - res.joints[j.name].position[k]))
            assert err <= TOL * L, (what, k, j.name, err / L)
        for p in scene.points:
            err = np.max(np.abs(np.array(g["points"][p.name]) - res.points[p.name].position[k]))
            assert err <= TOL * L, (what, k, p.name, err / L)


def solver_at(scene, Q):
    zeros = {d.joint: np.zeros(Q.shape[1]) for d in scene.drivers}
    return compile_plan(scene).run({d.joint: Q[i] for i, d in enumerate(scene.drivers)},
                                   zeros, zeros)


@pytest.mark.parametrize("name", example_names())
def test_the_page_solves_as_the_python_solver(browser, pages, name):
    scene = load_example(name)
    assert open_page(browser, pages(name))["error"] is None
    _, Q, qs = twelve(scene)
    assert_positions(page_solve(browser, qs), solver_at(scene, Q), scene, "as loaded")


@pytest.mark.parametrize("name", example_names())
def test_a_moved_ground_pivot_solves_as_analyze_of_the_downloaded_scene(browser, pages, name):
    scene = load_example(name)
    open_page(browser, pages(name))
    L = scene.characteristic_length()
    # a ground pivot that no gear turns on (moving one would break the mesh's geometry)
    gear = {p.name for j in scene.joints if j.type == "G" for p in scene.gear_pivots(j)}
    movable = [j for j in scene.joints if "ground" in j.links and j.type == "R"
               and j.name not in gear and not any(math.dist(j.at, g.at) <= 1e-12 * L
                                                  for g in scene.joints if g.name in gear)]
    if not movable:  # every ground pivot carries a gear: the page refuses to move it
        with pytest.raises(JavascriptException, match="is a gear's pivot"):
            browser.execute_script("window.linkageSym.moveJoint(arguments[0], 0.5, 0.5)",
                                   next(j.name for j in scene.joints if "ground" in j.links))
        return
    pivot = movable[0]
    x, y = pivot.at[0] + 0.01 * L, pivot.at[1] - 0.004 * L
    browser.execute_script("window.linkageSym.moveJoint(arguments[0], arguments[1], arguments[2])",
                           pivot.name, x, y)
    edited = parse_scene(browser.execute_script("return window.linkageSym.scene()"))
    assert edited.joint(pivot.name).at == (x, y)
    idx, _, qs = twelve(edited)
    assert_positions(page_solve(browser, qs), linkage_sym.analyze(edited), edited,
                     "after the move", idx)


@pytest.mark.parametrize("name", example_names())
def test_the_page_loads_alone_without_errors_and_draws(browser, pages, name):
    path = pages(name)
    html = path.read_text()
    assert "http://" not in html and "https://" not in html
    browser.get(path.as_uri())
    browser.execute_script("window.linkageSym.step(7)")
    severe = [e for e in browser.get_log("browser") if e["level"] == "SEVERE"]
    assert severe == []
    entries = browser.execute_script(
        "return performance.getEntries().map((e) => [e.entryType, e.name]);")
    fetched = {n for t, n in entries if t in ("navigation", "resource")}
    assert fetched == {path.as_uri()}
    from PIL import Image

    png = browser.find_element("id", "view").screenshot_as_png
    colours = Image.open(io.BytesIO(png)).convert("RGB").getcolors(maxcolors=1 << 20)
    assert len(colours) > 50  # the links, joints, traces and grid in their colours


def test_the_scene_of_the_page_is_the_file_layout(browser, pages):
    """``scene()`` before any edit is the scene itself, as a scene file writes it."""
    from linkage_sym.scene.load import dump_scene

    open_page(browser, pages("crank_rocker"))
    got = browser.execute_script("return window.linkageSym.scene()")
    assert got == json.loads(json.dumps(dump_scene(load_example("crank_rocker"))))


def test_a_drag_moves_a_ground_pivot_and_solves_again(browser, pages):
    """A pointer drag on the canvas (Selenium's actions) moves the pivot ``D`` of the
    crank-rocker: the scene's ``D`` moves, the other joints stay, the sweep is solved."""
    from selenium.webdriver.common.action_chains import ActionChains

    open_page(browser, pages("crank_rocker"))
    canvas = browser.find_element("id", "view")
    # D in the canvas's CSS pixels, from the page's own view transform
    at = browser.execute_script("""
        const r = arguments[0].getBoundingClientRect();
        const s = window.linkageSym.canvasPoint("D");
        return [s[0] * r.width / arguments[0].width - r.width / 2,
                s[1] * r.height / arguments[0].height - r.height / 2];""", canvas)
    ActionChains(browser).move_to_element_with_offset(canvas, round(at[0]), round(at[1])) \
        .click_and_hold().move_by_offset(15, -10).move_by_offset(5, 0).release().perform()
    scene = browser.execute_script("return window.linkageSym.scene()")
    joints = {j["name"]: j["at"] for j in scene["joints"]}
    before = {j.name: list(j.at) for j in load_example("crank_rocker").joints}
    assert joints["D"][0] > before["D"][0] and joints["D"][1] > before["D"][1]
    assert {n: joints[n] for n in "ABC"} == {n: before[n] for n in "ABC"}
    assert browser.execute_script("return window.linkageSym.summary()")["error"] is None


def test_a_typed_length_moves_the_second_joint_along_the_line(browser, pages):
    """Typing a length of the crank-rocker's A–B puts B at that distance from A on the line
    A B (A at the origin, B on the x-axis); the sweep is solved again, with the statuses
    of ``analyze`` of the edited scene (a longer crank: some steps no longer assemble)."""
    open_page(browser, pages("crank_rocker"))
    box = browser.find_element("css selector", "input[aria-label='length A–B']")
    box.clear()
    box.send_keys("0.03\n")  # Enter commits the value: its change event re-solves
    scene = browser.execute_script("return window.linkageSym.scene()")
    B = next(j["at"] for j in scene["joints"] if j["name"] == "B")
    assert B == pytest.approx([0.03, 0.0], abs=1e-15)
    status = linkage_sym.analyze(parse_scene(scene)).status
    want = {str(s): int(np.sum(status == s)) for s in set(status)}
    assert browser.execute_script("return window.linkageSym.summary()")["counts"] == want
    assert want["unassemblable"] > 0


CAMS = [n for n in example_names() if any(j.type == "cam" for j in load_example(n).joints)]


def _profiles():
    """Each shipped cam's profile, and a spline through points (no example has one)."""
    from linkage_sym.numeric.kinematics.cam_profile import CamProfile
    from linkage_sym.numeric.kinematics.cams import cam_geometry

    out = [(n, cam_geometry(j).profile) for n in CAMS for j in load_example(n).cams]
    t = np.linspace(0.0, 2 * np.pi, 13)[:-1]
    pts = np.stack([0.03 * np.cos(t) + 0.004 * np.cos(2 * t), 0.02 * np.sin(t)], axis=-1)
    return out + [("points", CamProfile("points", (pts[::-1],)))]


def test_the_page_evaluates_a_profile_as_scipy(browser, pages):
    """``cams.js``'s profile (SciPy's splines as data, evaluated as ``PPoly`` is) against
    :class:`~linkage_sym.numeric.kinematics.cam_profile.CamProfile` (SciPy itself): the
    point and its two derivatives at 97 parameters, to 1e-12 of the profile's size."""
    from linkage_sym.page.cam_model import profile_data

    open_page(browser, pages(CAMS[0]))
    u = np.linspace(-0.3, 2 * np.pi + 0.3, 97)
    for name, prof in _profiles():
        got = np.array(browser.execute_script(
            "const p = new LinkageCams.Profile(arguments[0], 720);"
            "return arguments[1].map((u) => p.evaluate(u));", profile_data(prof), u.tolist()))
        want = np.concatenate([np.stack(d, axis=-1) for d in prof.evaluate(u)], axis=-1)
        size = np.max(np.abs(want[:, :2]))
        assert np.max(np.abs(got - want)) <= 1e-12 * size, name


@pytest.mark.parametrize("name", CAMS)
def test_the_page_condition_number_of_a_cam_mechanism_is_the_solver_s(browser, pages, name):
    """The page's constraint Jacobian of a cam mechanism (its singularity test, used where a
    pressure angle nears 90 degrees) has the numeric solver's exact condition number at the
    12 steps, to 1e-6 relative."""
    scene = load_example(name)
    open_page(browser, pages(name))
    _, Q, qs = twelve(scene)
    got = browser.execute_script("""
        const m = new LinkageCams.Mechanism(MODEL);
        return m.solveSteps(arguments[0]).map((s) => {
          const sv = LinkageEvaluator.singularValues(m.jacobian(s.S));
          return sv[0] / sv[sv.length - 1];
        });""", qs)
    zeros = {d.joint: np.zeros(12) for d in scene.drivers}
    res = compile_plan(scene).run({d.joint: Q[i] for i, d in enumerate(scene.drivers)},
                                  zeros, zeros, exact_condition=True)
    np.testing.assert_allclose(got, res.condition, rtol=1e-6)


@pytest.mark.parametrize("name", CAMS)
def test_a_cam_page_says_what_a_drag_edits_and_keeps_the_contact(browser, pages, name):
    """The contact point lies on the profile (data): ``moveJoint`` refuses it, its inputs are
    disabled, and the page says so beside the joints."""
    scene = load_example(name)
    open_page(browser, pages(name))
    (cam,) = scene.cams
    with pytest.raises(JavascriptException, match="is a cam contact"):
        browser.execute_script("window.linkageSym.moveJoint(arguments[0], 0.1, 0.1)", cam.name)
    assert browser.find_element("css selector", f"input[aria-label='{cam.name} x']").get_attribute(
        "disabled")
    assert "profile is fixed data" in browser.find_element("id", "cam-note").text


def test_the_gallery_opens_alone_and_its_links_open_the_pages(browser, tmp_path):
    """The demo's gallery (three examples: a cam, a gear train, a linkage) loads with no
    console error and fetches nothing but itself; clicking a card opens that example's page,
    which solves its sweep."""
    from linkage_sym.page.gallery import write_gallery

    names = ["cam_cycloidal_roller", "planetary_train", "crank_rocker"]
    gallery = write_gallery(tmp_path, names)[0]
    for name in names:
        browser.get(gallery.as_uri())
        assert [e for e in browser.get_log("browser") if e["level"] == "SEVERE"] == []
        entries = browser.execute_script(
            "return performance.getEntries().map((e) => [e.entryType, e.name]);")
        assert {n for t, n in entries if t in ("navigation", "resource")} == {gallery.as_uri()}
        browser.find_element("id", name).click()
        assert browser.current_url == (tmp_path / "pages" / f"{name}.html").as_uri()
        assert browser.execute_script("return window.linkageSym.summary()")["error"] is None
        assert [e for e in browser.get_log("browser") if e["level"] == "SEVERE"] == []


@pytest.mark.parametrize("name", CAMS)
def test_a_cam_page_does_not_claim_the_symbolic_layer_s_equations(browser, pages, name):
    open_page(browser, pages(name))
    by = browser.find_element("css selector", "header .by").text
    assert "numeric cam solver" in by and "SymPy" not in by


def _cam_scene(follower, pivot, K):
    """An eccentric disc cam (circle of radius 0.025 about (0.015, 0), turning about the
    origin) and a follower on a ground pivot or vertical slide: the cases the shipped
    examples leave out; the follower loses the profile over part of the turn."""
    if pivot[0] == "R":
        pj = {"name": "D", "type": "R", "links": ["ground", "follower"], "at": list(pivot[1])}
    else:
        pj = {"name": "S", "type": "P", "links": ["ground", "follower"], "at": [K[0], 0.06],
              "axis_deg": 90}
    return parse_scene({
        "name": "cam case", "links": [{"name": "cam"}, {"name": "follower"}],
        "joints": [{"name": "A", "type": "R", "links": ["ground", "cam"], "at": [0.0, 0.0]}, pj,
                   {"name": "K", "type": "cam", "links": ["cam", "follower"], "at": list(K),
                    "profile": {"circle": {"centre": [0.015, 0.0], "radius": 0.025}},
                    "follower": follower}],
        "drivers": [{"joint": "A", "toward": "K", "start_deg": 0, "stop_deg": 360, "steps": 37,
                     "speed": 1.0}]})


CAM_CASES = {
    "knife on a rocker": ({"kind": "knife"}, ("R", (0.05, 0.04)), (0.04, 0.0)),
    "roller on a rocker": ({"kind": "roller", "radius": 0.01}, ("R", (0.06, 0.045)), (0.05, 0.0)),
    "flat face on a slide": ({"kind": "flat", "face_deg": 0}, ("P",), (0.015, 0.025)),
    "offset knife on a slide": ({"kind": "knife"}, ("P",), (0.03, 0.02)),
}


@pytest.mark.parametrize("case", sorted(CAM_CASES))
def test_the_page_solves_every_follower_case_as_analyze(browser, tmp_path, case):
    """Knife and roller on a rocker, flat face and offset knife on a slide: every step of the
    sweep (some unassemblable: the follower cannot reach the profile there) as ``analyze``,
    statuses and positions to 1e-9 of the size."""
    scene = _cam_scene(*CAM_CASES[case])
    path = tmp_path / "case.html"
    path.write_text(page_html(scene))
    assert open_page(browser, path)["error"] is None
    res = linkage_sym.analyze(scene)
    qs = [[float(q)] for q in res.drivers[scene.drivers[0].joint]["q"]]
    got = page_solve(browser, qs)
    if case != "flat face on a slide":
        assert {g["status"] for g in got} == {"ok", "unassemblable"}
    assert_positions(got, res, scene, case)


def test_the_page_solves_a_linkage_driven_by_a_cam_s_follower_as_the_solver(browser, tmp_path):
    """An RRR dyad driven by the flat-faced rocker of problem 3-8 (its follower): the 12
    steps as the numeric solver, and after a ground pivot of the dyad moves, as ``analyze``
    of the scene ``scene()`` returns."""
    d = json.loads(json.dumps(dump_scene_of("cam_eccentric_rocker")))
    d["links"] += [{"name": "c1"}, {"name": "c2"}]
    d["joints"] += [{"name": "E", "type": "R", "links": ["follower", "c1"], "at": [0.035, 0.015]},
                    {"name": "F", "type": "R", "links": ["c1", "c2"], "at": [0.05, 0.05]},
                    {"name": "G", "type": "R", "links": ["c2", "ground"], "at": [0.08, 0.03]}]
    d["points"] = [{"name": "T", "link": "c1", "at": [0.045, 0.04]}]
    scene = parse_scene(d)
    path = tmp_path / "cam_linkage.html"
    path.write_text(page_html(scene))
    assert open_page(browser, path)["error"] is None
    _, Q, qs = twelve(scene)
    assert_positions(page_solve(browser, qs), solver_at(scene, Q), scene, "as loaded")
    browser.execute_script("window.linkageSym.moveJoint('G', 0.081, 0.0295)")
    edited = parse_scene(browser.execute_script("return window.linkageSym.scene()"))
    idx, _, qs = twelve(edited)
    assert_positions(page_solve(browser, qs), linkage_sym.analyze(edited), edited, "moved", idx)


def dump_scene_of(name):
    from linkage_sym.scene.load import dump_scene

    return dump_scene(load_example(name))
