"""Newton groups in loop-closure coordinates: the links' angles and the slides.

A group whose joints are revolute, prismatic or gear meshes (a class-III
triad, the printing mechanism's triad with its slider, an actuator group with
its driven slide, a gear train's arm and planet, a class-IV group, ...) is solved in its links' angles and its slides
alone, the symbolic layer's unknowns, rows and order
(:meth:`linkage_sym.symbolic.mechanism.MechanismEquations._group`): each link
is placed from a link already placed through one of its joints (a spanning
tree taken in the group's joint order; through a P joint the slide is added
along the guide, which turns with the joint's ``links[0]``); every other
joint closes a loop, two rows (``P_a(J) - P_b(J)`` for R,
``P_b(J) - P_a(J) - s u`` for P) with each side reached along the tree; every
P joint adds its angle row ``theta_b - theta_a = 0`` (angles from the
assembly configuration), every gear mesh its rolling row (linear in the
angles; a mesh places no link) and every driver its row (``theta_b -
theta_a + phi0 - q`` for R, ``s - q`` for P).  For the triad that is 4
unknowns and 4 rows where pose coordinates have 12
(:class:`linkage_sym.numeric.kinematics.newton.NewtonSolver`, kept for groups with a
cam contact or any other row).  The symbolic layer writes a mesh's row among
the loops, in joint order; here the meshes follow the P joints' angle rows,
so the two runtimes' rows are the same up to that order.

**The linear form.**  With points as complex numbers, ``E_k = e^{i theta_k}``
and ``G_j`` the turn of slide ``j``'s guide (a group link's ``E`` or a known
link's), every point is ``E @ M + (s G) @ V + K``: ``M`` and ``V`` complex
constants made once from the tree, ``K`` the known links' points combined.
The rows are one such form (and the angle rows linear in ``theta``), so
residual and Jacobian are a few products per evaluation: ``d/dtheta_k = i
E_k M[k] + i s_j G_j V[j]`` for the slides ``j`` that link ``k`` guides,
``d/ds_j = G_j V[j]``.  The continuation (predictor, damped Newton, the
assembly mode's determinant sign, limits, re-entry searches) is
:mod:`linkage_sym.numeric.continuation`'s, unchanged.

**Rates** from the same form, differentiated: ``dE/dt = i omega E``,
``dG/dt = i omega_g G``; the velocity and acceleration problems have the
position Jacobian as their matrix, and each link's origin follows from its own
form.
"""

from __future__ import annotations

import numpy as np

from linkage_sym.numeric.continuation.roots import indicator, inverses
from linkage_sym.numeric.kinematics.constraints import GMesh, PJoint, RJoint
from linkage_sym.numeric.kinematics.newton import SINGULAR_IND, NewtonSolver, PoseProblem


def applies(scene, group, constraints) -> bool:
    """Whether ``group`` is solved in loop-closure coordinates: revolute and prismatic
    joints (with their drivers: an actuator's driven slide) and gear meshes."""
    return all(
        isinstance(constraints[n].joint, (RJoint, PJoint, GMesh))
        and scene.joint(n).type in ("R", "P", "G")
        for n in group.joints)


class _Form:
    """Points ``E @ M + (s G) @ V + K`` (complex), one column per point: ``M`` (links,
    points), ``V`` (slides, points), ``Ksel`` (known points, points) their signs."""

    def __init__(self, M, V, Ksel):
        self.M, self.V, self.Ksel = M, V, Ksel


