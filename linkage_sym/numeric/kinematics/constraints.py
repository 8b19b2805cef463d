"""The constraint equations of joints and drivers, in pose coordinates.

Each moving link has the coordinates ``(dx, dy, theta)`` of its pose.  A
joint or driver contributes rows ``Phi = 0``; this module evaluates, for any
set of rows and over all steps at once:

* ``residual``  ``Phi`` (positions),
* ``rate``      ``dPhi/dt`` (linear in the velocities),
* ``accel``     ``d2Phi/dt2`` (linear in the accelerations),
* ``jac``       ``dPhi/d(dx, dy, theta)`` of one link.

The velocity problem of a group is ``J v = -rate(v_group = 0)`` and the
acceleration problem ``J a = -accel(a_group = 0)``: the right-hand sides come
from the same expressions with the group's own unknown rates set to zero, so
no separate ``Phi_q`` or ``gamma`` has to be derived and kept in step.

Rows are scaled for a dimensionless Jacobian (spec: lengths divided by the
largest distance between two joints): a row measured in metres is divided by
``L``, the ``dx, dy`` columns multiplied by ``L``.
"""

from __future__ import annotations

import math

import numpy as np



def _dot(ax, ay, bx, by):
    return ax * bx + ay * by


class Constraint:
    """Base class: rows contributed by one joint or driver."""

    rows = 2
    length_rows: tuple[bool, ...] = (True, True)
    links: tuple[str, str]

    def involves(self, link: str) -> bool:
        return link in self.links


class RJoint(Constraint):
    """Revolute joint: the point ``X`` of both links coincides."""

    def __init__(self, a, b, X):
        self.links = (a, b)
        self.X = X

    def residual(self, S, q):
        a, b = S[self.links[0]], S[self.links[1]]
        pax, pay = a.point(self.X)
        pbx, pby = b.point(self.X)
        return [pax - pbx, pay - pby]

    def rate(self, S, qd):
        a, b = S[self.links[0]], S[self.links[1]]
        vax, vay = a.point_velocity(self.X)
        vbx, vby = b.point_velocity(self.X)
        return [vax - vbx, vay - vby]

    def accel(self, S, qdd):
        a, b = S[self.links[0]], S[self.links[1]]
        aax, aay = a.point_acceleration(self.X)
        abx, aby = b.point_acceleration(self.X)
        return [aax - abx, aay - aby]

    def jac(self, S, link):
        sign = 1.0 if link == self.links[0] else -1.0
        rx, ry = S[link].rot(self.X)
        return [(sign, 0.0, -sign * ry), (0.0, sign, sign * rx)]


class PJoint(Constraint):
    """Prismatic joint: no relative rotation; no relative offset normal to the axis."""

    length_rows = (False, True)

    def __init__(self, a, b, axis):
        self.links = (a, b)
        self.n0 = (-math.sin(axis), math.cos(axis))

    def _parts(self, S):
        a, b = S[self.links[0]], S[self.links[1]]
        nx, ny = a.rot(self.n0)
        return a, b, nx, ny, b.dx - a.dx, b.dy - a.dy

    def residual(self, S, q):
        a, b, nx, ny, Dx, Dy = self._parts(S)
        return [b.th - a.th, _dot(nx, ny, Dx, Dy)]

    def rate(self, S, qd):
        a, b, nx, ny, Dx, Dy = self._parts(S)
        Vx, Vy = b.vx - a.vx, b.vy - a.vy
        # d/dt n = w_a perp(n), perp(n) = (-ny, nx)
        return [b.w - a.w, a.w * _dot(-ny, nx, Dx, Dy) + _dot(nx, ny, Vx, Vy)]

    def accel(self, S, qdd):
        a, b, nx, ny, Dx, Dy = self._parts(S)
        Vx, Vy = b.vx - a.vx, b.vy - a.vy
        Ax, Ay = b.ax - a.ax, b.ay - a.ay
        w = a.w
        ndd_x, ndd_y = -a.al * ny - w * w * nx, a.al * nx - w * w * ny
        return [
            b.al - a.al,
            _dot(ndd_x, ndd_y, Dx, Dy) + 2 * w * _dot(-ny, nx, Vx, Vy) + _dot(nx, ny, Ax, Ay),
        ]

    def jac(self, S, link):
        a, b, nx, ny, Dx, Dy = self._parts(S)
        if link == self.links[1]:
            return [(0.0, 0.0, 1.0), (nx, ny, 0.0)]
        return [(0.0, 0.0, -1.0), (-nx, -ny, _dot(-ny, nx, Dx, Dy))]


