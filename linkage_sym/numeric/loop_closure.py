"""Newton groups of revolute joints in loop-closure coordinates: the links' angles.

A group whose joints are all revolute and which holds no driver (a class-III
triad, a class-IV group, ...) is solved in its links' angles alone.  Each
link is placed from a link already placed through one of its joints (a
spanning tree taken in the group's joint order, as the symbolic layer takes
it: :meth:`linkage_sym.symbolic.mechanism.MechanismEquations._group`); every
other joint closes a loop, two rows ``P_a(J) - P_b(J) = 0`` with each side
reached along the tree.  For the triad that is 4 unknowns and 4 rows where
pose coordinates have 12 (:class:`linkage_sym.numeric.newton.NewtonSolver`,
kept for every other group).  Both runtimes now solve the same equations.

**The linear form.**  With points as complex numbers and ``E_k = e^{i
theta_k}``, a point ``X`` of group link ``k`` is the point of a known link
where its branch of the tree starts plus ``sum_m E_m (X_m' - X_m)`` over the
links on the way (each turns the segment between the joint that places it and
the next one).  Every point is linear in ``E``, so the rows are ``E @ W + K``
(``W`` complex constants made once, ``K`` the known links' points combined)
and the Jacobian is ``dPhi_r / dtheta_k = i E_k W[k, r]``: a product and a
sum per evaluation, whatever the tree.  The continuation (predictor, damped
Newton, the assembly mode's determinant sign, limits, re-entry searches) is
:mod:`linkage_sym.numeric.continuation`'s, unchanged.

**Rates** from the same form: ``dPhi/dt = i (omega E) @ W + dK/dt`` and
``d2Phi/dt2 = ((i alpha - omega^2) E) @ W + d2K/dt2``, so ``J omega = -dK/dt``
and ``J alpha = -(d2K/dt2 - (omega^2 E) @ W)``; each link's origin follows from
its own row of the form.
"""

from __future__ import annotations

import numpy as np

from linkage_sym.numeric import continuation
from linkage_sym.numeric.constraints import RJoint
from linkage_sym.numeric.newton import SINGULAR_IND, NewtonSolver, _PoseProblem


def applies(scene, group, constraints) -> bool:
    """Whether ``group`` is solved in loop-closure coordinates: revolute joints only, no
    driver of its own (an actuator's slide stays in pose coordinates)."""
    return not group.drivers and all(
        isinstance(constraints[n].joint, RJoint) and scene.joint(n).type == "R"
        for n in group.joints)


