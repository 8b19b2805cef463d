"""The mass/acceleration-parameter module of one link (Song and Wang 1992, eqs. 1-8).

A link between joints ``u`` and ``v`` (length ``a``), with mass ``m``, centre
of mass at ``(p, q)`` in the link frame (origin ``u``, x-axis toward ``v``)
and radius of gyration ``k`` about its centre of mass, has about the global
origin the inertia moment (eq. 1)

    M_0 = -dH_0/dt = -m (x_s y_s'' - y_s x_s'' + k^2 phi'').

Song and Wang write it as ``M_0 = -sum_i M_i D_i`` (eq. 5): four *mass
parameters* ``M_i`` (geometry and mass only) times four *acceleration
parameters* ``D_i`` (joint coordinates and accelerations only, eq. 7).
:func:`link_module` derives ``M_0`` from eqs. 1-4 with SymPy and reads the
mass parameters off it as the coefficients of the bilinear form
``M_0(position, acceleration)``; it does not copy the printed eq. 6, whose
first line the OCR garbled (it prints ``m/a^2 - [...]`` where the product
``m/a^2 [...]`` is meant).  :func:`check_identity` proves
``M_0 + sum M_i D_i == 0`` identically.

Examples
--------
>>> mod = link_module()
>>> mod.mass_parameters[0]
m*(a**2 - 2*a*p + k**2 + p**2 + q**2)/a**2
>>> mod.mass_parameters[2]
m*q/a
>>> check_identity(mod)
True
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import sympy as sp


@dataclass(frozen=True)
class LinkModule:
    """The derived module of one link.

    Attributes
    ----------
    m, a, p, q, k : sympy.Symbol
        Mass, length ``|uv|``, centre of mass ``(p, q)`` in the link frame,
        radius of gyration about the centre of mass.
    u, v : tuple of sympy.Symbol
        ``(x, y, x'', y'')`` of joints ``u`` and ``v``.
    M0 : sympy.Expr
        Inertia moment about the global origin (eq. 1 with eqs. 2-4).
    mass_parameters : tuple of 4 sympy.Expr
        ``M_uv1 .. M_uv4`` (eq. 6, derived).
    acceleration_parameters : tuple of 4 sympy.Expr
        ``D_uv1 .. D_uv4`` (eq. 7).
    phidd : sympy.Expr
        Angular acceleration from the ``D``'s (eq. 8).
    """

    m: sp.Symbol
    a: sp.Symbol
    p: sp.Symbol
    q: sp.Symbol
    k: sp.Symbol
    u: tuple
    v: tuple
    M0: sp.Expr
    mass_parameters: tuple
    acceleration_parameters: tuple
    phidd: sp.Expr


def acceleration_parameters(u, v) -> tuple:
    """Song and Wang's eq. 7 for joints ``u = (x, y, x'', y'')`` and ``v``."""
    xu, yu, axu, ayu = u
    xv, yv, axv, ayv = v
    return (
        xu * ayu - yu * axu,
        xv * ayu + xu * ayv - yv * axu - yu * axv,
        yu * ayv + xu * axv - yv * ayu - xv * axu,
        xv * ayv - yv * axv,
    )


def _symbols(prefix: str):
    return sp.symbols(f"x_{prefix} y_{prefix} xdd_{prefix} ydd_{prefix}", real=True)


def link_module(m=None, a=None, p=None, q=None, k=None, u=None, v=None) -> LinkModule:
    """Derive the module of one link (Song and Wang 1992, eqs. 1-8).

    Any argument left out is a fresh symbol (``m, a, p, q, k``; joint
    symbols ``x_u, y_u, xdd_u, ydd_u`` and the same for ``v``); arguments
    given (symbols, or zeros for a fixed pin) replace them in the module
    derived once with the fresh symbols.

    The derivation: joint coordinates are functions of time; eq. 2 places
    the centre of mass; eq. 3 is its second derivative; the angular rate
    is ``(dx dy' - dy dx')/a^2`` for a rigid link (``dx^2 + dy^2 = a^2``),
    and its derivative is eq. 4 (the velocity products cancel).  The mass
    parameters are the coefficients of ``-M_0`` in front of the position x
    acceleration products that eq. 7 puts in ``D_1 .. D_4`` alone:
    ``x_u y_u''``, ``x_v y_u''``, ``y_u y_v''`` and ``x_v y_v''``.
    """
    mod = _generic_module()
    given = (m, a, p, q, k) + tuple(u or (None,) * 4) + tuple(v or (None,) * 4)
    fresh = (mod.m, mod.a, mod.p, mod.q, mod.k) + mod.u + mod.v
    rep = {f: g for f, g in zip(fresh, given) if g is not None}
    if not rep:
        return mod

    def sub(e):
        return e.xreplace(rep)

    return LinkModule(
        *(sub(s) for s in (mod.m, mod.a, mod.p, mod.q, mod.k)),
        tuple(sub(s) for s in mod.u), tuple(sub(s) for s in mod.v),
        sub(mod.M0), tuple(sub(e) for e in mod.mass_parameters),
        tuple(sub(e) for e in mod.acceleration_parameters), sub(mod.phidd),
    )


