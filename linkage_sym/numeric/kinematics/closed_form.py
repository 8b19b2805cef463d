"""Closed-form solvers of input links and of the five dyad types.

Every solver works on whole sweeps at once (NumPy arrays over the steps) and
fills the :class:`~linkage_sym.numeric.kinematics.state.LinkState` of its links in three
calls: ``position``, ``velocity``, ``acceleration``.  ``position`` returns a
*conditioning indicator* per step: a dimensionless number that vanishes
where the group's own Jacobian is singular (sine of the transmission angle,
half-chord over radius, ...), NaN where the group cannot be assembled.

The assembly mode (branch) of a dyad is the sign ``sigma`` of its closed
form, fixed once from the assembly configuration.  Along a branch ``sigma``
equals the sign of the group's constraint-Jacobian determinant up to a
constant factor, so keeping ``sigma`` keeps the spec's assembly mode, also
across a gap of unassemblable steps.
"""

from __future__ import annotations

import math

import numpy as np

from linkage_sym.errors import SceneError
from linkage_sym.model import GROUND, Scene
from linkage_sym.numeric.continuation import change_points, messages
from linkage_sym.numeric.kinematics.loci import (
    Circle,
    Line,
    clamp_tangent,
    coordinate_size,
    circle_circle,
    circle_line,
    line_line,
    solve2,
)
from linkage_sym.numeric.results.passages import PassageNote
from linkage_sym.structure import Group

ASSEMBLY_TOL = 1e-12
"""Relative size below which the assembly configuration's branch sign is undefined."""
EPS = float(np.finfo(float).eps)
COINCIDE_ULPS = 64.0
"""An RRR dyad's outer joints closer than this many units of rounding of the mechanism's
coordinates coincide: its inner joint's position is undefined there (unassemblable)."""


def coincide_tolerance(scene: Scene, E0, J0, E1) -> float:
    """Distance (m) within which the outer joints ``E0``, ``E1`` of an RRR dyad with inner
    joint ``J0`` (their points in the assembly configuration) coincide:
    :data:`COINCIDE_ULPS` units of rounding of the mechanism's coordinates."""
    size = max(abs(v) for j in scene.joints for v in j.at) + math.dist(J0, E0) \
        + math.dist(J0, E1)
    return COINCIDE_ULPS * EPS * size


def _other(joint, link):
    a, b = joint.links
    return b if a == link else a


def _sub(p, q):
    return p[0] - q[0], p[1] - q[1]


def _cross(a, b):
    return a[0] * b[1] - a[1] * b[0]


def _at(point, i):
    """Component values of a point at step ``i`` (a fixed point has scalar components)."""
    return tuple(float(np.asarray(v)[i]) if np.ndim(v) else float(v) for v in point)


def _set_from_point(st, Y, X):
    """Place a link whose rotation is set so that its local point X is at Y."""
    rx, ry = st.rot(X)
    st.dx, st.dy = Y[0] - rx, Y[1] - ry


def _set_vel_from_point(st, vY, X):
    rx, ry = st.rot(X)
    st.vx, st.vy = vY[0] + st.w * ry, vY[1] - st.w * rx


def _set_acc_from_point(st, aY, X):
    rx, ry = st.rot(X)
    w2 = st.w * st.w
    st.ax = aY[0] + st.al * ry + w2 * rx
    st.ay = aY[1] - st.al * rx + w2 * ry


