"""Counterweights and partial balancing by optimisation (NumPy/SciPy only).

A *counterweight* is a point mass fixed on a moving link.  This module adds
counterweights to a scene (:func:`with_counterweights`), evaluates their
effect on the shaking force, the shaking moment and the driver efforts over
a cycle without re-solving the mechanism (:class:`CycleModel`), and chooses
them by optimisation (:func:`optimize_counterweights`).

How a cycle is evaluated
------------------------
Counterweights change neither the motion nor (with the motion prescribed)
the linearity of the kinetostatics, so the scene's kinematics are solved
once.  A point mass ``mu`` at ``w`` in the frame of link ``j`` (the frame of
:func:`~linkage_sym.structure.parameters.link_frames`: origin at the link's
first joint ``u``, x-axis toward ``v``) is at ``r = r_u + R(phi) w`` and has
the acceleration ``a = a_u + alpha k x (R w) - omega^2 R w``.  It changes

* the shaking force by ``-mu a``,
* the shaking moment about the origin by ``-mu r x a``,
* the effort of driver ``k`` by ``mu (i a - g) . v^(k)`` (virtual power),
  where ``v^(k)`` is the point's partial velocity with respect to the rate of
  driver ``k`` (the velocity when that driver moves at unit rate and the
  others stand still), ``i`` is 1 when the scene's ``inertia`` effect is on,
  else 0, and ``g`` the scene's gravity (zero when off).

Written out, each of these changes is *linear* in the four numbers
``(mu, mu w_x, mu w_y, mu |w|^2)`` of the counterweight (its mass, first and
second moments about ``u`` in the link frame): the term quadratic in ``w``
reduces to ``-alpha mu |w|^2`` in the moment and ``i omega^(k) alpha mu |w|^2``
in the effort.  :class:`CycleModel` stores these linear maps over the steps
(one kinematic run at the scene's speeds, one at unit rate per driver) and
the baseline series of the original scene from the numeric force solver (the
frame force and moment with inertia as the only effect; the efforts with the
scene's effects).  Evaluating a set of counterweights is then one small
matrix product, exact to rounding.

Examples
--------
>>> from linkage_sym.examples import load_example
>>> scene = load_example("crank_rocker")
>>> model = CycleModel(scene)
>>> rms0 = model.rms([])
>>> rms1 = model.rms([Counterweight("crank", 0.3, (-0.02, 0.0))])
>>> bool(rms1["force"] < rms0["force"])
True
"""

from __future__ import annotations

import dataclasses
import math
import warnings
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np
from scipy import optimize as _opt

from linkage_sym.model import OUTPUTS, Effects, Link, Scene
from linkage_sym.numeric.plan import compile_plan, scene_sweep
from linkage_sym.scene import dump_scene, load_scene
from linkage_sym.structure.parameters import link_frames

__all__ = [
    "Counterweight",
    "CycleModel",
    "OptimizationResult",
    "default_bounds",
    "optimize_counterweights",
    "with_counterweights",
]

ZERO_START = 1e-9
"""A starting RMS at or below this fraction of its gross scale counts as zero
(see :attr:`CycleModel.gross`): that term is then normalised by the gross
scale instead."""


# -- counterweights ------------------------------------------------------------
@dataclass(frozen=True)
class Counterweight:
    """A point mass fixed on a moving link.

    Parameters
    ----------
    link : str
        Name of the moving link that carries it.
    mass : float
        Mass in kg, ``>= 0``.
    at : tuple of float
        Position in the link's frame of
        :func:`~linkage_sym.structure.parameters.link_frames` (origin at the
        link's first joint ``u`` in scene order, x-axis toward its second
        joint ``v``), in metres.

    Examples
    --------
    >>> Counterweight("crank", 0.1, (-0.01, 0))
    Counterweight(link='crank', mass=0.1, at=(-0.01, 0.0))
    >>> Counterweight("crank", -1.0, (0, 0))
    Traceback (most recent call last):
      ...
    ValueError: counterweight on crank: mass must be finite and >= 0, not -1.0
    """

    link: str
    mass: float
    at: tuple[float, float]

    def __post_init__(self):
        mass = float(self.mass)
        if not (math.isfinite(mass) and mass >= 0.0):
            raise ValueError(f"counterweight on {self.link}: mass must be finite and >= 0, not {self.mass!r}")
        at = tuple(float(c) for c in self.at)
        if len(at) != 2 or not all(math.isfinite(c) for c in at):
            raise ValueError(f"counterweight on {self.link}: at must be two finite numbers, not {self.at!r}")
        object.__setattr__(self, "mass", mass)
        object.__setattr__(self, "at", at)


