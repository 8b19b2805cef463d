"""Design sweeps with joint friction (contract part two, issue 29): each joint's friction
coefficient ``mu_<J>`` and an ``R`` joint's pin radius ``rpin_<J>`` are design parameters
(named as the springs' ``k_<k>``, ``c_<k>``, ``L0_<k>``), and the sweep's forces (the
generated force blocks with the friction's laws solved by the evaluator,
:mod:`linkage_sym.codegen.friction`) equal the numeric solver's run of each design's own
scene (which shares no code with them) at every step, to 1e-9."""

from __future__ import annotations

import numpy as np

import linkage_sym
from linkage_sym.design import SceneFiles, grid, sweep
from linkage_sym.design.evaluate import Model
from linkage_sym.design.scenes import design_scene
from linkage_sym.numeric.plan import compile_plan
from linkage_sym.structure.parameters import ident
from tests.design.test_design_sweep import _check_against_analyze, _designs_of
from tests.support.friction_scenes import with_friction

PRESS = "slider_crank_press_friction"
TOL = 1e-9


def test_the_parameter_table_names_the_friction():
    scene = linkage_sym.load_example(PRESS)
    rows = {n: (v, m) for n, v, m in linkage_sym.design.scene_parameters(scene)}
    assert rows["mu_B"][0] == 0.15 and rows["rpin_B"][0] == 0.015
    assert rows["mu_C_guide"][0] == 0.1 and "rpin_C_guide" not in rows
    assert "friction coefficient of joint B" in rows["mu_B"][1]
    assert "pin radius of joint B" in rows["rpin_B"][1]


def test_a_sweep_of_friction_coefficients_equals_analyze_of_each_design(tmp_path):
    scene = linkage_sym.load_example(PRESS)
    res = sweep(scene, {"mu_B": [0.0, 0.15, 0.3], "rpin_C": [0.01, 0.02],
                        "mu_C_guide": [0.05, 0.2]},
                ["assemblable", "peak_driving", "rms_driving", "peak_reaction"],
                scenes=SceneFiles(tmp_path))
    assert len(res) == 12
    scenes = _designs_of(tmp_path)
    assert sorted({sc.joint("B").friction.coefficient for sc in scenes.values()}) == \
        [0.0, 0.15, 0.3]
    assert sorted({sc.joint("C").friction.radius for sc in scenes.values()}) == [0.01, 0.02]
    _check_against_analyze(res, scenes)
    assert len({round(v, 9) for v in res["peak_driving_A"]}) == 12  # the friction matters


def _forces_against_analyze(scene, names, values):
    """Every design's reactions and efforts at every step against ``analyze`` of its scene."""
    model = Model(scene, forces=True)
    n = len(values)
    P = model.design_params(names, values)
    assembly = model.assemble(P, n)
    sol = model.solve(assembly[0], n, {"forces"}, assembly=assembly)
    fidx = model.art.force_index()
    L = scene.characteristic_length()
    for d in range(n):
        own = design_scene(model, *assembly[:2], assembly[3], d, f"design-{d}")
        an = compile_plan(own).run()
        ok = an.ok
        assert np.array_equal(ok, sol.ok[d])
        got = {}
        for j in own.joints:
            k = ident(j.name)
            if j.type == "R":
                got[j.name] = np.stack([sol.forces[fidx[f"R_{k}x"], d],
                                        sol.forces[fidx[f"R_{k}y"], d]], -1)
        for dr in own.drivers:
            got[dr.joint + ":effort"] = sol.forces[fidx[("tau_" if dr.kind == "R" else "f_")
                                                        + ident(dr.joint)], d]
        scale = max(float(np.nanmax(np.abs(an.forces.reactions[j.name][ok])))
                    for j in own.joints)
        for name, v in got.items():
            if name.endswith(":effort"):
                ref = an.forces.driving[name.split(":")[0]]
                div = L
            else:
                ref, div = an.forces.reactions[name], 1.0
            assert np.nanmax(np.abs(v[ok] - ref[ok])) / div <= TOL * scale, (d, name)
        for j in own.joints:  # the friction through its joint's reaction law
            if j.friction is not None and j.type == "R" and j.friction.coefficient > 0:
                mu = sol.forces[fidx[f"Mf_{ident(j.name)}"], d]
                assert np.nanmax(np.abs(mu[ok] - an.forces.friction[j.name][ok])) / L \
                    <= TOL * scale


