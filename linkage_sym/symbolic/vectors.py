"""Plane vectors as sums of link vectors, in the complex notation of the textbook
chapter "Kinematic analysis of planar mechanisms".

A :class:`Vec` is a sum of *polar* terms ``l e^{i theta}`` (a link vector:
length times the unit vector of an angle) and *Cartesian* terms ``x + i y``
(a point of the ground).  It prints as the complex form of the loop
equations (eq. 3-8) and projects onto the axes (eq. 3-9) without SymPy ever
expanding complex exponentials.
"""

from __future__ import annotations

import sympy as sp


class Vec:
    """A sum of polar terms ``(l, theta)`` and Cartesian terms ``(x, y)``."""

    __slots__ = ("polar", "cart")

    def __init__(self, polar=(), cart=()):
        self.polar = tuple(polar)
        self.cart = tuple(cart)

    @staticmethod
    def of(l, theta) -> "Vec":
        return Vec(polar=((l, theta),))

    @staticmethod
    def xy(x, y) -> "Vec":
        return Vec(cart=((x, y),))

    def __add__(self, other: "Vec") -> "Vec":
        return Vec(self.polar + other.polar, self.cart + other.cart)

    def __neg__(self) -> "Vec":
        return Vec(((-l, t) for l, t in self.polar), ((-x, -y) for x, y in self.cart))

    def __sub__(self, other: "Vec") -> "Vec":
        return self + (-other)

    def rotate(self, phi) -> "Vec":
        """This vector turned by ``phi`` (polar terms keep their form)."""
        c, s = sp.cos(phi), sp.sin(phi)
        return Vec(
            ((l, t + phi) for l, t in self.polar),
            ((c * x - s * y, s * x + c * y) for x, y in self.cart),
        )

    @property
    def x(self):
        return sp.Add(*(l * sp.cos(t) for l, t in self.polar), *(x for x, _ in self.cart))

    @property
    def y(self):
        return sp.Add(*(l * sp.sin(t) for l, t in self.polar), *(y for _, y in self.cart))

    def complex(self):
        """The kinematics chapter's complex form ``sum l e^{i theta} + (x + i y)``."""
        terms = [l * sp.exp(sp.I * t) for l, t in self.polar]
        terms += [x + sp.I * y for x, y in self.cart]
        return sp.Add(*terms)

    def xreplace(self, rule) -> "Vec":
        return Vec(
            ((l.xreplace(rule), t.xreplace(rule)) for l, t in self.polar),
            ((x.xreplace(rule), y.xreplace(rule)) for x, y in self.cart),
        )


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1]


def cross(a, b):
    return a[0] * b[1] - a[1] * b[0]