def _as_scene(scene) -> Scene:
    return scene if isinstance(scene, Scene) else load_scene(scene)


def _check_links(scene: Scene, counterweights) -> list[Counterweight]:
    cws = list(counterweights)
    names = set(scene.link_names)
    for cw in cws:
        if not isinstance(cw, Counterweight):
            raise TypeError(f"expected Counterweight, got {type(cw).__name__}")
        if cw.link not in names:
            raise ValueError(
                f"counterweight on {cw.link!r}: no such moving link (links: {', '.join(scene.link_names)})"
            )
    return cws


def _global_point(frame, w) -> tuple[float, float]:
    """Assembly-configuration (global) position of the link-frame point ``w``."""
    c, s = math.cos(frame.theta0), math.sin(frame.theta0)
    return (frame.origin[0] + c * w[0] - s * w[1], frame.origin[1] + s * w[0] + c * w[1])


def with_counterweights(scene, counterweights, name=None) -> dict:
    """A scene with counterweights merged into their links.

    Parameters
    ----------
    scene : Scene or mapping or path
        The scene (anything :func:`~linkage_sym.scene.load_scene` takes).
    counterweights : iterable of Counterweight
        Several on one link are all merged.
    name : str, optional
        Name of the new scene; default ``"<name> with counterweights"``.

    Returns
    -------
    dict
        The new scene in the file layout (:func:`~linkage_sym.scene.dump_scene`),
        which loads back with :func:`~linkage_sym.scene.load_scene`.  Each
        link that carries counterweights gets the total mass, the combined
        centre of mass (global coordinates of the assembly configuration)
        and the moment of inertia about that new centre of mass by the
        parallel-axis theorem (a counterweight is a point: it adds no inertia
        about its own centre).  A link whose total mass stays zero is left as
        it is.

    Examples
    --------
    >>> from linkage_sym.examples import load_example
    >>> s = with_counterweights(load_example("crank_rocker"), [Counterweight("crank", 0.2, (-0.012, 0))])
    >>> [round(v, 9) for v in s["links"][0]["com"]], round(s["links"][0]["mass"], 9)
    ([0.0, 0.0], 0.4)
    """
    scene = _as_scene(scene)
    cws = _check_links(scene, counterweights)
    frames = link_frames(scene)
    links = []
    for link in scene.links:
        mine = [cw for cw in cws if cw.link == link.name and cw.mass > 0]
        total = link.mass + sum(cw.mass for cw in mine)
        if not mine or total <= 0.0:
            links.append(link)
            continue
        pts = [(cw.mass, _global_point(frames[link.name], cw.at)) for cw in mine]
        if link.mass > 0:
            pts_all = [(link.mass, tuple(link.com))] + pts
        else:
            pts_all = pts
        cx = math.fsum(m * p[0] for m, p in pts_all) / total
        cy = math.fsum(m * p[1] for m, p in pts_all) / total
        inertia = math.fsum([link.inertia] + [m * ((p[0] - cx) ** 2 + (p[1] - cy) ** 2) for m, p in pts_all])
        links.append(Link(link.name, total, (cx, cy), inertia))
    new = dataclasses.replace(
        scene, links=tuple(links), name=f"{scene.name} with counterweights" if name is None else name
    )
    return dump_scene(new)


# -- the cycle model -------------------------------------------------------------
def _cross(ax, ay, bx, by):
    return ax * by - ay * bx


