"""The page's layers in a real browser (headless Chromium through Selenium).

For every shipped example the symbolic layer derives, ``window.linkageSym.layers(q)`` at 12
driver values across the sweep (the drivers at the scene's speeds and accelerations) equals
the numeric solver (:func:`linkage_sym.numeric.plan.compile_plan`, which shares no code with
the generated functions or the page's evaluator) and the Python instant centres
(:func:`linkage_sym.centres.instant_centres`, of which ``centres.js`` is a port): statuses
equal; at the ``ok`` steps the joints' and traced points' velocities and accelerations, the
joint reactions and the driving efforts each to ``1e-9`` of the largest magnitude of that
quantity over the 12 steps; every pair's instant centre of the same kind (finite, at
infinity, undefined; filled from the velocities or not), a finite one to ``1e-9`` of its
distance from the mechanism's centre (at least the mechanism's size), a direction to
``1e-9``; the transmission angles to ``1e-9`` of 180 degrees.  After ``moveJoint`` of a
ground pivot the same holds against :func:`linkage_sym.analyze` of the scene ``scene()``
returns.  The layers are off when the page opens, a layer the scene has no values for is
disabled with its reason on the page, each layer draws, and the arrows' scales are stated.
"""

from __future__ import annotations

import io
import math

import numpy as np
import pytest

from tests.support import browser as support
from tests.support.browser import open_page, twelve

pytestmark = [pytest.mark.skipif(support.missing() is not None, reason=str(support.missing())),
              pytest.mark.slow]

import linkage_sym  # noqa: E402
from linkage_sym.centres import instant_centres  # noqa: E402
from linkage_sym.codegen.javascript import page_scene  # noqa: E402
from linkage_sym.examples import example_dict, load_example  # noqa: E402
from linkage_sym.numeric.plan import compile_plan  # noqa: E402
from linkage_sym.page import page_html  # noqa: E402
from linkage_sym.scene import parse_scene  # noqa: E402
from tests.support.example_sets import symbolic_examples  # noqa: E402

TOL = 1e-9
LAYERS = ("velocity", "acceleration", "forces", "centres", "transmission")


def page_layers(browser, qs):
    return browser.execute_script("return arguments[0].map((q) => window.linkageSym.layers(q));", qs)


def solver_at(scene, Q):
    """The numeric solver at the driver values ``Q`` (D, K), the drivers at their speeds."""
    n = Q.shape[1]
    q = {d.joint: Q[i] for i, d in enumerate(scene.drivers)}
    qd = {d.joint: np.full(n, float(d.speed)) for d in scene.drivers}
    qdd = {d.joint: np.full(n, float(d.acceleration)) for d in scene.drivers}
    return compile_plan(page_scene(scene)).run(q, qd, qdd)


def biggest(arrays) -> float:
    vals = [np.abs(np.asarray(a, float)) for a in arrays]
    return max(float(np.nanmax(v)) if np.isfinite(v).any() else 0.0 for v in vals)


def assert_layers(got, res, scene, what, idx=None):
    """The page's layers ``got`` against the result ``res`` (at its steps ``idx``)."""
    idx = np.arange(len(got)) if idx is None else np.asarray(idx)
    assert [g["status"] for g in got] == [str(res.status[i]) for i in idx], what
    ok = [k for k, g in zip(idx, got) if g["status"] == "ok"]
    ok_got = [g for g in got if g["status"] == "ok"]
    L = scene.characteristic_length()
    for key, attr in (("velocities", "velocity"), ("accelerations", "acceleration")):
        records = [(res.joints[j.name], "joints", j.name) for j in scene.joints]
        records += [(res.points[p.name], "points", p.name) for p in scene.points]
        scale = biggest(getattr(r, attr)[ok] for r, _, _ in records)
        for g, k in zip(ok_got, ok):
            for rec, kind, name in records:
                err = np.max(np.abs(np.array(g[key][kind][name]) - getattr(rec, attr)[k]))
                assert err <= TOL * scale, (what, key, k, name, err / scale)
    if res.forces is not None:
        R, D = res.forces.reactions, res.forces.driving
        r_scale = biggest(r[ok] for r in R.values())
        d_scale = biggest(v[ok] for v in D.values())
        for g, k in zip(ok_got, ok):
            for name, r in R.items():
                err = np.max(np.abs(np.array(g["reactions"][name]) - r[k]))
                assert err <= TOL * r_scale, (what, "reaction", k, name, err / r_scale)
            for name, v in D.items():
                assert abs(g["driving"][name] - v[k]) <= TOL * d_scale, (what, "driving", k, name)
    else:
        assert all(g["reactions"] is None for g in ok_got)
    ic = instant_centres(scene, res)
    c = np.mean([j.at for j in scene.joints], axis=0)
    for g, k in zip(ok_got, ok):
        for p, (a, b) in enumerate(ic.pairs):
            rec = g["centres"][f"{a},{b}"]
            where = (what, k, a, b, rec)
            assert bool(rec.get("undefined")) == bool(ic.undefined[k, p]), where
            assert bool(rec.get("at_infinity")) == bool(ic.at_infinity[k, p]), where
            assert (rec.get("method") == "velocity") == bool(ic.from_velocities[k, p]
                                                             and not ic.undefined[k, p]), where
            if ic.at_infinity[k, p]:
                assert np.max(np.abs(np.array(rec["direction"]) - ic.direction[k, p])) <= TOL, where
            elif not ic.undefined[k, p]:
                pos = ic.position[k, p]
                scale = max(L, float(np.hypot(*(pos - c))))
                assert np.max(np.abs(np.array(rec["position"]) - pos)) <= TOL * scale, where
        for inner, gamma in res.transmission_angles.items():
            assert abs(g["transmission_deg"][inner] - math.degrees(gamma[k])) <= TOL * 180, \
                (what, k, inner)
        assert set(g["transmission_deg"]) == set(res.transmission_angles)


