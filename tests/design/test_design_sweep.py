"""Design sweeps (linkage_sym.sweep): every metric against the numeric solver's analysis of
each design's own written scene, Grashof class and K against formulas written here.

Tolerances: 1e-12 relative to each metric's scale (its value, or the largest magnitude of
the series it summarises); angles 1e-12 rad (degrees: 1e-12 * 180/pi), K 1e-12 relative.
Observed: at most about 5e-14.
"""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import numpy as np
import pytest

import linkage_sym
from linkage_sym.design import Execution, MonteCarlo, SceneFiles, SweepError, sweep
from linkage_sym.design.metrics import K_NOTES
from linkage_sym.model import OUTPUTS, Effects
from linkage_sym.numeric.extremes import find_extremes
from linkage_sym.numeric.results.transmission import transmission_angles
from linkage_sym.synthesis import fourbar

TOL = 1e-12
ALL = ["assemblable", "grashof", "K", "swing", "min_transmission_deg", "peak_driving",
       "rms_driving", "peak_reaction", "rms_shaking_force", "rms_shaking_moment", "path"]


def _close(a, b, scale=None):
    scale = max(abs(b), 1e-300) if scale is None else scale
    return abs(a - b) <= TOL * scale


def _designs_of(folder: Path):
    out = {}
    for f in sorted(folder.glob("design_*.json")):
        out[int(f.stem.split("_")[1])] = linkage_sym.load_scene(f)
    return out


def _check_against_analyze(res, scenes, output=None):
    """Every metric column of ``res`` against the numeric solver's run of each written scene."""
    assert scenes
    for i, sc in scenes.items():
        full = dataclasses.replace(sc, outputs=OUTPUTS)
        plan = linkage_sym.compile_plan(full)
        an = plan.run()
        ok = an.status == "ok"
        N = len(ok)
        assert res["assemblable"][i] == ok.sum() / N
        # the steps of a cycle average: a sweep over whole turns ends where it starts,
        # and that state counts once
        turns = [(d.stop - d.start) / (2 * np.pi) for d in sc.drivers if d.kind == "R"]
        counted = ok.copy()
        if (all(d.kind == "R" for d in sc.drivers) and ok[0]
                and all(abs(t - round(t)) < 1e-12 for t in turns) and any(t != 0 for t in turns)):
            counted[-1] = False
        for c in res.metrics:
            v = res[c][i]
            if c == "min_transmission_deg":
                g = np.concatenate([np.fmin(a, np.pi - a) for a in transmission_angles(sc, an).values()])
                assert _close(v, np.degrees(np.nanmin(g)), 180 / np.pi), c
            elif c.startswith("peak_driving_") or c.startswith("rms_driving_"):
                e = an.forces.driving[c.split("_", 2)[2]]
                ref = (np.abs(e[ok]).max() if c.startswith("peak")
                       else np.sqrt(np.mean(e[counted] ** 2)))
                assert _close(v, ref, np.abs(e[ok]).max()), c
            elif c.startswith("peak_reaction_"):
                r = np.hypot(*an.forces.reactions[c[len("peak_reaction_"):]][ok].T)
                assert _close(v, r.max()), c
            elif c in ("rms_shaking_force", "rms_shaking_moment"):
                # the frame force and moment of the design with inertia as the only effect
                sh = linkage_sym.analyze(dataclasses.replace(
                    full, effects=Effects(inertia=True, gravity=None, loads=False)))
                s = (np.hypot(*sh.forces.frame_force.T) if c.endswith("force")
                     else sh.forces.frame_moment)
                assert _close(v, np.sqrt(np.mean(s[counted] ** 2)), np.abs(s[ok]).max()), c
            elif c.startswith("path_"):
                # every step with positions, singular ones too (analyze keeps them)
                _, p, xy, k = c.split("_")
                ref = an.points[p].position[int(k), "xy".index(xy)]
                if an.status[int(k)] == "unassemblable":
                    assert math.isnan(v), c
                else:
                    assert _close(v, ref, sc.characteristic_length()), c
        if "K" in res.columns or "swing_deg" in res.columns:
            ext = find_extremes(full, plan, an)
            mm = ext.values[("links", output, "rotation")]
            if "swing_deg" in res.columns:
                swing = math.degrees(mm["max"].value - mm["min"].value)
                assert _close(res["swing_deg"][i], swing, 180 / np.pi)
            if "K" in res.columns:
                dq = abs(mm["max"].drivers["A"] - mm["min"].drivers["A"])
                K = max(dq, 2 * np.pi - dq) / min(dq, 2 * np.pi - dq)
                # K is defined by exactly two limit positions in the turn: two sign changes
                # of the output's angular velocity (the crank turns at a constant speed)
                w = an.links[output].omega
                turns = int(np.count_nonzero(np.sign(w[1:]) != np.sign(w[:-1])))
                q = an.drivers["A"]["q"]
                full_turn = abs(q[-1] - q[0]) >= 2 * np.pi * (1 - 1e-12)
                if (full_turn and ok.all() and turns == 2
                        and mm["max"].located == mm["min"].located == "rate root"):
                    assert _close(res["K"][i], K), (i, res["K"][i], K)
                    assert res["K_note"][i] == ""
                else:
                    assert math.isnan(res["K"][i])
                    assert res["K_note"][i] in K_NOTES.values(), res["K_note"][i]
                    if not full_turn:
                        assert res["K_note"][i] == K_NOTES["partial"]


