"""A link's centre of mass is ``xG_<link>, yG_<link>`` (issue 31: ``q`` meant both a driver
coordinate and a centre-of-mass offset); the former ``p_<link>, q_<link>`` are still accepted,
with a :class:`FutureWarning`, wherever a sweep names a parameter.

The reference is :func:`linkage_sym.analyze` of the scene with its coupler's centre of mass
moved by hand (global coordinates, from the joints' positions), sharing no code with the
parameter table or the compiled mechanism."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import linkage_sym
from linkage_sym.cli import main
from linkage_sym.design import MonteCarlo, sweep
from linkage_sym.examples import example_path

XG, YG = 0.03, -0.004  # the coupler's centre of mass in its frame (origin B, x toward C), m


def _scene_with_coupler_com(scene, xg, yg):
    """``scene`` with the coupler's centre of mass at ``(xg, yg)`` in the frame B -> C."""
    at = {j.name: np.asarray(j.at, float) for j in scene.joints}
    u = (at["C"] - at["B"]) / np.linalg.norm(at["C"] - at["B"])
    com = at["B"] + xg * u + yg * np.array([-u[1], u[0]])
    links = [dataclasses.replace(lk, com=tuple(com)) if lk.name == "coupler" else lk
             for lk in scene.links]
    return dataclasses.replace(scene, links=links)


def test_the_current_names_are_the_centre_of_mass_in_the_link_frame():
    scene = linkage_sym.load_example("crank_rocker")
    res = sweep(scene, {"xG_coupler": [XG], "yG_coupler": [YG]}, ["peak_driving"])
    an = linkage_sym.analyze(_scene_with_coupler_com(scene, XG, YG))
    want = np.nanmax(np.abs(an.forces.driving["A"]))
    assert res["peak_driving_A"][0] == pytest.approx(want, rel=1e-9)


@pytest.mark.parametrize("old, new", [("p_coupler", "xG_coupler"), ("q_coupler", "yG_coupler")])
def test_a_former_name_is_read_as_the_current_one_with_a_warning(old, new):
    scene = linkage_sym.load_example("crank_rocker")
    values = [XG, 0.02] if old.startswith("p") else [YG, 0.0]
    current = sweep(scene, {new: values}, ["peak_driving"])
    with pytest.warns(FutureWarning, match=rf"'{old}' is now named '{new}'"):
        former = sweep(scene, {old: values}, ["peak_driving"])
    assert former.parameters == (new,) and list(former.columns) == list(current.columns)
    np.testing.assert_array_equal(former["peak_driving_A"], current["peak_driving_A"])
    with pytest.warns(FutureWarning, match=rf"'{old}'"):
        spread = sweep(scene, MonteCarlo(3, {old: 1e-3}, random_state=2), ["peak_driving"])
    assert spread.parameters == (new,)


def test_the_command_line_accepts_a_former_name(tmp_path, capsys):
    out = tmp_path / "t.csv"
    with pytest.warns(FutureWarning, match="'p_coupler' is now named 'xG_coupler'"):
        assert main(["sweep", str(example_path("crank_rocker")), "--vary", "p_coupler=0.02,0.03",
                     "--metrics", "peak_driving", "-o", str(out)]) == 0
    assert out.read_text().splitlines()[0].startswith("design,xG_coupler,")
    (tmp_path / "s.csv").write_text("q_coupler\n0.001\n")
    with pytest.warns(FutureWarning, match="'q_coupler' is now named 'yG_coupler'"):
        assert main(["sweep", str(example_path("crank_rocker")), "--samples",
                     str(tmp_path / "s.csv"), "--metrics", "peak_driving"]) == 0
    capsys.readouterr()


def test_a_driver_coordinate_is_no_former_name():
    """``q_A`` names joint A's driver coordinate, not a link: it stays unknown."""
    scene = linkage_sym.load_example("crank_rocker")
    with pytest.raises(linkage_sym.design.SweepError, match="unknown parameter 'q_A'"):
        sweep(scene, {"q_A": [0.1]}, ["K"])


def test_the_list_gives_the_current_names_their_meaning(capsys):
    assert main(["sweep", str(example_path("crank_rocker")), "--list"]) == 0
    lines = capsys.readouterr().out.splitlines()
    row = next(ln for ln in lines if ln.split()[0] == "yG_coupler")
    assert row.endswith("centre of mass of link coupler: y in the link frame")
    assert not any(ln.split()[0] in ("p_coupler", "q_coupler") for ln in lines[1:])