class CycleModel:
    """Shaking force, shaking moment and driver efforts over a scene's cycle,
    for any counterweights: compile once, evaluate many.

    Construction runs the numeric solver on the scene (kinematics at the
    scene's speeds, the frame force and moment with inertia as the only
    effect, the driver efforts with the scene's effects) and the velocity
    problem once per driver at unit rate; see the module docstring for the
    linear maps it then stores.

    Parameters
    ----------
    scene : Scene or mapping or path
    disconnection : optional
        Passed to :func:`~linkage_sym.numeric.plan.compile_plan`.

    Attributes
    ----------
    scene : Scene
    links : tuple of str
        The moving links, in scene order (the column blocks of the maps).
    frames : dict
        :func:`~linkage_sym.structure.parameters.link_frames` of the scene.
    drivers : tuple of str
        The driven joints.
    status : ndarray of str (N,)
        Status of every step (``"ok"`` or why not).
    ok : ndarray of bool (N,)
        Steps solved at every stage (the only ones counted by :meth:`rms`).
    n_steps : int
        Number of steps of the sweep.
    n_excluded : int
        Number of steps that are not ``ok``.
    analysis : Analysis
        The numeric solver's run with inertia as the only effect (the
        kinematics and the baseline shaking force and moment).
    gross : dict
        ``force``, ``moment``, ``driving``: RMS over the cycle of the *sum of
        the magnitudes* of every link's own contribution (and, for the
        efforts, of the baseline); a scale of each quantity that does not
        vanish when the mechanism happens to be balanced.
    """

    def __init__(self, scene, disconnection=None):
        scene = _as_scene(scene)
        self.scene = scene
        self.links = scene.link_names
        self.frames = link_frames(scene)
        self.drivers = tuple(d.joint for d in scene.drivers)
        self.gravity = np.array(scene.effects.gravity or (0.0, 0.0), dtype=float)
        self.inertia = 1.0 if scene.effects.inertia else 0.0
        # baselines from the numeric force solver
        shaking = dataclasses.replace(
            scene, effects=Effects(inertia=True, gravity=None, loads=False), outputs=OUTPUTS
        )
        an = compile_plan(shaking, disconnection).run()
        own = compile_plan(dataclasses.replace(scene, outputs=OUTPUTS), disconnection).run()
        # partial velocities: the velocity problem with unit rate of one driver
        kin = compile_plan(dataclasses.replace(scene, effects=Effects(loads=False), outputs=("kinematics",)))
        q, qd, _ = scene_sweep(scene)
        N = len(an.status)
        unit = {}
        for k in self.drivers:
            rates = {j: np.full(N, 1.0 if j == k else 0.0) for j in qd}
            unit[k] = kin.run(q, rates, {j: np.zeros(N) for j in qd})
        ok = an.ok & own.ok
        for u in unit.values():
            ok = ok & u.ok
        self.status = an.status.copy()
        self.status[~ok & (self.status == "ok")] = "inconsistent"
        self.ok = ok
        self.n_steps = N
        self.n_excluded = int((~ok).sum())
        self.analysis = an
        self._build(an, unit, own)

    # -- construction of the linear maps -----------------------------------------------
    def _build(self, an, unit, own):
        N, nL, D = self.n_steps, len(self.links), len(self.drivers)
        g, ii = self.gravity, self.inertia
        # rows: force x, force y, moment, then one block per driver
        B = np.zeros((3 + D, N, 4 * nL))
        for i, name in enumerate(self.links):
            fr = self.frames[name]
            lk = an.links[name]
            O = fr.origin
            ph = fr.theta0 + lk.rotation
            c, s = np.cos(ph), np.sin(ph)
            e1x, e1y, e2x, e2y = c, s, -s, c
            w, al = lk.omega, lk.alpha
            w2 = w * w
            rx, ry = lk.point(O).T
            ax, ay = lk.point_acceleration(O).T
            f1x, f1y = al * e2x - w2 * e1x, al * e2y - w2 * e1y
            f2x, f2y = -al * e1x - w2 * e2x, -al * e1y - w2 * e2y
            col = slice(4 * i, 4 * i + 4)
            B[0, :, col] = np.stack([-ax, -f1x, -f2x, np.zeros(N)], axis=1)
            B[1, :, col] = np.stack([-ay, -f1y, -f2y, np.zeros(N)], axis=1)
            B[2, :, col] = np.stack(
                [
                    -_cross(rx, ry, ax, ay),
                    -(_cross(rx, ry, f1x, f1y) + _cross(e1x, e1y, ax, ay)),
                    -(_cross(rx, ry, f2x, f2y) + _cross(e2x, e2y, ax, ay)),
                    -al,
                ],
                axis=1,
            )
            bx, by = ii * ax - g[0], ii * ay - g[1]
            for k, dname in enumerate(self.drivers):
                uk = unit[dname].links[name]
                vx, vy = uk.point_velocity(O).T
                wk = uk.omega
                B[3 + k, :, col] = np.stack(
                    [
                        bx * vx + by * vy,
                        ii * (f1x * vx + f1y * vy) + wk * (bx * e2x + by * e2y),
                        ii * (f2x * vx + f2y * vy) - wk * (bx * e1x + by * e1y),
                        ii * wk * al,
                    ],
                    axis=1,
                )
        Y0 = np.zeros((3 + D, N))
        Y0[0] = an.forces.frame_force[:, 0]
        Y0[1] = an.forces.frame_force[:, 1]
        Y0[2] = an.forces.frame_moment
        for k, dname in enumerate(self.drivers):
            Y0[3 + k] = own.forces.driving[dname]
        self._B, self._Y0 = B, Y0
        okc = self.ok
        self._Bok = B[:, okc, :]
        self._Y0ok = Y0[:, okc]
        # the links' own mass distributions as (mu, s_x, s_y, J) about u: gross scales
        p_own = np.zeros(4 * nL)
        for i, link in enumerate(self.scene.links):
            if link.mass > 0:
                fr = self.frames[link.name]
                dx, dy = link.com[0] - fr.origin[0], link.com[1] - fr.origin[1]
                c, s = math.cos(fr.theta0), math.sin(fr.theta0)
                px, py = c * dx + s * dy, -s * dx + c * dy
                p_own[4 * i: 4 * i + 4] = (link.mass, link.mass * px, link.mass * py,
                                            link.inertia + link.mass * (px * px + py * py))
            elif link.inertia > 0:
                p_own[4 * i + 3] = link.inertia
        contrib = np.abs(self._Bok * p_own)  # (3 + D, Nok, 4 nL)
        per_link = contrib.reshape(3 + D, -1, nL, 4).sum(axis=3)
        fx, fy = per_link[0], per_link[1]
        gross_f = np.hypot(fx, fy).sum(axis=1)
        gross_m = per_link[2].sum(axis=1)
        gross_t = per_link[3:].sum(axis=2) + np.abs(self._Y0ok[3:])
        nok = max(1, int(okc.sum()))
        self.gross = {
            "force": float(np.sqrt(np.sum(gross_f ** 2) / nok)),
            "moment": float(np.sqrt(np.sum(gross_m ** 2) / nok)),
            "driving": float(np.sqrt(np.sum(gross_t ** 2) / nok)),
        }

    # -- parameters ------------------------------------------------------------
    def parameters(self, counterweights) -> np.ndarray:
        """The vector ``(mu, mu w_x, mu w_y, mu |w|^2)`` per link (links in scene order)."""
        cws = _check_links(self.scene, counterweights)
        p = np.zeros(4 * len(self.links))
        index = {n: i for i, n in enumerate(self.links)}
        for cw in cws:
            i = 4 * index[cw.link]
            wx, wy = cw.at
            p[i: i + 4] += (cw.mass, cw.mass * wx, cw.mass * wy, cw.mass * (wx * wx + wy * wy))
        return p

    def _series(self, p, ok_only=False):
        B, Y0 = (self._Bok, self._Y0ok) if ok_only else (self._B, self._Y0)
        return Y0 + B @ p

    @staticmethod
    def _rms_of(Y) -> dict:
        n = max(1, Y.shape[1])
        return {
            "force": float(np.sqrt(np.sum(Y[0] ** 2 + Y[1] ** 2) / n)),
            "moment": float(np.sqrt(np.sum(Y[2] ** 2) / n)),
            "driving": float(np.sqrt(np.sum(Y[3:] ** 2) / n)),
        }

    # -- evaluation ------------------------------------------------------------
    def evaluate(self, counterweights) -> dict:
        """Series over every step of the scene with the counterweights added.

        Parameters
        ----------
        counterweights : iterable of Counterweight

        Returns
        -------
        dict
            ``"force"`` (N, 2): shaking force (what the moving links exert on
            the ground, inertia as the only effect); ``"moment"`` (N,): shaking
            moment about the global origin; ``"driving"``: ``{joint: (N,)}``
            driver efforts with the scene's own effects.  NaN at steps that
            are not ``ok``.
        """
        Y = self._series(self.parameters(counterweights))
        return {
            "force": np.stack([Y[0], Y[1]], axis=1),
            "moment": Y[2],
            "driving": {k: Y[3 + i] for i, k in enumerate(self.drivers)},
        }

    def rms(self, counterweights) -> dict:
        """RMS over the ``ok`` steps of the series of :meth:`evaluate`.

        Returns
        -------
        dict
            ``force``: ``sqrt(mean |F|^2)``; ``moment``: ``sqrt(mean M^2)``;
            ``driving``: ``sqrt(mean over steps of the sum over drivers of
            effort^2)``.
        """
        return self._rms_of(self._series(self.parameters(counterweights), ok_only=True))


