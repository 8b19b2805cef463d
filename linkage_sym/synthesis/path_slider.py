"""The slider-crank with a coupler point in closed form, vectorized: path synthesis's second linkage.

A design is ``(Ax, Ay, a, b, e, g, u, v)`` and an assembly mode
``sigma = +-1``: the crank ``A B`` (length ``a``) at the angle ``theta`` from
``+x``; the guide, the line at the angle ``g`` (rad) from ``+x`` passing at
the signed distance ``e`` (the offset) from ``A`` (the point ``A + e n``,
``n`` the guide's normal, ``u_g`` turned a quarter turn counter-clockwise);
the connecting rod ``B C`` (``b``) with ``C`` on the guide, ahead of the
foot of ``B`` along ``u_g`` for ``sigma = +1`` (the sign of
``(C - B) . u_g``, constant along a branch); the coupler point
``P = B + u e_r + v e_r_perp`` with ``e_r`` the unit vector ``B -> C``.

Three points are met exactly (:func:`exact_three`); the crank dyad obeys the
standard dyad equation ``W (e^(i beta_j) - 1) + Z (e^(i alpha_j) - 1) = P_j -
P_1`` (A. G. Erdman, G. N. Sandor, *Mechanism Design: Analysis and
Synthesis*, vol. 1, "complex-number synthesis") and the slider's pin ``C_j =
P_j - Z_s e^(i alpha_j)`` stays on a line of direction ``g``:
``Im((P_j - P_1 - Z_s (e^(i alpha_j) - 1)) e^(-i g)) = 0``, linear in ``Z_s``.
The batched solver (:class:`linkage_sym.design.evaluate.Model`) solves many
random slider-cranks at once (:func:`batched_curves`).

This is the synthesis's own model; every reported design is checked by the
solver (:mod:`linkage_sym.synthesis.path_check`).  NumPy only.

Examples
--------
>>> z = np.array([0.0, 0.0, 1.0, 3.0, 0.5, 0.0, 1.0, 0.5])
>>> B, C, P, h2 = pins(z[None, :], np.array([[np.pi / 2]]), 1.0)
>>> round(float(C[0, 0].real), 9), round(float(C[0, 0].imag), 9), bool(h2[0, 0] > 0)
(2.958039892, 0.5, True)
"""

from __future__ import annotations

import math

import numpy as np

from linkage_sym.synthesis.path_dyads import crank_turns, dyad_through

NPAR = 8
"""``Ax, Ay, a, b, e, g, u, v``."""

LENGTHS = (2, 3)
"""The positive lengths among the parameters: crank ``a`` and rod ``b``."""

KIND = "slider-crank"


def _guide(z):
    g = z[..., 5, None]
    return np.exp(1j * g)


def pins(z, theta, sigma):
    """``B, C, P`` (complex) and the squared rod component along the guide ``h2`` at ``theta``.

    ``z``: parameters (..., 8) broadcast against ``theta`` (..., k); where the
    rod cannot reach the guide (``h2 < 0``) that component is taken as 0.
    """
    z = np.asarray(z, dtype=float)
    Ax, Ay, a, b, e = (z[..., i, None] for i in range(5))
    u, v = z[..., 6, None], z[..., 7, None]
    ug = _guide(z)
    A = Ax + 1j * Ay
    B = A + a * np.exp(1j * theta)
    rel = (B - A) * ug.conjugate()  # B in the guide's frame about A
    h2 = b * b - (e - rel.imag) ** 2
    sigma = np.asarray(sigma, dtype=float)
    sigma = sigma[..., None] if sigma.ndim else sigma
    C = A + (rel.real + sigma * np.sqrt(np.maximum(h2, 0.0)) + 1j * e) * ug
    with np.errstate(divide="ignore", invalid="ignore"):
        er = (C - B) / b
    P = B + (u + 1j * v) * er
    return B, C, P, h2


