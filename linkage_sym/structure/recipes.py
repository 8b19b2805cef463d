"""Parameter recipes: how each named parameter is read off a scene, in any number type.

A recipe is what :class:`~linkage_sym.structure.parameters.ParameterTable` registers for
each named parameter (``l_BC`` is the distance from the coupler's frame origin to
``C``...).  It is written into a compiled mechanism's artifact as a tuple (its
:attr:`Recipe.key`, e.g. ``("l", "coupler", "C")``) and read back by
:meth:`Recipe.of`.  :meth:`Recipe.value` evaluates it on a scene with a *number type*
(:class:`Numbers`): binary64 floats by default (:data:`FLOAT`), or mpmath numbers for
``--precision`` (:class:`linkage_sym.codegen.precision.MpNumbers`) -- one definition of
every parameter for every number type, each scene number taken as the binary64 number
it is.

Examples
--------
>>> from linkage_sym.examples import load_example
>>> scene = load_example("crank_rocker")
>>> r = Recipe.of(("l", "coupler", "C"))
>>> type(r).__name__, r.key
('PointDistance', ('l', 'coupler', 'C'))
>>> from linkage_sym.structure.parameters import link_frames
>>> round(r.value(scene, link_frames(scene)), 6)
0.063032
"""

from __future__ import annotations

import math
from abc import ABC, abstractmethod
from typing import ClassVar

from linkage_sym.model import GROUND, Scene

__all__ = ["FLOAT", "Numbers", "Recipe", "RECIPES"]


class Numbers:
    """A number type for recipes: binary64 floats and :mod:`math` (subclass for another).

    ``number(v)`` converts a scene number (a binary64 float) exactly; ``atan2``, ``hypot``,
    ``cos``, ``sin`` are the type's own.
    """

    number = staticmethod(float)
    atan2 = staticmethod(math.atan2)
    hypot = staticmethod(math.hypot)
    cos = staticmethod(math.cos)
    sin = staticmethod(math.sin)

    def zero(self):
        return self.number(0.0)

    def wrap(self, a):
        """``a`` wrapped into ``(-pi, pi]``."""
        return self.atan2(self.sin(a), self.cos(a))

    def point(self, p):
        return self.number(p[0]), self.number(p[1])


FLOAT = Numbers()
"""Binary64 floats (the default number type)."""


class Context:
    """A scene, its link frames and a number type: what a recipe reads.

    The frames' joints (which joint is a link's origin ``u`` and which sets its x-axis
    ``v``) are :func:`~linkage_sym.structure.parameters.link_frames`' choice, made in
    binary64; their origins and angles are computed here in the number type.
    """

    def __init__(self, scene: Scene, frames, numbers: Numbers = FLOAT):
        self.scene, self.frames, self.num = scene, frames, numbers
        self._frame: dict = {}

    def frame(self, link):
        """``((ox, oy), theta0)`` of a moving link's frame, in the number type."""
        got = self._frame.get(link)
        if got is None:
            num, fr = self.num, self.frames[link]
            U = num.point(self.scene.joint(fr.u).at)
            if fr.v is None:
                th = num.zero()
            else:
                V = num.point(self.scene.joint(fr.v).at)
                th = num.atan2(V[1] - U[1], V[0] - U[0])
            got = self._frame[link] = (U, th)
        return got

    def theta0(self, link):
        """A link's assembly angle (0 for the ground)."""
        return self.num.zero() if link == GROUND else self.frame(link)[1]

    def local(self, link, at):
        """Coordinates of the assembly point ``at`` in ``link``'s frame."""
        (ox, oy), th = self.frame(link)
        x, y = self.num.point(at)
        dx, dy = x - ox, y - oy
        c, s = self.num.cos(th), self.num.sin(th)
        return c * dx + s * dy, -s * dx + c * dy

    def direction(self, a, b):
        """Angle of the line from point ``a`` to point ``b`` (assembly coordinates)."""
        A, B = self.num.point(a), self.num.point(b)
        return self.num.atan2(B[1] - A[1], B[0] - A[0])