class InputSolver:
    """A link set directly by a driver on its joint with a known link.

    The stages take the driver values ``q``, ``qd``, ``qdd`` (dicts of arrays
    keyed by driven joint) over the steps being solved.
    """

    notes = ()
    """Jumps worth a warning: none (a closed form keeps its assembly mode by its sign)."""

    def __init__(self, scene: Scene, group: Group, phi0):
        (self.link,) = group.links
        (dname,) = group.drivers
        j = scene.joint(dname)
        self.group = group
        self.name = dname
        self.kind = j.type
        self.X = j.at
        self.known = _other(j, self.link)
        # an input turning on the ground takes the driver value itself, never wrapped
        self.wraps = self.known != GROUND
        # +1 when the unknown link is the joint's links[1]
        self.sign = 1.0 if j.links[1] == self.link else -1.0
        if self.kind == "R":
            self.phi0 = phi0[dname]
        else:
            self.u0 = (math.cos(j.axis), math.sin(j.axis))

    def position(self, S, q):
        k, u = S[self.known], S[self.link]
        qq = q[self.name]
        if self.kind == "R":
            u.set_pose(k.th + self.sign * (qq - self.phi0), 0.0, 0.0)
            _set_from_point(u, k.point(self.X), self.X)
        else:
            ux, uy = k.rot(self.u0)
            u.set_pose(k.th, k.dx + self.sign * qq * ux, k.dy + self.sign * qq * uy, k.c, k.s)
        return None  # always assemblable, never singular

    def velocity(self, S, q, qd):
        k, u = S[self.known], S[self.link]
        v = qd[self.name]
        if self.kind == "R":
            u.w = k.w + self.sign * v
            _set_vel_from_point(u, k.point_velocity(self.X), self.X)
        else:
            # d_u = d_k + sign q u_k  ->  v_u = v_k + sign (qd u + q w perp(u))
            u.w = k.w
            ux, uy = k.rot(self.u0)
            qq, s = q[self.name], self.sign
            u.vx = k.vx + s * (v * ux - qq * k.w * uy)
            u.vy = k.vy + s * (v * uy + qq * k.w * ux)

    def acceleration(self, S, q, qd, qdd):
        k, u = S[self.known], S[self.link]
        a = qdd[self.name]
        if self.kind == "R":
            u.al = k.al + self.sign * a
            _set_acc_from_point(u, k.point_acceleration(self.X), self.X)
        else:
            # a_u = a_k + sign (qdd u + 2 qd w perp(u) + q (al perp(u) - w^2 u))
            u.al = k.al
            ux, uy = k.rot(self.u0)
            qq, v, s, w, al = q[self.name], qd[self.name], self.sign, k.w, k.al
            u.ax = k.ax + s * (a * ux - 2 * v * w * uy + qq * (-al * uy - w * w * ux))
            u.ay = k.ay + s * (a * uy + 2 * v * w * ux + qq * (al * ux - w * w * uy))