class GMesh(Constraint):
    """Gear mesh (a higher pair, one row): rolling without slip on a carrier.

    ``ra (theta_a - theta_c) + kb (theta_b - theta_c) = 0`` with ``kb = rb``
    for an external mesh and ``-rb`` for an internal one; the angles are the
    links' rotations from the assembly configuration, so the row is linear
    and homogeneous in them (a length row: radii times angles).
    """

    rows = 1
    length_rows = (True,)

    def __init__(self, a, b, c, radii, internal):
        self.links = (a, b, c)
        ra, rb = radii
        self.k = (ra, -rb if internal else rb, -(ra + (-rb if internal else rb)))

    def _row(self, S, field):
        return sum(k * getattr(S[n], field) for k, n in zip(self.k, self.links))

    def residual(self, S, q):
        return [self._row(S, "th")]

    def rate(self, S, qd):
        return [self._row(S, "w")]

    def accel(self, S, qdd):
        return [self._row(S, "al")]

    def jac(self, S, link):
        return [(0.0, 0.0, self.k[self.links.index(link)])]


class RDriver(Constraint):
    """Driven revolute joint: ``theta_b - theta_a + phi0 = q``."""

    rows = 1
    length_rows = (False,)

    def __init__(self, a, b, phi0, name):
        self.links = (a, b)
        self.phi0 = phi0
        self.name = name

    def residual(self, S, q):
        a, b = S[self.links[0]], S[self.links[1]]
        return [b.th - a.th + self.phi0 - q[self.name]]

    def rate(self, S, qd):
        a, b = S[self.links[0]], S[self.links[1]]
        return [b.w - a.w - qd[self.name]]

    def accel(self, S, qdd):
        a, b = S[self.links[0]], S[self.links[1]]
        return [b.al - a.al - qdd[self.name]]

    def jac(self, S, link):
        return [(0.0, 0.0, 1.0 if link == self.links[1] else -1.0)]


class PDriver(Constraint):
    """Driven prismatic joint: displacement ``u_a . (d_b - d_a) = q``."""

    rows = 1
    length_rows = (True,)

    def __init__(self, a, b, axis, name):
        self.links = (a, b)
        self.u0 = (math.cos(axis), math.sin(axis))
        self.name = name

    def _parts(self, S):
        a, b = S[self.links[0]], S[self.links[1]]
        ux, uy = a.rot(self.u0)
        return a, b, ux, uy, b.dx - a.dx, b.dy - a.dy

    def residual(self, S, q):
        a, b, ux, uy, Dx, Dy = self._parts(S)
        return [_dot(ux, uy, Dx, Dy) - q[self.name]]

    def rate(self, S, qd):
        a, b, ux, uy, Dx, Dy = self._parts(S)
        Vx, Vy = b.vx - a.vx, b.vy - a.vy
        return [a.w * _dot(-uy, ux, Dx, Dy) + _dot(ux, uy, Vx, Vy) - qd[self.name]]

    def accel(self, S, qdd):
        a, b, ux, uy, Dx, Dy = self._parts(S)
        Vx, Vy = b.vx - a.vx, b.vy - a.vy
        Ax, Ay = b.ax - a.ax, b.ay - a.ay
        w = a.w
        udd_x, udd_y = -a.al * uy - w * w * ux, a.al * ux - w * w * uy
        return [
            _dot(udd_x, udd_y, Dx, Dy)
            + 2 * w * _dot(-uy, ux, Vx, Vy)
            + _dot(ux, uy, Ax, Ay)
            - qdd[self.name]
        ]

    def jac(self, S, link):
        a, b, ux, uy, Dx, Dy = self._parts(S)
        if link == self.links[1]:
            return [(ux, uy, 0.0)]
        return [(-ux, -uy, _dot(-uy, ux, Dx, Dy))]


def stack_rows(values) -> np.ndarray:
    """Stack per-row arrays/scalars into an array of shape (N, rows)."""
    arrs = np.broadcast_arrays(*[np.asarray(v, dtype=float) for v in values])
    return np.stack(arrs, axis=-1)


def jacobian(constraints, S, links, n_steps, L=None) -> np.ndarray:
    """Jacobian ``(n_steps, rows, 3 * len(links))`` of ``constraints`` wrt ``links``' poses.

    With ``L`` given, rows and columns are scaled to make it dimensionless.
    """
    nrows = sum(c.rows for c in constraints)
    # each (row, column) entry comes from one constraint and one link (a joint joins
    # two different links), so the entries are gathered and written in one assignment;
    # constant zeros are skipped
    rr, cc, vals = [], [], []
    r = 0
    for c in constraints:
        for k, name in enumerate(links):
            if not c.involves(name):
                continue
            for i, row in enumerate(c.jac(S, name)):
                for m in range(3):
                    v = row[m]
                    if type(v) is float and v == 0.0:
                        continue
                    rr.append(r + i)
                    cc.append(3 * k + m)
                    vals.append(v)
        r += c.rows
    J = np.zeros((n_steps, nrows, 3 * len(links)))
    if vals:
        V = np.empty((len(vals), n_steps))
        for e, v in enumerate(vals):
            V[e] = v
        J[:, rr, cc] = V.T
    if L is not None:
        length_rows = np.concatenate([c.length_rows for c in constraints])
        rs = np.where(length_rows, 1.0 / L, 1.0)
        cs = np.tile([L, L, 1.0], len(links))
        J *= rs[None, :, None] * cs[None, None, :]
    return J