class LoopClosureSolver(NewtonSolver):
    """A Newton group of R and P joints solved in its angles and slides (module docstring)."""

    def __init__(self, scene, group, constraints, L):
        super().__init__(scene, group, constraints, L)
        joints = [scene.joint(n) for n in group.joints]
        links = list(group.links)
        used = self._place_tree(scene, joints, links)
        self.column = {n: links.index(n) for n in links}  # unknown k: theta of links[k]
        self.n_links = len(links)
        self.prismatic = [J for J in joints if J.type == "P"]
        self.slide = {J.name: self.n_links + j for j, J in enumerate(self.prismatic)}
        self.guide = [J.links[0] for J in self.prismatic]  # each slide turns with its guide
        self.nvar = self.n_links + len(self.prismatic)
        self.loops = [J for k, J in enumerate(joints) if k not in used and J.type != "G"]
        meshes = [constraints[J.name].joint for J in joints if J.type == "G"]
        self.keys = []  # (link, X) of the known links' points used
        rows = []
        for J in self.loops:
            a, b = J.links
            pa, pb = self._point(a, J.at), self._point(b, J.at)
            if J.type == "R":
                rows.append(_combine(pa, pb, -1.0))
            else:  # P_b - P_a - s u(theta_a)
                row = _combine(pb, pa, -1.0)
                row[1][J.name] = row[1].get(J.name, 0.0) - np.exp(1j * J.axis)
                rows.append(row)
        origins = [self._point(n, (0.0, 0.0)) for n in links]
        # the forms after every point is written: they hold a row for every known point
        self.rows, self.origins = self._form(rows), self._form(origins)
        self._linear_rows(scene, group, constraints, meshes)
        self.lin_scale = np.where(self.lin_length, 1.0 / L, 1.0)
        self.guide_known = [g for g in dict.fromkeys(self.guide) if g not in self.column]
        # the dimensionless problem's constants: loop rows over L
        self.M_L = self.rows.M / L
        self.dM = np.ascontiguousarray(1j * self.rows.M.T / L)  # (rows, links)
        self.VT = np.ascontiguousarray(self.rows.V.T)  # (rows, slides)
        # rows over L and slides over L: the physical problem's rows times row_scale, its
        # unknowns over col_scale
        nr = self.rows.M.shape[1]
        self.row_scale = np.r_[np.full(2 * nr, 1.0 / L), self.lin_scale]
        self.col_scale = np.r_[np.ones(self.n_links), np.full(len(self.prismatic), L)]

    def _place_tree(self, scene, joints, links) -> set:
        """The spanning tree: each link placed through the first joint (group order) that
        joins it to a link already placed (``anchor``); returns the joints used, by index."""
        placed = {n for n in [*scene.link_names, "ground"] if n not in links}
        pending = list(links)
        used = set()
        self.anchor = {}  # link -> (joint, the link it is placed from)
        while pending:
            for k, J in enumerate(joints):
                if k in used or J.type == "G":  # a mesh places no link
                    continue
                a, b = J.links
                if (a in placed) != (b in placed) and (a in pending or b in pending):
                    new, old = (b, a) if a in placed else (a, b)
                    self.anchor[new] = (J, old)
                    placed.add(new)
                    pending.remove(new)
                    used.add(k)
                    break
            else:  # pragma: no cover - a group is always connected to solved links
                raise ValueError(f"group {links} is not connected to solved links")
        return used

    def _linear_rows(self, scene, group, constraints, meshes) -> None:
        """The linear rows, after the loops: each P joint's angle row ``theta_b - theta_a``,
        each mesh's rolling row ``r_a (th_a - th_c) +- r_b (th_b - th_c)`` (a length), then
        each driver's row (R: ``theta_b - theta_a + phi0 - q``; P: ``s - q``, a length); on
        the group's angles (``T``) and slides (``Ts``), the known links' angles
        (``T_known``), a constant and the driver."""
        drivers = [d for d in scene.drivers if d.joint in group.drivers]
        nlin = len(self.prismatic) + len(meshes) + len(drivers)
        self.T = np.zeros((self.n_links, nlin))
        self.Ts = np.zeros((len(self.prismatic), nlin))
        self.T_known = []
        self.lin_const = np.zeros(nlin)
        self.lin_length = np.zeros(nlin, bool)
        self.lin_driver = []  # (row, driver joint)

        def angle_terms(r, links, coefs):
            for link, k in zip(links, coefs):
                if link in self.column:
                    self.T[self.column[link], r] += k
                else:
                    self.T_known.append((r, link, k))

        for r, J in enumerate(self.prismatic):
            angle_terms(r, J.links, (-1.0, 1.0))
        for r, mesh in enumerate(meshes, start=len(self.prismatic)):
            angle_terms(r, mesh.links, mesh.k)
            self.lin_length[r] = True
        for r, d in enumerate(drivers, start=len(self.prismatic) + len(meshes)):
            J = scene.joint(d.joint)
            self.lin_driver.append((r, d.joint))
            if J.type == "R":
                angle_terms(r, J.links, (-1.0, 1.0))
                self.lin_const[r] = constraints[d.joint].driver.phi0
            else:
                self.Ts[self.slide[J.name] - self.n_links, r] = 1.0
                self.lin_length[r] = True

    # -- the linear form -------------------------------------------------------
    def _point(self, link, X):
        """Point ``X`` of ``link`` as ``({group link: c}, {slide: w}, {known key: sign})``."""
        if link not in self.column:  # a known link
            if (link, X) not in self.keys:
                self.keys.append((link, X))
            return {}, {}, {self.keys.index((link, X)): 1.0}
        J, parent = self.anchor[link]
        XA = J.at
        coef, slides, known = self._point(parent, XA)
        coef, slides = dict(coef), dict(slides)
        if J.type == "P":  # the slide along the guide, away from links[0]
            w = np.exp(1j * J.axis) * (1.0 if link == J.links[1] else -1.0)
            slides[J.name] = slides.get(J.name, 0.0) + w
        coef[link] = coef.get(link, 0.0) + _c(X) - _c(XA)
        return coef, slides, known

    def _form(self, points) -> _Form:
        M = np.zeros((self.n_links, len(points)), complex)
        V = np.zeros((len(self.prismatic), len(points)), complex)
        Ksel = np.zeros((len(self.keys), len(points)))
        for col, (coef, slides, known) in enumerate(points):
            for n, v in coef.items():
                M[self.column[n], col] = v
            for name, v in slides.items():
                V[self.slide[name] - self.n_links, col] = v
            for k, v in known.items():
                Ksel[k, col] = v
        return _Form(M, V, Ksel)

    def known_points(self, S, rate=None) -> np.ndarray:
        """The known links' points (complex) in ``S`` -- or their velocities or
        accelerations (``rate``: ``"point_velocity"``, ``"point_acceleration"``): (N, keys),
        or (1, keys) if all are constant."""
        cols = [getattr(S[link], rate or "point")(X) for link, X in self.keys]
        n = max([np.size(v) for xy in cols for v in xy] + [1])
        out = np.empty((n, len(cols)), complex)
        for k, (x, y) in enumerate(cols):
            out[:, k].real, out[:, k].imag = x, y
        return out

    def known_turns(self, S, field="th") -> dict:
        """Each known guide's (or angle row's) ``field`` in ``S``."""
        return {n: getattr(S[n], field) for n in
                dict.fromkeys([*self.guide_known, *(l for _, l, _ in self.T_known)])}

    def _per_guide(self, group, known):
        """(m, slides): for each slide, its guide's value -- the column of ``group`` (m,
        links) for a group link, ``known[g]`` for a known one."""
        out = np.empty((len(group), len(self.guide)), group.dtype)
        for j, g in enumerate(self.guide):
            out[:, j] = group[:, self.column[g]] if g in self.column else known[g]
        return out

    def _guides(self, E, known_th):
        """``G`` (m, slides): the turn of each slide's guide."""
        return self._per_guide(E, {g: np.exp(1j * known_th[g]) for g in self.guide_known})

    def _linear_known(self, known, q, m):
        """The linear rows' part without the group's unknowns (physical units): the known
        links' angles ``known``, the constants, minus the drivers' values ``q``."""
        return self._linear_rates(known, q, m) + self.lin_const

    def _linear_rates(self, known, qrate, m):
        """The linear rows' rate with the group's rates zero: the known links' rates
        ``known`` minus the drivers' rates ``qrate`` (without the constants)."""
        out = np.zeros((m, self.T.shape[1]))
        for r, link, sign in self.T_known:
            out[:, r] += sign * known[link]
        for r, name in self.lin_driver:
            out[:, r] -= qrate[name]
        return out

    def scaled_jacobian(self, E, us, G):
        """``d rows / d u`` (m, rows, nvar) of the dimensionless problem: loop rows over
        ``L``, angle rows as they are, unknowns the angles and the slides over ``L``
        (``us``).  ``d/dtheta_k = i E_k M[k] / L + i us_j G_j V[j]`` (the slides that
        link ``k`` guides), ``d/dus_j = G_j V[j]``."""
        f, nl, ns = self.rows, self.n_links, len(self.prismatic)
        nlin = self.T.shape[1]
        if not nlin:
            return _real_jacobian(E, self.dM)
        m, nr = len(E), f.M.shape[1]
        J = np.empty((m, 2 * nr + nlin, self.nvar))
        if nr:
            Jc = np.empty((m, nr, self.nvar), complex)
            np.multiply(E[:, None, :], self.dM, out=Jc[:, :, :nl])
            turn = (1j * us * G)[:, :, None] * f.V[None]  # (m, slides, rows)
            for j, g in enumerate(self.guide):
                if g in self.column:
                    Jc[:, :, self.column[g]] += turn[:, j, :]
            np.multiply(G[:, None, :], self.VT, out=Jc[:, :, nl:])
            J[:, :2 * nr] = Jc.view(float).reshape(m, nr, self.nvar, 2).transpose(
                0, 1, 3, 2).reshape(m, 2 * nr, self.nvar)
        J[:, 2 * nr:, :nl] = self.T.T * self.lin_scale[:, None]
        J[:, 2 * nr:, nl:] = self.Ts.T * (self.lin_scale * self.L)[:, None]
        return J

    # -- positions -----------------------------------------------------------
    def _problem(self, S, q):
        return _AngleProblem(self, S, q)

    def _set_poses(self, S, problem, sol):
        for n, (th, dx, dy, c, s) in problem.poses(sol.u).items():
            S[n].set_pose(th, dx, dy, c, s)

    # -- rates -----------------------------------------------------------------
    def _state(self, S):
        """The group's angles' ``E``, slides ``s`` and guides' ``G`` at the steps (from the
        poses of ``S``)."""
        n_steps = len(S[self.links[0]].c)
        E = np.empty((n_steps, self.n_links), complex)
        for n, k in self.column.items():
            E[:, k].real, E[:, k].imag = S[n].c, S[n].s
        G = self._guides(E, self.known_turns(S))
        s = np.empty((n_steps, len(self.prismatic)))
        for j, J in enumerate(self.prismatic):
            a, b = S[J.links[0]], S[J.links[1]]
            pa, pb = a.point(J.at), b.point(J.at)  # b's reference point from a's
            ux, uy = G[:, j].real * np.cos(J.axis) - G[:, j].imag * np.sin(J.axis), \
                G[:, j].imag * np.cos(J.axis) + G[:, j].real * np.sin(J.axis)
            s[:, j] = (pb[0] - pa[0]) * ux + (pb[1] - pa[1]) * uy
        return E, s, G

    def _rate_block(self, S):
        """The dimensionless rate matrix's inverse at the steps and where it is solvable (its
        indicator above :data:`SINGULAR_IND`); made once for the velocities and the
        accelerations (the same poses)."""
        cached = self._rates_cache
        th = [S[n].th for n in self.column]
        if cached is not None and all(a is b for a, b in zip(cached[0], th)):
            return cached[1]
        E, s, G = self._state(S)
        J = self.scaled_jacobian(E, s / self.L, G)
        finite = np.isfinite(J).all(axis=(1, 2))
        if not finite.all():
            J = np.where(finite[:, None, None], J, np.eye(self.nvar))
        inv = inverses(J)
        solvable = finite & (indicator(J, inv) > SINGULAR_IND)
        block = (E, s, G, inv, solvable)
        self._rates_cache = (th, block)
        return block

    def _solve(self, S, which, qrate):
        """The velocity or acceleration problem: ``J x = -(the rows' rate with x = 0)``, ``x``
        the angular rates and slide rates; then every link's rates from the form."""
        E, s, G, inv, solvable = self._rate_block(S)
        n_steps, nl = len(E), self.n_links
        f, o = self.rows, self.origins
        velocity = which == "velocity"
        Kd = self.known_points(S, "point_velocity" if velocity else "point_acceleration")
        wk = self.known_turns(S, "w")
        if velocity:
            known_rates = wk
        else:
            ak = known_rates = self.known_turns(S, "al")
            w = np.stack([S[n].w for n in self.column], axis=1)
            wg = self._per_guide(w, wk)  # the guides' angular velocities, all known now
            sdot = self._slide_rates  # the velocity stage's

        def rate(form, x):
            """The form's velocity or acceleration with the group's angular rates and slide
            rates ``x``: ``dE/dt = i omega E``, ``dG/dt = i omega_g G``."""
            om, sr = x[:, :nl], x[:, nl:]
            if velocity:
                return ((1j * om * E) @ form.M + ((sr + s * 1j * self._per_guide(om, wk)) * G)
                        @ form.V + Kd @ form.Ksel)
            alg = self._per_guide(om, ak)
            return (((1j * om - w * w) * E) @ form.M
                    + ((sr + 2 * sdot * 1j * wg + s * (1j * alg - wg * wg)) * G) @ form.V
                    + Kd @ form.Ksel)

        # the right-hand side: the rows' rate with the group's own rates zero
        nr = f.M.shape[1]
        rhs = np.empty((n_steps, 2 * nr + self.T.shape[1]))
        rhs[:, :2 * nr] = _interleave(rate(f, np.zeros((n_steps, self.nvar))), n_steps)
        rhs[:, 2 * nr:] = self._linear_rates(known_rates, qrate, n_steps)
        np.negative(rhs, out=rhs)
        x = np.full((n_steps, self.nvar), np.nan)
        idx = np.flatnonzero(solvable & np.isfinite(rhs).all(axis=1))
        if len(idx):  # the physical problem through the dimensionless one's inverse
            every = len(idx) == n_steps
            Ji, r = (inv, rhs) if every else (inv[idx], rhs[idx])
            x[idx] = np.einsum("kij,kj->ki", Ji, r * self.row_scale) * self.col_scale
        om = x[:, :nl]
        O = rate(o, x)  # every link's origin from its form, differentiated
        if velocity:
            self._slide_rates = x[:, nl:]
        for n, k in self.column.items():
            st = S[n]
            if velocity:
                st.w, st.vx, st.vy = om[:, k], O[:, k].real, O[:, k].imag
            else:
                st.al, st.ax, st.ay = om[:, k], O[:, k].real, O[:, k].imag

    def velocity(self, S, q, qd):
        self._solve(S, "velocity", qd)

    def acceleration(self, S, q, qd, qdd):
        self._solve(S, "acceleration", qdd)
        self._rates_cache = None
        self._slide_rates = None