@functools.lru_cache(maxsize=1)
def _generic_module() -> LinkModule:
    m = sp.Symbol("m", positive=True)
    a = sp.Symbol("a", positive=True)
    p, q = sp.symbols("p q", real=True)
    k = sp.Symbol("k", nonnegative=True)
    u, v = _symbols("u"), _symbols("v")

    t = sp.Symbol("t", real=True)
    X = {name: sp.Function(f"{name}_of_t", real=True)(t) for name in ("xu", "yu", "xv", "yv")}
    xu, yu, xv, yv = X["xu"], X["yu"], X["xv"], X["yv"]
    # eq. 2: centre of mass from the joints
    xs = p / a * (xv - xu) - q / a * (yv - yu) + xu
    ys = p / a * (yv - yu) + q / a * (xv - xu) + yu
    # rigid link: phi' = (dx dy' - dy dx') / a^2, its derivative is phi''
    dx, dy = xv - xu, yv - yu
    omega = (dx * sp.diff(dy, t) - dy * sp.diff(dx, t)) / a**2
    phidd_t = sp.diff(omega, t)
    M0_t = -m * (xs * sp.diff(ys, t, 2) - ys * sp.diff(xs, t, 2) + k**2 * phidd_t)
    # functions of time -> the module's symbols (second derivatives first)
    rep = {}
    for f, acc in zip((xu, yu, xv, yv), (u[2], u[3], v[2], v[3])):
        rep[sp.diff(f, t, 2)] = acc
    pos = {xu: u[0], yu: u[1], xv: v[0], yv: v[1]}
    M0 = sp.expand(M0_t.subs(rep).subs(pos))
    phidd = sp.expand(phidd_t.subs(rep).subs(pos))
    if M0.has(t) or phidd.has(t):  # a velocity term survived: the link is not rigid
        raise AssertionError("velocity terms left in the link module")

    D = acceleration_parameters(u, v)
    # the monomial each D_i holds alone (with sign +1 in D_i)
    lead = ((u[0], u[3]), (v[0], u[3]), (u[1], v[3]), (v[0], v[3]))
    M = tuple(sp.factor(-sp.diff(M0, x, y)) for x, y in lead)
    # eq. 8: phi'' in the acceleration parameters, checked here, not assumed
    phidd8 = (D[0] + D[3] - D[1]) / a**2
    if sp.expand(phidd - phidd8) != 0:
        raise AssertionError("eq. 8 does not hold")
    return LinkModule(m, a, p, q, k, u, v, M0, M, D, phidd8)


def check_identity(mod: LinkModule) -> bool:
    """``True`` when ``M_0 + sum_i M_i D_i`` expands to zero identically."""
    total = mod.M0 + sum(Mi * Di for Mi, Di in zip(mod.mass_parameters, mod.acceleration_parameters))
    return sp.expand(total) == 0


def regrouped(mod: LinkModule) -> tuple:
    """The module as Song and Wang's eqs. 17-18 regroup it.

    Returns ``(c_u, c_v, X, c_3)`` with

        M_0 = -(c_u D_1 + c_v D_4 + X phi'' + c_3 D_3),

    ``c_u = m (1 - p/a)`` and ``c_v = m p/a`` (the shares of the mass at
    ``u`` and ``v``: the real parts of the link's shaking-force
    coefficients), ``X = m (p^2 + q^2 + k^2 - a p)`` and ``c_3 = m q/a``.
    With ``q = 0`` and the joint terms cancelled by force balance, only
    ``X phi''`` is left: eq. 18.
    """
    M1, M2, M3, M4 = mod.mass_parameters
    m, a, p, q, k = mod.m, mod.a, mod.p, mod.q, mod.k
    c_u, c_v = sp.factor(M1 + M2), sp.factor(M4 + M2)
    X = sp.factor(-M2 * a**2)
    out = (c_u, c_v, X, M3)
    expected = (m * (1 - p / a), m * p / a, m * (p**2 + q**2 + k**2 - a * p), m * q / a)
    if any(sp.simplify(x - y) != 0 for x, y in zip(out, expected)):
        raise AssertionError("regrouping of the module failed")
    return out