def test_the_sweeps_forces_at_every_step_equal_analyze_of_each_design():
    scene = linkage_sym.load_example(PRESS)
    d = grid({"mu_A": [0.0, 0.2], "rpin_B": [0.005, 0.03], "mu_C_guide": [0.0, 0.15]})
    _forces_against_analyze(scene, d.names, d.values)


def test_a_sixbar_with_friction_everywhere():
    scene = linkage_sym.load_scene(with_friction("stephenson_sixbar"))
    names = [n for n, _, _ in linkage_sym.design.scene_parameters(scene)
             if n.startswith("mu_")][:2]
    d = grid({names[0]: [0.0, 0.25], names[1]: [0.05, 0.3]})
    _forces_against_analyze(scene, d.names, d.values)


def test_a_class3_design_keeps_its_friction_one_design_at_a_time(tmp_path):
    """A class-III group has no closed form: such designs are solved one at a time by the
    numeric plan on each design's scene, which carries the design's friction."""
    scene = linkage_sym.load_scene(with_friction("sixbar_class3"))
    names = [n for n, _, _ in linkage_sym.design.scene_parameters(scene) if n.startswith("mu_")]
    res = sweep(scene, {names[0]: [0.0, 0.2], names[1]: [0.1]},
                ["assemblable", "peak_driving", "peak_reaction"], scenes=SceneFiles(tmp_path))
    _check_against_analyze(res, _designs_of(tmp_path))
    assert res["peak_driving_A"][0] != res["peak_driving_A"][1]


def _inclined_sweep():
    from tests.support.friction_scenes import inclined_slider

    scene = linkage_sym.load_scene(inclined_slider(0.3))
    mus = [0.0, 0.3, 0.6, 1.2]
    return scene, mus, sweep(scene, {"mu_C_guide": mus}, ["assemblable", "peak_driving",
                                                           "rms_driving", "peak_reaction"])


def test_a_design_that_self_locks_is_not_given_a_finite_peak_effort():
    """The inclined slider self-locks over part of its stroke above the friction angle's
    coefficient: a design's ``self_locking`` column is the share of steps the numeric solver
    reports ``self-locking`` for its own scene, and its efforts and reactions over the cycle
    are unbounded (``inf``), never the largest of its other steps; a design that never
    locks has the solver's peak effort (1e-9)."""
    from tests.support.friction_scenes import inclined_slider

    scene, mus, res = _inclined_sweep()
    shares = []
    for k, mu in enumerate(mus):
        r = linkage_sym.analyze(linkage_sym.load_scene(inclined_slider(mu)))
        status = np.asarray(r.status)
        locked = int(np.sum(status == "self-locking"))
        shares.append(locked)
        assert res["self_locking"][k] == locked / scene.steps
        assert res["assemblable"][k] == 1.0  # every step assembles: locking is no defect of it
        if locked:
            assert np.isinf(res["peak_driving_A"][k]) and np.isinf(res["rms_driving_A"][k])
            assert all(np.isinf(res[f"peak_reaction_{j}"][k]) for j in ("A", "B", "C", "C_guide"))
        else:
            peak = np.max(np.abs(r.forces.driving["A"]))
            assert abs(res["peak_driving_A"][k] - peak) <= TOL * peak
    assert shares[0] == 0 and 0 < shares[1] < shares[2] < shares[3] == scene.steps


def test_designs_solved_one_at_a_time_report_self_locking_alike(monkeypatch):
    """Designs with a group without a closed form are solved by the numeric plan one at a
    time (its statuses say ``self-locking``): forced onto that route, the inclined slider's
    sweep has the same columns as the closed forms' (locked steps are assembled steps)."""
    _, _, direct = _inclined_sweep()
    init = Model.__init__

    def one_at_a_time(self, *args, **kwargs):
        init(self, *args, **kwargs)
        self.one_at_a_time = True

    monkeypatch.setattr(Model, "__init__", one_at_a_time)
    _, _, planned = _inclined_sweep()
    for col in direct.metrics:
        a, b = np.asarray(direct[col], float), np.asarray(planned[col], float)
        assert np.array_equal(np.isinf(a), np.isinf(b)), col
        fin = np.isfinite(a)
        assert np.allclose(a[fin], b[fin], rtol=TOL, atol=0.0), col