class Recipe(ABC):
    """How one parameter is read off a scene: a kind (the subclass) and a ``tag`` that
    selects the component (``x``/``y``, ``m``/``I``...), with the scene names it reads
    (``args``).  Subclasses list their ``tags`` and implement :meth:`read`."""

    tags: ClassVar[tuple] = ()

    def __init__(self, tag: str, args: tuple):
        if tag not in self.tags:
            raise ValueError(f"unknown parameter recipe {(tag,) + tuple(args)!r}")
        self.tag, self.args = tag, tuple(args)

    @property
    def key(self) -> tuple:
        """The recipe as the artifact writes it: ``(tag, *args)``."""
        return (self.tag,) + self.args

    def __eq__(self, other):
        return isinstance(other, Recipe) and self.key == other.key

    def __hash__(self):
        return hash(self.key)

    def __repr__(self):
        return f"{type(self).__name__}{self.key!r}"

    @staticmethod
    def of(key) -> "Recipe":
        """The recipe written as ``key`` (a tuple or list: ``(tag, *args)``)."""
        key = tuple(key)
        kind = RECIPES.get(key[0]) if key else None
        if kind is None:
            raise ValueError(f"unknown parameter recipe {key!r}")
        return kind(key[0], key[1:])

    def value(self, scene: Scene, frames, numbers: Numbers = FLOAT):
        """The parameter's value in ``scene`` with its link frames ``frames``
        (:func:`~linkage_sym.structure.parameters.link_frames`) in the number type."""
        return self.read(Context(scene, frames, numbers))

    @abstractmethod
    def read(self, ctx: Context):
        """The value, from the scene, frames and number type of ``ctx``."""

    def scaled_load(self) -> int | None:
        """The load whose factor over the cycle scales this parameter, if any."""
        return None


class PointDistance(Recipe):
    """``l``: distance of a joint from a link's frame origin; ``beta``: its angle from the
    link's x-axis.  Args ``(link, joint)``."""

    tags = ("l", "beta")

    def read(self, ctx):
        link, point = self.args
        x, y = ctx.local(link, ctx.scene.joint(point).at)
        return ctx.num.hypot(x, y) if self.tag == "l" else ctx.num.atan2(y, x)


class GroundPoint(Recipe):
    """``x``, ``y``: a coordinate of a point of the ground.  Args ``(joint,)``."""

    tags = ("x", "y")

    def read(self, ctx):
        return ctx.num.number(ctx.scene.joint(self.args[0]).at[0 if self.tag == "x" else 1])


class AssemblyAngle(Recipe):
    """``theta0``: a link's x-axis angle in the assembly configuration.  Args ``(link,)``."""

    tags = ("theta0",)

    def read(self, ctx):
        return ctx.frame(self.args[0])[1]


class SlideDirection(Recipe):
    """``gamma``: a ``P`` joint's slide direction from the x-axis of its first link."""

    tags = ("gamma",)

    def read(self, ctx):
        j = ctx.scene.joint(self.args[0])
        return ctx.num.wrap(ctx.num.number(j.axis) - ctx.theta0(j.links[0]))


class DriverDirection(Recipe):
    """``delta``: the angle of a driver's ``joint -> toward`` from the x-axis of the
    joint's second link.  Args ``(joint, toward)``."""

    tags = ("delta",)

    def read(self, ctx):
        j, t = ctx.scene.joint(self.args[0]), ctx.scene.joint(self.args[1])
        return ctx.num.wrap(ctx.direction(j.at, t.at) - ctx.theta0(j.links[1]))