class LoopClosureSolver(NewtonSolver):
    """A revolute-only Newton group solved in its links' angles (see the module docstring)."""

    def __init__(self, scene, group, constraints, L):
        super().__init__(scene, group, constraints, L)
        joints = [constraints[n].joint for n in group.joints]
        links = list(group.links)
        # the spanning tree: each link placed through the first joint (group order) that
        # joins it to a link already placed
        placed = {n for n in [*scene.link_names, "ground"] if n not in links}
        pending = list(links)
        used = set()
        self.parent, self.anchor_X = {}, {}
        while pending:
            for k, c in enumerate(joints):
                if k in used:
                    continue
                a, b = c.links
                if (a in placed) != (b in placed) and (a in pending or b in pending):
                    new, old = (b, a) if a in placed else (a, b)
                    self.parent[new], self.anchor_X[new] = old, c.X
                    placed.add(new)
                    pending.remove(new)
                    used.add(k)
                    break
            else:  # pragma: no cover - a group is always connected to solved links
                raise ValueError(f"group {links} is not connected to solved links")
        self.column = {n: links.index(n) for n in links}  # unknown k is theta of links[k]
        self.loops = [c for k, c in enumerate(joints) if k not in used]
        self.nvar = len(links)
        # every point of the group is linear in E = e^{i theta} of its links: a point X of
        # link k is K + sum_m E_m c_m, K a combination of the known links' points
        self.keys = []  # (link, X) of the known links' points used
        loops = [self._difference(self._point(a, c.X), self._point(b, c.X))
                 for c in self.loops for a, b in [c.links]]
        self.W, self.K_loops = self._matrices(loops)
        self.M_origins, self.K_origins = self._matrices(
            [self._point(n, (0.0, 0.0)) for n in links])

    # -- the linear form -------------------------------------------------------
    def _point(self, link, X):
        """Point ``X`` of ``link`` as ``({group link: coefficient}, {known key: sign})``."""
        if link not in self.column:  # a known link
            if (link, X) not in self.keys:
                self.keys.append((link, X))
            return {}, {self.keys.index((link, X)): 1.0}
        XA = self.anchor_X[link]
        coef, known = self._point(self.parent[link], XA)
        coef = dict(coef)
        coef[link] = coef.get(link, 0.0) + _c(X) - _c(XA)
        return coef, known

    @staticmethod
    def _difference(p, q):
        coef = dict(p[0])
        for k, v in q[0].items():
            coef[k] = coef.get(k, 0.0) - v
        known = dict(p[1])
        for k, v in q[1].items():
            known[k] = known.get(k, 0.0) - v
        return coef, known

    def _matrices(self, points):
        """``(M, Ksel)``: the coefficients ``M`` (links, points) and the known points'
        signs ``Ksel`` (keys, points) of ``points``."""
        M = np.zeros((self.nvar, len(points)), complex)
        Ksel = np.zeros((len(self.keys), len(points)))
        for j, (coef, known) in enumerate(points):
            for n, v in coef.items():
                M[self.column[n], j] = v
            for k, v in known.items():
                Ksel[k, j] = v
        return M, Ksel

    def known_points(self, S) -> np.ndarray:
        """The known links' points (complex) in ``S``: (K, keys) arrays, or (keys,) if all
        are constant."""
        cols = [S[link].point(X) for link, X in self.keys]
        if not any(np.ndim(x) or np.ndim(y) for x, y in cols):
            return np.array([complex(x, y) for x, y in cols])
        n = max(np.size(x) for xy in cols for x in xy)
        out = np.empty((n, len(cols)), complex)
        for k, (x, y) in enumerate(cols):
            out[:, k].real, out[:, k].imag = x, y
        return out

    # -- positions -----------------------------------------------------------
    def _problem(self, S, q):
        return _AngleProblem(self, S, q)

    def _set_poses(self, S, problem, sol):
        for n, (th, dx, dy, c, s) in problem.poses(sol.u).items():
            S[n].set_pose(th, dx, dy, c, s)

    # -- rates -----------------------------------------------------------------
    def _known_rates(self, S, which):
        """The known links' points' velocities or accelerations (complex): (N, keys) or
        (keys,)."""
        rate = "point_velocity" if which == "velocity" else "point_acceleration"
        cols = [getattr(S[link], rate)(X) for link, X in self.keys]
        n = max([np.size(v) for xy in cols for v in xy] + [1])
        out = np.empty((n, len(cols)), complex)
        for k, (x, y) in enumerate(cols):
            out[:, k].real, out[:, k].imag = x, y
        return out

    def _solve(self, S, which):
        """``J x = -(loops' rates with x = 0)``, ``x`` the angular velocities or accelerations;
        then every link's rates from the linear form."""
        n_steps = len(S[self.links[0]].c)
        E = np.empty((n_steps, self.nvar), complex)
        for n, k in self.column.items():
            E[:, k].real, E[:, k].imag = S[n].c, S[n].s
        inv, solvable = self._rate_block(E)
        Kd = self._known_rates(S, which)
        rhs = Kd @ self.K_loops
        if which == "acceleration":  # the centripetal part: -w^2 E per link
            w = np.stack([S[n].w for n in self.column], axis=1)  # column order
            cent = -(w * w) * E
            rhs = rhs + cent @ self.W
        rhs = -np.ascontiguousarray(np.broadcast_to(rhs, (n_steps, rhs.shape[-1]))).view(float)
        x = np.full((n_steps, self.nvar), np.nan)
        idx = np.flatnonzero(solvable & np.isfinite(rhs).all(axis=1))
        if len(idx):
            x[idx] = np.einsum("kij,kj->ki", inv[idx], rhs[idx])
        turn = 1j * x * E
        if which == "acceleration":
            turn += cent
        O = turn @ self.M_origins + Kd @ self.K_origins
        for n, k in self.column.items():
            st = S[n]
            if which == "velocity":
                st.w, st.vx, st.vy = x[:, k], O[:, k].real, O[:, k].imag
            else:
                st.al, st.ax, st.ay = x[:, k], O[:, k].real, O[:, k].imag

    def _rate_block(self, E):
        """The inverse of the group block at the steps (rows in length units) and where it
        is solvable: where the indicator of the dimensionless block (rows over ``L``;
        :func:`~linkage_sym.numeric.continuation.indicator`, at most ``sigma_min /
        sigma_max``) is above :data:`SINGULAR_IND`.  Computed once for the velocities and
        the accelerations (the same poses)."""
        cached = self._rates_cache
        if cached is not None and cached[0].shape == E.shape and np.array_equal(cached[0], E):
            return cached[1], cached[2]
        J = _real_jacobian(E, 1j * self.W.T)
        finite = np.isfinite(J).all(axis=(1, 2))
        inv = continuation.inverses(np.where(finite[:, None, None], J, np.eye(J.shape[1])))
        # the indicator is invariant to the rows' common scale (J over L has inverse L J^-1);
        # NaN where J is not finite
        solvable = continuation.indicator(J, inv) > SINGULAR_IND
        self._rates_cache = (E, inv, solvable)
        return inv, solvable

    def velocity(self, S, q, qd):
        self._solve(S, "velocity")

    def acceleration(self, S, q, qd, qdd):
        self._solve(S, "acceleration")
        self._rates_cache = None


