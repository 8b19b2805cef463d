"""Known four-bars measured by the solver: the references of the function and path tests.

Shares no code with ``linkage_sym.synthesis.function_gen`` or ``path_gen``: the
four-bar is built by ``linkage_sym.synthesis.builders.fourbar`` (its own
assembly), solved by ``compile_plan``, and its angles and coupler points read
from the solved joints.
"""

from __future__ import annotations

import numpy as np

import linkage_sym
from linkage_sym.synthesis.builders import fourbar


def solve_at(scene_dict, q):
    """The solver's analysis of the scene at crank angles ``q`` (rad)."""
    plan = linkage_sym.compile_plan(linkage_sym.load_scene(scene_dict))
    q = np.asarray(q, dtype=float)
    res = plan.run(q={"A": q}, qd={"A": np.ones(len(q))}, qdd={"A": np.zeros(len(q))})
    assert (res.status == "ok").all(), res.messages
    return res


def random_crank_rocker(rng, coupler_point=False):
    """A Grashof crank-rocker (crank shortest) with a random coupler point, as a scene."""
    while True:
        a, b, c, d = rng.uniform(0.2, 1.0), rng.uniform(0.8, 2.0), rng.uniform(0.8, 2.0), 1.5
        L = sorted([a, b, c, d])
        if a == L[0] and L[0] + L[3] < L[1] + L[2] - 0.1:
            break
    uv = (float(rng.uniform(-0.5, 1.5)), float(rng.uniform(0.2, 1.0))) if coupler_point else None
    return fourbar(a, b, c, d, crank_deg=float(rng.uniform(0, 360)), coupler_point=uv)


def rocker_angle(scene_dict, q):
    """The rocker's angle (rad, from +x) at crank angles ``q``, from the solved ``C`` and ``D``."""
    res = solve_at(scene_dict, q)
    C, D = res.joints["C"].position, res.joints["D"].position
    return np.arctan2(C[:, 1] - D[:, 1], C[:, 0] - D[:, 0])


def coupler_points(scene_dict, q):
    """The traced point ``P`` at crank angles ``q`` (rad): (n, 2)."""
    return np.asarray(solve_at(scene_dict, q).points["P"].position, dtype=float)


def branch_modes(scene_dict, q):
    """The sign of ``(D - B) x (C - B)`` at each crank angle by the solver."""
    res = solve_at(scene_dict, q)
    B, C, D = (res.joints[k].position for k in "BCD")
    u, v = D - B, C - B
    return np.sign(u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0])