def transmission(z, theta, sigma):
    """The transmission angle (rad, 0..pi/2): between the rod and the guide's normal."""
    B, C, _, _ = pins(z, theta, sigma)
    b = z[..., 3, None]
    normal = 1j * _guide(z)
    comp = ((C - B) * normal.conjugate()).real
    return np.arccos(np.clip(np.abs(comp) / b, 0.0, 1.0))


def grashof_crank(z) -> np.ndarray:
    """Whether the crank turns fully: ``a + |e| < b``."""
    return z[..., 2] + np.abs(z[..., 4]) < z[..., 3]


def short(z) -> np.ndarray:
    """The rod's length: the scale of the closed forms' reach test."""
    return z[..., 3]


def scene_of(z, sigma, thetas, name="path-generator", steps=181, speed=1.0) -> dict:
    """The design ``z`` as a slider-crank scene at ``thetas[0]`` (the coupler point ``P``)."""
    t = np.array([thetas[0]])
    B, C, P, _ = (w[0, 0] for w in pins(np.asarray(z)[None, :], t[None, :], sigma))
    xy = lambda w: [float(w.real), float(w.imag)]  # noqa: E731
    joints = [
        {"name": "A", "type": "R", "links": ["ground", "crank"], "at": [float(z[0]), float(z[1])]},
        {"name": "B", "type": "R", "links": ["crank", "coupler"], "at": xy(B)},
        {"name": "C", "type": "R", "links": ["coupler", "slider"], "at": xy(C)},
        {"name": "C_guide", "type": "P", "links": ["ground", "slider"], "at": xy(C),
         "axis_deg": math.degrees(math.remainder(float(z[5]), 2 * math.pi))},
    ]
    drv = {"joint": "A", "toward": "B", "start_deg": math.degrees(thetas[0]),
           "stop_deg": math.degrees(thetas[-1]), "steps": steps, "speed": speed,
           "acceleration": 0.0}
    return {"name": name, "links": [{"name": "crank"}, {"name": "coupler"}, {"name": "slider"}],
            "joints": joints, "points": [{"name": "P", "link": "coupler", "at": xy(P)}],
            "drivers": [drv], "outputs": ["kinematics"]}


def _slider_side(delta, alpha, g):
    """``Z_s`` with ``C_j = P_j - Z_s e^(i alpha_j)`` on a line of direction ``g`` (j = 1..3):
    ``Im((delta_j - Z_s b_j) w) = 0`` with ``b_j = e^(i alpha_j) - 1``, ``w = e^(-i g)``."""
    w = np.exp(-1j * g)
    rows = []
    for j in range(2):
        bw = (np.exp(1j * alpha[:, j]) - 1) * w
        # Im(Z bw) = x Im(bw) + y Re(bw)
        rows.append((bw.imag, bw.real, (delta[j] * w).imag))
    (p, q, r), (s, t, h) = rows
    det = p * t - q * s
    with np.errstate(divide="ignore", invalid="ignore"):
        return (r * t - q * h) / det + 1j * (p * h - r * s) / det


