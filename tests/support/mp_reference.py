"""A 50-digit reference of any scene, written without linkage_sym's solvers.

For any scene (read with ``linkage_sym.load_scene``: data only) and the steps of an
Analysis, :func:`reference` solves the scene format's own equations in mpmath:

* **positions**: every moving link's pose ``(dx, dy, theta)`` (the link point at the
  global origin in the assembly configuration, and the rotation from it), from the
  constraint equations of the format (an R joint's point coincides on both links; a P
  joint keeps the relative rotation and the offset normal to its axis; an R driver sets
  the angle of ``joint -> toward`` from ``links[0]``'s axis, a P driver the displacement
  along the axis), by Newton's method started from the Analysis' own rotations and
  origins (so it finds the root nearest the one being checked: the error measured is the
  distance to the nearest exact configuration);
* **rates**: ``J zd = qd`` and ``J zdd = qdd - (dJ/dt) zd`` (mpmath LU);
* **forces**: every moving link's force and moment balance (about the origin) with
  every joint reaction and driver effort unknown, one mpmath LU solve per step (the
  "global" statement, not the solver's group-by-group one); conventions of the format:
  a reaction is the force ``links[0]`` exerts on ``links[1]`` at the joint's point; a P
  joint carries a force along the slide normal (the axis turned by +90 degrees, fixed on
  ``links[0]``) and a couple; an effort acts on ``links[1]``; the frame loads are what
  the moving links exert on the ground, moments about the origin.

The returned records mirror the Analysis: ``links[name]`` (rotation, omega, alpha, origin,
com and its rates), ``joints[name]`` (position, velocity, acceleration), ``points``,
``reactions``, ``reaction_moments``, ``driving``, ``frame`` (fx, fy, m).
"""

from __future__ import annotations

import mpmath as mp
import numpy as np

GROUND = "ground"
NEWTON_ITER = 40


def _f(x):
    return mp.mpf(float(x))


def _rot(th, p):
    c, s = mp.cos(th), mp.sin(th)
    return c * p[0] - s * p[1], s * p[0] + c * p[1]


class _Pose:
    def __init__(self, dx=0, dy=0, th=0):
        self.dx, self.dy, self.th = mp.mpf(dx), mp.mpf(dy), mp.mpf(th)
        self.vx = self.vy = self.w = mp.mpf(0)
        self.ax = self.ay = self.al = mp.mpf(0)

    def point(self, X):
        rx, ry = _rot(self.th, X)
        return self.dx + rx, self.dy + ry

    def velocity(self, X):
        rx, ry = _rot(self.th, X)
        return self.vx - self.w * ry, self.vy + self.w * rx

    def acceleration(self, X):
        rx, ry = _rot(self.th, X)
        w2 = self.w * self.w
        return self.ax - self.al * ry - w2 * rx, self.ay + self.al * rx - w2 * ry


