"""Joint friction in the evaluator of generated code (contract part two; no SymPy here).

Where a scene's friction acts, :func:`linkage_sym.codegen.compile.build_artifact` derives
the force equations with the friction in them (:mod:`linkage_sym.symbolic.friction`):
each joint's friction ``Mf_<J>`` (an ``R`` joint's couple) or ``Ff_<J>`` (a ``P`` joint's
force along its axis) is a force name after the reactions and efforts, and a column of
the force blocks' ``C``, so a group's block reads ``A_g F_g = b_g - C_g F_later``, with
the frictions among ``F_later``.  The generated code is linear in the frictions; their
laws (``Mf = -rho nu |R|``, ``Ff = -f nu |N|``) are solved here, per entry (a step, or a
design's step), vectorised over the entries:

* the sign ``nu`` of each joint's relative motion from the generated rates
  (``"frate:<joint>"``): the relative velocity, where it is not zero (more than
  :data:`ZERO_RATE` of the mechanism's largest of its kind at that entry), else the
  relative acceleration, else none (the joint has no friction there);
* group by group from the last one back, as the frictionless solve: the group's block
  solved with its own joints' frictions 0 (``R0``) and once per own friction with a unit
  friction alone (``U``: the columns ``-C``), then Newton's method on
  ``g(mu) = mu + rho nu |R0 + U mu| = 0`` from ``mu = 0``, the frictionless solution.
  Where it fails (an iterate with ``det dg/dmu <= 0``, or no convergence) the entry is
  followed again in :data:`STAGES` stages of the friction's scale ``lam``, and is
  *self-locking* where that branch meets ``det dg/dmu <= 0``: no finite driving effort
  moves the mechanism (the criterion of the numeric methods, there written apart,
  :mod:`linkage_sym.numeric.forces.friction`); the joints named are those of the
  singular direction.  A group's frictions are then known forces for the groups solved
  after it (the links it shares with them).

The arithmetic is the backend's (:class:`NumpyOps`: arrays over the entries; the mpmath
backend's, one step at a time, carried to the working precision); this module shares no
code with the numeric group routines but the scene's data and the threshold
:data:`ZERO_RATE`.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from linkage_sym.model import GROUND
from linkage_sym.numeric.forces.friction import ZERO_RATE
from linkage_sym.numeric.results.result import OK, SELF_LOCKING
from linkage_sym.numeric.results.wording import steps_text
from linkage_sym.structure.parameters import ident

__all__ = ["MAX_NEWTON", "STAGES", "FrictionSolution", "NumpyOps", "lock_message", "mark_locked",
           "no_direction_note", "solve_with_friction"]

MAX_NEWTON = 60
"""Newton iterations per stage before an entry is taken as having no solution on its branch."""
STAGES = 8
"""Stages of the friction's scale in which an entry that Newton fails is followed again."""


def lock_message(names) -> str:
    """The message of a self-locking step (the numeric methods' words)."""
    return (f"{SELF_LOCKING}: no finite driving effort moves the mechanism as prescribed: the "
            f"friction at joint(s) {', '.join(dict.fromkeys(names))} grows with the effort "
            "faster than the effort can move it")


def no_direction_note(name: str, steps) -> str:
    """The warning for a joint without relative motion at ``steps`` (the numeric methods')."""
    return (f"joint {name}: neither its relative velocity nor its relative acceleration is "
            f"non-zero at {len(steps)} step(s) (steps {steps_text(steps, len(steps))}): its "
            "friction, whose direction opposes them, is taken as zero there")


def mark_locked(status, messages, forces) -> None:
    """Give the ``ok`` steps at which the friction locks the mechanism (``forces.lock_messages``)
    the status ``self-locking`` and their message."""
    if forces is None or forces.locked is None:
        return
    for i, text in forces.lock_messages.items():
        if status[i] == OK:
            status[i] = SELF_LOCKING
            messages[i] = text