def exact_three(T, betas, rng, draws=20000):
    """Slider-cranks through three targets exactly: ``(z (m, 8), sigma (m,), thetas (m, 3))``.

    ``betas``: the crank's rotations from the first target to the second and
    third (rad), or None to draw them too (one sense, within a turn); the
    coupler's rotations and the guide's direction are drawn.
    """
    P = T[:, 0] + 1j * T[:, 1]
    delta = P[1:] - P[0]
    b = crank_turns(betas, rng, draws)
    alpha = rng.uniform(-np.pi, np.pi, (draws, 2))
    g = rng.uniform(-np.pi / 2, np.pi / 2, draws)
    W, Z = dyad_through(delta, b, alpha)
    Zs = _slider_side(delta, alpha, g)
    B1, C1 = P[0] - Z, P[0] - Zs
    A = B1 - W
    ug = np.exp(1j * g)
    e = ((C1 - A) * ug.conjugate()).imag
    bl = np.abs(C1 - B1)
    uv = Z * ((C1 - B1) / bl).conjugate()
    z = np.column_stack([A.real, A.imag, np.abs(W), bl, e, g, uv.real, uv.imag])
    thetas = np.angle(W)[:, None] + np.column_stack([np.zeros(draws), b])
    # the assembly mode at each target from the dyads' own configuration
    Cj = P[None, :] - Zs[:, None] * np.exp(1j * np.column_stack([np.zeros(draws), alpha]))
    Bj = A[:, None] + np.abs(W)[:, None] * np.exp(1j * thetas)
    modes = np.sign(((Cj - Bj) * ug[:, None].conjugate()).real)
    same = (modes == modes[:, :1]).all(axis=1) & np.isfinite(z).all(axis=1)
    return z[same], modes[same, 0], thetas[same]


def _template(branch):
    from linkage_sym.design.evaluate import Model
    from linkage_sym.scene import load_scene
    from linkage_sym.synthesis.builders import slider_crank

    d = slider_crank(1.0, 3.0, 0.5, branch=branch, steps=121)
    return Model(load_scene(d.scene))


def batched_curves(T, starts, rng, per_design=4):
    """Random slider-cranks solved at once over a crank turn by the batched solver.

    Returns
    -------
    list of (z (m, 8), sigma (m,), curves (n, per_design, N) complex, q (N,))
        Per assembly mode: each (design, coupler point) pair's parameters and the
        coupler point's curve (NaN where the design cannot be assembled).
    """
    L = float(np.max(np.hypot(*(T[:, None] - T[None]).transpose(2, 0, 1))))
    m0 = T.mean(axis=0)
    out = []
    for sigma, branch in ((1.0, "right"), (-1.0, "left")):
        model = _template(branch)
        n = starts // 2
        A = np.column_stack([m0[0] + L * rng.uniform(-1.5, 1.5, n),
                             m0[1] + L * rng.uniform(-1.5, 1.5, n)])
        a, b = L * rng.uniform(0.1, 1.0, n), L * rng.uniform(0.3, 2.5, n)
        e, g = L * rng.uniform(-1.0, 1.0, n), rng.uniform(-np.pi / 2, np.pi / 2, n)
        foot = A + e[:, None] * np.column_stack([-np.sin(g), np.cos(g)])
        V = np.column_stack([A, a, b, g, foot])
        names = ["x_A", "y_A", "l_AB", "l_BC", "gamma_C_guide", "x_C_guide", "y_C_guide"]
        with np.errstate(all="ignore"):
            sol = model.solve(model.design_params(names, V), n, {"points"})
        rows = {k: model.point_rows(f"joint:{k}:0")[0] for k in "BC"}
        B = sol.points[rows["B"]] + 1j * sol.points[rows["B"] + 1]
        C = sol.points[rows["C"]] + 1j * sol.points[rows["C"] + 1]
        B, C = np.where(sol.ok, B, np.nan)[:, :-1], np.where(sol.ok, C, np.nan)[:, :-1]
        with np.errstate(all="ignore"):
            er = (C - B) / np.abs(C - B)
        uv = (L * rng.uniform(-1.5, 1.5, (n, per_design))
              + 1j * L * rng.uniform(-1.5, 1.5, (n, per_design)))
        curves = B[:, None, :] + uv[:, :, None] * er[:, None, :]
        z = np.repeat(np.column_stack([A, a, b, e, g]), per_design, axis=0)
        z = np.column_stack([z, uv.ravel().real, uv.ravel().imag])
        out.append((z, np.full(len(z), sigma), curves, model.Q[0][:-1]))
    return out


__all__ = ["KIND", "LENGTHS", "NPAR", "batched_curves", "exact_three", "grashof_crank", "pins",
           "scene_of", "short", "transmission"]
