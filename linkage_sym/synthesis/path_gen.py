"""Path generation: a four-bar or a slider-crank whose coupler point passes through given points.

Targets ``P_1 .. P_n`` (m), with or without the crank's rotations ``beta_j``
from the first target (prescribed timing).

* **Three points: exact.**  Each dyad of the four-bar meets the standard
  dyad equations (A. G. Erdman, G. N. Sandor, *Mechanism Design: Analysis and
  Synthesis*, vol. 1, "complex-number synthesis")
  ``W (e^(i beta_j) - 1) + Z (e^(i alpha_j) - 1) = P_j - P_1`` (crank ``W``,
  coupler side ``Z``) and the same with the rocker's rotations ``gamma_j``;
  with ``beta_j`` given and ``alpha_j``, ``gamma_j`` chosen they are linear in
  ``W, Z``.  Many choices are drawn (and ``beta_j`` too without timing), each a
  design through the three points exactly; those with a defect are dropped,
  the rest ranked by their minimum transmission angle.
* **More points: optimisation.**  Many random four-bars are solved at once
  over a full crank turn by the design-sweep engine's batched solver
  (:class:`linkage_sym.design.evaluate.Model`), each with several coupler
  points; the crank angles where each curve comes nearest the targets (in
  the given timing when prescribed) make the starts, the best refined by
  ``scipy.optimize.least_squares`` on the closed forms of
  :mod:`~linkage_sym.synthesis.path_model`.

**Slider-crank** (``linkage="slider-crank"``, :mod:`~linkage_sym.synthesis.path_slider`):
the offset and the guide's direction are design variables.  Three points:
exact as above (the slider's pin on a line of a drawn direction).  More:
random slider-cranks solved at once by the batched solver, refined by
``least_squares`` alike; up to eight points (eight parameters and one crank
angle per point: as many unknowns as equations or more) the designs that
meet every point to ``1e-9`` of the coupler length are reported alone
(``exact``) when there are any.

**Constraints.**  A design is kept only if the crank meets the targets in
order turning one way within one turn, in one assembly mode, without a dead
centre between the first and the last, with a transmission angle of at least
``min_transmission_deg`` over that motion, and (``grashof_crank``) a crank that
turns fully.  Every kept design is then analysed by the solver
(:func:`~linkage_sym.synthesis.path_check.check`); the error reported is the
solver's, and a design the solver finds a defect in is dropped.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from linkage_sym.synthesis import path_model, path_slider
from linkage_sym.synthesis.path_dyads import crank_turns, dyad_through
from linkage_sym.synthesis.common import SynthesisError, number
from linkage_sym.synthesis.path_check import Check, check, scene_of

LINKAGES = ("four-bar", "slider-crank")
"""The linkages path generation designs."""

EXACT_POINTS = {"four-bar": 3, "slider-crank": 8}
"""Most points a design can meet exactly by the optimisation's count of unknowns (a
slider-crank: 8 parameters and one crank angle per point, two equations per point);
the four-bar's optimisation reports best fits beyond its exact three-point solutions."""

__all__ = ["PathDesign", "read_targets", "resample", "synthesize_path"]

MOTION_SAMPLES = 181
"""Crank angles at which a candidate's motion is screened by the closed forms."""

MAX_NFEV = 200
"""Residual evaluations of one local refinement at most (a start that has not converged by then
is rarely the best)."""

EXACT_DRAWS = 20000
"""Free-angle choices drawn for the exact three-point solutions."""


@dataclass
class PathDesign:
    """A path-generation design: parameters, the scene, the solver's check.

    ``z``: ``Ax, Ay, Dx, Dy, a, b, c, u, v`` (a slider-crank: ``Ax, Ay, a, b, e, g, u, v``,
    :mod:`~linkage_sym.synthesis.path_slider`); ``sigma``: the assembly mode;
    ``thetas``: the crank angles (rad) at the targets; ``exact``: from the
    three-point solution or, a slider-crank, meeting every point to ``1e-9`` of the
    coupler (else the optimisation's best fit).
    """

    z: np.ndarray
    sigma: float
    thetas: np.ndarray
    scene: dict
    check: Check
    exact: bool