class _AngleProblem(PoseProblem):
    """A group of R and P joints in its angles and slides, for
    :func:`continuation.solve_path`.

    Unknowns ``u``: the angles of ``group.links`` (radians) and the slides over
    ``L``; rows: the loop-closing joints' two coordinates over ``L``, then the P
    joints' angle rows, in the group's joint order (:class:`LoopClosureSolver`).
    The known links' points and turns are taken once along the whole path (the
    batched walk indexes them).
    """

    def __init__(self, solver: LoopClosureSolver, S, q):
        super().__init__(solver, S, q)
        self.scale = np.r_[np.ones(solver.n_links), np.full(len(solver.prismatic), solver.L)]
        self.angles = np.r_[np.ones(solver.n_links, bool), np.zeros(len(solver.prismatic), bool)]
        self.path_keys = solver.known_points(self.known)  # (K or 1, keys)
        self.path_th = solver.known_turns(self.known)
        self.K_loops = self.path_keys @ solver.rows.Ksel / solver.L
        n = len(next(iter(q.values())))
        self.path_linear = (solver._linear_known(self.path_th, q, n) * solver.lin_scale
                            if solver.T.shape[1] else None)

    def _rows(self, U, K, known_th, lin):
        """Residual and Jacobian of the dimensionless problem; ``K`` the known points'
        part of the loop rows over ``L``, ``lin`` the linear rows' known part (scaled)."""
        sv = self.sv
        nl = sv.n_links
        if not sv.T.shape[1]:
            E = np.exp(1j * U)
            return (E @ sv.M_L + K).view(float), _real_jacobian(E, sv.dM)
        E = np.exp(1j * U[:, :nl])
        us = U[:, nl:]
        G = sv._guides(E, known_th)
        nr = sv.rows.M.shape[1]
        R = np.empty((len(U), 2 * nr + sv.T.shape[1]))
        Rc = E @ sv.M_L + K
        if sv.prismatic:
            Rc = Rc + (us * G) @ sv.rows.V
        R[:, :2 * nr] = Rc.view(float)
        R[:, 2 * nr:] = (U[:, :nl] @ sv.T + us @ sv.Ts * sv.L) * sv.lin_scale + lin
        return R, sv.scaled_jacobian(E, us, G)

    def evaluate_many(self, U, ctx):
        Sk = ctx[0]
        sv = self.sv
        th = sv.known_turns(Sk)
        lin = sv._linear_known(th, ctx[1], 1) * sv.lin_scale if sv.T.shape[1] else None
        return self._rows(U, sv.known_points(Sk) @ sv.rows.Ksel / sv.L, th, lin)

    def evaluate_points(self, U, idx):
        K = self.K_loops[idx] if len(self.K_loops) > 1 else self.K_loops
        th = {n: (v[idx] if np.ndim(v) else v) for n, v in self.path_th.items()}
        lin = None if self.path_linear is None else self.path_linear[idx]
        return self._rows(U, K, th, lin)

    def poses(self, U):
        """Each group link's ``(theta, dx, dy, cos, sin)`` at every path point (``U``: the
        solution's rows; NaN rows stay NaN)."""
        sv = self.sv
        nl = sv.n_links
        E = np.exp(1j * U[:, :nl])
        o = sv.origins
        O = E @ o.M + self.path_keys @ o.Ksel
        if len(sv.prismatic):
            O = O + (U[:, nl:] * sv.L * sv._guides(E, self.path_th)) @ o.V
        return {n: (U[:, k], O[:, k].real, O[:, k].imag, E[:, k].real, E[:, k].imag)
                for n, k in sv.column.items()}


def _combine(p, q, sign):
    """The form ``p + sign q`` of two points."""
    out = []
    for a, b in zip(p, q):
        d = dict(a)
        for k, v in b.items():
            d[k] = d.get(k, 0.0) + sign * v
        out.append(d)
    return out


def _real_jacobian(E, dM):
    """The real Jacobian (m, 2 loops, links) of the rows ``E @ M`` from ``dM = i M^T``
    (times a scale): the x and y rows of each loop in turn."""
    m, (nl, n) = len(E), dM.shape
    Jc = np.multiply(E[:, None, :], dM, order="C")  # (m, loops, links): d(x + i y)/d theta
    return Jc.view(float).reshape(m, nl, n, 2).transpose(0, 1, 3, 2).reshape(m, 2 * nl, n)


def _interleave(Z, n):
    """Complex (n or 1, r) as real (n, 2 r): x and y of each in turn."""
    Z = np.ascontiguousarray(np.broadcast_to(Z, (n, Z.shape[-1])))
    return Z.view(float)


def _c(X) -> complex:
    return complex(X[0], X[1])