class Inertia(Recipe):
    """``m``, ``I``: a link's mass and moment of inertia; ``p``, ``q``: its centre of mass
    in its frame.  Args ``(link,)``."""

    tags = ("m", "I", "p", "q")

    def read(self, ctx):
        link = ctx.scene.link(self.args[0])
        if self.tag in ("m", "I"):
            return ctx.num.number(link.mass if self.tag == "m" else link.inertia)
        x, y = ctx.local(link.name, link.com)
        return x if self.tag == "p" else y


class Gravity(Recipe):
    """``gx``, ``gy``: gravity's components (0 without gravity)."""

    tags = ("gx", "gy")

    def read(self, ctx):
        g = ctx.scene.effects.gravity or (0.0, 0.0)
        return ctx.num.number(g[0 if self.tag == "gx" else 1])


class Mesh(Recipe):
    """``radius`` (args ``(joint, gear)``), ``phi``, ``epsilon`` (args ``(joint,)``): a gear
    mesh's pitch radius, pressure angle, and line of centres from its carrier's x-axis."""

    tags = ("radius", "phi", "epsilon")

    def read(self, ctx):
        j = ctx.scene.joint(self.args[0])
        if self.tag == "radius":
            return ctx.num.number(j.radii[self.args[1]])
        if self.tag == "phi":
            return ctx.num.number(j.pressure_angle)
        a, b = (p.at for p in ctx.scene.gear_pivots(j))
        return ctx.num.wrap(ctx.direction(a, b) - ctx.theta0(j.carrier))


class Load(Recipe):
    """``Fx``, ``Fy``, ``T``: a load's force and torque (scaled by its factor over the
    cycle); ``xi``, ``eta``: its point in its link's frame.  Args ``(load index,)``."""

    tags = ("Fx", "Fy", "T", "xi", "eta")

    def read(self, ctx):
        ld = ctx.scene.loads[self.args[0]]
        if self.tag in ("Fx", "Fy"):
            return ctx.num.number(ld.force[0 if self.tag == "Fx" else 1])
        if self.tag == "T":
            return ctx.num.number(ld.torque)
        x, y = ctx.local(ld.link, ld.at)
        return x if self.tag == "xi" else y

    def scaled_load(self):
        return self.args[0] if self.tag in ("Fx", "Fy", "T") else None


class SpringValue(Recipe):
    """``k``, ``c``, ``L0``, ``theta_f``: a spring's stiffness, damping, free length and
    free angle (rad); ``xi_s``, ``eta_s``: the point of its end ``i`` in the frame of
    ``links[i]`` (the ground's: global).  Args ``(spring name,)`` or ``(spring name, i)``."""

    tags = ("k", "c", "L0", "theta_f", "xi_s", "eta_s")

    def read(self, ctx):
        k = next(k for k in ctx.scene.springs if k.name == self.args[0])
        if self.tag in ("xi_s", "eta_s"):
            i = self.args[1]
            link, at = k.links[i], k.at[i]
            x, y = ctx.num.point(at) if link == GROUND else ctx.local(link, at)
            return x if self.tag == "xi_s" else y
        if self.tag == "theta_f":  # the scene's degrees in the number type's radians
            return ctx.num.number(k.free_angle_deg) * (ctx.num.atan2(1, 0) * 2) / 180
        value = {"k": k.stiffness, "c": k.damping, "L0": k.free_length}[self.tag]
        return ctx.num.number(value)


class FrictionValue(Recipe):
    """``mu``: a joint's friction coefficient; ``rpin``: an ``R`` joint's pin radius (m)
    (``joints[i].friction``, contract part two).  Args ``(joint name,)``."""

    tags = ("mu", "rpin")

    def read(self, ctx):
        f = ctx.scene.joint(self.args[0]).friction
        return ctx.num.number(f.coefficient if self.tag == "mu" else f.radius)


RECIPES = {tag: kind for kind in (PointDistance, GroundPoint, AssemblyAngle, SlideDirection,
                                  DriverDirection, Inertia, Gravity, Mesh, Load, SpringValue,
                                  FrictionValue)
           for tag in kind.tags}
"""Every recipe kind by its tag."""