def read_targets(points, field="points") -> np.ndarray:
    """The targets as an ``(n, 2)`` array, checked (at least 3 distinct rows of 2 finite numbers)."""
    try:
        T = np.array([[number(field, v) for v in row] for row in points], dtype=float)
    except TypeError:
        raise SynthesisError(field, "a list of [x, y] points is expected") from None
    if T.ndim != 2 or T.shape[1] != 2 or len(T) < 3:
        raise SynthesisError(field, f"at least 3 points [x, y] are expected, got shape {T.shape}")
    if np.min(np.hypot(*(T[:, None] - T[None]).transpose(2, 0, 1))
              + np.eye(len(T)) * 1e300) <= 1e-9 * _size(T):
        raise SynthesisError(field, "two points coincide")
    return T


def resample(curve, n: int) -> np.ndarray:
    """``n`` points equally spaced by arc length along a polyline ``curve`` (k, 2).

    Examples
    --------
    >>> resample([[0, 0], [1, 0], [1, 1]], 5).tolist()
    [[0.0, 0.0], [0.5, 0.0], [1.0, 0.0], [1.0, 0.5], [1.0, 1.0]]
    """
    C = np.asarray(curve, dtype=float)
    s = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(C, axis=0).T))])
    t = np.linspace(0.0, s[-1], n)
    return np.column_stack([np.interp(t, s, C[:, 0]), np.interp(t, s, C[:, 1])])


def _size(T) -> float:
    return float(np.max(np.hypot(*(T[:, None] - T[None]).transpose(2, 0, 1))))


# ------------------------------------------------------------------ exact: three points


def exact_three(T, betas, rng, draws=EXACT_DRAWS):
    """Designs through three targets exactly: ``(z (m, 9), sigma (m,), thetas (m, 3))``.

    ``betas``: the crank's rotations from the first target to the second and
    third (rad), or None to draw them too (one sense, within a turn).
    """
    P = T[:, 0] + 1j * T[:, 1]
    delta = P[1:] - P[0]
    b = crank_turns(betas, rng, draws)
    alpha = rng.uniform(-np.pi, np.pi, (draws, 2))
    gamma = rng.uniform(-np.pi, np.pi, (draws, 2))
    W, Z = dyad_through(delta, b, alpha)
    Ws, Zs = dyad_through(delta, gamma, alpha)
    B1, C1 = P[0] - Z, P[0] - Zs
    A, D = B1 - W, C1 - Ws
    bl = np.abs(C1 - B1)
    e = (C1 - B1) / bl
    uv = Z * e.conjugate()
    z = np.column_stack([A.real, A.imag, D.real, D.imag, np.abs(W), bl, np.abs(Ws), uv.real,
                         uv.imag])
    theta1 = np.angle(W)
    thetas = theta1[:, None] + np.column_stack([np.zeros(draws), b])
    # the assembly mode at each target from the dyads' own configuration
    Cj = P[None, :] - Zs[:, None] * np.exp(1j * np.column_stack([np.zeros(draws), alpha]))
    Bj = A[:, None] + np.abs(W)[:, None] * np.exp(1j * thetas)
    modes = np.sign(((D[:, None] - Bj).conjugate() * (Cj - Bj)).imag)
    same = (modes == modes[:, :1]).all(axis=1) & np.isfinite(z).all(axis=1)
    return z[same], modes[same, 0], thetas[same]


# ------------------------------------------------------------------ optimisation


def _template(sigma_name):
    from linkage_sym.design.evaluate import Model
    from linkage_sym.scene import load_scene
    from linkage_sym.synthesis.builders import fourbar

    d = fourbar(1.0, 3.0, 3.0, 3.5, branch=sigma_name, coupler_point=(1.0, 1.0), steps=121)
    return Model(load_scene(d.scene))