class NumpyOps:
    """The arithmetic of the friction's solve on NumPy arrays over the entries."""

    tol = 1e-12
    nan = np.nan
    sqrt = staticmethod(np.sqrt)
    abs = staticmethod(np.abs)
    sign = staticmethod(np.sign)
    where = staticmethod(np.where)
    and_ = staticmethod(np.logical_and)
    or_ = staticmethod(np.logical_or)
    not_ = staticmethod(np.logical_not)
    finite = staticmethod(np.isfinite)

    @staticmethod
    def const(value, like):
        return np.full(np.shape(like), value)

    @staticmethod
    def any(mask) -> bool:
        return bool(np.any(mask))

    @staticmethod
    def maximum(values):
        return np.maximum.reduce([np.asarray(v, float) for v in values])

    @staticmethod
    def ratio(a, b):
        """``a / b`` where ``b > 0``, else 0."""
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(b > 0, a / b, 0.0)

    @staticmethod
    def step(J, g, live):
        """``(det J > 0, -J^-1 g)`` at every entry (the step 0 where not ``live`` or not
        positive); ``J`` nested lists (m x m) and ``g`` a list of arrays."""
        M = np.stack([np.stack([np.broadcast_to(v, np.shape(g[0])) for v in row], -1)
                      for row in J], -2)
        G = np.stack(g, -1)
        with np.errstate(invalid="ignore", over="ignore"):
            good = np.linalg.det(M) > 0
        d = np.zeros_like(G)
        use = good & live
        if use.any():
            d[use] = -np.linalg.solve(M[use], G[use][..., None])[..., 0]
        return good, list(np.moveaxis(d, -1, 0))

    @staticmethod
    def null_joints(J, locked) -> dict:
        """Entry -> indices of the frictions in the singular direction of ``J`` there."""
        out = {}
        for i in np.flatnonzero(locked):
            M = np.array([[float(np.broadcast_to(v, locked.shape)[i]) for v in row] for row in J])
            v = np.abs(np.linalg.svd(M)[2][-1])
            out[int(i)] = [k for k, x in enumerate(v) if x >= 0.1 * v.max()]
        return out


@dataclass
class FrictionSolution:
    """What :func:`solve_with_friction` found at the entries.

    Attributes
    ----------
    F : list
        The forces (reactions, efforts, then the frictions) in the order of the force
        names; NaN at the self-locking entries.
    mu : dict
        Joint -> its friction.
    rate, moving, direction : dict
        Joint -> its relative rate (rad/s, m/s), where it is not zero, and where its
        friction has a direction (a relative velocity or acceleration).
    locked : array or bool
        The self-locking entries.
    lockers : dict
        Entry -> names of the joints whose friction locks it.
    """

    F: list
    mu: dict = field(default_factory=dict)
    rate: dict = field(default_factory=dict)
    moving: dict = field(default_factory=dict)
    direction: dict = field(default_factory=dict)
    locked: object = False
    lockers: dict = field(default_factory=dict)

    def power(self, ops):
        """The power the friction dissipates (W, >= 0) at the entries."""
        p = 0
        for name, m in self.mu.items():
            p = p + ops.where(self.moving[name], -m * self.rate[name], 0 * m)
        return p


def _rates(ev, rows, slide, f, ops):
    """``(v, a, v_size, a_size)`` of friction joint ``f`` from its ``"frate"`` rows (and a
    ``P`` joint's axis ``slide``)."""
    scene = ev.scene
    links = list(scene.link_names)
    a, b = scene.joint(f.joint).links
    if f.kind == "R":
        w, al = rows[0::2], rows[1::2]

        def rel(x):
            return ((x[links.index(b)] if b != GROUND else 0)
                    - (x[links.index(a)] if a != GROUND else 0))

        return (rel(w), rel(al), ops.maximum([ops.abs(x) for x in w]),
                ops.maximum([ops.abs(y) + x * x for x, y in zip(w, al)]))
    ux, uy = slide
    pts = [rows[4 * k:4 * k + 4] for k in range(len(links))]

    def at(link):
        return pts[links.index(link)] if link != GROUND else (0, 0, 0, 0)

    (vbx, vby, abx, aby), (vax, vay, aax, aay) = at(b), at(a)
    return ((vbx - vax) * ux + (vby - vay) * uy, (abx - aax) * ux + (aby - aay) * uy,
            ops.maximum([ops.sqrt(p[0] * p[0] + p[1] * p[1]) for p in pts]),
            ops.maximum([ops.sqrt(p[2] * p[2] + p[3] * p[3]) for p in pts]))