@pytest.mark.parametrize("name", symbolic_examples())
def test_the_layers_equal_the_python_analysis(browser, pages, name):
    scene = load_example(name)
    assert open_page(browser, pages(name))["error"] is None
    _, Q, qs = twelve(scene)
    assert_layers(page_layers(browser, qs), solver_at(scene, Q), scene, "as loaded")


@pytest.mark.parametrize("name", ["crank_rocker", "watt_sixbar", "sixbar_class3", "shaper"])
def test_the_layers_after_a_drag_equal_analyze_of_the_edited_scene(browser, pages, name):
    scene = load_example(name)
    open_page(browser, pages(name))
    L = scene.characteristic_length()
    pivot = next(j for j in scene.joints if "ground" in j.links and j.type == "R"
                 and j.name not in {d.joint for d in scene.drivers})
    x, y = pivot.at[0] + 0.01 * L, pivot.at[1] - 0.004 * L
    browser.execute_script("window.linkageSym.moveJoint(arguments[0], arguments[1], arguments[2])",
                           pivot.name, x, y)
    edited = parse_scene(browser.execute_script("return window.linkageSym.scene()"))
    assert edited.joint(pivot.name).at == (x, y)
    idx, _, qs = twelve(edited)
    assert_layers(page_layers(browser, qs), linkage_sym.analyze(edited), edited, "after the move",
                  idx)


def test_the_layers_are_off_when_the_page_opens(browser, pages):
    open_page(browser, pages("crank_rocker"))
    boxes = {n: browser.find_element("id", f"layer-{n}") for n in LAYERS}
    assert {n: b.is_selected() for n, b in boxes.items()} == dict.fromkeys(LAYERS, False)
    assert all(b.is_enabled() for b in boxes.values())
    assert browser.execute_script("return window.linkageSym.layersAvailable()") == \
        dict.fromkeys(LAYERS)


def massless_scene():
    """The crank-rocker without masses, inertias or loads, asking for kinematics only."""
    d = example_dict("crank_rocker")
    d["name"] = "massless crank-rocker"
    for link in d["links"]:
        link["mass"] = 0.0
        link["inertia"] = 0.0
    d.pop("loads", None)
    d["outputs"] = ["kinematics"]
    return parse_scene(d)


def test_a_layer_without_values_is_disabled_with_its_reason(browser, pages):
    """No mass, inertia or load: no forces (the layer says why); a slider-crank has no RRR
    dyad: no transmission angle; the other layers stay available, and the page still has
    velocities (its equations are derived with the kinematics the scene did not ask for)."""
    from selenium.common.exceptions import JavascriptException

    cases = {"massless": (massless_scene(), "forces", "no masses, inertias or loads"),
             "slider_crank_offset": (load_example("slider_crank_offset"), "transmission",
                                     "no RRR dyad")}
    for name, (scene, layer, why) in cases.items():
        open_page(browser, pages(name, scene))
        box = browser.find_element("id", f"layer-{layer}")
        assert not box.is_enabled() and not box.is_selected()
        assert why in browser.find_element("id", "layer-notes").text
        avail = browser.execute_script("return window.linkageSym.layersAvailable()")
        assert [n for n, v in avail.items() if v is not None] == [layer]
        with pytest.raises(JavascriptException, match="is not available"):
            browser.execute_script("window.linkageSym.setLayer(arguments[0], true)", layer)
    got = page_layers(browser, [[0.3]])[0]  # the slider-crank has forces
    assert got["reactions"] is not None
    open_page(browser, pages("massless"))
    got = page_layers(browser, [[0.3]])[0]
    assert got["reactions"] is None and got["velocities"]["joints"]["B"] != [0, 0]


def canvas_colours(browser):
    from PIL import Image

    png = browser.find_element("id", "view").screenshot_as_png
    return dict((c, n) for n, c in Image.open(io.BytesIO(png)).convert("RGB").getcolors(1 << 20))


def test_each_layer_draws_and_states_its_scale(browser, pages):
    """Each layer ticked changes the drawing (its own colours appear); the arrows' scales
    are written on the page; nothing is logged as an error."""
    open_page(browser, pages("crank_rocker"))
    browser.execute_script("window.linkageSym.step(40)")
    plain = canvas_colours(browser)
    colours = {"velocity": (0x00, 0x83, 0x8f), "acceleration": (0xc2, 0x18, 0x5b),
               "forces": (0xe6, 0x51, 0x00), "centres": (0x79, 0x55, 0x48),
               "transmission": (0x6a, 0x1b, 0x9a)}
    scales = {"velocity": "velocity: 1 m/s drawn", "acceleration": "acceleration: 1 m/s² drawn",
              "forces": "reactions: 1 N drawn"}
    for layer in LAYERS:
        browser.find_element("id", f"layer-{layer}").click()
        browser.execute_script("window.linkageSym.step(40)")
        drawn = canvas_colours(browser)
        assert colours[layer] not in plain and drawn.get(colours[layer], 0) > 20, layer
        text = browser.find_element("id", "layer-scales").text
        if layer in scales:
            assert scales[layer] in text
        browser.find_element("id", f"layer-{layer}").click()
    got = browser.execute_script("return window.linkageSym.layerScales()")
    assert got == {}
    assert [e for e in browser.get_log("browser") if e["level"] == "SEVERE"] == []
