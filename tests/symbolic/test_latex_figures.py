"""The TikZ figure of each vector loop (``derive --latex``), checked against the numeric solver.

The coordinates are read back from the TikZ source (centimetres, the picture's stated scale
times the scene's) and compared with the joint positions the numeric solver finds in the
scene's assembly configuration (each driver started at its assembly value): every joint, and
both ends of every vector of the loop, to 1e-9 of the mechanism's size.  The vectors are as
many as the printed loop equation's terms, and each arc named by a link angle ``\\theta``
ends at the angle of that link's axis between the solver's joints.
"""

from __future__ import annotations

import math
import re

import numpy as np
import pytest
import sympy as sp

import linkage_sym
from linkage_sym.cli import main
from linkage_sym.examples import example_dict, example_path, load_example
from linkage_sym.structure.parameters import driver_q0, ident, link_frames
from linkage_sym.symbolic import derive
from linkage_sym.symbolic.latex import latex_document, standalone
from tests.support.example_sets import symbolic_examples
from tests.support.marks import fast_cases

REL = 1e-9
"""Positions agree to this fraction of the mechanism's size (its characteristic length)."""

NUM = r"(-?[0-9.]+)"
PT = rf"\({NUM}, {NUM}\)"
SCALE = re.compile(r"% coordinates in cm: figure = ([0-9.e+-]+) \* scene")
JOINT = re.compile(rf"\\coordinate \(\w+\) at {PT}; % joint (.+)$", re.M)
VECTOR = re.compile(rf"\\draw\[(vec|ground vec)\] {PT} -- {PT} node\[pos=([0-9.]+)")
ARC = re.compile(rf"\\draw\[angle\] {PT} arc\[start angle=0, end angle={NUM}, radius={NUM}\]; "
                 rf"\\node\[anchor=[a-z ]+\] at {PT} {{\$(.+?)\$}};")
THETA = re.compile(r"\\theta_\{\\mathrm\{(.+)\}\}")


def solver_at_assembly(name: str) -> tuple[dict, float]:
    """The numeric solver's joint positions with every driver at its assembly value, and the
    mechanism's size."""
    scene = load_example(name)
    q0 = driver_q0(scene)
    data = example_dict(name)
    for d in data["drivers"]:
        if "start_deg" in d:
            d["start_deg"], d["stop_deg"] = math.degrees(q0[d["joint"]]), math.degrees(q0[d["joint"]]) + 1
        else:
            d["start"], d["stop"] = q0[d["joint"]], q0[d["joint"]] + 1e-3
        d["steps"] = 2
    result = linkage_sym.analyze(linkage_sym.load_scene(data))
    return ({j: np.asarray(k.position[0]) for j, k in result.joints.items()},
            scene.characteristic_length())


def figures(tex: str) -> list[str]:
    """The ``figure`` environments of a LaTeX text."""
    return re.findall(r"\\begin\{figure\}.*?\\end\{figure\}", tex, re.S)


@pytest.mark.parametrize("name", fast_cases(symbolic_examples(), {"crank_rocker", "sixbar_class3"}))
def test_each_loop_figure_is_where_the_numeric_solver_puts_the_mechanism(name):
    eqs = derive(load_example(name))
    figs = figures(latex_document(eqs, figures=True))
    assert len(figs) == len(eqs.loops)
    joints, size = solver_at_assembly(name)
    frames = link_frames(eqs.scene)
    links = {ident(n): n for n in frames}  # a link angle's symbol is named after ident(link)
    for fig, (jname, loop) in zip(figs, eqs.loops):
        assert r"\label{fig:" in fig and "loop-" + re.sub(r"[^A-Za-z0-9:.-]", "-", jname) in fig
        scale = float(SCALE.search(fig).group(1))
        tol = REL * size * scale
        drawn = {n: np.array([float(x), float(y)]) for x, y, n in JOINT.findall(fig)}
        assert set(drawn) == set(joints)
        for n, p in drawn.items():
            assert np.hypot(*(p / scale - joints[n])) <= REL * size, (n, p / scale, joints[n])
        ends = [np.zeros(2)] + [p * scale for p in joints.values()]

        def on_a_joint(x, y):
            return min(np.hypot(x - e[0], y - e[1]) for e in ends) <= tol

        vectors = VECTOR.findall(fig)
        for kind, x1, y1, x2, y2, pos in vectors:
            assert on_a_joint(float(x1), float(y1)), (kind, x1, y1)
            if float(pos) < 1:  # not a slide drawn as its axis (a slide at 0)
                assert on_a_joint(float(x2), float(y2)), (kind, x2, y2)
        # as many vectors as the printed loop has link vectors and ground points off the origin
        terms = sp.Add.make_args(loop.complex())
        polar = [t for t in terms if t.has(sp.exp)]
        printed, values = loop.complex().free_symbols, eqs.parameter_values()
        off_origin = [g for g in loop.cart if (g[0].free_symbols | g[1].free_symbols) <= printed
                      and any(float(c.xreplace(values)) != 0 for c in g)]
        assert sum(k == "vec" for k, *_ in vectors) == len(polar)
        assert sum(k == "ground vec" for k, *_ in vectors) == len(off_origin)
        arcs = ARC.findall(fig)
        assert len(arcs) == len(polar)
        for x, y, deg, _, _, _, name_tex in arcs:
            m = THETA.fullmatch(name_tex)
            if m is None:
                continue
            fr = frames[links[m.group(1).replace(r"\_", "_")]]
            u, v = joints[fr.u], joints[fr.v]
            axis = math.degrees(math.atan2(v[1] - u[1], v[0] - u[0]))
            assert abs(math.remainder(float(deg) - axis, 360)) < 1e-7, (link, deg, axis)


def test_the_fragment_without_figures_is_unchanged_and_the_document_loads_tikz_only_with_them():
    eqs = derive(load_example("crank_rocker"))
    plain, drawn = latex_document(eqs), latex_document(eqs, figures=True)
    assert not figures(plain) and len(figures(drawn)) == 1
    assert r"\usepackage{tikz}" not in standalone(plain)
    assert r"\usepackage{tikz}" in standalone(drawn)
    assert "% The figures of the vector loops need \\usepackage{tikz}." in drawn


def test_derive_latex_draws_the_figures_unless_told_not_to(tmp_path, capsys):
    scene = str(example_path("crank_rocker"))
    assert main(["derive", scene, "--latex", "-o", str(tmp_path / "a.tex")]) == 0
    assert main(["derive", scene, "--latex", "--no-figures", "-o", str(tmp_path / "b.tex")]) == 0
    assert len(figures((tmp_path / "a.tex").read_text())) == 1
    assert not figures((tmp_path / "b.tex").read_text())
    capsys.readouterr()
    assert main(["derive", scene, "--no-figures"]) == 2
    assert "--no-figures" in capsys.readouterr().err