def _signs(ev, pts, take, ops, sol):
    """Each friction joint's relative rate and the sign of its friction's direction."""
    signs = {}
    for f in ev.art.friction:
        rows = [take(r) for r in ev.art.rows(pts, f"frate:{f.joint}")]
        slide = [take(r) for r in ev.art.rows(pts, f"slide:{f.joint}")] if f.kind == "P" else None
        v, a, vs, as_ = _rates(ev, rows, slide, f, ops)
        moving = ops.abs(v) > ZERO_RATE * vs
        accel = ops.and_(ops.not_(moving), ops.abs(a) > ZERO_RATE * as_)
        signs[f.joint] = ops.where(moving, ops.sign(v), ops.where(accel, ops.sign(a), 0 * v))
        sol.rate[f.joint], sol.moving[f.joint] = v, moving
        sol.direction[f.joint] = ops.or_(moving, accel)
    return signs


def _reaction_columns(ev, f) -> list:
    """The force indices of joint ``f``'s reaction whose size the law reads."""
    fidx = ev.art.force_index()
    n = ident(f.joint)
    return [fidx[f"R_{n}x"], fidx[f"R_{n}y"]] if f.kind == "R" else [fidx[f"N_{n}"]]


def solve_with_friction(ev, pts, take, P, ops) -> FrictionSolution:
    """Reactions, efforts and frictions of every group, from the last one back (see the
    module docstring).

    Parameters
    ----------
    ev : Evaluator
        The generated functions and their backend (:meth:`dense_solve`, :meth:`force_zeros`).
    pts : list
        Its ``points`` outputs.
    take : callable
        The entries' selection of each output (the steps solved).
    P : list
        The parameters the outputs were evaluated with: the frictions' coefficients and pin
        radii are read there (per entry in a design sweep).
    ops : NumpyOps or the mpmath backend's
        The arithmetic.

    Returns
    -------
    FrictionSolution
    """
    art = ev.art
    sol = FrictionSolution(F=[])
    signs = _signs(ev, pts, take, ops, sol)
    arm = {f.joint: P[f.coefficient] * (P[f.radius] if f.radius is not None else 1)
           for f in art.friction}
    F = None
    locked = None
    for g, blk in reversed(list(zip(art.groups, art.forces))):
        k = g.index
        A = [take(v) for v in art.rows(pts, f"A:{k}")]
        b = [take(v) for v in art.rows(pts, f"b:{k}")]
        C = [(i, fi, take(v)) for (i, fi), v in zip(blk.C, art.rows(pts, f"C:{k}"))]
        if F is None:
            F = ev.force_zeros(b[0])
            locked = ops.const(False, b[0])
        for i, fi, v in C:
            b[i] = b[i] - v * F[fi]
        x = ev.dense_solve(blk.A, A, b)
        pos = {u: r for r, u in enumerate(blk.unknowns)}
        own = [f for f in art.friction if _reaction_columns(ev, f)[0] in pos]
        if own:
            units = []
            for f in own:  # the block's response to a unit friction alone
                rhs = [0 * b[0] for _ in b]
                for i, fi, v in C:
                    if fi == f.force:
                        rhs[i] = rhs[i] - v
                units.append(ev.dense_solve(blk.A, A, rhs))
            cols = [[pos[c] for c in _reaction_columns(ev, f)] for f in own]
            R0 = [[x[c] for c in cs] for cs in cols]
            U = [[[u[c] for c in cs] for cs in cols] for u in units]  # U[l][k]: joint k by l
            rs = [arm[f.joint] * signs[f.joint] for f in own]
            skip = ops.or_(locked, ops.not_(ops.finite(sum(r[0] for r in R0))))
            mu, lk, J = _friction_newton(ops, R0, U, rs, skip)
            for e, ks in ops.null_joints(J, lk).items():
                sol.lockers.setdefault(e, []).extend(own[q].joint for q in ks)
            locked = ops.or_(locked, lk)
            x = [xi + sum(m * u[r] for m, u in zip(mu, units)) for r, xi in enumerate(x)]
            for f, m in zip(own, mu):
                F[f.force] = m
                sol.mu[f.joint] = m
        for u, s in zip(blk.unknowns, x):
            F[u] = s
    if ops.any(locked):  # nothing is reported at a self-locking entry
        F = [ops.where(locked, ops.nan, v) for v in F]
        sol.mu = {n: ops.where(locked, ops.nan, m) for n, m in sol.mu.items()}
    sol.F, sol.locked = F, locked
    return sol


