"""Shaking-moment balance: what is left once the force is balanced, and the conditions that cancel it.

Song and Wang's (1992) reasoning (eqs. 12-18), carried out for any hinged linkage:

1. *Normal offsets.*  A link whose ``D_3`` does not vanish (both its pins
   move, or one is a fixed pivot away from the origin) contributes
   ``(m yG / a) D_3``; Song and Wang cancel it with ``yG = 0`` (its eq. 13 for the
   couplers 2 and 4).
2. *Force balance.*  The force conditions (:mod:`~.force`) are solved for
   the centre of mass ``(xG, yG)`` (Song and Wang's ``(p, q)``) of every
   independent link.
3. *Remaining moment.*  With 1 and 2 substituted, the regrouped moment
   (:mod:`~.assembly`) becomes ``-sum_j X_j phi''_j - sum_P C_P D_P``;
   when every pin share ``C_P`` cancels (as in the four-bar and Song and Wang's
   six-bar) this is eq. 18, ``M_0 = -sum_j m_j (xG_j^2 + k_j^2 - a_j xG_j) phi''_j``.
4. *Moment conditions.*  ``yG_j = 0`` from step 1; ``C_P = 0`` for every pin
   share that force balance does not cancel; and ``X_j = 0`` for every link
   whose angular acceleration is not identically zero -- the input link of a
   driver at constant speed needs none.

The acceleration parameters are not independent functions of time, so these
conditions are *sufficient*: Song and Wang's design 2 cancels the moment with
``X_4 = X_5`` instead, because there ``phi''_4 = -phi''_5``.

Examples
--------
>>> from linkage_sym.examples import load_example
>>> b = derive_balance(load_example("crank_rocker"))
>>> b.remaining
m_coupler*phidd_coupler*(a_coupler*xG_coupler - k_coupler**2 - xG_coupler**2) + m_crank*phidd_crank*(a_crank*xG_crank - k_crank**2 - xG_crank**2) + m_rocker*phidd_rocker*(a_rocker*xG_rocker - k_rocker**2 - xG_rocker**2)
>>> [c.name for c in b.moment_conditions]
['yG_coupler', 'yG_rocker', 'X_coupler', 'X_rocker']
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import sympy as sp

from linkage_sym.balancing.assembly import ShakingMoment, shaking_moment
from linkage_sym.balancing.force import ForceBalance, force_balance
from linkage_sym.balancing.pins import BalanceModel, tag
from linkage_sym.model import GROUND, Scene


@dataclass(frozen=True)
class MomentCondition:
    """One condition ``expr = 0`` and why it is needed."""

    name: str
    expr: sp.Expr
    reason: str


@dataclass
class Balance:
    """Everything :func:`derive_balance` derives for one scene.

    Attributes
    ----------
    model, moment, force
        The :class:`~.pins.BalanceModel`, :class:`~.assembly.ShakingMoment`
        and :class:`~.force.ForceBalance`.
    normal_links : tuple of str
        Links whose ``D_3`` does not vanish (step 1).
    force_solution : dict
        ``{xG_k or yG_k symbol: expression}`` solving the force conditions.
    pin_residuals : dict
        ``C_P`` that force balance leaves non-zero (empty: eq. 18 holds).
    remaining : sympy.Expr
        The shaking moment with steps 1-2 substituted, in ``phidd_<link>``
        and pin acceleration-parameter symbols.
    constant_speed_links : tuple of str
        Input links driven at constant speed (``phi'' = 0``).
    moment_conditions : list of MomentCondition
    seconds : dict
        Time taken by each derivation step.
    """

    model: BalanceModel
    moment: ShakingMoment
    force: ForceBalance
    normal_links: tuple
    force_solution: dict
    pin_residuals: dict
    remaining: sp.Expr
    constant_speed_links: tuple
    moment_conditions: list
    seconds: dict = field(default_factory=dict)


def constant_speed_links(scene: Scene) -> tuple:
    """Links turned about the ground by an ``R`` driver with zero acceleration."""
    out = []
    for d in scene.drivers:
        j = scene.joint(d.joint)
        if d.kind == "R" and d.acceleration == 0 and GROUND in j.links:
            out.append(j.links[1] if j.links[0] == GROUND else j.links[0])
    return tuple(out)


def solve_force(fb: ForceBalance, fixed: dict) -> dict:
    """Solve the force conditions (linear in the ``p, q`` of the independent
    links) after substituting ``fixed``; the system comes from its jacobian."""
    model = fb.model
    unknowns = []
    for k in fb.independent:
        _, _, p, q, _ = model.link_symbols(k)
        unknowns += [s for s in (p, q) if s not in fixed]
    eqs = sp.Matrix([c.expr.xreplace(fixed) for c in fb.conditions])
    A = eqs.jacobian(unknowns)
    b = -eqs.xreplace({u: 0 for u in unknowns})
    if A.shape[0] != A.shape[1]:
        raise ValueError("force conditions: as many unknowns as conditions expected")
    sol = A.LUsolve(b)
    return {u: sp.simplify(s) for u, s in zip(unknowns, sol)}


def derive_balance(scene: Scene) -> Balance:
    """Derive the shaking moment, the force and the moment balance conditions."""
    seconds = {}
    t0 = time.perf_counter()
    model = BalanceModel(scene)
    sm = shaking_moment(scene, model)
    seconds["shaking_moment"] = time.perf_counter() - t0
    t0 = time.perf_counter()
    fb = force_balance(scene, model)
    seconds["force_conditions"] = time.perf_counter() - t0

    t0 = time.perf_counter()
    normal = tuple(link for link, (_, D) in sm.normal_terms.items() if D is not None)
    # q = 0 on dependent links; an independent link's q follows from force balance
    fixed = {model.link_symbols(link)[3]: sp.Integer(0) for link in normal if link not in fb.independent}
    solution = solve_force(fb, fixed)
    implied = {link for link in normal if link in fb.independent
               and solution[model.link_symbols(link)[3]] == 0}
    full = dict(fixed)
    full.update(solution)
    residuals = {}
    for P, C in sm.pin_coefficients.items():
        r = sp.simplify(C.xreplace(full))
        if r != 0:
            residuals[P] = r
    # eq. 18 keeps each link's own p: only the vanishing q are substituted
    zero_q = dict(fixed)
    zero_q.update({model.link_symbols(k)[3]: sp.Integer(0) for k in fb.independent
                   if solution[model.link_symbols(k)[3]] == 0})
    remaining = -sum(sp.factor(sm.X[link].xreplace(zero_q)) * model.phidd(link) for link in model.links)
    pin_D = sm.pin_parameters
    remaining -= sum(r * sm.acceleration_parameter(pin_D[P]).symbol for P, r in residuals.items())

    steady = constant_speed_links(scene)
    conditions = [
        MomentCondition(
            f"yG_{tag(link)}", model.link_symbols(link)[3],
            f"cancels (m yG/a) D_3 of link {link}, whose pins are not a fixed pivot at the origin"
            + (" (implied by force balance once the other yG vanish: Song and Wang 1992, eq. 15)"
               if link in implied else " (Song and Wang 1992, eq. 13)"))
        for link in normal
    ]
    conditions += [
        MomentCondition(f"C_{tag(P)}", r, f"the mass shares at pin {P} that force balance leaves")
        for P, r in residuals.items()
    ]
    for link in model.links:
        if link in steady:
            continue
        X = sp.factor(sm.X[link].xreplace(zero_q))
        conditions.append(MomentCondition(
            f"X_{tag(link)}", X,
            f"cancels m (xG^2 + yG^2 + k^2 - a xG) phi'' of link {link} (Song and Wang 1992, eq. 18)"))
    seconds["moment_conditions"] = time.perf_counter() - t0
    return Balance(model, sm, fb, normal, solution, residuals, remaining, steady, conditions, seconds)