@pytest.mark.slow
def test_every_metric_equals_analyze_of_the_written_scene(tmp_path):
    scene = linkage_sym.load_example("crank_rocker")
    # 0.036: the crank no longer turns fully (gaps of unassemblable steps, K undefined)
    res = sweep(scene, {"l_AB": [0.02, 0.036], "l_BC": [0.06, 0.066], "m_coupler": [0.5, 0.8],
                        "F_2y": [-5.0]}, ALL, scenes=SceneFiles(tmp_path))
    assert len(res) == 8
    assert sorted(res.parameters) == ["F_2y", "l_AB", "l_BC", "m_coupler"]
    assert 0 < res["assemblable"][4] < 1 and res["assemblable"][0] == 1
    scenes = _designs_of(tmp_path)
    assert sorted(scenes) == list(range(8))
    _check_against_analyze(res, scenes, output="rocker")


@pytest.mark.parametrize("name", ["slider_crank_offset",
                                  pytest.param("shaper", marks=pytest.mark.slow),
                                  pytest.param("watt_sixbar", marks=pytest.mark.slow)])
def test_sliders_and_ternary_links_equal_analyze(tmp_path, name):
    """P joints (the designs' own assembly angles theta0 of blocks and sliders), ternary
    links (beta), frame origins on P joints."""
    scene = linkage_sym.load_example(name)
    rows = {n: v for n, v, _ in linkage_sym.design.scene_parameters(scene)}
    names = [n for n in rows if n.startswith(("l_", "beta_", "gamma_"))][:3]
    axes = {n: [rows[n] * 0.97 if n.startswith("l_") else rows[n] + 0.02, rows[n]] for n in names}
    metrics = ["assemblable", "peak_driving", "rms_driving", "peak_reaction", "rms_shaking_force",
               "rms_shaking_moment"] + (["path"] if scene.points else [])
    res = sweep(scene, axes, metrics, scenes=SceneFiles(tmp_path))
    scenes = _designs_of(tmp_path)
    assert len(scenes) >= 4
    _check_against_analyze(res, scenes)


@pytest.mark.slow
@pytest.mark.parametrize("name, metrics", [
    ("printing_mechanism", ["K", "swing", "peak_driving", "rms_driving", "peak_reaction",
                            "rms_shaking_force", "rms_shaking_moment"]),
    ("sixbar_class3", ["grashof", "K", "swing", "peak_reaction"]),
    ("hydraulic_boom", ["swing", "peak_driving", "peak_reaction", "rms_shaking_moment"]),
])
def test_groups_without_closed_form_one_design_at_a_time(tmp_path, name, metrics):
    """A class-III triad and a driven (actuator) group: each design assembled by
    continuation in the parameters from the scene's configuration, solved by the numeric
    plan of its own scene; every metric equals analyze's of the written scene."""
    scene = linkage_sym.load_example(name)
    rows = {n: v for n, v, _ in linkage_sym.design.scene_parameters(scene)}
    first, second = [n for n in rows if n.startswith("l_")][:2]
    res = sweep(scene, {first: [rows[first], rows[first] * 1.03], second: [rows[second] * 0.98]},
                ["assemblable"] + metrics, scenes=SceneFiles(tmp_path))
    assert res.one_at_a_time and (res["assemblable"] == 1).all()
    # the scene's own values: the scene itself, to rounding
    assert abs(res[first][0] - rows[first]) == 0
    output = linkage_sym.design.metrics.MetricPlan(scene, ["swing"])._output(None)
    _check_against_analyze(res, _designs_of(tmp_path), output=output)