# -- optimisation ------------------------------------------------------------------
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


def _per_link(value, links, default, what) -> dict:
    if value is None:
        return {n: float(default[n]) for n in links}
    if isinstance(value, Mapping):
        unknown = set(value) - set(links)
        if unknown:
            raise ValueError(f"{what}: links {sorted(unknown)} are not optimised")
        out = {n: float(value.get(n, default[n])) for n in links}
    else:
        out = {n: float(value) for n in links}
    for n, v in out.items():
        if not (math.isfinite(v) and v >= 0):
            raise ValueError(f"{what} of {n}: must be finite and >= 0, not {v!r}")
    return out


def default_bounds(scene) -> tuple[dict, dict]:
    """Default bounds of :func:`optimize_counterweights`, per moving link.

    ``max_mass``: the mechanism's total moving mass (1 kg if every link is
    massless).  ``max_radius``: twice the link's length ``|uv|`` (its frame's
    x-axis), or twice the mechanism's characteristic length (the largest
    distance between two joints) for a link whose joints all coincide.

    Examples
    --------
    >>> from linkage_sym.examples import load_example
    >>> mm, mr = default_bounds(load_example("crank_rocker"))
    >>> round(mm["crank"], 12), round(mr["crank"], 12)
    (1.0, 0.048)
    """
    scene = _as_scene(scene)
    frames = link_frames(scene)
    total = sum(link.mass for link in scene.links)
    mass = total if total > 0 else 1.0
    L = scene.characteristic_length() or 1.0
    mm, mr = {}, {}
    for n in scene.link_names:
        fr = frames[n]
        length = 0.0 if fr.v is None else math.dist(fr.origin, scene.joint(fr.v).at)
        mm[n] = mass
        mr[n] = 2.0 * (length if length > 0 else L)
    return mm, mr


