"""Design sweeps under springs and dampers (the contract's ``springs``, issue 29): the
springs' stiffness, damping, free length and ends are design parameters (``k_<k>``,
``c_<k>``, ``L0_<k>``...), and the force metrics (computed with the symbolic layer's
functions, the springs derived) equal the numeric solver's run of each design's own
scene (which shares no code with them)."""

from __future__ import annotations

import linkage_sym
from linkage_sym.design import SceneFiles, sweep
from tests.design.test_design_sweep import _check_against_analyze, _designs_of


def test_the_parameter_table_names_the_springs():
    scene = linkage_sym.load_example("crank_rocker_spring")
    rows = {n: (v, m) for n, v, m in linkage_sym.design.scene_parameters(scene)}
    assert rows["k_k1"][0] == 500.0 and rows["c_k1"][0] == 2.0 and rows["L0_k1"][0] == 0.03
    assert rows["k_k2"][0] == 1.5 and rows["theta_f_k2"][0] == 0.0
    assert "stiffness of spring k1" in rows["k_k1"][1]


def test_a_sweep_of_a_springs_stiffness_equals_analyze_of_each_design(tmp_path):
    scene = linkage_sym.load_example("crank_rocker_spring")
    res = sweep(scene, {"k_k1": [0.0, 500.0, 2000.0], "L0_k1": [0.03, 0.05], "c_k1": [2.0],
                        "k_k2": [1.5, 4.0]},
                ["assemblable", "peak_driving", "rms_driving", "peak_reaction",
                 "rms_shaking_force", "rms_shaking_moment"], scenes=SceneFiles(tmp_path))
    assert len(res) == 12
    scenes = _designs_of(tmp_path)
    assert sorted(scenes) == list(range(12))
    assert sorted({sc.springs[0].stiffness for sc in scenes.values()}) == [0.0, 500.0, 2000.0]
    _check_against_analyze(res, scenes)
    # the springs matter: the designs' peak driving torques differ, but where k_k1 is 0
    # (its free length then does nothing)
    assert len({round(v, 9) for v in res["peak_driving_A"]}) == 10