def _grashof_formula(a, b, c, d):
    """Class of the four-bar ground d, crank a, coupler b, rocker c (written here)."""
    ls = {"ground": d, "crank": a, "coupler": b, "rocker": c}
    s_name = min(ls, key=ls.get)
    s, l = min(ls.values()), max(ls.values())
    pq = sum(ls.values()) - s - l
    if abs(s + l - pq) <= 1e-9 * sum(ls.values()):
        return "change point"
    if s + l > pq:
        return "triple-rocker"
    return {"ground": "double-crank", "coupler": "double-rocker"}.get(s_name, "crank-rocker")


def _K_formula(a, b, c, d):
    """Crank-rocker: the crank angles at the extremes (crank and coupler in line), law of
    cosines in the triangles A C1 D (AC1 = b + a) and A C2 D (AC2 = b - a)."""
    ang = lambda x: math.acos((x * x + d * d - c * c) / (2 * x * d))  # noqa: E731
    theta = abs(ang(b + a) - ang(b - a))
    return (math.pi + theta) / (math.pi - theta)


def test_grashof_and_K_of_random_fourbars_against_formulas():
    base = fourbar(0.024, 0.06, 0.05, 0.078, crank_deg=30.0, steps=361).scene
    scene = linkage_sym.load_scene(base)
    rng = np.random.default_rng(7)
    n = 40
    vals = {"l_AB": rng.uniform(0.01, 0.05, n), "l_BC": rng.uniform(0.03, 0.09, n),
            "l_CD": rng.uniform(0.03, 0.08, n), "x_D": rng.uniform(0.05, 0.1, n)}
    d = linkage_sym.design.Designs(tuple(vals), np.stack(list(vals.values()), axis=1), "samples")
    res = sweep(scene, d, ["grashof", "K", "assemblable"])
    kinds = set()
    for i in range(n):
        a, b, c, g = (vals[k][i] for k in ("l_AB", "l_BC", "l_CD", "x_D"))
        cls = _grashof_formula(a, b, c, g)
        # the class of the lengths, whether or not the design assembles
        assert res["grashof"][i] == cls, i
        kinds.add((cls, bool(res["assemblable"][i] > 0)))
        if cls == "crank-rocker" and min(a, b, c, g) == a:
            assert abs(res["K"][i] - _K_formula(a, b, c, g)) <= TOL * _K_formula(a, b, c, g), i
            assert res["K_note"][i] == ""
        else:
            assert math.isnan(res["K"][i]) and res["K_note"][i] != "", i
    assert {("crank-rocker", True), ("double-rocker", True), ("triple-rocker", False)} <= kinds


@pytest.mark.slow
def test_results_do_not_depend_on_the_chunks():
    scene = linkage_sym.load_example("crank_rocker")
    axes = {"l_AB": np.linspace(0.02, 0.04, 5), "l_BC": [0.06, 0.065, 0.07]}
    ms = ["assemblable", "K", "swing", "min_transmission_deg", "peak_driving", "rms_shaking_force"]
    one = sweep(scene, axes, ms, execution=Execution(chunk_designs=1))
    big = sweep(scene, axes, ms)
    for c in one.columns:
        np.testing.assert_array_equal(one[c], big[c])
    # designs solved one at a time (an actuator group): each design's numbers are its own
    boom = linkage_sym.load_example("hydraulic_boom")
    ms = ["assemblable", "swing", "peak_reaction"]
    one = sweep(boom, {"l_OR": [1.15, 1.2, 1.25]}, ms, execution=Execution(chunk_designs=1))
    big = sweep(boom, {"l_OR": [1.15, 1.2, 1.25]}, ms)
    for c in one.columns:
        np.testing.assert_array_equal(one[c], big[c])


