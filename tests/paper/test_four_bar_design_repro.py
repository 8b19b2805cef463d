"""The textbook section 'Design of four-bar mechanisms' ([2] of the README's Sources), worked
in ``paper_repro/four_bar_design.py``: the K procedure written out against the synthesis and the
solver, and statics examples 2-9 and 2-10 solved by the force solver against the section's
printed values (with its errata: N printed for kN in 2-9, 2-10's moment from a rounded force).
"""

from __future__ import annotations

import math

import pytest

import four_bar_design as fb  # noqa: E402


@pytest.fixture(scope="module")
def part1():
    return fb.part1()


def test_the_procedure_written_out_equals_the_synthesis(part1):
    h, d = part1["by_hand"], part1["design"]
    assert math.degrees(h["theta"]) == pytest.approx(36.0, rel=1e-15)
    assert math.degrees(h["angle_C1OC2"]) == pytest.approx(72.0, rel=1e-12)
    assert math.degrees(h["angle_C1AC2"]) == pytest.approx(36.0, rel=1e-12)
    assert h["admissible"]
    assert h["crank"] == pytest.approx(d.lengths["crank"], rel=1e-12)
    assert h["coupler"] == pytest.approx(d.lengths["coupler"], rel=1e-12)


def test_the_solver_meets_the_requests(part1):
    assert math.degrees(part1["solver_swing"]) == pytest.approx(fb.SWING_DEG, rel=1e-9)
    assert part1["solver_K"] == pytest.approx(fb.K, rel=1e-9)
    assert part1["solver_stroke"] == pytest.approx(0.1, rel=1e-9)
    assert part1["solver_K_slider"] == pytest.approx(1.4, rel=1e-9)
    assert math.degrees(part1["solver_swing_guide"]) == pytest.approx(60.0, rel=1e-9)
    assert part1["solver_K_guide"] == pytest.approx(2.0, rel=1e-9)
    assert part1["best"].gamma_min > part1["design"].gamma_min


def test_example_2_9_by_the_force_solver():
    r = fb.example_2_9()
    assert r["F_N"] == pytest.approx(r["F_N_closed"], rel=1e-12)
    assert r["F_T"] == pytest.approx(r["F_T_closed"], rel=1e-12)
    assert r["F_N_direction_deg"] == pytest.approx(fb.BETA_DEG, rel=1e-12)
    assert abs(r["N_moment"]) <= 1e-12 * fb.G
    # the printed values, to their printed digits, once N is read as kN (the erratum)
    assert round(r["F_N"] / 1e3, 3) == fb.EX_2_9_PRINTED["F_N"]
    assert round(r["F_T"] / 1e3, 3) == fb.EX_2_9_PRINTED["F_T"]


@pytest.mark.parametrize("rod_run", [0.3, 0.15, 0.35])
def test_example_2_10_by_the_force_solver(rod_run):
    r = fb.example_2_10(rod_run)
    exact_f = fb.F_Q * fb.TAN_ALPHA
    for key in ("F_NB", "F_Ox"):
        assert r[key] == pytest.approx(exact_f, rel=1e-12)
        assert round(r[key] / 1e3, 3) * 1e3 == pytest.approx(fb.EX_2_10_PRINTED[key], rel=1e-12)
    assert r["F_Oy"] == pytest.approx(fb.EX_2_10_PRINTED["F_Oy"], rel=1e-12)
    assert r["M"] == pytest.approx(exact_f * fb.OB, rel=1e-12)  # 53.333 N m
    # the printed 53.2 N m is the rounded force times OB (the erratum), not the moment
    assert fb.EX_2_10_PRINTED["M"] == pytest.approx(r["M_from_rounded_F_NB"], rel=1e-12)
    assert abs(r["M"] - fb.EX_2_10_PRINTED["M"]) > 0.1


def test_the_script_runs(capsys):
    fb.main()
    out = capsys.readouterr().out
    assert "erratum" in out and "seed" not in out.lower()
