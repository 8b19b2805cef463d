"""Checks of synthesized linkages by the solver (a method sharing no code with the synthesis).

The output's extreme positions are found as roots of its velocity, computed by
``Plan.run`` at single driver values and located by SciPy's ``brentq`` (not read
off a sampled sweep): the swing or stroke is the difference of the output's
positions at the two roots, ``K`` the ratio of the crank angles between them.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import brentq

import linkage_sym

XTOL = 1e-15
"""brentq's absolute tolerance on the crank angle (rad)."""


def plan_of(scene_dict):
    scene = linkage_sym.load_scene(scene_dict)
    return scene, linkage_sym.compile_plan(scene)


def _at(plan, phi, quantity):
    """``quantity(analysis)`` at the single crank angle ``phi`` (speed 1 rad/s)."""
    res = plan.run(q={"A": np.array([phi])}, qd={"A": np.array([1.0])}, qdd={"A": np.array([0.0])})
    assert res.status[0] == "ok", res.messages[0]
    return quantity(res)


def output_extremes(scene_dict, rate, value, grid=720):
    """The output's extremes over one crank turn from the scene's start angle.

    ``rate(analysis)`` is the output's velocity, ``value(analysis)`` its
    position (a rotation or a displacement).  Returns ``(roots, values)``:
    the two crank angles (rad, increasing, within one turn of the start) where
    ``rate`` vanishes and the output's position there.
    """
    scene, plan = plan_of(scene_dict)
    drv = scene.drivers[0]
    # a grid offset from the start (which may be an extreme itself)
    phis = drv.start + (np.arange(grid) + 0.5) * (2 * math.pi / grid)
    res = plan.run(q={"A": phis}, qd={"A": np.ones(grid)}, qdd={"A": np.zeros(grid)})
    assert (res.status == "ok").all()
    w = rate(res)
    roots = []
    for i in range(grid):
        j = (i + 1) % grid
        lo, hi = phis[i], phis[j] + (2 * math.pi if j == 0 else 0.0)
        if np.sign(w[i]) != np.sign(w[j]):
            f = lambda p: float(_at(plan, p, rate)[0])
            roots.append(brentq(f, lo, hi, xtol=XTOL, rtol=4 * np.finfo(float).eps))
    assert len(roots) == 2, roots
    roots.sort()
    values = [float(_at(plan, r, value)[0]) for r in roots]
    return roots, values


def rocker_swing_and_K(scene_dict, link="rocker"):
    """``(psi, K)`` of a crank-rocker (or guide-bar) scene from the solver."""
    (r1, r2), (v1, v2) = output_extremes(
        scene_dict, lambda res: res.links[link].omega, lambda res: res.links[link].rotation)
    span = r2 - r1
    return abs(v2 - v1), max(span, 2 * math.pi - span) / min(span, 2 * math.pi - span)


def slider_stroke_and_K(scene_dict, joint="C"):
    """``(H, K)`` of a slider-crank scene from the solver (slider along x)."""
    (r1, r2), (v1, v2) = output_extremes(
        scene_dict, lambda res: res.joints[joint].velocity[:, 0],
        lambda res: res.joints[joint].position[:, 0])
    span = r2 - r1
    return abs(v2 - v1), max(span, 2 * math.pi - span) / min(span, 2 * math.pi - span)
