"""Defects found by the solver against four-bars constructed to have each one."""

import math

from linkage_sym.synthesis.builders import fourbar
from linkage_sym.synthesis.defects import check_motion


def _targets(lengths, degs, branch="open"):
    """The coupler point's positions of a built four-bar at the crank angles (the builder's
    closed-form assembly, not the solver)."""
    return [fourbar(*lengths, crank_deg=x, branch=branch, coupler_point=(1.0, 0.5))
            .scene["points"][0]["at"] for x in degs]


def _scene(lengths, deg, branch="open"):
    return fourbar(*lengths, crank_deg=deg, branch=branch, coupler_point=(1.0, 0.5)).scene


CRANK_ROCKER = (1.0, 3.0, 3.0, 3.5)
TRIPLE_ROCKER = (2.0, 3.0, 2.5, 4.0)  # s + l = 6 > p + q = 5.5


def test_defect_free_motion_meets_every_target_to_1e_12():
    degs = [30, 80, 150, 220, 300]
    r = check_motion(_scene(CRANK_ROCKER, 30), degs, point="P", targets=_targets(CRANK_ROCKER, degs))
    assert r.defect_free and r.grashof == "crank-rocker" and r.sense == 1
    assert max(r.errors) < 1e-12 * 3.0
    assert 0 < r.gamma_min < math.pi / 2


def test_branch_defect_a_target_of_the_crossed_mode():
    degs = [30, 80, 150, 220]
    targets = _targets(CRANK_ROCKER, degs)
    targets[2] = _targets(CRANK_ROCKER, [150], branch="crossed")[0]
    r = check_motion(_scene(CRANK_ROCKER, 30), degs, point="P", targets=targets)
    assert r.branch and not r.order and not r.dead_centre and not r.missed and not r.defect_free
    assert r.circuit  # a crank-rocker's assembly modes are its two circuits


def test_branch_defect_of_a_triple_rocker_is_on_its_one_circuit():
    degs = [50, 20, 0]
    targets = _targets(TRIPLE_ROCKER, degs)
    targets[2] = _targets(TRIPLE_ROCKER, [0], branch="crossed")[0]
    r = check_motion(_scene(TRIPLE_ROCKER, 50), degs, point="P", targets=targets)
    assert r.branch and not r.circuit and not r.missed


def test_circuits_of_a_grashof_double_rocker_are_not_its_assembly_modes():
    # shortest link the coupler, which turns fully relative to the ground: a circuit keeps C
    # on one side of the ground line AD (C crosses it only with B, C, D or A, B, C in line,
    # which the fully turning coupler never is); the assembly modes at a crank angle are C
    # mirrored in BD, on one side of AD or on both
    lengths = (3.0, 1.0, 3.5, 4.0)  # crank, coupler, rocker, ground: 1 + 4 < 3 + 3.5
    degs = [45, 60, 75]
    for deg in (60, 75):
        targets = _targets(lengths, degs)
        targets[degs.index(deg)] = _targets(lengths, [deg], branch="crossed")[0]
        r = check_motion(_scene(lengths, 45), degs, point="P", targets=targets)
        assert r.grashof == "double-rocker" and r.branch and not r.missed
        c1 = _scene(lengths, 45)["joints"][2]["at"]
        c2 = _scene(lengths, deg, branch="crossed")["joints"][2]["at"]
        assert r.circuit == ((c1[1] > 0) != (c2[1] > 0))


def test_order_defect_targets_swapped():
    degs = [30, 150, 80, 220]
    r = check_motion(_scene(CRANK_ROCKER, 30), degs, point="P", targets=_targets(CRANK_ROCKER, degs))
    assert r.order and not r.branch and not r.dead_centre and not r.defect_free


def test_dead_centre_of_a_triple_rocker_between_targets():
    # turning clockwise 50 -> 0 -> -50 the crank stays within its range: no defect
    degs = [50, 0, -50]
    r = check_motion(_scene(TRIPLE_ROCKER, 50), degs, point="P",
                     targets=_targets(TRIPLE_ROCKER, degs))
    assert r.grashof == "triple-rocker" and r.sense == -1 and r.defect_free
    # 50 -> -50 -> 0 comes in order only counter-clockwise, through 180 degrees, out of reach
    degs = [50, -50, 0]
    r = check_motion(_scene(TRIPLE_ROCKER, 50), degs, point="P",
                     targets=_targets(TRIPLE_ROCKER, degs))
    assert r.sense == 1 and r.dead_centre and not r.order and not r.defect_free


def test_targets_of_another_linkage_are_missed():
    degs = [30, 80, 150, 220]
    targets = _targets((1.0, 3.0, 3.0, 3.6), degs)
    r = check_motion(_scene(CRANK_ROCKER, 30), degs, point="P", targets=targets)
    assert r.missed == (0, 1, 2, 3) and not r.defect_free


def test_branch_defect_with_rotations_of_the_coupler():
    # the crossed mode's coupler is turned otherwise at assembly: its rotations are compared
    # with the targets' after that turn
    degs = [30, 80, 150, 220]
    scenes = [_scene(CRANK_ROCKER, x) for x in degs]
    scenes[2] = _scene(CRANK_ROCKER, 150, branch="crossed")

    def angle(s):
        j = {x["name"]: x["at"] for x in s["joints"]}
        return math.atan2(j["C"][1] - j["B"][1], j["C"][0] - j["B"][0])

    rotations = [angle(s) - angle(scenes[0]) for s in scenes]
    targets = [s["points"][0]["at"] for s in scenes]
    r = check_motion(scenes[0], degs, point="P", targets=targets, rotations=rotations)
    assert r.branch and not r.missed


def _slider(deg, branch="right"):
    from linkage_sym.synthesis.builders import slider_crank

    sc = slider_crank(1.0, 3.0, 0.5, crank_deg=deg, branch=branch).scene
    B, C = sc["joints"][1]["at"], sc["joints"][2]["at"]
    sc["points"] = [{"name": "P", "link": "coupler",
                     "at": [0.5 * (B[0] + C[0]) - 0.5 * (C[1] - B[1]),
                            0.5 * (B[1] + C[1]) + 0.5 * (C[0] - B[0])]}]
    return sc


def test_slider_crank_defect_free_and_branch_defect_on_its_other_circuit():
    degs = [30, 100, 170, 250]
    targets = [_slider(x)["points"][0]["at"] for x in degs]
    r = check_motion(_slider(30), degs, point="P", targets=targets)
    assert r.defect_free and r.kind == "slider-crank" and r.grashof == "slider-crank"
    assert max(r.errors) < 1e-12 * 3.0
    # the builder's closed form: the smallest transmission angle acos((a + |e|) / b)
    assert r.gamma_min >= math.acos(1.5 / 3.0) - 1e-12
    targets[2] = _slider(170, branch="left")["points"][0]["at"]
    r = check_motion(_slider(30), degs, point="P", targets=targets)
    assert r.branch and r.circuit and not r.order and not r.dead_centre and not r.missed


def test_slider_rocker_dead_centre_between_targets():
    from linkage_sym.synthesis.builders import slider_crank

    # crank + |offset| = 1.5 > rod 1.2: the rod reaches the guide for 0.5 - 1.2 <= sin(phi)
    sc = slider_crank(1.0, 1.2, 0.5, crank_deg=0.0).scene
    r = check_motion(sc, [0.0, -30.0, -60.0])
    assert r.dead_centre and r.grashof == "slider-rocker" and not r.full_turn
