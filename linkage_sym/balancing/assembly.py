"""The shaking moment of a hinged linkage, assembled from link modules
(Song and Wang 1992, eqs. 9-12, 17-18).

:func:`shaking_moment` fills one module (:mod:`~linkage_sym.balancing.module`)
per moving link with the link's symbols and its pins (eq. 9), drops the
acceleration parameters that vanish because a pin is fixed or sits at the
origin (eq. 10), and merges those that are the same quantity at a common pin
(eq. 11: ``D_1`` of a link whose ``u`` is pin ``P`` and ``D_4`` of a link
whose ``v`` is ``P`` are both ``x_P y_P'' - y_P x_P''``).  What is left is the
total shaking moment about the origin in mass and acceleration parameters
(eq. 12).

It also gives the regrouped form that Song and Wang reach in eqs. 17-18 for its
six-bar, here for any hinged linkage (an identity, checked by the tests):

    M_0 = -[ sum_P C_P D_P + sum_j X_j phi''_j + sum_j (m_j q_j / a_j) D_3j ]

``C_P`` is the sum of the mass shares ``m (1 - p/a)`` and ``m p/a`` that the
links put at moving pin ``P``; ``X_j = m_j (p_j^2 + q_j^2 + k_j^2 - a_j p_j)``.

Examples
--------
>>> from linkage_sym.examples import load_example
>>> sm = shaking_moment(load_example("crank_rocker"))
>>> sm.vanishing  # the crank turns about the origin A
('D_AB_1', 'D_AB_2', 'D_AB_3', 'D_CD_4')
>>> sm.merged
(('D_AB_4', ('D_BC_1',)), ('D_BC_4', ('D_CD_1',)))
>>> sm.expression
-D_AB_4*(M_AB_4 + M_BC_1) - D_BC_2*M_BC_2 - D_BC_3*M_BC_3 - D_BC_4*(M_BC_4 + M_CD_1) - D_CD_2*M_CD_2 - D_CD_3*M_CD_3
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

from linkage_sym.balancing.module import link_module, regrouped
from linkage_sym.balancing.pins import BalanceModel, tag
from linkage_sym.model import Scene


def pair(u: str, v: str) -> str:
    """Song and Wang's subscript for a link between pins ``u`` and ``v`` (``AB``, or ``C2_E``)."""
    u, v = tag(u), tag(v)
    return u + v if len(u) == 1 and len(v) == 1 else f"{u}_{v}"


@dataclass(frozen=True)
class AccelerationParameter:
    """One acceleration parameter after merging: ``D_{link,i} = sign * expr`` for each member.

    Attributes
    ----------
    name, symbol
        ``D_<uv>_<i>`` of its first member (eq. 7), and that symbol.
    expr : sympy.Expr
        In the pins' coordinates and accelerations.
    members : tuple
        ``((link, i, sign), ...)``: every link parameter that is this quantity.
    """

    name: str
    symbol: sp.Symbol
    expr: sp.Expr
    members: tuple


@dataclass(frozen=True)
class ShakingMoment:
    """The assembled shaking moment of a hinged linkage about the global origin,
    ``M_0 = -sum_i M_i D_i`` over every link's module (eq. 12), its parameters merged.

    Attributes
    ----------
    model : BalanceModel
    mass_parameters : dict
        ``{"M_AB_1": expression in m, a, p, q, k}`` for every link and i = 1..4.
    vanishing : tuple of str
        Acceleration parameters that are identically zero (eq. 10).
    merged : tuple
        ``(kept, (equal, ...))``: parameters that are the same quantity (eq. 11);
        a parameter equal to minus another is listed as ``-name``.
    terms : tuple of (sympy.Expr, AccelerationParameter)
        Coefficient (a sum of mass-parameter symbols) and parameter (eq. 12).
    expression : sympy.Expr
        ``-sum coefficient * D`` in mass- and acceleration-parameter symbols.
    explicit : sympy.Expr
        The same in link symbols and pin coordinates and accelerations.
    force : tuple of 2 sympy.Expr
        The shaking force ``-sum m_j a_sj`` (eq. 3) in the same symbols.
    pin_coefficients : dict
        ``C_P`` of every moving pin (regrouped form, module docstring).
    X : dict
        ``X_j = m_j (p_j^2 + q_j^2 + k_j^2 - a_j p_j)`` of every link.
    normal_terms : dict
        ``{link: (m q / a, AccelerationParameter of its D_3 or None)}``.
    """

    model: BalanceModel
    mass_parameters: dict
    vanishing: tuple
    merged: tuple
    terms: tuple
    expression: sp.Expr
    explicit: sp.Expr
    force: tuple
    pin_coefficients: dict
    X: dict
    normal_terms: dict

    def symbol_meanings(self) -> dict:
        """Meaning of every mass- and acceleration-parameter symbol."""
        out = {}
        for name in self.mass_parameters:
            link, i = self._mass_owner[name]
            out[name] = f"mass parameter M_{i} of link {link} (Song and Wang 1992, eq. 6)"
        for _, D in self.terms:
            link, i, _ = D.members[0]
            out[D.name] = f"acceleration parameter D_{i} of link {link} (Song and Wang 1992, eq. 7)"
        return out

    @property
    def _mass_owner(self) -> dict:
        out = {}
        for link in self.model.links:
            u, v = self.model.uv(link)
            for i in range(1, 5):
                out[f"M_{pair(u, v)}_{i}"] = (link, i)
        return out

    def acceleration_parameter(self, name: str) -> AccelerationParameter:
        for _, D in self.terms:
            if D.name == name:
                return D
        raise KeyError(name)

    def phidd_in_D(self, link: str) -> sp.Expr:
        """``phi''`` of ``link`` in acceleration-parameter symbols (eq. 8, merged names)."""
        a = self.model.link_symbols(link)[1]
        D = self._link_D[link]
        return (D[0] + D[3] - D[1]) / a**2

    @property
    def _link_D(self) -> dict:
        """Each link's ``D_1 .. D_4`` as signed merged symbols (0 where they vanish)."""
        out = {link: [sp.Integer(0)] * 4 for link in self.model.links}
        for _, D in self.terms:
            for link, i, sign in D.members:
                out[link][i - 1] = sign * D.symbol
        return out

    def regrouped_expression(self) -> sp.Expr:
        """The regrouped form (module docstring) in ``D`` and ``phidd_<link>`` symbols."""
        m = self.model
        pin_D = self.pin_parameters
        total = sum(C * self.acceleration_parameter(pin_D[P]).symbol
                    for P, C in self.pin_coefficients.items() if P in pin_D)
        total += sum(self.X[link] * m.phidd(link) for link in m.links)
        total += sum(c * D.symbol for c, D in self.normal_terms.values() if D is not None)
        return -total

    @property
    def pin_parameters(self) -> dict:
        """Name of the merged parameter ``x_P y_P'' - y_P x_P''`` of each moving pin."""
        out = {}
        for _, D in self.terms:
            for link, i, _ in D.members:
                if i in (1, 4):
                    u, v = self.model.uv(link)
                    out[u if i == 1 else v] = D.name
        return out


