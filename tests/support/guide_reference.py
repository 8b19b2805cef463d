"""Known inverted slider-cranks measured by the solver: the references of the guide (RP) dyad tests.

Shares no code with ``linkage_sym.synthesis.burmester_rp``, ``burmester_slider``, ``burmester`` or
``motion``: the linkage (a crank ``A B``, the coupler pinned at ``B`` whose line slides through a
block pinned to the ground at ``D``) is written here as a scene from random dimensions, solved by
``compile_plan``, and its poses read from the solved traced point and coupler rotation.
"""

from __future__ import annotations

import json
import math

import numpy as np

from tests.support.slider_reference import solve_at


def random_inverted_slider_crank(rng, kind="oscillating", offset=None):
    """An inverted slider-crank with random crank, frame, offset (``B``'s distance from the
    coupler's line), placement and traced point ``P``, as a scene (joints ``A B D_slide D``,
    links ``crank coupler slider``), assembled at a random crank angle in a random mode.

    ``kind``: ``oscillating`` (crank + |offset| < frame: the crank turns fully, the coupler
    swings) or ``rotating`` (crank - |offset| > frame: both turn fully); ``offset`` (m): the
    offset, random when None."""
    while True:
        a, g, e = rng.uniform(0.2, 1.0), rng.uniform(0.3, 1.2), rng.uniform(-0.3, 0.3)
        e = e if offset is None else offset
        if (kind == "oscillating" and a + abs(e) < g - 0.15) or (kind == "rotating"
                                                                 and a - abs(e) > g + 0.15):
            break
    A = rng.uniform(-1.0, 1.0, 2)
    frame = float(rng.uniform(-math.pi, math.pi))
    D = A + g * np.array([math.cos(frame), math.sin(frame)])
    phi = float(rng.uniform(-math.pi, math.pi))
    B = A + a * np.array([math.cos(phi), math.sin(phi)])
    r = B - D
    alpha, s = math.atan2(r[1], r[0]), math.asin(e / np.linalg.norm(r))
    psi = alpha - s if rng.uniform() < 0.5 else alpha - math.pi + s  # either assembly mode
    u = np.array([math.cos(psi), math.sin(psi)])
    n = np.array([-u[1], u[0]])
    P = B + rng.uniform(-1.0, 1.0) * u + rng.uniform(0.2, 0.8) * n
    xy = lambda p: [float(p[0]), float(p[1])]  # noqa: E731
    return {
        "name": "inverted-slider-crank",
        "links": [{"name": "crank"}, {"name": "coupler"}, {"name": "slider"}],
        "joints": [
            {"name": "A", "type": "R", "links": ["ground", "crank"], "at": xy(A)},
            {"name": "B", "type": "R", "links": ["crank", "coupler"], "at": xy(B)},
            {"name": "D_slide", "type": "P", "links": ["coupler", "slider"], "at": xy(D),
             "axis_deg": math.degrees(psi)},
            {"name": "D", "type": "R", "links": ["slider", "ground"], "at": xy(D)},
        ],
        "points": [{"name": "P", "link": "coupler", "at": xy(P)}],
        "drivers": [{"joint": "A", "toward": "B", "start_deg": math.degrees(phi),
                     "stop_deg": math.degrees(phi) + 360.0, "steps": 361, "speed": 1.0}],
        "outputs": ["kinematics"],
    }


def poses_of(scene, n, span_deg=210.0):
    """The scene's poses (``[x, y, angle_deg]``: the traced point ``P``, the coupler's
    rotation) at ``n`` crank angles spread over ``span_deg`` from its assembly, solved."""
    th = np.radians(scene["drivers"][0]["start_deg"] + np.linspace(0.0, span_deg, n))
    res = solve_at(scene, th)
    P, rot = res.points["P"].position, res.links["coupler"].rotation
    return [[float(P[j, 0]), float(P[j, 1]), math.degrees(rot[j])] for j in range(n)]


def other_assembly(scene):
    """The same linkage assembled in its other mode at the same crank angle: the coupler (its
    slide's axis and the traced point) turned about ``B`` by the angle, other than 0, at which
    its line passes through ``D`` again -- found by scanning and root finding on the distance."""
    from scipy.optimize import brentq

    j = {x["name"]: x for x in scene["joints"]}
    B, D = np.array(j["B"]["at"]), np.array(j["D"]["at"])
    t0 = math.radians(j["D_slide"]["axis_deg"])

    r = D - B

    def off(turn):  # D's signed distance from the turned line, less the assembled one
        return ((math.cos(t0 + turn) * r[1] - math.sin(t0 + turn) * r[0])
                - (math.cos(t0) * r[1] - math.sin(t0) * r[0]))

    grid = np.linspace(1e-3, 2 * math.pi - 1e-3, 2001)
    f = [off(t) for t in grid]
    roots = [brentq(off, grid[k], grid[k + 1], xtol=1e-15) for k in range(len(grid) - 1)
             if f[k] * f[k + 1] < 0]
    assert len(roots) == 1, roots
    turn = roots[0]
    c, s = math.cos(turn), math.sin(turn)
    out = json.loads(json.dumps(scene))
    for x in out["joints"]:
        if x["name"] == "D_slide":
            x["axis_deg"] = x["axis_deg"] + math.degrees(turn)
    for p in out["points"]:
        v = np.array(p["at"]) - B
        p["at"] = [float(B[0] + c * v[0] - s * v[1]), float(B[1] + s * v[0] + c * v[1])]
    return out, turn


def random_guide_slider(rng):
    """A guide-slider with random pivot ``A`` (the driven block's), coupler line, guide and pin
    offset, as a scene (joints ``A``, the slide ``B`` of the coupler's line through the block,
    ``C``, ``C_guide``; links ``crank`` -- the block -- ``coupler``, ``slider``), its coupler
    line and guide at 60 to 120 degrees in the assembly."""
    A = rng.uniform(-1.0, 1.0, 2)
    psi = float(rng.uniform(-math.pi, math.pi))
    chi = psi + math.radians(rng.uniform(60.0, 120.0))  # the guide's direction
    u, n = np.array([math.cos(psi), math.sin(psi)]), np.array([-math.sin(psi), math.cos(psi)])
    C = A + rng.uniform(0.3, 1.0) * u + rng.uniform(-0.4, 0.4) * n  # the pin, off the line
    B = A + rng.uniform(0.2, 0.6) * u  # the block's point on the coupler's line
    P = C + rng.uniform(-0.5, 0.5, 2)
    xy = lambda p: [float(p[0]), float(p[1])]  # noqa: E731
    return {
        "name": "guide-slider",
        "links": [{"name": "crank"}, {"name": "coupler"}, {"name": "slider"}],
        "joints": [
            {"name": "A", "type": "R", "links": ["ground", "crank"], "at": xy(A)},
            {"name": "B", "type": "P", "links": ["coupler", "crank"], "at": xy(B),
             "axis_deg": math.degrees(psi)},
            {"name": "C", "type": "R", "links": ["coupler", "slider"], "at": xy(C)},
            {"name": "C_guide", "type": "P", "links": ["ground", "slider"], "at": xy(C),
             "axis_deg": math.degrees(chi)},
        ],
        "points": [{"name": "P", "link": "coupler", "at": xy(P)}],
        "drivers": [{"joint": "A", "toward": "B", "start_deg": math.degrees(psi),
                     "stop_deg": math.degrees(psi) + 360.0, "steps": 361, "speed": 1.0}],
        "outputs": ["kinematics"],
    }