def test_K_and_transmission_do_not_depend_on_the_angles_being_asked_for(monkeypatch):
    """``K`` and ``min_transmission_deg`` alone take the angles' cosines and sines without
    the angles (no arctangent); with ``swing`` (which reads the angles) the angles are
    evaluated too: the same numbers, bit for bit.  And the limit positions of a run of
    chunks located together equal those located chunk by chunk (one design per run)."""
    from linkage_sym.design import execute

    scene = linkage_sym.load_example("crank_rocker")
    drv = dataclasses.replace(scene.drivers[0], start=0.0, stop=2 * math.pi, steps=181)
    scene = dataclasses.replace(scene, drivers=(drv,))
    axes = {"l_BC": np.linspace(0.045, 0.085, 7), "l_CD": np.linspace(0.025, 0.075, 6)}
    alone = sweep(scene, axes, ["K", "min_transmission_deg"])
    assert np.isfinite(np.asarray(alone["K"], float)).sum() >= 20  # most designs have K
    with_swing = sweep(scene, axes, ["K", "swing", "min_transmission_deg"])
    for c in ("K", "K_note", "min_transmission_deg"):
        np.testing.assert_array_equal(alone[c], with_swing[c])
    monkeypatch.setattr(execute, "RUN_DESIGNS", 1)
    by_chunk = sweep(scene, axes, ["K", "swing", "min_transmission_deg"],
                     execution=Execution(chunk_designs=5))
    for c in with_swing.columns:
        np.testing.assert_array_equal(by_chunk[c], with_swing[c])


def test_monte_carlo_is_reproducible():
    scene = linkage_sym.load_example("crank_rocker")
    tol = {"l_AB": 5e-5, "l_BC": 5e-5}
    a = sweep(scene, MonteCarlo(6, tol, random_state=3), metrics=["K"])
    b = sweep(scene, MonteCarlo(6, tol, random_state=3), metrics=["K"])
    c = sweep(scene, MonteCarlo(6, tol, random_state=4), metrics=["K"])
    np.testing.assert_array_equal(a["l_AB"], b["l_AB"])
    np.testing.assert_array_equal(a["K"], b["K"])
    assert not np.array_equal(a["l_AB"], c["l_AB"])
    assert abs(a["l_AB"] - 0.024).max() < 10 * 5e-5


def test_bad_input_is_refused_by_name():
    scene = linkage_sym.load_example("crank_rocker")
    with pytest.raises(SweepError, match=r"parameters: unknown parameter 'l_XY'; the scene's "
                                         r"parameters are x_A, y_A, l_AB, l_BC"):
        sweep(scene, {"l_XY": [1.0]})
    with pytest.raises(SweepError, match="theta0_slider.*cannot be varied"):
        sweep(linkage_sym.load_example("slider_crank_offset"), {"theta0_slider": [0.1]})
    with pytest.raises(SweepError, match="metrics: unknown metric 'Kk'; the metrics are assemblable"):
        sweep(scene, {"l_AB": [0.02]}, ["Kk"])
    # one argument holds the designs (a grid, Designs, a MonteCarlo or a CSV file): two kinds
    # at once cannot be given; anything else is refused by name
    with pytest.raises(SweepError, match=r"^parameters: a mapping of names to values \(a grid\), "
                                         r"Designs, MonteCarlo or the path of a CSV file is "
                                         r"expected, got list"):
        sweep(scene, [0.02])
    with pytest.raises(SweepError, match="metrics: K: .* not driven by one R joint"):
        sweep(linkage_sym.load_example("hydraulic_boom"), {"l_OR": [1.2]}, ["K"])
    with pytest.raises(SweepError, match="output: unknown link 'rockr'"):
        sweep(scene, {"l_AB": [0.02]}, ["K"], output="rockr")
    with pytest.raises(SweepError, match="^tolerance: unknown parameter 'l_ZZ'"):
        sweep(scene, MonteCarlo(3, {"l_ZZ": 1e-5}))