def batched_starts(T, betas, starts, rng, per_design=4):
    """Random four-bars solved at once by the batched solver, matched to the targets.

    Returns ``(z (m, 9), sigma (m,), thetas (m, n), cost (m,))`` of every
    (design, coupler point) pair: the crank angles of the curve's samples
    nearest the targets (shifted by ``betas`` when the timing is given).
    """
    L, m0 = _size(T), T.mean(axis=0)
    out = []
    for sigma, name in ((1.0, "open"), (-1.0, "crossed")):
        model = _template(name)
        n = starts // 2
        V = np.column_stack([m0[0] + L * rng.uniform(-1.5, 1.5, n), m0[1] + L * rng.uniform(-1.5, 1.5, n),
                             L * rng.uniform(0.1, 1.0, n), L * rng.uniform(0.3, 2.5, n),
                             L * rng.uniform(0.3, 2.5, n), m0[0] + L * rng.uniform(-1.5, 1.5, n),
                             m0[1] + L * rng.uniform(-1.5, 1.5, n)])
        names = ["x_A", "y_A", "l_AB", "l_BC", "l_CD", "x_D", "y_D"]
        with np.errstate(all="ignore"):
            sol = model.solve(model.design_params(names, V), n, {"points"})
        rows = {k: model.point_rows(f"joint:{k}:0")[0] for k in "BC"}
        B = sol.points[rows["B"]] + 1j * sol.points[rows["B"] + 1]
        C = sol.points[rows["C"]] + 1j * sol.points[rows["C"] + 1]
        ok = sol.ok
        B, C = np.where(ok, B, np.nan), np.where(ok, C, np.nan)
        q = model.Q[0][:-1]
        B, C = B[:, :-1], C[:, :-1]
        with np.errstate(all="ignore"):
            e = (C - B) / np.abs(C - B)
        uv = L * rng.uniform(-1.5, 1.5, (n, per_design)) + 1j * L * rng.uniform(-1.5, 1.5, (n, per_design))
        Pc = B[:, None, :] + uv[:, :, None] * e[:, None, :]  # (n, k, N)
        th, cost = _match(Pc, T, q, betas)
        z = np.column_stack([V[:, 0], V[:, 1], V[:, 5], V[:, 6], V[:, 2], V[:, 3], V[:, 4]])
        z = np.repeat(z, per_design, axis=0)
        z = np.column_stack([z, uv.ravel().real, uv.ravel().imag])
        out.append((z, np.full(len(z), sigma), th.reshape(len(z), -1), cost.ravel()))
    return tuple(np.concatenate([o[i] for o in out]) for i in range(4))


def _match(Pc, T, q, betas):
    """Crank angles and squared error of each curve's best match to the targets."""
    Pt = T[:, 0] + 1j * T[:, 1]
    N = len(q)
    dq = q[1] - q[0]
    if betas is None:
        d2 = np.abs(Pc[..., None, :] - Pt[:, None]) ** 2  # (n, k, targets, N)
        d2 = np.where(np.isfinite(d2), d2, np.inf)
        idx = np.argmin(d2, axis=-1)
        cost = np.take_along_axis(d2, idx[..., None], -1)[..., 0].sum(axis=-1)
        return q[idx], cost
    off = np.round(np.concatenate([[0.0], betas]) / dq).astype(int)
    cols = (np.arange(N)[:, None] + off[None, :]) % N  # (N starts, targets)
    G = Pc[..., cols]  # (n, k, N, targets)
    d2 = (np.abs(G - Pt) ** 2).sum(axis=-1)
    d2 = np.where(np.isfinite(d2), d2, np.inf)
    k = np.argmin(d2, axis=-1)
    cost = np.take_along_axis(d2, k[..., None], -1)[..., 0]
    return q[k][..., None] + np.concatenate([[0.0], betas]), cost