class DyadSolver:
    """Closed-form solver of a dyad of type RRR, RRP, RPR, PRP or RPP.

    The stages keep no state between calls: the velocity and acceleration
    stages read the geometry back from the link states, so positions can be
    solved on a longer path (assembly configuration to first step, refined
    steps) than the steps whose rates are wanted.
    """

    notes = ()
    wraps = True  # rotations from atan2
    """Jumps worth a warning: none (a closed form keeps its assembly mode by its sign), but
    for a dyad of two slides (``PRP``, ``RPP``) the passages of its joint through infinity
    (the slides parallel) between two solved path points of the last ``position`` call, and
    for an RRR dyad whose outer joints can meet its change points there (set by the plan once
    the groups' positions are solved: :meth:`change_points`)."""

    meets = False
    """Whether the dyad is an RRR whose links are equally long (to rounding): its outer joints
    can meet, at a change point (:meth:`change_points`)."""

    def __init__(self, scene: Scene, group: Group):
        self.group = group
        self.type = t = group.dyad_type
        b0, b1 = group.links
        e0, ji, e1 = (scene.joint(n) for n in group.joints)
        self.links = (b0, b1)
        self.k0, self.k1 = _other(e0, b0), _other(e1, b1)
        self.E0, self.E1, self.J0 = E0, E1, J0 = e0.at, e1.at, ji.at
        self.names = (e0.name, ji.name, e1.name)
        # which link of the dyad turns about an external revolute ("pivot", with its circle)
        # and which takes its rotation from a known link through a prismatic joint ("slide")
        if t == "RRR":
            self.loci = (Circle(self.k0, E0, math.dist(J0, E0)), Circle(self.k1, E1, math.dist(J0, E1)))
            self.sigma = self._branch(_cross(_sub(E1, E0), _sub(J0, E0)), math.dist(E0, E1) ** 2)
            # outer joints that coincide to rounding (equal links crossing a change point):
            # the two circles are one, the inner joint anywhere on it, and the half-chord's
            # formula has lost every digit (the distance is at the rounding of the radii);
            # no configuration is defined there, as where the distance is exactly zero
            self.coincide_tol = coincide_tolerance(scene, E0, J0, E1)
            # links equally long (to rounding): the outer joints can meet, a change point
            self.meets = abs(self.loci[0].r - self.loci[1].r) <= self.coincide_tol
        elif t == "RRP":
            circle, line = Circle(self.k0, E0, math.dist(J0, E0)), Line(self.k1, J0, e1.axis)
            self.loci = (circle, line)
            # Y = F + sigma h u, F the foot of the perpendicular from the centre:
            # sigma = sign(u.(J0 - F)) = sign(u.(J0 - E0)) in the assembly configuration
            self.sigma = self._branch(
                (J0[0] - E0[0]) * line.u0[0] + (J0[1] - E0[1]) * line.u0[1], circle.r
            )
        elif t == "PRP":
            self.loci = (Line(self.k0, J0, e0.axis), Line(self.k1, J0, e1.axis))
            self.sigma = 1.0
            self.slides = (e0.name, e1.name)
        elif t == "RPP":
            self.loci = (Line(b0, J0, ji.axis), Line(self.k1, J0, e1.axis))
            self.sigma = 1.0
            self.slides = (ji.name, e1.name)
        elif t == "RPR":
            self.n0 = (-math.sin(ji.axis), math.cos(ji.axis))
            D0 = _sub(E1, E0)
            self.h = self.n0[0] * D0[0] + self.n0[1] * D0[1]
            self.sigma = self._branch(_cross(D0, self.n0), math.hypot(*D0))
        else:  # pragma: no cover - structure refuses other types
            raise ValueError(t)
        self.pivots = {"RRR": (0, 1), "RRP": (0,)}.get(t, ())
        self.driver_kinds = {d.joint: scene.joint(d.joint).type for d in scene.drivers}
        # links (by index) whose rotation a prismatic joint copies from a known link
        self.copied = {
            "RRP": ((1, self.k1),),
            "PRP": ((0, self.k0), (1, self.k1)),
            "RPP": ((0, self.k1), (1, self.k1)),
        }.get(t, ())

    def _branch(self, value, scale):
        if abs(value) <= ASSEMBLY_TOL * scale:
            b0, b1 = self.links
            raise SceneError(
                [
                    f"joints: the assembly configuration is a singular position of the "
                    f"dyad {self.type} ({b0}, {b1}): its assembly mode is undefined; "
                    "move the joints' `at` points off the dead-centre position"
                ]
            )
        return 1.0 if value > 0 else -1.0

    def _copy_rotations(self, S, b0, b1):
        """Set the rotations a prismatic joint copies; place RPP's pinned link."""
        for i, k in self.copied:
            ks = S[k]
            (b0 if i == 0 else b1).set_pose(ks.th, 0.0, 0.0, ks.c, ks.s)
        if self.type == "RPP":
            _set_from_point(b0, S[self.k0].point(self.E0), self.E0)

    # -- positions ---------------------------------------------------------
    def position(self, S, q):
        t = self.type
        b0, b1 = S[self.links[0]], S[self.links[1]]
        if t == "RPR":
            return self._rpr_position(S, b0, b1)
        self._copy_rotations(S, b0, b1)
        c0, c1 = self.loci
        if t == "RRR":
            C0, C1 = c0.center(S), c1.center(S)
            Yx, Yy, h, d = circle_circle(C0, c0.r, C1, c1.r, self.sigma)
            ind = h * d / (c0.r * c1.r)  # sine of the angle between the two links
            coincide = d <= self.coincide_tol
            if np.any(coincide):
                ind = np.where(coincide, np.nan, ind)
            centres = (C0, C1)
            if self.meets:  # for change_points, after the groups' positions
                self.outer = (C1[0] - C0[0], C1[1] - C0[1])
        elif t == "RRP":
            C0 = c0.center(S)
            Yx, Yy, h = circle_line(C0, c0.r, *c1.frame(S), self.sigma)
            ind = h / c0.r  # cosine of the angle between link and slide normal
            centres = (C0,)
        else:  # PRP, RPP: two lines (NaN where they are parallel)
            Yx, Yy, ind = line_line(*c0.frame(S), *c1.frame(S))
            self.notes = self._crossings(ind, q)
            centres = ()
        for i, C in zip(self.pivots, centres):
            v = (Yx - C[0], Yy - C[1])
            v0 = _sub(self.J0, self.E0 if i == 0 else self.E1)
            st = b0 if i == 0 else b1
            cr, dt = _cross(v0, v), v0[0] * v[0] + v0[1] * v[1]
            # cos and sin of the rotation from the two vectors: no transcendental call
            with np.errstate(invalid="ignore", divide="ignore"):
                scale = 1.0 / (math.hypot(*v0) * np.hypot(v[0], v[1]))
            st.set_pose(np.arctan2(cr, dt), 0.0, 0.0, dt * scale, cr * scale)
        _set_from_point(b1, (Yx, Yy), self.J0)
        if t != "RPP":
            _set_from_point(b0, (Yx, Yy), self.J0)
        return np.abs(ind)

    def change_points(self, q, ind, upstream) -> list:
        """The notes of the change points of an RRR dyad whose outer joints can meet
        (:attr:`meets`) between consecutive solved points of the last ``position`` call
        (:mod:`linkage_sym.numeric.continuation.change_points`), each ``(first point past
        it, text(step))``.

        ``q`` are the driver values of that call, ``ind`` its indicator; ``upstream(qs)``
        solves the groups before the dyad at the driver values ``qs`` into a new state
        (``None``: they have no closed form, and only path points where the joints coincide
        are found).
        """
        K = len(next(iter(q.values())))
        e = tuple(np.broadcast_to(np.asarray(v, float), (K,)) for v in self.outer)
        solved = np.isfinite(np.broadcast_to(ind, (K,)))
        own = ~solved & np.isfinite(e[0]) & np.isfinite(e[1])  # the groups before it solved

        def evaluate(qs):
            S = upstream(qs)
            C0, C1 = (c.center(S) for c in self.loci)
            return C1[0] - C0[0], C1[1] - C0[1]

        kinds = {k: self.driver_kinds.get(k, "R") for k in q}
        names = (f"dyad {self.type} ({self.links[0]}, {self.links[1]})",
                 (self.names[0], self.names[2]), self.names[1], self.links)
        return change_points.change_point_notes(e, solved, own, self.coincide_tol, q, kinds,
                                                None if upstream is None else evaluate, names)

    def _crossings(self, cross, q) -> list:
        """The notes of the sign changes of the slides' cross product ``cross`` between
        consecutive solved path points (the slides parallel between them: the joint
        passes through infinity), each ``(first point past it, text(step))``."""
        cross = np.asarray(cross)
        if cross.ndim == 0:
            return []  # two fixed slide directions: never parallel along the path
        solved = np.flatnonzero(np.isfinite(cross))
        side = cross[solved] > 0
        kinds = {k: self.driver_kinds.get(k, "R") for k in q}
        head = f"dyad {self.type} ({self.links[0]}, {self.links[1]})"
        out = []
        for k in np.flatnonzero(side[1:] != side[:-1]):
            a, b = int(solved[k]), int(solved[k + 1])
            before = messages.driver_values_text(q, kinds, a)
            after = messages.driver_values_text(q, kinds, b)
            out.append(PassageNote(b, lambda step, before=before, after=after: messages.parallel_note(
                head, self.slides, self.names[1], before, after, step), self.names[1]))
        return out

    def _rpr_position(self, S, b0, b1):
        E0 = S[self.k0].point(self.E0)
        E1 = S[self.k1].point(self.E1)
        Dx, Dy = E1[0] - E0[0], E1[1] - E0[1]
        D2 = Dx * Dx + Dy * Dy
        h = self.h
        with np.errstate(invalid="ignore", divide="ignore"):
            dd = np.sqrt(D2)
            f1, f2 = dd - h, dd + h
            prod = clamp_tangent(f1 * f2, (f1, f2), lambda: coordinate_size(h, *E0, *E1))
            w = np.sqrt(prod)
            # unit normal n of the slide with n.D = h, on the branch sigma = sign(cross(D, n))
            nx = (h * Dx - self.sigma * w * Dy) / D2
            ny = (h * Dy + self.sigma * w * Dx) / D2
            ind = w / dd
        n0x, n0y = self.n0
        # n and n0 are unit vectors: cos and sin of the rotation without a transcendental call
        c, s = n0x * nx + n0y * ny, n0x * ny - n0y * nx
        th = np.arctan2(s, c)
        for st, E, X in ((b0, E0, self.E0), (b1, E1, self.E1)):
            st.set_pose(th, 0.0, 0.0, c, s)
            _set_from_point(st, E, X)
        return ind

    # -- velocities --------------------------------------------------------
    def _locus_frames(self, S):
        return [loc.frame(S) if isinstance(loc, Line) else loc.center(S) for loc in self.loci]

    def velocity(self, S, q, qd):
        t = self.type
        b0, b1 = S[self.links[0]], S[self.links[1]]
        if t == "RPR":
            return self._rpr_rates(S, b0, b1, acc=False)
        for i, k in self.copied:
            (b0 if i == 0 else b1).w = S[k].w
        if t == "RPP":
            _set_vel_from_point(b0, S[self.k0].point_velocity(self.E0), self.E0)
        Y = b1.point(self.J0)
        geo = self._locus_frames(S)
        (a1x, a1y, r1, _), (a2x, a2y, r2, _) = (
            loc.vel_row(S, Y, g) for loc, g in zip(self.loci, geo)
        )
        vY = solve2(a1x, a1y, r1, a2x, a2y, r2)
        for i in self.pivots:
            loc, C = self.loci[i], geo[i]
            vC = S[loc.link].point_velocity(loc.C)
            st = b0 if i == 0 else b1
            with np.errstate(invalid="ignore"):
                st.w = ((Y[0] - C[0]) * (vY[1] - vC[1]) - (Y[1] - C[1]) * (vY[0] - vC[0])) / (
                    loc.r * loc.r
                )
        _set_vel_from_point(b1, vY, self.J0)
        if t != "RPP":
            _set_vel_from_point(b0, vY, self.J0)

    # -- accelerations -----------------------------------------------------
    def acceleration(self, S, q, qd, qdd):
        t = self.type
        b0, b1 = S[self.links[0]], S[self.links[1]]
        if t == "RPR":
            return self._rpr_rates(S, b0, b1, acc=True)
        for i, k in self.copied:
            (b0 if i == 0 else b1).al = S[k].al
        if t == "RPP":
            _set_acc_from_point(b0, S[self.k0].point_acceleration(self.E0), self.E0)
        Y = b1.point(self.J0)
        vY = b1.point_velocity(self.J0)
        geo = self._locus_frames(S)
        rows = []
        for loc, g in zip(self.loci, geo):
            vg = S[loc.link].point_velocity(loc.C if isinstance(loc, Circle) else loc.Q)
            rows.append(loc.acc_row(S, Y, vY, g, vg))
        (a1x, a1y, r1), (a2x, a2y, r2) = rows
        aY = solve2(a1x, a1y, r1, a2x, a2y, r2)
        for i in self.pivots:
            loc, C = self.loci[i], geo[i]
            aC = S[loc.link].point_acceleration(loc.C)
            st = b0 if i == 0 else b1
            with np.errstate(invalid="ignore"):
                st.al = ((Y[0] - C[0]) * (aY[1] - aC[1]) - (Y[1] - C[1]) * (aY[0] - aC[0])) / (
                    loc.r * loc.r
                )
        _set_acc_from_point(b1, aY, self.J0)
        if t != "RPP":
            _set_acc_from_point(b0, aY, self.J0)

    def _rpr_rates(self, S, b0, b1, acc):
        k0, k1 = S[self.k0], S[self.k1]
        E0, E1 = k0.point(self.E0), k1.point(self.E1)
        Dx, Dy = E1[0] - E0[0], E1[1] - E0[1]
        nx, ny = b0.rot(self.n0)
        v0, v1 = k0.point_velocity(self.E0), k1.point_velocity(self.E1)
        Vx, Vy = v1[0] - v0[0], v1[1] - v0[1]
        cr = nx * Dy - ny * Dx  # cross(n, D)
        if not acc:
            # d/dt (n.D) = 0 with dn/dt = w perp(n):  w cross(n, D) + n.V = 0
            with np.errstate(invalid="ignore", divide="ignore"):
                w = -(nx * Vx + ny * Vy) / cr
            for st, v, X in ((b0, v0, self.E0), (b1, v1, self.E1)):
                st.w = w
                _set_vel_from_point(st, v, X)
            return
        a0, a1 = k0.point_acceleration(self.E0), k1.point_acceleration(self.E1)
        Ax, Ay = a1[0] - a0[0], a1[1] - a0[1]
        w = b0.w
        # al cross(n, D) - w^2 n.D + 2 w perp(n).V + n.A = 0, with n.D = h
        pv = -ny * Vx + nx * Vy
        with np.errstate(invalid="ignore", divide="ignore"):
            al = (w * w * self.h - 2 * w * pv - (nx * Ax + ny * Ay)) / cr
        for st, a, X in ((b0, a0, self.E0), (b1, a1, self.E1)):
            st.al = al
            _set_acc_from_point(st, a, X)

    # -- messages ----------------------------------------------------------
    def failure(self, S, i) -> str:
        """Why step ``i`` cannot be assembled (the known links' states are valid there)."""
        b0, b1 = self.links
        e0, ji, e1 = self.names
        head = f"dyad {self.type} ({b0}, {b1})"
        if self.type == "RRR":
            C0, C1 = (_at(c.center(S), i) for c in self.loci)
            d = math.hypot(C1[0] - C0[0], C1[1] - C0[1])
            r0, r1 = self.loci[0].r, self.loci[1].r
            if d <= self.coincide_tol and abs(r0 - r1) <= self.coincide_tol:
                return (
                    f"{head}: joints {e0} and {e1} coincide (to rounding): joint {ji} can be "
                    f"anywhere on one circle about them, so no configuration is defined here"
                )
            return (
                f"{head}: joints {e0} and {e1} are {d:.6g} m apart, outside the reach "
                f"[{abs(r0 - r1):.6g}, {r0 + r1:.6g}] m of links {b0} and {b1}"
            )
        if self.type == "RRP":
            return f"{head}: link {b0} ({self.loci[0].r:.6g} m) cannot reach the slide of joint {e1}"
        if self.type == "RPR":
            return (
                f"{head}: joints {e0} and {e1} are closer than the offset "
                f"{abs(self.h):.6g} m of the slide of joint {ji}"
            )
        return messages.parallel_failure(head, self.slides)
