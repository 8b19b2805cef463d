"""Known slider-cranks measured by the solver: the references of the slider-crank synthesis tests.

Shares no code with ``linkage_sym.synthesis.path_slider``, ``path_gen``, ``burmester`` or
``motion``: the slider-crank is built by ``linkage_sym.synthesis.builders.slider_crank`` (its
own assembly, guide along ``+x``), turned and moved as a rigid body here, solved by
``compile_plan``, and its points read from the solved joints.
"""

from __future__ import annotations

import math

import numpy as np

import linkage_sym
from linkage_sym.synthesis.builders import slider_crank


def _moved(p, turn, shift):
    c, s = math.cos(turn), math.sin(turn)
    return [c * p[0] - s * p[1] + shift[0], s * p[0] + c * p[1] + shift[1]]


def random_slider_crank(rng, full_turn=True):
    """A slider-crank with random crank, rod, offset, guide direction and coupler point, as a
    scene (joints ``A B C C_guide``, the traced point ``P``), assembled at a random crank angle."""
    while True:
        a, b, e = rng.uniform(0.2, 0.6), rng.uniform(0.9, 2.0), rng.uniform(-0.4, 0.4)
        if (a + abs(e) < b - 0.15) == full_turn:
            break
    deg = float(rng.uniform(0.0, 360.0))
    sc = slider_crank(a, b, e, crank_deg=deg, branch=str(rng.choice(["right", "left"]))).scene
    turn, shift = float(rng.uniform(-math.pi, math.pi)), rng.uniform(-1.0, 1.0, 2)
    for j in sc["joints"]:
        j["at"] = _moved(j["at"], turn, shift)
        if j["type"] == "P":
            j["axis_deg"] = math.degrees(turn)
    B, C = (np.array(sc["joints"][i]["at"]) for i in (1, 2))
    ex = (C - B) / np.linalg.norm(C - B)
    u, v = rng.uniform(-0.5, 1.5) * b, rng.uniform(0.2, 1.0) * b
    P = B + u * ex + v * np.array([-ex[1], ex[0]])
    sc["points"] = [{"name": "P", "link": "coupler", "at": [float(P[0]), float(P[1])]}]
    sc["drivers"][0]["start_deg"] = deg + math.degrees(turn)
    sc["drivers"][0]["stop_deg"] = deg + math.degrees(turn) + 360.0
    return sc


def solve_at(scene_dict, q):
    """The solver's analysis at crank angles ``q`` (rad); every step must solve."""
    plan = linkage_sym.compile_plan(linkage_sym.load_scene(scene_dict))
    q = np.asarray(q, dtype=float)
    res = plan.run(q={"A": q}, qd={"A": np.ones(len(q))}, qdd={"A": np.zeros(len(q))})
    assert (res.status == "ok").all(), res.messages
    return res


def coupler_points(scene_dict, q):
    """The traced point ``P`` at crank angles ``q`` (rad): (n, 2)."""
    return np.asarray(solve_at(scene_dict, q).points["P"].position, dtype=float)


def slider_modes_and_gamma(scene_dict, q):
    """The assembly mode (sign of ``(C - B) . u``, ``u`` along the guide) and the transmission
    angle (rad: between the rod and the guide's normal, folded to 0..pi/2) at ``q``."""
    res = solve_at(scene_dict, q)
    axis = [j for j in scene_dict["joints"] if j["type"] == "P"][0]["axis_deg"]
    u = np.array([math.cos(math.radians(axis)), math.sin(math.radians(axis))])
    r = res.joints["C"].position - res.joints["B"].position
    g = np.arccos(np.abs(r @ np.array([-u[1], u[0]])) / np.linalg.norm(r, axis=1))
    return np.sign(r @ u), g