class _AngleProblem(_PoseProblem):
    """A revolute-only group in its links' angles, for :func:`continuation.solve_path`.

    Unknowns ``u``: the angles of ``group.links`` (radians, unscaled); rows: the
    loop-closing joints' two coordinates over ``L``, in the group's joint order,
    ``(E @ W + K) / L`` (:class:`LoopClosureSolver`); the Jacobian is
    ``i E_k W[k, r] / L``.  The known links' points are taken once along the
    whole path (the batched walk indexes them).
    """

    def __init__(self, solver: LoopClosureSolver, S, q):
        super().__init__(solver, S, q)
        self.scale = np.ones(solver.nvar)
        self.angles = np.ones(solver.nvar, bool)
        self.path_keys = solver.known_points(self.known)  # (K, keys), or (keys,) constants
        self.K_loops = self.path_keys @ solver.K_loops
        self.dJ = np.ascontiguousarray(1j * solver.W.T / solver.L)  # (loops, links)

    def _rows(self, U, K):
        sv = self.sv
        E = np.exp(1j * U)
        R = ((E @ sv.W + K) / sv.L).view(float)  # x, y of each loop in turn
        return R, _real_jacobian(E, self.dJ)

    def evaluate_many(self, U, ctx):
        return self._rows(U, self.sv.known_points(ctx[0]) @ self.sv.K_loops)

    def evaluate_points(self, U, idx):
        K = self.K_loops[idx] if self.K_loops.ndim == 2 else self.K_loops
        return self._rows(U, K)

    def poses(self, U):
        """Each group link's ``(theta, dx, dy, cos, sin)`` at every path point (``U``: the
        solution's rows; NaN rows stay NaN)."""
        sv = self.sv
        E = np.exp(1j * U)
        O = E @ sv.M_origins + self.path_keys @ sv.K_origins
        return {n: (U[:, k], O[:, k].real, O[:, k].imag, E[:, k].real, E[:, k].imag)
                for n, k in sv.column.items()}


def _real_jacobian(E, dW):
    """The real Jacobian (m, 2 loops, links) of the rows ``E @ W``: ``dW = i W^T`` (over a
    scale), the x and y rows of each loop in turn."""
    m, (nl, n) = len(E), dW.shape
    Jc = np.multiply(E[:, None, :], dW, order="C")  # (m, loops, links): d(x + i y)/d theta
    return Jc.view(float).reshape(m, nl, n, 2).transpose(0, 1, 3, 2).reshape(m, 2 * nl, n)


def _c(X) -> complex:
    return complex(X[0], X[1])
