"""Complex Assur groups by disconnection and superposition (Dang and Zhang, "A simplified
method for the force analysis of complex planar multi-bar mechanisms").

Dang Zuqi and Zhang Qixian solve a class-III (or higher) group with dyad
routines only.  A :class:`~linkage_sym.structure.Disconnection` removes one
binary link, two binary links or one joint; the rest of the group becomes a
*virtual pure-dyad mechanism* driven by one or two hypothetical input links.

The cut joints' reactions are split as the removed links' own equilibrium
allows: for a removed binary link with two revolutes, the component normal
to the link follows from its moment balance (eq. 1) and the component along
it is the unknown ``X``.  By linearity, the equilibrium residual of each
hypothetical input link (its moment about its pivot, or its force along its
guide when it slides: eqs. 8-9) is ``M_bar + K X`` (eq. 4).  The dyad
routines run once with every known load and ``X = 0`` (giving ``M_bar`` and
the reactions ``R'``) and once per unknown with no load and a unit ``X``
(giving ``K`` and ``R''``); ``X = -M_bar / K`` (eq. 6, or the 2x2 system of
eq. 10) and every reaction is ``R' + R'' X`` (eqs. 7, 11) with no further
run.

Conditioning.  Superposition cancels: when ``K`` is small, ``X`` is large
and ``R' + R'' X`` is a difference of large numbers.  Each step's
*amplification* ``max(|R'| + |R''| |X|) / max |R|`` measures that loss
(about ``log10`` of it in digits).  Where the chosen disconnection's
amplification exceeds :data:`AMPLIFICATION_LIMIT`, every other
disconnection of the group is tried and the best-conditioned one is used at
that step; the result records which.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from linkage_sym.errors import POINTERS, SceneError
from linkage_sym.model import GROUND, Scene
from linkage_sym.numeric.forces.global_statics import assemble, dense_system, unpack
from linkage_sym.numeric.forces.loads import Wrench, applied_wrenches
from linkage_sym.numeric.forces.policy import AMPLIFICATION_LIMIT
from linkage_sym.numeric.kinematics.state import LinkState
from linkage_sym.numeric.forces.statics import DyadForces, Geometry, InputForces, push
from linkage_sym.structure import Group
from linkage_sym.structure.disconnection import Disconnection, default_choice, usable_disconnections



@dataclass
class SuperpositionTerms:
    """Dang and Zhang's intermediates of one disconnection over ``K`` steps.

    With ``n`` unknowns (one or two), each hypothetical input's residual is
    ``residual[i] + sum_k coefficients[i, k] X[k]`` (eq. 4, 8 or 10) and
    every reaction is ``particular[j] + sum_k X[k] units[k][j]`` (eqs. 7, 11).

    Attributes
    ----------
    choice : Disconnection
    unknowns : tuple of str
        What each ``X`` is, in words.
    residual : ndarray, shape (n, K)
        ``M_bar``: each input's residual (moment about its pivot, or force
        along its guide, in the joint's own orientation) with every known
        load and ``X = 0``.
    coefficients : ndarray, shape (n, n, K)
        ``K``: residual ``i`` per unit ``X[k]`` with no other load.
    X : ndarray, shape (n, K)
        The unknowns, ``-coefficients^-1 residual`` (eq. 6 or 10).
    particular, units : dict of joint to (fx, fy, m)
        ``R'`` (``X = 0``) and ``R''`` (per unit ``X[k]``) of every joint of
        the group, as the reaction of ``links[0]`` on ``links[1]``.
    """

    choice: Disconnection
    unknowns: tuple
    residual: np.ndarray
    coefficients: np.ndarray
    X: np.ndarray
    particular: dict
    units: list


def superposition_terms(plan, analysis, choice: int, group: int | None = None) -> SuperpositionTerms:
    """The intermediates of disconnection ``choice`` of a complex group at the ``ok`` steps of
    ``analysis`` (a run of ``plan``), for a reader who checks a hand calculation step by step.

    ``group`` is the group's index in ``plan.decomposition.groups`` (default: the only group
    solved by disconnection).  The loads of the groups hanging from it are those of
    ``analysis.forces``; ``choice`` indexes the choices as ``linkage-sym structure`` lists them.
    """
    scene = plan.scene
    groups = plan.decomposition.groups
    if group is None:
        complex_ = [i for i, g in enumerate(groups) if g.kind not in ("input", "dyad")]
        if len(complex_) != 1:
            raise ValueError(f"group: the mechanism has {len(complex_)} complex groups; name one by its index")
        (group,) = complex_
    g = groups[group]
    choices = usable_disconnections(scene, g)
    if not 0 <= choice < len(choices):
        raise ValueError(f"choice: group {group} has {len(choices)} disconnections (0 to {len(choices) - 1})")
    idx = np.flatnonzero(np.asarray(analysis.status) == "ok")
    S = {}
    for name, lk in analysis.links.items():
        st = LinkState(lk.rotation[idx], lk.origin[idx, 0], lk.origin[idx, 1])
        if lk.omega is not None:
            st.w, st.vx, st.vy = lk.omega[idx], lk.origin_velocity[idx, 0], lk.origin_velocity[idx, 1]
        if lk.alpha is not None:
            st.al, st.ax, st.ay = lk.alpha[idx], lk.origin_acceleration[idx, 0], lk.origin_acceleration[idx, 1]
        S[name] = st
    S[GROUND] = LinkState()
    geo = Geometry(scene, S)
    W = applied_wrenches(scene, S, q={k: np.asarray(d["q"])[idx] for k, d in analysis.drivers.items()})
    forces = analysis.forces
    for later in groups[group + 1:]:  # solved before this one: their reactions load it
        inside = set(later.links)
        for name in later.external:
            r = forces.reactions[name][idx]
            eff = forces.driving.get(name)
            push(W, scene.joint(name), geo, (r[:, 0], r[:, 1], forces.reaction_moments[name][idx]),
                 None if eff is None else eff[idx], only=W.keys() - inside)
    return _Choice(scene, g, choices[choice]).terms(W, geo, plan.L, len(idx))


class _Choice:
    """One disconnection compiled for the force runs."""

    def __init__(self, scene: Scene, group: Group, d: Disconnection):
        self.d = d
        self.scene = scene
        self.removed = set(d.removed_links)
        self.remaining = [n for n in group.links if n not in self.removed]
        self.cut = [scene.joint(j) for j in d.removed_joints]
        self.driven = set(group.drivers)
        self.inputs = [InputForces(scene, link, joint) for link, joint in d.inputs]
        self.dyads = [DyadForces(scene, g) for g in d.dyads]
        self.n = d.unknowns
        # the classic split of Dang and Zhang's eq. 1: one removed link with two revolutes
        self.rr = None
        if len(d.removed_links) == 1:
            (b,) = d.removed_links
            js = [j for j in self.cut if b in j.links]
            if len(js) == 2 and all(j.type == "R" and j.name not in self.driven for j in js):
                self.rr = (b, js[0], js[1])

    # -- the cut joints' reactions: particular part and unit parts ---------
    def split(self, W, geo: Geometry, L, K):
        """``(zp, Z)``: cut-joint reactions for ``X = 0`` and for each unit ``X``.

        Each is ``{joint: (fx, fy, m, effort)}`` (effort ``None`` for an
        undriven joint).
        """
        if not self.removed:
            (j,) = self.cut
            zero = np.zeros(K)
            zp = {j.name: (zero, zero, zero, None)}
            if j.type == "R":
                Z = [{j.name: (1.0, 0.0, 0.0, None)}, {j.name: (0.0, 1.0, 0.0, None)}]
            else:
                nx, ny, _, _ = geo.normal(j.name)
                Z = [{j.name: (nx, ny, 0.0, None)}, {j.name: (0.0, 0.0, L, None)}]
            return zp, Z
        if self.rr is not None:
            return self._split_rr(W, geo)
        return self._split_svd(W, geo, L, K)

    def _split_rr(self, W, geo):
        b, j1, j2 = self.rr
        w = W[b]
        p1x, p1y = geo.point(j1.name)
        p2x, p2y = geo.point(j2.name)
        dx, dy = p2x - p1x, p2y - p1y
        length = np.hypot(dx, dy)
        ex, ey = dx / length, dy / length
        # forces on b: g2 = X e + s n at j2 (s from b's moment about j1, eq. 1), g1 = -F - g2
        s = -w.moment_about(p1x, p1y) / length
        g2x, g2y = -ey * s, ex * s
        g1x, g1y = -w.fx - g2x, -w.fy - g2y

        def as_reaction(j, gx, gy):
            sg = 1.0 if j.links[1] == b else -1.0
            return (sg * gx, sg * gy, 0.0, None)

        zp = {j1.name: as_reaction(j1, g1x, g1y), j2.name: as_reaction(j2, g2x, g2y)}
        Z = [{j1.name: as_reaction(j1, -ex, -ey), j2.name: as_reaction(j2, ex, ey)}]
        return zp, Z

    def _split_svd(self, W, geo, L, K):
        """Any removed links: minimum-norm particular part and an orthonormal null basis."""
        joints = [j.name for j in self.cut]
        drivers = [j.name for j in self.cut if j.name in self.driven]
        links = list(self.d.removed_links)
        entries, b, cols, ncols = assemble(self.scene, links, joints, drivers, geo, W, L)
        nrows = 3 * len(links)
        A, rhs = dense_system(entries, b, nrows, ncols, K)
        U, sv, Vt = np.linalg.svd(A)
        y = np.einsum("kij,ki->kj", U, rhs) / sv
        zp = np.einsum("kji,kj->ki", Vt[:, :nrows, :], y)
        null = Vt[:, nrows:, :]  # (K, n, ncols)

        def as_cut(z):
            reactions, efforts = unpack(self.scene, z, cols, joints, drivers, geo, L)
            return {name: (*r, efforts.get(name)) for name, r in reactions.items()}

        return as_cut(zp), [as_cut(null[:, k, :]) for k in range(null.shape[1])]

    # -- one run of the virtual pure-dyad mechanism ------------------------
    def virtual_run(self, W0, cut, geo):
        """Reactions of the remaining joints and the inputs' residuals under ``W0`` plus ``cut``.

        ``W0`` holds the remaining links' wrenches (modified in place).
        """
        jdict = self.scene.joint
        for name, (fx, fy, m, eff) in cut.items():
            push(W0, jdict(name), geo, (fx, fy, m), eff, only=W0)
        reactions = {}
        for dy in reversed(self.dyads):
            res = dy.solve(W0, geo)
            reactions.update(res)
            for name in dy.group.external:
                push(W0, jdict(name), geo, res[name], only=W0.keys() - set(dy.group.links))
        residuals = []
        for inp in self.inputs:
            r, e = inp.solve(W0, geo)
            reactions[inp.joint.name] = r
            residuals.append(e)
        return reactions, residuals

    def _parts(self, W, geo: Geometry, L, K):
        """The runs of the virtual mechanism: ``(zp, Z, R0, m0, runs, Kmat, X)``."""
        zp, Z = self.split(W, geo, L, K)
        base = {n: W[n].copy() for n in self.remaining}
        R0, m0 = self.virtual_run(base, zp, geo)
        runs = []
        for Zk in Z:
            Wk = {n: Wrench(W[n].rx, W[n].ry) for n in self.remaining}
            runs.append(self.virtual_run(Wk, Zk, geo))
        Kmat = [[np.broadcast_to(runs[k][1][i], (K,)) for k in range(self.n)] for i in range(self.n)]
        m0 = [np.broadcast_to(v, (K,)) for v in m0]
        with np.errstate(divide="ignore", invalid="ignore"):
            if self.n == 1:
                X = [-m0[0] / Kmat[0][0]]
            elif self.n == 2:
                (a, b), (c, d) = Kmat
                det = a * d - b * c
                X = [(-m0[0] * d + b * m0[1]) / det, (-a * m0[1] + c * m0[0]) / det]
            else:
                A = np.stack([np.stack(row, axis=-1) for row in Kmat], axis=-2)
                X = list(np.linalg.solve(A, -np.stack(m0, axis=-1)[..., None])[..., 0].T)
        return zp, Z, R0, m0, runs, Kmat, X

    def terms(self, W, geo: Geometry, L, K) -> "SuperpositionTerms":
        """Dang and Zhang's intermediates of this disconnection (see :class:`SuperpositionTerms`)."""
        zp, Z, R0, m0, runs, Kmat, X = self._parts(W, geo, L, K)

        def arrays(parts):
            return tuple(np.broadcast_to(np.asarray(v, dtype=float), (K,)).copy() for v in parts[:3])

        particular = {n: arrays(r) for n, r in R0.items()}
        particular.update({n: arrays(r) for n, r in zp.items()})
        units = []
        for (Rk, _), Zk in zip(runs, Z):
            u = {n: arrays(r) for n, r in Rk.items()}
            u.update({n: arrays(r) for n, r in Zk.items()})
            units.append(u)
        return SuperpositionTerms(
            choice=self.d,
            unknowns=self.unknowns(),
            residual=np.array([np.asarray(v, dtype=float) for v in m0]),
            coefficients=np.array([[np.asarray(v, dtype=float) for v in row] for row in Kmat]),
            X=np.array([np.broadcast_to(v, (K,)) for v in X], dtype=float),
            particular=particular,
            units=units,
        )

    def unknowns(self) -> tuple:
        """What each unknown ``X`` is, in words (the unit runs' loads on the cut joints)."""
        if not self.removed:
            (j,) = self.cut
            if j.type == "R":
                return (f"x component of the reaction at {j.name}", f"y component of the reaction at {j.name}")
            return (f"normal force of the slide {j.name}", f"couple of the slide {j.name}")
        if self.rr is not None:
            b, j1, j2 = self.rr
            return (f"force on '{b}' at {j2.name} along {j1.name}->{j2.name} (the opposite of the "
                    f"component along it at {j1.name}, less '{b}''s own load along it)",)
        return tuple(f"null-space coordinate {k + 1} of the cut joints' reactions" for k in range(self.n))

    def solve(self, W, geo: Geometry, L, K):
        """Reactions and efforts of the group, and the amplification per step."""
        zp, Z, R0, m0, runs, Kmat, X = self._parts(W, geo, L, K)
        reactions, efforts = {}, {}
        num = np.zeros(K)
        den = np.zeros(K)

        def combine(parts0, parts):
            total = [np.broadcast_to(np.asarray(v, dtype=float), (K,)).copy() for v in parts0]
            size = _size(parts0, L)
            for Xk, pk in zip(X, parts):
                for i in range(3):
                    total[i] += Xk * pk[i]
                size = size + np.abs(Xk) * _size(pk, L)
            return total, size

        for name in R0:
            (fx, fy, m), size = combine(R0[name], [r[0][name] for r in runs])
            reactions[name] = (fx, fy, m)
            num = np.fmax(num, size)
            den = np.fmax(den, _size((fx, fy, m), L))
        for name in zp:
            (fx, fy, m), size = combine(zp[name][:3], [Zk[name][:3] for Zk in Z])
            reactions[name] = (fx, fy, m)
            num = np.fmax(num, size)
            den = np.fmax(den, _size((fx, fy, m), L))
            if zp[name][3] is not None:
                e = np.broadcast_to(zp[name][3], (K,)).copy()
                for Xk, Zk in zip(X, Z):
                    e += Xk * Zk[name][3]
                efforts[name] = e
        with np.errstate(divide="ignore", invalid="ignore"):
            amp = num / den
        amp = np.where(den == 0, np.where(num == 0, 1.0, np.inf), amp)
        return reactions, efforts, amp