def _residual(ops, R0, U, rs, mu, lam):
    """``g`` (a list over the frictions) and ``dg/dmu`` (nested lists) at ``mu``."""
    m = len(mu)
    g, J = [], []
    for k in range(m):
        comps = [R0[k][c] + sum(mu[q] * U[q][k][c] for q in range(m)) for c in range(len(R0[k]))]
        size = ops.sqrt(sum(c * c for c in comps))
        g.append(mu[k] + lam * rs[k] * size)
        J.append([(1 if q == k else 0)
                  + lam * rs[k] * ops.ratio(sum(c * u for c, u in zip(comps, U[q][k])), size)
                  for q in range(m)])
    return g, J


def _newton(ops, R0, U, rs, mu, lam):
    """Newton on ``g_lam`` from ``mu``: ``(mu, ok, J)``, ``ok`` where it converged with
    ``det dg/dmu > 0`` at every iterate."""
    like = R0[0][0]
    ok, done = ops.const(True, like), ops.const(False, like)
    scale = ops.maximum([ops.abs(lam * r * ops.sqrt(sum(c * c for c in R)))
                         for r, R in zip(rs, R0)])
    J = None
    for _ in range(MAX_NEWTON):
        g, J = _residual(ops, R0, U, rs, mu, lam)
        live = ops.and_(ok, ops.not_(done))
        good, d = ops.step(J, g, live)
        ok = ops.and_(ok, ops.or_(good, done))
        live = ops.and_(live, good)
        d = [ops.where(live, v, 0 * v) for v in d]
        mu = [a + v for a, v in zip(mu, d)]
        size = ops.maximum([ops.abs(v) for v in mu]) + scale
        small = ops.maximum([ops.abs(v) for v in d]) <= ops.tol * size
        done = ops.or_(done, ops.and_(live, small))
        if not ops.any(ops.and_(ok, ops.not_(done))):
            break
    return mu, ops.and_(ok, done), J


def _friction_newton(ops, R0, U, rs, skip):
    """``(mu, locked, J)``: Newton from the frictionless solution at every entry not
    skipped, then the entries it fails followed in :data:`STAGES` stages of the scale."""
    zero = [0 * R0[0][0] for _ in rs]
    mu, ok, J = _newton(ops, R0, U, rs, list(zero), 1)
    bad = ops.and_(ops.not_(ok), ops.not_(skip))
    locked = ops.const(False, R0[0][0])
    if ops.any(bad):
        mu_s, fine = list(zero), ops.const(True, R0[0][0])
        for s in range(1, STAGES + 1):
            mu_s, ok_s, J_s = _newton(ops, R0, U, rs, mu_s, s / STAGES)
            fine = ops.and_(fine, ok_s)
        mu = [ops.where(bad, a, c) for a, c in zip(mu_s, mu)]
        J = [[ops.where(bad, a, c) for a, c in zip(ra, rc)] for ra, rc in zip(J_s, J)]
        locked = ops.and_(bad, ops.not_(fine))
    out = ops.or_(locked, skip)
    return [ops.where(out, ops.nan, m) for m in mu], locked, J