def test_partial_sweep_and_singular_step(tmp_path):
    """Half a turn of the crank: the swing over the steps it has (find_extremes over that
    analysis), K without a value and K_note saying why.  A design whose dyad reaches its
    dead centre at one step (coupler and rocker in line: singular): the traced point keeps
    its position there, as analyze keeps it."""
    scene = linkage_sym.load_example("crank_rocker")
    half = dataclasses.replace(scene, drivers=(dataclasses.replace(scene.drivers[0], stop=math.pi,
                                                                   steps=181),))
    res = sweep(half, {"l_AB": [0.02, 0.024]}, ["assemblable", "K", "swing"],
                scenes=SceneFiles(tmp_path / "half"))
    assert res["K_note"].tolist() == [K_NOTES["partial"]] * 2
    _check_against_analyze(res, _designs_of(tmp_path / "half"), output="rocker")
    l_CD = dict((n, v) for n, v, _ in linkage_sym.design.scene_parameters(scene))["l_CD"]
    # B at (-0.024, 0) at the crank's step 180: |BD| = 0.102 = l_BC + l_CD
    res = sweep(scene, {"l_BC": [0.078 + 0.024 - l_CD]}, ["assemblable", "K", "path"],
                scenes=SceneFiles(tmp_path / "sing"))
    scenes = _designs_of(tmp_path / "sing")
    an = linkage_sym.analyze(scenes[0])
    assert an.status.tolist().count("singular") == 1 and (an.status != "unassemblable").all()
    assert np.isfinite([res[c][0] for c in res.metrics if c.startswith("path_")]).all()
    assert res["K_note"][0] == K_NOTES["steps"]
    _check_against_analyze(res, scenes, output="rocker")


def test_a_design_that_cannot_be_assembled_is_marked(tmp_path):
    scene = linkage_sym.load_example("crank_rocker")
    res = sweep(scene, {"l_BC": [0.063, 0.2]}, ["assemblable", "K", "min_transmission_deg"],
                scenes=SceneFiles(tmp_path))
    assert res["assemblable"][1] == 0
    assert math.isnan(res["K"][1]) and math.isnan(res["min_transmission_deg"][1])
    assert res["K_note"][1] == K_NOTES["assembly"]
    assert [p.name for p in tmp_path.iterdir()] == ["design_0.json"]


def _reader_problem(change) -> str:
    """The scene reader's own problem for the crank-rocker's file with ``change`` made to its
    mapping (the reference the sweep's check of each design must agree with)."""
    from linkage_sym.errors import SceneError
    from linkage_sym.examples import example_dict

    d = example_dict("crank_rocker")
    change(d)
    with pytest.raises(SceneError) as err:
        linkage_sym.load_scene(d)
    assert len(err.value.problems) == 1
    return err.value.problems[0]


def test_designs_that_break_the_scene_s_rules_are_marked_not_solved(tmp_path):
    """Issue 27: a negative mass or inertia, a length <= 0, a torque of 1e308 were solved
    (as if the length were positive) and their scenes written, which analyze refuses.  Each
    such design is marked with the rule it breaks -- the scene reader's own words for the
    field it fills -- its metrics left empty, and its scene not written."""
    scene = linkage_sym.load_example("crank_rocker")
    mass = _reader_problem(lambda d: d["links"][1].update(mass=-1.0))
    inertia = _reader_problem(lambda d: d["links"][0].update(inertia=-2e-5))
    torque = _reader_problem(lambda d: d["loads"][0].update(torque=1e308))
    assert mass == "links[1].mass: must be a finite number >= 0, got -1.0"
    res = sweep(scene, {"l_AB": [-0.02, 0.0, 0.024], "m_coupler": [-1.0, 0.5]},
                ["assemblable", "K", "grashof"], scenes=SceneFiles(tmp_path))
    length = "l_AB: joints[1].at: a length must be > 0 (a distance between two joints), got "
    assert res["invalid"].tolist() == [length + "-0.02"] * 2 + [length + "0.0"] * 2 + [
        "m_coupler: " + mass, ""]
    assert list(res.columns)[:4] == ["design", "l_AB", "m_coupler", "invalid"]
    assert np.isnan(res["assemblable"][:5]).all() and np.isnan(res["K"][:5]).all()
    assert res["grashof"][:5].tolist() == [""] * 5 and res["grashof"][5] == "crank-rocker"
    # the valid design's numbers are those of a sweep of it alone
    alone = sweep(scene, {"l_AB": [0.024], "m_coupler": [0.5]}, ["assemblable", "K", "grashof"])
    assert res["K"][5] == alone["K"][0] and res["assemblable"][5] == 1
    assert [p.name for p in tmp_path.iterdir()] == ["design_5.json"]
    assert [i for i, _ in res.bad_scene] == [0, 1, 2, 3, 4]
    res = sweep(scene, {"I_crank": [-2e-5, 1e-5], "T_1": [1e308, -0.5]}, ["assemblable"])
    assert res["invalid"].tolist() == ["I_crank: " + inertia] * 2 + ["T_1: " + torque, ""]
    assert np.isnan(res["assemblable"][:3]).all() and res["assemblable"][3] == 1
    # a valid sweep's table is as before: no invalid column
    assert "invalid" not in sweep(scene, {"l_AB": [0.02]}, ["K"]).columns