class Reference:
    """The scene's equations in mpmath (see the module docstring)."""

    def __init__(self, scene, digits=50):
        self.scene = scene
        self.digits = digits
        self.links = list(scene.link_names)
        self.col = {n: 3 * k for k, n in enumerate(self.links)}
        self.n = 3 * len(self.links)
        self.drivers = {d.joint: d for d in scene.drivers}
        with mp.workdps(digits + 10):
            self.at = {j.name: (_f(j.at[0]), _f(j.at[1])) for j in scene.joints}
            self.phi0 = {}
            for d in scene.drivers:
                j = scene.joint(d.joint)
                if j.type == "R":
                    J, T = self.at[d.joint], self.at[d.toward]
                    phi = mp.atan2(T[1] - J[1], T[0] - J[0])
                    # the representative nearest the sweep's start (the format's rule)
                    self.phi0[d.joint] = phi + 2 * mp.pi * mp.nint((_f(d.start) - phi) / (2 * mp.pi))

    # -- equations ----------------------------------------------------------------
    def _rows(self, P, q):
        """Residuals and Jacobian rows ``[(value, {col: deriv})]``."""
        out = []
        for j in self.scene.joints:
            a, b = j.links
            A, B = P[a], P[b]
            if j.type == "R":
                X = self.at[j.name]
                pa, pb = A.point(X), B.point(X)
                ra, rb = _rot(A.th, X), _rot(B.th, X)
                for k in (0, 1):
                    d = {}
                    if a != GROUND:
                        d[self.col[a] + k] = 1
                        d[self.col[a] + 2] = -ra[1] if k == 0 else ra[0]
                    if b != GROUND:
                        d[self.col[b] + k] = -1
                        d[self.col[b] + 2] = rb[1] if k == 0 else -rb[0]
                    out.append((pa[k] - pb[k], d))
            else:
                ax = _f(j.axis)
                d = {}
                if b != GROUND:
                    d[self.col[b] + 2] = 1
                if a != GROUND:
                    d[self.col[a] + 2] = -1
                out.append((B.th - A.th, d))
                n = _rot(A.th, (-mp.sin(ax), mp.cos(ax)))
                out.append(self._along(A, B, a, b, n, 0))
            if j.name in self.drivers:
                if j.type == "R":
                    d = {}
                    if b != GROUND:
                        d[self.col[b] + 2] = 1
                    if a != GROUND:
                        d[self.col[a] + 2] = -1
                    out.append((B.th - A.th + self.phi0[j.name] - q[j.name], d))
                else:
                    ax = _f(j.axis)
                    u = _rot(A.th, (mp.cos(ax), mp.sin(ax)))
                    out.append(self._along(A, B, a, b, u, q[j.name]))
        return out

    def _along(self, A, B, a, b, u, q):
        """``u . (d_b - d_a) - q`` with ``u`` fixed on link ``a``, and its derivatives."""
        Dx, Dy = B.dx - A.dx, B.dy - A.dy
        d = {}
        if b != GROUND:
            d[self.col[b]], d[self.col[b] + 1] = u[0], u[1]
        if a != GROUND:
            d[self.col[a]], d[self.col[a] + 1] = -u[0], -u[1]
            d[self.col[a] + 2] = -u[1] * Dx + u[0] * Dy
        return u[0] * Dx + u[1] * Dy - q, d

    def _matrix(self, rows):
        J = mp.matrix(len(rows), self.n)
        for i, (_, d) in enumerate(rows):
            for c, v in d.items():
                J[i, c] += v
        return J

    def _second(self, P):
        """``(dJ/dt) zd`` of every row (the terms of d2(Phi)/dt2 without accelerations)."""
        out = []
        for j in self.scene.joints:
            a, b = j.links
            A, B = P[a], P[b]
            if j.type == "R":
                X = self.at[j.name]
                ra, rb = _rot(A.th, X), _rot(B.th, X)
                for k in (0, 1):
                    out.append(-A.w ** 2 * ra[k] + B.w ** 2 * rb[k])
            else:
                ax = _f(j.axis)
                out.append(mp.mpf(0))
                out.append(self._along2(A, B, _rot(A.th, (-mp.sin(ax), mp.cos(ax)))))
            if j.name in self.drivers:
                if j.type == "R":
                    out.append(mp.mpf(0))
                else:
                    ax = _f(j.axis)
                    out.append(self._along2(A, B, _rot(A.th, (mp.cos(ax), mp.sin(ax)))))
        return out

    @staticmethod
    def _along2(A, B, u):
        Dx, Dy = B.dx - A.dx, B.dy - A.dy
        Vx, Vy = B.vx - A.vx, B.vy - A.vy
        w = A.w
        return -w * w * (u[0] * Dx + u[1] * Dy) + 2 * w * (-u[1] * Vx + u[0] * Vy)

    # -- one step -------------------------------------------------------------------
    def solve(self, res, i, q=None):
        """The reference at step ``i`` of Analysis ``res`` (``None`` if Newton fails), at its
        float64 driver values, or at ``q`` (``{driver: value}``, e.g. mpf) if given."""
        with mp.workdps(self.digits + 10):
            return self._solve(res, i, q)

    def _solve(self, res, i, q=None):
        scene = self.scene
        if q is None:
            q = {k: _f(v["q"][i]) for k, v in res.drivers.items()}
        qd = {k: _f(v["qd"][i]) for k, v in res.drivers.items()}
        qdd = {k: _f(v["qdd"][i]) for k, v in res.drivers.items()}
        P = {GROUND: _Pose()}
        for n in self.links:
            lk = res.links[n]
            P[n] = _Pose(_f(lk.origin[i, 0]), _f(lk.origin[i, 1]), _f(lk.rotation[i]))
        L = _f(scene.characteristic_length() or 1.0)
        tol = mp.mpf(10) ** (-self.digits - 5)
        for _ in range(NEWTON_ITER):
            rows = self._rows(P, q)
            J = self._matrix(rows)
            dz = mp.lu_solve(J, mp.matrix([r for r, _ in rows]))
            for n in self.links:
                c = self.col[n]
                P[n].dx -= dz[c]
                P[n].dy -= dz[c + 1]
                P[n].th -= dz[c + 2]
            if max(abs(dz[k]) / (L if k % 3 < 2 else 1) for k in range(self.n)) <= tol:
                break
        else:
            return None
        rows = self._rows(P, q)
        J = self._matrix(rows)
        out = {"links": {}, "joints": {}, "points": {}}
        rates = res.status[i] == "ok" and res.links[self.links[0]].omega is not None
        if rates:
            rhs = []
            for j in scene.joints:
                rhs += [mp.mpf(0)] * (2 if j.type == "R" else 2)
                if j.name in self.drivers:
                    rhs.append(qd[j.name])
            zd = mp.lu_solve(J, mp.matrix(rhs))
            for n in self.links:
                c = self.col[n]
                P[n].vx, P[n].vy, P[n].w = zd[c], zd[c + 1], zd[c + 2]
            sec = self._second(P)
            rhs, k = [], 0
            for j in scene.joints:
                for _ in range(2):
                    rhs.append(-sec[k])
                    k += 1
                if j.name in self.drivers:
                    rhs.append(qdd[j.name] - sec[k])
                    k += 1
            zdd = mp.lu_solve(J, mp.matrix(rhs))
            for n in self.links:
                c = self.col[n]
                P[n].ax, P[n].ay, P[n].al = zdd[c], zdd[c + 1], zdd[c + 2]
        for link in scene.links:
            n = link.name
            p = P[n]
            rec = {"rotation": p.th, "origin": (p.dx, p.dy)}
            if rates:
                rec.update(omega=p.w, alpha=p.al, origin_velocity=(p.vx, p.vy),
                           origin_acceleration=(p.ax, p.ay))
            if link.com is not None:
                X = (_f(link.com[0]), _f(link.com[1]))
                rec["com"] = p.point(X)
                if rates:
                    rec["com_velocity"], rec["com_acceleration"] = p.velocity(X), p.acceleration(X)
            out["links"][n] = rec
        for name, link, X in ([(j.name, j.links[1], self.at[j.name]) for j in scene.joints]
                              + [(pt.name, pt.link, (_f(pt.at[0]), _f(pt.at[1])))
                                 for pt in scene.points]):
            p = P[link]
            rec = {"position": p.point(X)}
            if rates:
                rec["velocity"], rec["acceleration"] = p.velocity(X), p.acceleration(X)
            out["joints" if name in self.at else "points"][name] = rec
        if rates and res.forces is not None:
            out.update(self._forces(P, out))
        out["cond"] = _cond(J, self.links, scene, L)
        return out

    # -- forces ---------------------------------------------------------------------
    def _forces(self, P, kin):
        scene = self.scene
        eff = scene.effects
        unknowns = []  # (kind, name)
        for j in scene.joints:
            unknowns += [("R" if j.type == "R" else "N", j.name), ("Ry" if j.type == "R" else "M", j.name)]
        for d in scene.drivers:
            unknowns.append(("E", d.joint))
        uidx = {u: k for k, u in enumerate(unknowns)}
        row = {n: 3 * k for k, n in enumerate(self.links)}
        M = mp.matrix(self.n, len(unknowns))
        rhs = [mp.mpf(0)] * self.n

        def add_force(link, col, fx, fy, at):
            """Unknown ``col`` times force ``(fx, fy)`` at point ``at`` on ``link``."""
            if link == GROUND:
                return
            r = row[link]
            M[r, col] += fx
            M[r + 1, col] += fy
            M[r + 2, col] += at[0] * fy - at[1] * fx

        def add_couple(link, col, c):
            if link != GROUND:
                M[row[link] + 2, col] += c

        def load(link, fx, fy, at, couple=0):
            r = row[link]
            rhs[r] -= fx
            rhs[r + 1] -= fy
            rhs[r + 2] -= at[0] * fy - at[1] * fx + couple

        for j in scene.joints:
            a, b = j.links
            p = kin["joints"][j.name]["position"]
            if j.type == "R":
                cx, cy = uidx["R", j.name], uidx["Ry", j.name]
                for link, s in ((b, 1), (a, -1)):
                    add_force(link, cx, s, 0, p)
                    add_force(link, cy, 0, s, p)
            else:
                ax = _f(j.axis)
                nx, ny = _rot(P[a].th, (-mp.sin(ax), mp.cos(ax)))
                cn, cm = uidx["N", j.name], uidx["M", j.name]
                for link, s in ((b, 1), (a, -1)):
                    add_force(link, cn, s * nx, s * ny, p)
                    add_couple(link, cm, s)
            if j.name in self.drivers:
                ce = uidx["E", j.name]
                if j.type == "R":
                    add_couple(b, ce, 1)
                    add_couple(a, ce, -1)
                else:
                    ax = _f(j.axis)
                    ux, uy = _rot(P[a].th, (mp.cos(ax), mp.sin(ax)))
                    add_force(b, ce, ux, uy, p)
                    add_force(a, ce, -ux, -uy, p)
        g = eff.gravity
        for link in scene.links:
            n = link.name
            rec = kin["links"][n]
            m = _f(link.mass)
            if link.com is not None and m != 0:
                G = rec["com"]
                if g is not None:
                    load(n, m * _f(g[0]), m * _f(g[1]), G)
                if eff.inertia:
                    aG = rec["com_acceleration"]
                    load(n, -m * aG[0], -m * aG[1], G)
            if eff.inertia and link.inertia:
                load(n, 0, 0, (0, 0), -_f(link.inertia) * rec["alpha"])
        if eff.loads:
            for ld in scene.loads:
                p = P[ld.link]
                if ld.force is not None:
                    at = p.point((_f(ld.at[0]), _f(ld.at[1])))
                    load(ld.link, _f(ld.force[0]), _f(ld.force[1]), at)
                if ld.torque:
                    load(ld.link, 0, 0, (0, 0), _f(ld.torque))
        x = mp.lu_solve(M, mp.matrix(rhs))
        reactions, moments, driving = {}, {}, {}
        fx = fy = mz = mp.mpf(0)
        for j in scene.joints:
            a, b = j.links
            p = kin["joints"][j.name]["position"]
            if j.type == "R":
                F, c = (x[uidx["R", j.name]], x[uidx["Ry", j.name]]), mp.mpf(0)
            else:
                ax = _f(j.axis)
                nx, ny = _rot(P[a].th, (-mp.sin(ax), mp.cos(ax)))
                N = x[uidx["N", j.name]]
                F, c = (N * nx, N * ny), x[uidx["M", j.name]]
            reactions[j.name], moments[j.name] = F, c
            if j.name in self.drivers:
                e = x[uidx["E", j.name]]
                driving[j.name] = e
                if j.type == "R":
                    c = c + e
                else:
                    ax = _f(j.axis)
                    ux, uy = _rot(P[a].th, (mp.cos(ax), mp.sin(ax)))
                    F = (F[0] + e * ux, F[1] + e * uy)
            if GROUND in j.links:
                s = 1 if b == GROUND else -1  # what the moving link puts on the ground
                fx += s * F[0]
                fy += s * F[1]
                mz += s * (p[0] * F[1] - p[1] * F[0] + c)
        return {"reactions": reactions, "reaction_moments": moments, "driving": driving,
                "frame": (fx, fy, mz)}


def _cond(J, links, scene, L):
    """Dimensionless condition number of the pose Jacobian (lengths over L), in float."""
    Jf = np.array(J.tolist(), dtype=float)
    rows = []
    for j in scene.joints:
        rows += [True, True] if j.type == "R" else [False, True]
        if j.name in {d.joint for d in scene.drivers}:
            rows.append(j.type == "P")
    Lf = float(L)
    Jf = Jf * np.where(rows, 1 / Lf, 1.0)[:, None] * np.tile([Lf, Lf, 1.0], len(links))[None, :]
    s = np.linalg.svd(Jf, compute_uv=False)
    return float(s[0] / s[-1]) if s[-1] > 0 else float("inf")


def reference(scene, res, steps=None, digits=50):
    """:meth:`Reference.solve` at ``steps`` (default: every step with positions)."""
    ref = Reference(scene, digits)
    steps = range(res.n_steps) if steps is None else steps
    return {i: (ref.solve(res, i) if res.status[i] != "unassemblable" else None) for i in steps}