class _Problem:
    """The objective in scaled variables ``z = (m/max_mass, w/max_radius)`` per link.

    Each term's mean square is a quadratic form in ``x = (p, 1)``, with ``p``
    the links' ``(mu, mu w_x, mu w_y, mu |w|^2)``: ``mean |Y0 + B p|^2 =
    |R x|^2`` where ``R`` is the triangular factor of the QR factorisation
    of ``[B, Y0] / sqrt(N)``.  So an evaluation costs the same for any
    number of steps.
    """

    TERMS = ("force", "moment", "driving")

    def __init__(self, model: CycleModel, links, weights, scales, Mmax, Rmax):
        idx = [model.links.index(n) for n in links]
        cols = np.concatenate([np.arange(4 * i, 4 * i + 4) for i in idx])
        B = model._Bok[:, :, cols]  # (3 + D, Nok, 4 n)
        Y0 = model._Y0ok
        nok = max(1, Y0.shape[1])
        rows = (slice(0, 2), slice(2, 3), slice(3, None))
        self.R = []
        for sl in rows:
            A = np.concatenate([B[sl], Y0[sl][:, :, None]], axis=2).reshape(-1, B.shape[2] + 1)
            self.R.append(np.linalg.qr(A / math.sqrt(nok), mode="r"))
        self.M = np.array([Mmax[n] for n in links])
        self.Rmax = np.array([Rmax[n] for n in links])
        self.w = np.asarray(weights, dtype=float)
        self.sc = np.array([scales[k] for k in self.TERMS])
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

    y0 = np.tile([0.3, 0.0, 0.0, 0.1], n)
    with warnings.catch_warnings():
        # trust-constr's quasi-Newton updates warn when a step leaves the gradient unchanged
        # (a linear stretch of the objective); harmless here, and the only warning meant
        warnings.filterwarnings("ignore", message="delta_grad == 0.0", category=UserWarning)
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
        Upper bound of each counterweight's mass (kg).  Default: the
        mechanism's total moving mass (see :func:`default_bounds`).
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

    Notes
    -----
    Each term of ``J`` is the norm of a function that is linear in the
    counterweights' masses, first moments ``mu w`` and second moments
    ``mu |w|^2`` (module docstring), compressed once by a QR factorisation,
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
    the added mass: with the default bounds, the optimum often puts the
    largest allowed mass on several links; give ``max_mass`` for a
    realistic design.

    Examples
    --------
    >>> from linkage_sym.examples import load_example
    >>> res = optimize_counterweights(load_example("crank_rocker"), links=["crank"], weights=(1, 0, 0))
    >>> res.objective < res.objective_start, res.counterweights[0].link
    (True, 'crank')
    """
    scene = _as_scene(scene)
    model = CycleModel(scene) if model is None else model
    links = list(scene.link_names if links is None else links)
    if not links:
        raise ValueError("links: no link to optimise")
    unknown = [n for n in links if n not in scene.link_names]
    if unknown:
        raise ValueError(f"links: {unknown} are not moving links of the scene")
    if len(set(links)) != len(links):
        raise ValueError("links: a link is listed twice")
    w = np.asarray(weights, dtype=float)
    if w.shape != (3,) or not np.all(np.isfinite(w)) or np.any(w < 0) or not np.any(w > 0):
        raise ValueError(f"weights: three finite numbers >= 0, not all zero, not {weights!r}")
    dm, dr = default_bounds(scene)
    Mmax = _per_link(max_mass, links, dm, "max_mass")
    Rmax = _per_link(max_radius, links, dr, "max_radius")
    # the start, in normalised variables
    z0 = np.zeros(3 * len(links))
    start_cws = _check_links(scene, start or [])
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
    if not model.ok.any():
        raise ValueError("the scene has no step whose status is ok: nothing to optimise")
    rms_start = model.rms(start_cws)
    scales = {}
    for k in ("force", "moment", "driving"):
        v = rms_start[k]
        if v > ZERO_START * model.gross[k] and v > 0:
            scales[k] = v
        elif model.gross[k] > 0:
            scales[k] = model.gross[k]
        else:
            scales[k] = 1.0
    prob = _Problem(model, links, w, scales, Mmax, Rmax)
    # bounds of the scaled variables (a zero bound scales its variable to no effect)
    lo = np.tile([0.0, -1.0, -1.0], len(links))
    hi = np.tile([1.0, 1.0, 1.0], len(links))
    J_start = prob.objective(z0)
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
        starts.append(("a generic start", np.tile([0.3, 0.0, 0.0], len(links))))
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
        scales=scales,
        max_mass=Mmax,
        max_radius=Rmax,
        n_excluded=model.n_excluded,
    )

