"""Counterweights chosen by optimisation: partial balancing (NumPy/SciPy only).

:func:`optimize_counterweights` puts one counterweight on each chosen link so
as to reduce a weighted sum of the RMS shaking force, shaking moment and
driver effort over the cycle, each evaluated by a
:class:`~.cycle.CycleModel` (no re-solving per trial); its options are
checked by :func:`~.options.search_options`.  The search itself (a convex
relaxation for a global bound and a start, then local searches) is
described under :func:`optimize_counterweights`.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np
from scipy import optimize as _opt

from linkage_sym.balancing.counterweight import (
    Counterweight,
    as_scene,
    check_counterweights,
    with_counterweights,
)
from linkage_sym.balancing.cycle import TERMS, CycleModel
from linkage_sym.balancing.options import search_options

__all__ = ["OptimizationResult", "ZERO_START", "optimize_counterweights"]

ZERO_START = 1e-9
"""A starting RMS at or below this fraction of its gross scale counts as zero
(see :attr:`CycleModel.gross`): that term is then normalised by the gross
scale instead."""


@dataclass(frozen=True)
class OptimizationResult:
    """What :func:`optimize_counterweights` found.

    Attributes
    ----------
    counterweights : tuple of Counterweight
        One per optimised link (a zero mass is put at the frame origin).
    scene : dict
        The scene with them (:func:`with_counterweights`).
    objective, objective_start : float
        ``J`` of the result and of the starting design (``J_start`` is
        ``wF + wM + wT`` unless a term was normalised by its gross scale).
    rms_start, rms_final : dict
        ``force``, ``moment``, ``driving`` RMS values (see :meth:`CycleModel.rms`).
    success : bool
        A SciPy run converged and the result is not worse than the start.
    message : str
        What ran, and why the start was returned if it was.
    n_evaluations : int
        Evaluations of the cycle (objective or residual values, and their
        Jacobians) over every run.
    scales : dict
        The normalisation of each term of ``J``.
    max_mass, max_radius : dict
        The bounds used, per link.
    n_excluded : int
        Steps left out of every RMS (not ``ok``).
    objective_bound : float or None
        ``J`` at the solution of the convex relaxation (each counterweight
        allowed any moment of inertia about its centre): a lower bound of
        ``J`` over all counterweights within the bounds, to the tolerance of
        the solver; ``None`` when that solver did not converge.  When
        ``objective`` is close to it, the design is globally optimal.
    notes : tuple of str
        What did not go as planned, also at the end of ``message``: the
        convex relaxation did not converge (no bound then), a run failed,
        the relaxation ended above the design found.
    """

    counterweights: tuple
    scene: dict
    objective: float
    objective_start: float
    rms_start: dict
    rms_final: dict
    success: bool
    message: str
    n_evaluations: int
    scales: dict
    max_mass: dict
    max_radius: dict
    n_excluded: int
    objective_bound: float | None = None
    notes: tuple = ()


# -- the search --------------------------------------------------------------------
class _Problem:
    """The objective in scaled variables ``z = (m/max_mass, w/max_radius)`` per link.

    Each term's mean square is a quadratic form in ``x = (p, 1)``, with ``p``
    the links' ``(mu, mu w_x, mu w_y, mu |w|^2)``: ``|R x|^2`` with the
    triangular factors of :meth:`CycleModel.mean_square_factors`.  So an
    evaluation costs the same for any number of steps.
    """

    def __init__(self, model: CycleModel, links, weights, scales, Mmax, Rmax):
        factors = model.mean_square_factors(links)
        self.R = [factors[k] for k in TERMS]
        self.M = np.array([Mmax[n] for n in links])
        self.Rmax = np.array([Rmax[n] for n in links])
        self.w = np.asarray(weights, dtype=float)
        self.sc = np.array([scales[k] for k in TERMS])
        self.n_eval = 0
        # residuals of the surrogate sum_i w_i (rms_i / scale_i)^2
        self.Rls = np.concatenate(
            [math.sqrt(self.w[i]) / self.sc[i] * self.R[i] for i in range(3) if self.w[i] > 0]
        )

    def p(self, z):
        z = z.reshape(-1, 3)
        mu = z[:, 0] * self.M
        wx, wy = z[:, 1] * self.Rmax, z[:, 2] * self.Rmax
        return np.stack([mu, mu * wx, mu * wy, mu * (wx * wx + wy * wy)], axis=1).ravel()

    def dp(self, z):
        """Jacobian (4 n, 3 n) of ``p`` with respect to ``z`` (block diagonal)."""
        z = z.reshape(-1, 3)
        n = len(z)
        mu = z[:, 0] * self.M
        R = self.Rmax
        wx, wy = z[:, 1] * R, z[:, 2] * R
        J = np.zeros((4 * n, 3 * n))
        for i in range(n):
            r, c = 4 * i, 3 * i
            J[r: r + 4, c] = self.M[i] * np.array([1.0, wx[i], wy[i], wx[i] ** 2 + wy[i] ** 2])
            J[r + 1, c + 1] = R[i] * mu[i]
            J[r + 3, c + 1] = R[i] * 2 * mu[i] * wx[i]
            J[r + 2, c + 2] = R[i] * mu[i]
            J[r + 3, c + 2] = R[i] * 2 * mu[i] * wy[i]
        return J

    def _x(self, z):
        return np.append(self.p(z), 1.0)

    def rms(self, z):
        """RMS of the three terms (force, moment, driving) at ``z``."""
        self.n_eval += 1
        x = self._x(z)
        return np.array([np.linalg.norm(R @ x) for R in self.R])

    def objective(self, z):
        return float(self.w @ (self.rms(z) / self.sc))

    def objective_grad(self, z):
        self.n_eval += 1
        x = self._x(z)
        val = 0.0
        gx = np.zeros_like(x)
        for i, R in enumerate(self.R):
            if self.w[i] == 0:
                continue
            y = R @ x
            r = np.linalg.norm(y)
            val += self.w[i] * r / self.sc[i]
            if r > 0:
                gx += (self.w[i] / (self.sc[i] * r)) * (R.T @ y)
        return val, gx[:-1] @ self.dp(z)

    def residuals(self, z):
        self.n_eval += 1
        return self.Rls @ self._x(z)

    def residual_jac(self, z):
        self.n_eval += 1
        return self.Rls[:, :-1] @ self.dp(z)

    def surrogate(self, z):
        self.n_eval += 1
        r = self.Rls @ self._x(z)
        return float(r @ r), 2.0 * (r @ self.Rls[:, :-1]) @ self.dp(z)


def _relaxation_objective(prob: _Problem, smooth: bool):
    """``(fun, hess)`` of the relaxation's ``J`` in the scaled variables ``y`` (``fun``
    returns the value and the gradient); with ``smooth``, ``J^2`` as a quadratic."""
    scale = np.concatenate([[M, M * R, M * R, M * R * R] for M, R in zip(prob.M, prob.Rmax)])
    act = [i for i in range(3) if prob.w[i] > 0]
    As = [prob.R[i][:, :-1] * scale for i in act]
    cs = [prob.R[i][:, -1] for i in act]
    ks = [prob.w[i] / prob.sc[i] for i in act]
    if smooth:  # one term: J^2 has the same minimisers and is a smooth QP
        A, c = ks[0] * As[0], ks[0] * cs[0]
        H = 2.0 * A.T @ A
        b = 2.0 * A.T @ c
        c2 = float(c @ c)

        def fun(y):
            return float(y @ (0.5 * H @ y + b) + c2), H @ y + b

        def hess(y):
            return H
    else:
        def fun(y):
            v, g = 0.0, np.zeros_like(y)
            for A, c, k in zip(As, cs, ks):
                r = A @ y + c
                nr = math.sqrt(r @ r)
                v += k * nr
                if nr > 0:
                    g += (k / nr) * (A.T @ r)
            return v, g

        def hess(y):
            H = np.zeros((len(y), len(y)))
            for A, c, k in zip(As, cs, ks):
                r = A @ y + c
                nr = math.sqrt(r @ r)
                if nr > 0:
                    u = A.T @ r
                    H += (k / nr) * (A.T @ A - np.outer(u, u) / (nr * nr))
            return H
    return fun, hess


def _relaxation_constraints(n: int):
    """``(cone, cone_jac, cone_hess, lin)``: ``mu J >= |s|^2`` per link (the cone, with its
    derivatives) and the linear ``|s_x|, |s_y| <= R mu``, ``J <= 2 R^2 mu``."""
    rows = []
    for i in range(n):
        k = 4 * i
        for j in (1, 2):
            for sg in (1.0, -1.0):
                r = np.zeros(4 * n)
                r[k], r[k + j] = 1.0, -sg
                rows.append(r)
        r = np.zeros(4 * n)
        r[k], r[k + 3] = 2.0, -1.0
        rows.append(r)
    lin = _opt.LinearConstraint(np.array(rows), 0.0, np.inf)
    ii = np.arange(n)
    k4 = 4 * ii

    def cone(y):
        Y = y.reshape(-1, 4)
        return Y[:, 0] * Y[:, 3] - Y[:, 1] ** 2 - Y[:, 2] ** 2

    def cone_jac(y):
        Y = y.reshape(-1, 4)
        J = np.zeros((n, 4 * n))
        J[ii, k4], J[ii, k4 + 3] = Y[:, 3], Y[:, 0]
        J[ii, k4 + 1], J[ii, k4 + 2] = -2 * Y[:, 1], -2 * Y[:, 2]
        return J

    def cone_hess(y, v):
        H = np.zeros((4 * n, 4 * n))
        H[k4, k4 + 3] = H[k4 + 3, k4] = v
        H[k4 + 1, k4 + 1] = H[k4 + 2, k4 + 2] = -2 * v
        return H

    return cone, cone_jac, cone_hess, lin


def _relaxation(prob: _Problem, smooth: bool):
    """Solve the convex relaxation of the problem; see :func:`optimize_counterweights`.

    Variables per link, scaled to the bounds: ``y = (mu/M, s_x/(M R),
    s_y/(M R), J/(M R^2))`` with ``s`` the first and ``J`` the second moment
    about the frame origin.  A point mass has ``mu J = |s|^2``; the
    relaxation allows ``mu J >= |s|^2`` (any rigid body), with ``|s_x|,
    |s_y| <= R mu`` and ``J <= 2 R^2 mu`` as for a point in the box.  Every
    term of ``J`` is the norm of an affine function of ``y``, so the
    relaxation is convex and a local solution is global.

    Returns
    -------
    z : ndarray
        The solution projected on point masses (``w = s/mu``), scaled variables.
    value : float
        ``J`` of the relaxation's solution.
    converged : bool
        First-order optimality reached to ``1e-7`` and constraints met.
    nfev : int
    """
    n = len(prob.M)
    fun, hess = _relaxation_objective(prob, smooth)
    cone, cone_jac, cone_hess, lin = _relaxation_constraints(n)
    y0 = np.tile([0.3, 0.0, 0.0, 0.1], n)
    with warnings.catch_warnings():
        # trust-constr's quasi-Newton updates warn when a step leaves the gradient unchanged
        # (a linear stretch of the objective); harmless here, and the only warning meant
        warnings.filterwarnings("ignore", message="delta_grad == 0.0", category=UserWarning)
        # a counterweight whose mass goes to 0 leaves its cone row with a zero gradient (its
        # point undetermined), so the constraints' Jacobian is rank-deficient there and
        # trust-constr factorises it by SVD instead of QR, saying so: the right method, and
        # the result's convergence test below still judges the outcome
        warnings.filterwarnings("ignore", message="Singular Jacobian matrix",
                                category=UserWarning)
        res = _opt.minimize(
            fun, y0, jac=True, hess=hess, method="trust-constr",
            bounds=_opt.Bounds(np.tile([0.0, -1.0, -1.0, 0.0], n), np.tile([1.0, 1.0, 1.0, 2.0], n)),
            constraints=[_opt.NonlinearConstraint(cone, 0.0, np.inf, jac=cone_jac, hess=cone_hess), lin],
            options={"gtol": 1e-12, "xtol": 1e-14, "maxiter": 400},
        )
    Y = res.x.reshape(-1, 4)
    z = np.zeros((n, 3))
    z[:, 0] = np.clip(Y[:, 0], 0.0, 1.0)
    big = Y[:, 0] > 1e-12
    z[big, 1:] = np.clip(Y[big, 1:3] / Y[big, :1], -1.0, 1.0)
    value = math.sqrt(max(float(res.fun), 0.0)) if smooth else float(res.fun)
    converged = bool(
        res.optimality <= 1e-7 * max(1.0, abs(float(res.fun))) and res.constr_violation <= 1e-10
    )
    return z.ravel(), value, converged, int(res.nfev + res.njev + res.nhev)


def optimize_counterweights(
    scene,
    links=None,
    weights=(1.0, 1.0, 1.0),
    max_mass=None,
    max_radius=None,
    start=None,
    model: CycleModel | None = None,
) -> OptimizationResult:
    """Choose one counterweight per link to reduce shaking force, shaking moment and driver effort.

    Minimises ``J = wF rms_F/rms_F0 + wM rms_M/rms_M0 + wT rms_T/rms_T0``
    (RMS values of :meth:`CycleModel.rms`, normalised by those of the
    starting design; a starting value that is zero, at most
    :data:`ZERO_START` of its gross scale :attr:`CycleModel.gross`, is
    replaced by that gross scale, and by 1 if that is zero too).

    Parameters
    ----------
    scene : Scene or mapping or path
    links : sequence of str, optional
        Links that get a counterweight; default every moving link.
    weights : (float, float, float)
        ``(wF, wM, wT)``, each ``>= 0``, not all zero.
    max_mass : float or dict, optional
        Upper bound of each counterweight's mass (kg).  Default: its link's
        own mass (a massless link: the mean moving-link mass), see
        :func:`~.options.default_bounds`.
    max_radius : float or dict, optional
        Bound on each coordinate of a counterweight's position in its link
        frame, ``|x|, |y| <= max_radius`` (m).  Default: twice the link's
        length ``|uv|``.
    start : sequence of Counterweight, optional
        The starting design (at most one per optimised link; others start
        with no counterweight).  Default: no counterweights.  It must lie
        within the bounds.
    model : CycleModel, optional
        A model of the same scene, to reuse its kinematics.

    Returns
    -------
    OptimizationResult

    Raises
    ------
    OptionsError
        (a ``ValueError``) for options that cannot be used: see
        :func:`~.options.search_options`, which checks them.
    ValueError
        For a start outside the bounds or on a link not optimised, and for a
        scene with no ``ok`` step.

    Notes
    -----
    Each term of ``J`` is the norm of a function that is linear in the
    counterweights' masses, first moments ``mu w`` and second moments
    ``mu |w|^2`` (:mod:`~.cycle`), compressed once by a QR factorisation,
    so an evaluation does not depend on the number of steps.  The search,
    in variables scaled to the bounds:

    1. the *convex relaxation* (each counterweight may be any rigid body
       with its centre in the box: ``mu J >= |s|^2`` instead of ``=``) is
       solved with :func:`scipy.optimize.minimize` (``trust-constr``,
       analytic derivatives; for a single nonzero weight, ``J^2`` as a
       smooth quadratic).  Its optimum is global and is reported as
       :attr:`OptimizationResult.objective_bound` when the solver converged;
       its solution, projected on point masses (``w = s/mu``), is a start;
    2. ``L-BFGS-B`` on ``J`` (analytic gradient) from that projection and
       from the given start (and from a generic start if the relaxation did
       not converge);
    3. with a single nonzero weight, :func:`scipy.optimize.least_squares`
       (``trf``) from the best design so far, which reaches rounding
       accuracy when the term can vanish (full force balance).

    The design returned is the best seen by ``J``, never worse than the
    start.  The relaxation is tight on every link whose second moment
    matters (all but cranks turning at constant speed, whose ``alpha`` is
    0), so in practice the result attains the bound.  ``J`` does not count
    the added mass: the optimum often puts the largest allowed mass on
    several links, which is why the default bound is each link's own mass;
    give ``max_mass`` for the design's own limit.

    Examples
    --------
    >>> from linkage_sym.examples import load_example
    >>> res = optimize_counterweights(load_example("crank_rocker"), links=["crank"], weights=(1, 0, 0))
    >>> res.objective < res.objective_start, res.counterweights[0].link
    (True, 'crank')
    """
    scene = as_scene(scene)
    options = search_options(scene, links, weights, max_mass, max_radius)
    links, Mmax, Rmax = list(options.links), options.max_mass, options.max_radius
    w = np.asarray(options.weights, dtype=float)
    model = CycleModel(scene) if model is None else model
    z0, start_cws = _start(scene, links, Mmax, Rmax, start)
    if not model.ok.any():
        raise ValueError("the scene has no step whose status is ok: nothing to optimise")
    rms_start = model.rms(start_cws)
    scales = _term_scales(model, rms_start)
    prob = _Problem(model, links, w, scales, Mmax, Rmax)
    J_start = prob.objective(z0)
    candidates, notes, converged, bound, n_relax = _search(prob, z0, J_start, w, len(links))
    z_best, msg, bound = _best(candidates, z0, J_start, bound, notes)
    cws = _designs(links, z_best, z0, start_cws, Mmax, Rmax)
    rms_final = model.rms(cws)
    J_final = sum(
        float(w[i]) * rms_final[k] / scales[k] for i, k in enumerate(("force", "moment", "driving"))
    )
    if J_final > J_start:  # rounding of the reconstructed design: keep the start
        cws = [next((cw for cw in start_cws if cw.link == n), Counterweight(n, 0.0, (0.0, 0.0))) for n in links]
        rms_final, J_final = rms_start, J_start
        msg = "no design better than the start was found; returning the start"
    return OptimizationResult(
        counterweights=tuple(cws),
        scene=with_counterweights(scene, cws),
        objective=float(J_final),
        objective_start=float(J_start),
        rms_start=rms_start,
        rms_final=rms_final,
        success=bool(converged and J_final <= J_start),
        message=msg,
        n_evaluations=prob.n_eval + n_relax,
        objective_bound=bound,
        notes=tuple(notes),
        scales=scales,
        max_mass=Mmax,
        max_radius=Rmax,
        n_excluded=model.n_excluded,
    )


def _start(scene, links: list, Mmax: dict, Rmax: dict, start) -> tuple:
    """``(z0, counterweights)``: the starting design checked against the links and the
    bounds, and in normalised variables."""
    z0 = np.zeros(3 * len(links))
    start_cws = check_counterweights(scene, start or [])
    seen = set()
    for cw in start_cws:
        if cw.link not in links:
            raise ValueError(f"start: link {cw.link!r} is not among the optimised links")
        if cw.link in seen:
            raise ValueError(f"start: two counterweights on {cw.link!r}")
        seen.add(cw.link)
        i = links.index(cw.link)
        M, R = Mmax[cw.link], Rmax[cw.link]
        tol = 1e-12
        if cw.mass > M * (1 + tol) or max(abs(cw.at[0]), abs(cw.at[1])) > R * (1 + tol):
            raise ValueError(
                f"start: counterweight on {cw.link!r} is outside the bounds "
                f"(mass <= {M:g} kg, |x|, |y| <= {R:g} m)"
            )
        z0[3 * i] = min(cw.mass / M, 1.0) if M > 0 else 0.0
        z0[3 * i + 1: 3 * i + 3] = np.clip(np.array(cw.at) / R, -1, 1) if R > 0 else 0.0
    return z0, start_cws


def _term_scales(model: CycleModel, rms_start: dict) -> dict:
    """What each term of ``J`` is normalised by: its starting RMS, or its gross scale where
    that is zero (:data:`ZERO_START`), or 1."""
    scales = {}
    for k in ("force", "moment", "driving"):
        v = rms_start[k]
        if v > ZERO_START * model.gross[k] and v > 0:
            scales[k] = v
        elif model.gross[k] > 0:
            scales[k] = model.gross[k]
        else:
            scales[k] = 1.0
    return scales


def _search(prob: _Problem, z0, J_start: float, w, n_links: int) -> tuple:
    """The searches of :func:`optimize_counterweights` (its Notes, steps 1 to 3).

    Returns ``(candidates, notes, converged, bound, n_relax)``: every design found as
    ``(J, z, how)``, the start first; what failed; whether a SciPy run converged; the
    relaxation's ``J`` if it converged; its evaluations.
    """
    # bounds of the scaled variables (a zero bound scales its variable to no effect)
    lo = np.tile([0.0, -1.0, -1.0], n_links)
    hi = np.tile([1.0, 1.0, 1.0], n_links)
    candidates = [(J_start, z0, "the start")]
    notes = []
    converged = False
    single = int(np.count_nonzero(w)) == 1
    starts = [("the start", z0)]
    bound = None
    n_relax = 0
    try:
        z_rel, value, ok_rel, n_relax = _relaxation(prob, single)
        starts.append(("the convex relaxation", z_rel))
        candidates.append((prob.objective(z_rel), z_rel, "the convex relaxation (projected)"))
        if ok_rel:
            bound = value
        else:
            notes.append("the convex relaxation did not converge")
    except (ValueError, np.linalg.LinAlgError) as err:  # pragma: no cover - defensive
        notes.append(f"convex relaxation failed: {err}")
    if bound is None:
        starts.append(("a generic start", np.tile([0.3, 0.0, 0.0], n_links)))
    bounds = list(zip(lo, hi))
    for label, zs in starts:
        try:
            mn = _opt.minimize(
                prob.objective_grad, zs, jac=True, method="L-BFGS-B", bounds=bounds,
                options={"ftol": 1e-15, "gtol": 1e-12, "maxiter": 1000},
            )
            converged |= bool(mn.success)
            candidates.append((prob.objective(mn.x), mn.x, f"L-BFGS-B on J from {label}"))
        except (ValueError, np.linalg.LinAlgError) as err:  # pragma: no cover - defensive
            notes.append(f"local search from {label} failed: {err}")
    if single:  # Gauss-Newton reaches rounding accuracy where the term can vanish (full balance)
        J_b, z_b, how = min(candidates, key=lambda c: c[0])
        try:
            ls = _opt.least_squares(
                prob.residuals, z_b, jac=prob.residual_jac, bounds=(lo, hi), method="trf",
                ftol=1e-15, xtol=1e-15, gtol=1e-15, max_nfev=100 * len(z_b),
            )
            converged |= bool(ls.status > 0)
            candidates.append((prob.objective(ls.x), ls.x, f"least squares after {how}"))
        except (ValueError, np.linalg.LinAlgError) as err:  # pragma: no cover - defensive
            notes.append(f"least squares failed: {err}")
    return candidates, notes, converged, bound, n_relax


def _best(candidates: list, z0, J_start: float, bound, notes: list) -> tuple:
    """``(z, message, bound)``: the best design by ``J`` (the start unless one is better),
    what the message says of it, and the bound if it is one (``notes`` may grow)."""
    J_best, z_best, how = min(candidates, key=lambda c: c[0])
    if J_best >= J_start:
        z_best, J_best = z0, J_start
        msg = "no design better than the start was found; returning the start"
    else:
        msg = f"best design from {how}"
    if bound is not None:
        if bound > J_best * (1 + 1e-6) + 1e-12:  # not a bound after all: do not claim one
            notes.append(f"the convex relaxation ended above the design found ({bound:.6g})")
            bound = None
        else:
            msg += f"; convex relaxation: J >= {bound:.6g}"
    if notes:
        msg += " (" + "; ".join(notes) + ")"
    return z_best, msg, bound


def _designs(links: list, z_best, z0, start_cws, Mmax: dict, Rmax: dict) -> list:
    """One counterweight per link from the scaled variables ``z_best`` (the start's own
    counterweights when ``z_best`` is the start)."""
    cws = []
    zb = z_best.reshape(-1, 3)
    for i, n in enumerate(links):
        mass = float(min(max(zb[i, 0], 0.0), 1.0) * Mmax[n])
        at = (0.0, 0.0) if mass == 0 else (float(zb[i, 1] * Rmax[n]), float(zb[i, 2] * Rmax[n]))
        if z_best is z0:
            prev = next((cw for cw in start_cws if cw.link == n), None)
            if prev is not None:
                mass, at = prev.mass, prev.at
        cws.append(Counterweight(n, mass, at))
    return cws