def refine(z0, sigma, th0, T, betas, model=path_model):
    """``least_squares`` from one start: ``(z, thetas, rms error)`` (closed forms of ``model``,
    :mod:`~linkage_sym.synthesis.path_model` or :mod:`~linkage_sym.synthesis.path_slider`)."""
    from scipy.optimize import least_squares

    L = _size(T)
    Pt = T[:, 0] + 1j * T[:, 1]
    free = betas is None
    shift = None if free else np.concatenate([[0.0], betas])

    k = model.NPAR

    def unpack(x):
        return x[:k], (x[k:] if free else x[k] + shift)

    def res(x):
        z, th = unpack(x)
        _, _, P, h2 = model.pins(z[None], th[None], sigma)
        r = (P[0] - Pt) / L
        return np.concatenate([r.real, r.imag, 10.0 * np.maximum(0.0, -h2[0]) / L ** 2])

    x0 = np.concatenate([z0, th0 if free else th0[:1]])
    lo = np.full(len(x0), -np.inf)
    lengths = list(model.LENGTHS)
    lo[lengths] = 1e-3 * L
    x0[lengths] = np.maximum(x0[lengths], 2e-3 * L)
    with np.errstate(all="ignore"):
        sol = least_squares(res, x0, bounds=(lo, np.inf), method="trf", xtol=1e-15, ftol=1e-15,
                            gtol=1e-15, max_nfev=MAX_NFEV)
    z, th = unpack(sol.x)
    return z, np.asarray(th, dtype=float), float(np.sqrt(np.mean(sol.fun[:2 * len(T)] ** 2)) * L)


def screen(z, sigma, thetas, min_gamma_deg, full_turn, model=path_model):
    """Which candidates meet the constraints by the closed forms, and their minimum transmission
    angle (deg) over the motion from the first target to the last."""
    z = np.atleast_2d(z)
    thetas = np.atleast_2d(thetas)
    s = np.linspace(0.0, 1.0, MOTION_SAMPLES)
    th = thetas[:, :1] + s[None] * (thetas[:, -1:] - thetas[:, :1])
    th = np.concatenate([th, thetas], axis=1)
    _, _, _, h2 = model.pins(z, th, sigma)
    short = model.short(z)
    solved = (h2 > (1e-6 * short[:, None]) ** 2).all(axis=1)
    steps = np.diff(thetas, axis=1)
    order = (((steps > 0).all(axis=1) | (steps < 0).all(axis=1))
             & (np.abs(thetas[:, -1] - thetas[:, 0]) < 2 * np.pi))
    with np.errstate(all="ignore"):
        gam = np.degrees(np.nanmin(model.transmission(z, th, sigma), axis=1))
    ok = solved & order & (gam >= min_gamma_deg) & np.isfinite(z).all(axis=1)
    if full_turn:
        ok &= model.grashof_crank(z)
    return ok, gam


def _unique(z, L):
    seen, keep = set(), []
    for i, row in enumerate(z):
        key = tuple(np.round(row / L, 6).tolist())
        if key not in seen:
            seen.add(key)
            keep.append(i)
    return np.array(keep, dtype=int)


def _betas(crank_deg, n):
    if crank_deg is None:
        return None
    c = np.array([number("crank_deg", v) for v in crank_deg])
    if len(c) != n:
        raise SynthesisError("crank_deg", f"one crank angle per point ({n}), got {len(c)}")
    return np.radians(c[1:] - c[0])


def synthesize_path(points, crank_deg=None, *, starts=4000, refine_best=20, keep=5,
                    min_transmission_deg=20.0, full_turn=False, random_state=0,
                    name="path-generator", steps=181, linkage="four-bar"):
    """Four-bars or slider-cranks whose coupler point passes through the points, best first.

    Parameters
    ----------
    points : sequence of (float, float)
        At least three targets (m), in the order the coupler point meets them.
    crank_deg : sequence of float, optional
        The crank's angle at each point (deg; only the differences count:
        prescribed timing).
    starts : int
        Random linkages solved at once for the optimisation (4 points or more).
    refine_best : int
        Starts refined by the local method.
    keep : int
        Designs returned at most.
    min_transmission_deg : float
        Smallest transmission angle allowed between the first point and the last.
    full_turn : bool
        Only designs whose crank turns fully (Grashof crank; a slider-crank's
        ``crank + |offset| < coupler``).
    random_state : int
        The generator's state: the same value gives the same designs.
    name, steps
        The scenes' name and sweep steps (first point to last).
    linkage : str
        ``four-bar`` or ``slider-crank`` (offset and guide direction free).

    Returns
    -------
    list of PathDesign
        No design with a defect, each checked by the solver; best (smallest
        error, then largest transmission angle) first.  Empty if none meets the
        constraints.
    """
    if linkage not in LINKAGES:
        raise SynthesisError("linkage", f"one of {', '.join(LINKAGES)} is expected, got {linkage!r}")
    T = read_targets(points)
    betas = _betas(crank_deg, len(T))
    gmin = number("min_transmission_deg", min_transmission_deg)
    rng = np.random.default_rng(random_state)
    if linkage == "slider-crank":
        return _slider_path(T, betas, rng, (starts, refine_best, keep, gmin, full_turn),
                            name, steps)
    L = _size(T)
    if len(T) == 3:
        z, sig, th = exact_three(T, betas, rng)
        ok, gam = screen(z, sig, th, gmin, full_turn)
        idx = np.flatnonzero(ok)[np.argsort(-gam[ok])]
        cands = [(z[i], sig[i], th[i], 0.0) for i in idx[_unique(z[idx], L)][:4 * keep]]
        exact = True
    else:
        z, sig, th, cost = batched_starts(T, betas, starts, rng)
        best = np.argsort(cost)[:refine_best]
        cands = []
        for i in best:
            zi, ti, err = refine(z[i], sig[i], th[i], T, betas)
            if screen(zi[None], sig[i], ti[None], gmin, full_turn)[0][0]:
                cands.append((zi, sig[i], ti, err))
        cands.sort(key=lambda c: c[3])
        exact = False
    return _checked(cands, T, keep, exact, name, steps, gmin)