def shaking_moment(scene: Scene, model: BalanceModel | None = None) -> ShakingMoment:
    """Assemble the shaking moment of a hinged linkage (see the module docstring)."""
    model = model or BalanceModel(scene)
    mass_parameters = {}
    entries = []  # (link, i, name, expr of D)
    explicit = sp.Integer(0)
    fx = fy = sp.Integer(0)
    pin_C: dict = {}
    X: dict = {}
    c3: dict = {}
    for link in model.links:
        m, a, p, q, k = model.link_symbols(link)
        u, v = model.uv(link)
        U, V = model.pin_symbols(u), model.pin_symbols(v)
        mod = link_module(m, a, p, q, k, U, V)
        uv = pair(u, v)
        for i, (Mi, Di) in enumerate(zip(mod.mass_parameters, mod.acceleration_parameters), 1):
            mass_parameters[f"M_{uv}_{i}"] = Mi
            entries.append((link, i, f"D_{uv}_{i}", sp.expand(Di)))
        explicit += mod.M0
        # eq. 3, the centre of mass acceleration; the shaking force is -m a_s
        fx -= m * ((1 - p / a) * U[2] + q / a * U[3] + p / a * V[2] - q / a * V[3])
        fy -= m * ((1 - p / a) * U[3] - q / a * U[2] + q / a * V[2] + p / a * V[3])
        c_u, c_v, X[link], c3[link] = regrouped(mod)
        for P, c in ((u, c_u), (v, c_v)):
            if not model.pins[P].ground:
                pin_C[P] = pin_C.get(P, 0) + c

    vanishing = tuple(name for _, _, name, e in entries if e == 0)
    groups: list = []  # [name, expr, members]
    for link, i, name, e in entries:
        if e == 0:
            continue
        for g in groups:
            if sp.expand(e - g[1]) == 0:
                g[2].append((link, i, 1))
                break
            if sp.expand(e + g[1]) == 0:
                g[2].append((link, i, -1))
                break
        else:
            groups.append([name, e, [(link, i, 1)]])

    msym = {name: sp.Symbol(name, real=True) for name in mass_parameters}
    terms = []
    merged = []
    for name, e, members in groups:
        D = AccelerationParameter(name, sp.Symbol(name, real=True), e, tuple(members))
        coef = 0
        for link, i, sign in members:
            u, v = model.uv(link)
            coef += sign * msym[f"M_{pair(u, v)}_{i}"]
        terms.append((coef, D))
        if len(members) > 1:
            others = []
            for link, i, sign in members[1:]:
                u, v = model.uv(link)
                others.append(("" if sign > 0 else "-") + f"D_{pair(u, v)}_{i}")
            merged.append((name, tuple(others)))
    expression = -sum(c * D.symbol for c, D in terms)
    normal = {}
    for link in model.links:
        D = next((D for _, D in terms if any(mm[0] == link and mm[1] == 3 for mm in D.members)), None)
        normal[link] = (c3[link], D)
    return ShakingMoment(
        model, mass_parameters, vanishing, tuple(merged), tuple(terms), expression,
        sp.expand(explicit), (sp.expand(fx), sp.expand(fy)), pin_C, X, normal,
    )
