"""Joint friction in the derived force equations (contract part two, issue 29).

Where a scene's friction acts (``effects.friction`` and a joint's positive
coefficient), :func:`linkage_sym.symbolic.derive` writes it into every link's
equilibrium: the friction ``Mf_<J>`` (an ``R`` joint's couple about its pin) or
``Ff_<J>`` (a ``P`` joint's force along its axis, at its reference point) that
``links[0]`` exerts on ``links[1]``, and its law

* ``Mf_J = -rho_J nu_J sqrt(R_Jx^2 + R_Jy^2)`` (``rho_J = f r``, the friction circle's
  radius),
* ``Ff_J = -mu_J nu_J |N_J|`` (``mu_J`` the coefficient),

with ``nu_J`` the sign of the joint's relative motion (+1, -1; 0 where neither its
relative velocity nor its acceleration has one).  A group's block
``A_g F_g = b_g - C_g F_later`` then carries the frictions in ``b_g``, and the laws
close the system: nonlinear in the reactions, solved by the numeric methods
(:mod:`linkage_sym.numeric.forces.friction`) and, on the generated force blocks, by the
compiled symbolic runtime (:mod:`linkage_sym.codegen.friction`).

Examples
--------
>>> from linkage_sym.examples import load_example
>>> from linkage_sym.symbolic import derive
>>> eqs = derive(load_example("slider_crank_press_friction"))
>>> [(law.friction, law.law) for law in eqs.friction_laws][-1]
(Ff_C_guide, -mu_C_guide*nu_C_guide*Abs(N_C_guide))
"""

from __future__ import annotations

from typing import NamedTuple

import sympy as sp

from linkage_sym.model import GROUND
from linkage_sym.structure.parameters import ident

__all__ = ["FrictionLaw", "friction_laws", "friction_loads"]


class FrictionLaw(NamedTuple):
    """One joint's friction: its symbol, arm, sign of relative motion and law."""

    joint: str
    kind: str
    """``"R"`` (a couple) or ``"P"`` (a force along the axis)."""
    friction: sp.Symbol
    """``Mf_<J>`` or ``Ff_<J>``: what ``links[0]`` exerts on ``links[1]``."""
    arm: sp.Expr
    """``rho_<J>`` (m) or ``mu_<J>`` (1), or its number when the scene's numbers are used."""
    arm_value: float
    sign: sp.Symbol
    """``nu_<J>``: the sign of the joint's relative motion."""
    law: sp.Expr
    """The friction in terms of the joint's reaction."""


def _keep_symbol(symbolic) -> bool:
    """Whether the friction's arms stay symbols (``derive``'s ``symbolic``: ``True``, or a
    collection naming ``"friction"``)."""
    if isinstance(symbolic, bool):
        return symbolic
    return "friction" in symbolic


def friction_laws(eqs) -> list:
    """The :class:`FrictionLaw` of every joint whose friction acts, in scene order."""
    scene = eqs.scene
    if not scene.effects.friction:
        return []
    keep = _keep_symbol(eqs.symbolic)
    out = []
    for j in scene.joints:
        if j.friction is None or j.friction.coefficient <= 0:
            continue
        n = ident(j.name)
        sign = sp.Symbol(f"nu_{n}", real=True)
        if j.type == "R":
            arm_s = sp.Symbol(f"rho_{n}", positive=True)
            Rx, Ry = eqs.F[j.name]
            size, sym = sp.sqrt(Rx ** 2 + Ry ** 2), sp.Symbol(f"Mf_{n}", real=True)
        else:
            arm_s = sp.Symbol(f"mu_{n}", positive=True)
            size, sym = sp.Abs(eqs.F[j.name][0]), sp.Symbol(f"Ff_{n}", real=True)
        value = j.friction.arm
        arm = arm_s if keep else sp.Float(value)
        out.append(FrictionLaw(j.name, j.type, sym, arm, value, sign, -arm * sign * size))
    return out


def friction_loads(eqs, laws, add) -> None:
    """Add each friction to the rows ``acc`` of its two links through ``add(link, f, lever,
    couple)`` (:func:`linkage_sym.symbolic.forces._add` bound to the rows)."""
    for law in laws:
        j = eqs.scene.joint(law.joint)
        a, b = j.links
        mu = law.friction
        if law.kind == "R":
            add(b, couple=mu)
            add(a, couple=-mu)
            continue
        ux, uy = eqs.slide_unit(j.name)
        for link, s in ((b, 1), (a, -1)):
            if link != GROUND:
                add(link, (s * mu * ux, s * mu * uy), eqs._at_point(j, link))


def on_frame(law, slide_unit):
    """``(fx, fy, couple)`` the friction ``law`` puts on its joint's ``links[1]``."""
    if law.kind == "R":
        return sp.Integer(0), sp.Integer(0), law.friction
    ux, uy = slide_unit
    return law.friction * ux, law.friction * uy, sp.Integer(0)
