"""Motion state of one link over the steps of a sweep, and of its points.

A link's frame coincides with the global frame in the assembly
configuration, so a point of the link is named by its assembly position
``X`` (its *local* coordinates).  Its global position at a step is
``d + R(theta) X``; velocities and accelerations follow from the link's
``omega``/``alpha`` and the velocity/acceleration of its origin ``d``.

All fields are NumPy arrays of shape ``(N,)`` (or Python floats for the
ground, which broadcast).

The rate fields (``w, vx, vy, al, ax, ay``) can be *bound* to rows of a
result block (:meth:`LinkState.bind_rates`): a value assigned to a bound
field is written into its row, so a solver's output lands in the result
without a separate array or a later copy.
"""

from __future__ import annotations

import numpy as np


RATES = ("w", "vx", "vy", "al", "ax", "ay")


def _rate_field(name):
    slot = "_" + name

    def get(self):
        return getattr(self, slot)

    def set(self, value):
        row = self._rows.get(name) if self._rows else None
        if row is not None:
            row[...] = value
            value = row
            if name in self._pending:
                self._pending.remove(name)
        setattr(self, slot, value)

    return property(get, set, doc=f"``{name}`` (written into its row when bound)")


class LinkState:
    """Pose, velocity and acceleration of one link (component arrays)."""

    __slots__ = ("th", "c", "s", "dx", "dy", "_rot", "_rows", "_pending") + tuple("_" + n for n in RATES)
    _fields = ("th", "c", "s", "dx", "dy") + RATES
    w, vx, vy, al, ax, ay = (_rate_field(n) for n in RATES)

    def __init__(self, th=0.0, dx=0.0, dy=0.0):
        self._rows = None
        self._pending = ()
        self.set_pose(th, dx, dy)
        self.w = self.vx = self.vy = 0.0
        self.al = self.ax = self.ay = 0.0

    def bind_rates(self, rows: dict):
        """Write the rate fields named in ``rows`` into those arrays from now on.

        A field keeps its current value until it is set; :meth:`fill_rates`
        then writes the value of every field never set into its row.
        """
        self._rows = dict(rows)
        self._pending = set(rows)

    def fill_rates(self):
        """Write the value of every bound field never set since binding into its row."""
        for name in self._pending:
            row = self._rows[name]
            row[...] = getattr(self, name)
            setattr(self, "_" + name, row)
        self._pending = ()

    def set_pose(self, th, dx, dy, c=None, s=None):
        self.th = th
        self.c = np.cos(th) if c is None else c
        self.s = np.sin(th) if s is None else s
        self.dx = dx
        self.dy = dy
        self._rot = {}  # R(theta) X for the points asked so far: each is needed 3-4 times

    def rot(self, X):
        """``R(theta) X`` as two component arrays (cached until the pose changes)."""
        r = self._rot.get(X)
        if r is None:
            x, y = X
            c, s = self.c, self.s
            r = self._rot[X] = (c * x - s * y, s * x + c * y)
        return r

    def point(self, X):
        """Global position of the link point with local coordinates ``X``."""
        rx, ry = self.rot(X)
        return self.dx + rx, self.dy + ry

    def point_velocity(self, X):
        rx, ry = self.rot(X)
        w = self.w
        return self.vx - w * ry, self.vy + w * rx

    def point_acceleration(self, X):
        rx, ry = self.rot(X)
        w2, al = self.w * self.w, self.al
        return self.ax - al * ry - w2 * rx, self.ay + al * rx - w2 * ry

    # -- writing into given rows (no temporaries): the result assembly ------
    def point_into(self, X, ox, oy):
        """Write :meth:`point` into the arrays ``ox, oy``."""
        rx, ry = self.rot(X)
        np.add(self.dx, rx, out=ox)
        np.add(self.dy, ry, out=oy)

    def point_velocity_into(self, X, ox, oy):
        """Write :meth:`point_velocity` into the arrays ``ox, oy``."""
        rx, ry = self.rot(X)
        np.multiply(self.w, ry, out=ox)
        np.subtract(self.vx, ox, out=ox)
        np.multiply(self.w, rx, out=oy)
        np.add(self.vy, oy, out=oy)

    def point_acceleration_into(self, X, ox, oy, w2, tmp):
        """Write :meth:`point_acceleration` into ``ox, oy``; ``w2`` is ``w*w``, ``tmp`` scratch."""
        rx, ry = self.rot(X)
        al = self.al
        np.multiply(al, ry, out=ox)
        np.subtract(self.ax, ox, out=ox)
        np.multiply(w2, rx, out=tmp)
        np.subtract(ox, tmp, out=ox)
        np.multiply(al, rx, out=oy)
        np.add(self.ay, oy, out=oy)
        np.multiply(w2, ry, out=tmp)
        np.subtract(oy, tmp, out=oy)

    def take(self, idx) -> "LinkState":
        """The state at a subset of steps (fancy or boolean index)."""
        out = LinkState.__new__(LinkState)
        out._rows = None
        out._pending = ()
        for name in self._fields:
            v = getattr(self, name)
            setattr(out, name, v[idx] if isinstance(v, np.ndarray) else v)
        out._rot = {}
        return out