def _slider_path(T, betas, rng, opts, name, steps):
    """:func:`synthesize_path` for the slider-crank: ``opts`` = ``(starts, refine_best, keep,
    min transmission (deg), full turn)``."""
    starts, refine_best, keep, gmin, full_turn = opts
    model = path_slider
    if len(T) == 3:
        z, sig, th = path_slider.exact_three(T, betas, rng)
        ok, gam = screen(z, sig, th, gmin, full_turn, model)
        idx = np.flatnonzero(ok)[np.argsort(-gam[ok])]
        cands = [(z[i], sig[i], th[i], 0.0) for i in idx[_unique(z[idx], _size(T))][:4 * keep]]
        return _checked(cands, T, keep, True, name, steps, gmin, path_slider.scene_of)
    parts = [(z, sig, *_match(c, T, q, betas)) for z, sig, c, q in
             path_slider.batched_curves(T, starts, rng)]
    z, sig = (np.concatenate([p[i] for p in parts]) for i in (0, 1))
    th = np.concatenate([p[2].reshape(len(p[0]), -1) for p in parts])
    cost = np.concatenate([p[3].ravel() for p in parts])
    cands = []
    for i in np.argsort(cost)[:refine_best]:
        zi, ti, err = refine(z[i], sig[i], th[i], T, betas, model)
        if screen(zi[None], sig[i], ti[None], gmin, full_turn, model)[0][0]:
            cands.append((zi, sig[i], ti, err))
    cands.sort(key=lambda c: c[3])
    out = []
    if len(T) <= EXACT_POINTS["slider-crank"]:  # the exact ones alone when there are any
        near = [c for c in cands if c[3] <= 1e-10 * _size(T)]
        out = _checked(near, T, keep, True, name, steps, gmin, path_slider.scene_of)
    if not out:
        out = _checked(cands, T, keep, False, name, steps, gmin, path_slider.scene_of)
    return out


def _checked(cands, T, keep, exact, name, steps, gmin, scene_of=scene_of):
    """The candidates the solver finds without a defect, at most ``keep``."""
    out, seen = [], set()
    L = _size(T)
    for z, sigma, th, _ in cands:
        key = tuple(np.round(z / L, 6).tolist())
        if key in seen:
            continue
        seen.add(key)
        scene = scene_of(z, sigma, th, name=f"{name}-{len(out) + 1:02d}", steps=steps)
        c = check(scene, T, th)
        if c.defects or not c.gamma_min_deg >= gmin - 1e-9:
            continue
        if exact and not c.error <= 1e-9 * c.coupler:
            continue
        out.append(PathDesign(np.asarray(z), float(sigma), np.asarray(th), scene, c, exact))
        if len(out) == keep:
            break
    if not exact:
        out.sort(key=lambda d: (d.check.error, -d.check.gamma_min_deg))
    return out
