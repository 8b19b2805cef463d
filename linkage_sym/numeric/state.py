"""Motion state of one link over the steps of a sweep, and of its points.

A link's frame coincides with the global frame in the assembly
configuration, so a point of the link is named by its assembly position
``X`` (its *local* coordinates).  Its global position at a step is
``d + R(theta) X``; velocities and accelerations follow from the link's
``omega``/``alpha`` and the velocity/acceleration of its origin ``d``.

All fields are NumPy arrays of shape ``(N,)`` (or Python floats for the
ground, which broadcast).
"""

from __future__ import annotations

import numpy as np


class LinkState:
    """Pose, velocity and acceleration of one link (component arrays)."""

    __slots__ = ("th", "c", "s", "dx", "dy", "w", "vx", "vy", "al", "ax", "ay", "_rot")
    _fields = ("th", "c", "s", "dx", "dy", "w", "vx", "vy", "al", "ax", "ay")

    def __init__(self, th=0.0, dx=0.0, dy=0.0):
        self.set_pose(th, dx, dy)
        self.w = self.vx = self.vy = 0.0
        self.al = self.ax = self.ay = 0.0

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

    def take(self, idx) -> "LinkState":
        """The state at a subset of steps (fancy or boolean index)."""
        out = LinkState.__new__(LinkState)
        for name in self._fields:
            v = getattr(self, name)
            setattr(out, name, v[idx] if isinstance(v, np.ndarray) else v)
        out._rot = {}
        return out