def _size(parts, L):
    fx, fy, m = parts[:3]
    return np.hypot(np.hypot(fx, fy), np.asarray(m) / L)


class SuperpositionForces:
    """A complex group solved by Dang and Zhang's method, with a fallback disconnection per step."""

    def __init__(self, scene: Scene, group: Group, choices: list[Disconnection], preferred=None):
        self.group = group
        self.choices = choices
        self.compiled = [_Choice(scene, group, d) for d in choices]
        self.preferred = default_choice(choices) if preferred is None else preferred
        if not 0 <= self.preferred < len(choices):
            raise SceneError(
                [
                    f"disconnection: choice {preferred} of group {', '.join(group.links)} does "
                    f"not exist (it has {len(choices)}: 0 to {len(choices) - 1}, in the order "
                    f"{POINTERS['disconnections']})"
                ]
            )

    def solve(self, W, geo: Geometry, L, K):
        """``(reactions, efforts, used, amplification)`` over ``K`` steps."""
        best = self.compiled[self.preferred].solve(W, geo, L, K)
        reactions, efforts, amp = best
        used = np.full(K, self.preferred)
        bad = ~(amp <= AMPLIFICATION_LIMIT)
        if bad.any():
            for k, ch in enumerate(self.compiled):
                if k == self.preferred or not bad.any():
                    continue
                r2, e2, a2 = ch.solve(W, geo, L, K)
                better = bad & (a2 < amp) | (~np.isfinite(amp) & np.isfinite(a2))
                if not better.any():
                    continue
                for name in reactions:
                    reactions[name] = tuple(
                        np.where(better, b2, b1) for b1, b2 in zip(reactions[name], r2[name])
                    )
                for name in efforts:
                    efforts[name] = np.where(better, e2[name], efforts[name])
                amp = np.where(better, a2, amp)
                used[better] = k
                bad = ~(amp <= AMPLIFICATION_LIMIT)
        return reactions, efforts, used, amp