def test_options_that_give_no_valid_design_are_refused():
    """A grid axis with no valid value, and a Monte Carlo spread of 1e308 (every draw beyond
    1e30, or beyond float64), are refused naming the parameter and the rule."""
    scene = linkage_sym.load_example("crank_rocker")
    with pytest.raises(SweepError, match=r"^parameters: no value of l_AB gives a valid design: "
                                         r"l_AB: joints\[1\]\.at: a length must be > 0"):
        sweep(scene, {"m_coupler": [-1.0, 0.5], "l_AB": [-0.01, 0.0]})
    with pytest.raises(SweepError, match=r"^tolerance: none of the 50 designs is valid; design "
                                         r"0: l_AB: joints\[1\]\.at: must be within \+-1e\+30"):
        sweep(scene, MonteCarlo(50, {"l_AB": 1e308}))


def test_the_designs_argument_takes_each_kind(tmp_path):
    """``parameters`` holds the designs whatever their kind: a CSV file's path (str or
    Path) is read as read_samples reads it, a MonteCarlo is drawn about the scene's values
    as monte_carlo draws it, and each table is that of the Designs given directly."""
    from linkage_sym.design import Designs, monte_carlo, read_samples, scene_parameters

    scene = linkage_sym.load_example("crank_rocker")
    f = tmp_path / "s.csv"
    f.write_text("l_AB,l_BC\n0.02,0.06\n0.025,0.065\n")
    given = sweep(scene, read_samples(f), ["K"])
    for path in (f, str(f)):
        res = sweep(scene, path, ["K"])
        assert res.kind == "samples" and list(res.columns) == list(given.columns)
        for c in res.columns:
            np.testing.assert_array_equal(res[c], given[c])
    base = {n: v for n, v, _ in scene_parameters(scene)}
    drawn = monte_carlo(base, {"l_AB": 5e-5}, 5, random_state=2)
    res = sweep(scene, MonteCarlo(5, {"l_AB": 5e-5}, random_state=2), ["K"])
    np.testing.assert_array_equal(res["l_AB"], drawn.values[:, 0])
    alone = sweep(scene, Designs(drawn.names, drawn.values, "monte-carlo"), ["K"])
    np.testing.assert_array_equal(res["K"], alone["K"])


def test_rates_at_a_root_not_found_are_not_a_number():
    """A limit position the metrics' Newton did not find has no step (NaN): the rates and
    the coordinate there are NaN, without a RuntimeWarning of a cast of NaN to an integer
    (an error in the tests), as between two steps they are the closed forms' own."""
    import warnings

    from linkage_sym.design.evaluate import Model

    scene = linkage_sym.load_example("crank_rocker")
    model = Model(scene)
    P = model.params
    col = model.angle_of["rocker"]
    d = np.zeros(3, int)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        rate, drate, value = model.rate_at(P, d, np.array([np.nan, 10.0, 10.5]), col)
    assert np.isnan(rate[0]) and np.isnan(drate[0]) and np.isnan(value[0])
    assert np.all(np.isfinite(rate[1:])) and np.all(np.isfinite(value[1:]))
    # at a whole step the closed forms' value is the step's own rotation
    res = linkage_sym.compile_plan(scene).run()
    assert abs(value[1] - (model.cm.x0[col] + res.links["rocker"].rotation[10])) <= 1e-12


def test_loads_over_the_cycle_act_in_design_sweeps_as_in_analyze():
    """A load whose factor follows the cycle (the engine's gas force) is scaled at every
    step of every design, as ``analyze`` scales it: the design sweep at the scene's own
    crank length gives the driving torque ``analyze`` gives, to 1e-9 (the sweep had applied
    the load at its full value at every step: 1141 N·m for 358 N·m, with status ok)."""
    scene = linkage_sym.load_example("engine_four_stroke")
    assert any(ld.driver is not None for ld in scene.loads)
    res = linkage_sym.analyze(scene)
    from linkage_sym.design import scene_parameters

    own = {n: v for n, v, _ in scene_parameters(scene)}["l_AB"]
    r = sweep(scene, {"l_AB": [own]}, ["peak_driving", "rms_shaking_force"])
    want = np.nanmax(np.abs(res.forces.driving["A"]))
    assert abs(r.columns["peak_driving_A"][0] - want) <= 1e-9 * want
