"""Shaking-force balance conditions of a hinged linkage, by linearly independent vectors.

The mass centre of the moving links, ``sum_j m_j z_sj`` (complex numbers
``z = x + i y``), is written in the unit vectors ``e_j`` of the link frames
(``z_v - z_u = a_j e_j``; a third pin ``P`` of a link sits at
``z_u + (xi + i eta) e_j``) by walking a spanning tree from the ground;
every pin reached a second time closes a loop, ``sum_j c_j e_j = const``.
The loop equations eliminate as many *dependent* vectors (floating links
first, as Berkof and Lowen eliminate the coupler); the remaining vectors are
linearly independent functions of time for a mechanism of general
dimensions, so the mass centre is stationary -- the shaking force vanishes --
exactly when each of their coefficients is zero: a real and an imaginary
condition per independent link (Song and Wang 1992's ref. [1]; Berkof & Lowen 1969).

For special dimensions (a parallelogram, where two vectors stay parallel)
the conditions remain sufficient but are no longer necessary.

Examples
--------
>>> from linkage_sym.examples import load_example
>>> fb = force_balance(load_example("crank_rocker"))
>>> fb.independent, fb.dependent
(('crank', 'rocker'), ('coupler',))
>>> for c in fb.conditions:
...     print(c.name, "=", c.expr, "= 0")
Re_crank = m_coupler + m_crank*xG_crank/a_crank - m_coupler*xG_coupler/a_coupler = 0
Im_crank = m_crank*yG_crank/a_crank - m_coupler*yG_coupler/a_coupler = 0
Re_rocker = -m_rocker + m_rocker*xG_rocker/a_rocker - m_coupler*xG_coupler/a_coupler = 0
Im_rocker = m_rocker*yG_rocker/a_rocker - m_coupler*yG_coupler/a_coupler = 0
"""

from __future__ import annotations

import random
from dataclasses import dataclass

import numpy as np
import sympy as sp

from linkage_sym.balancing.pins import BalanceModel, tag
from linkage_sym.errors import SceneError
from linkage_sym.model import Scene


@dataclass(frozen=True)
class ForceCondition:
    """One real condition ``expr = 0``: the real or imaginary part of the
    coefficient of an independent link's unit vector, divided by its length."""

    name: str
    link: str
    part: str  # "real" or "imag"
    expr: sp.Expr


@dataclass(frozen=True)
class ForceBalance:
    """The shaking-force balance conditions of a hinged linkage.

    Attributes
    ----------
    model : BalanceModel
    unit_vectors : dict
        ``{link: Symbol e_<link>}``.
    loops : tuple of dict
        Loop equations ``sum_j c_j e_j = const`` as ``{link: c_j}``.
    mass_centre : dict
        ``{link: coefficient}`` of ``sum m z_s`` before elimination.
    independent, dependent : tuple of str
        Links whose vectors are kept / eliminated.
    coefficients : dict
        ``{independent link: coefficient / a_link}`` after elimination.
    conditions : tuple of ForceCondition
    """

    model: BalanceModel
    unit_vectors: dict
    loops: tuple
    mass_centre: dict
    independent: tuple
    dependent: tuple
    coefficients: dict
    conditions: tuple

    def expressions(self) -> list:
        return [c.expr for c in self.conditions]


def _add(a: dict, b: dict, s=1) -> dict:
    out = dict(a)
    for k, v in b.items():
        out[k] = out.get(k, 0) + s * v
    return out


def _nonzero(d: dict) -> dict:
    out = {}
    for k, v in d.items():
        v = sp.expand(v)
        if v != 0:
            out[k] = v
    return out


def re_im(expr: sp.Expr) -> tuple:
    """Real and imaginary parts of an expression in real symbols."""
    n, d = sp.fraction(sp.together(expr))
    if d.has(sp.I):
        dc = sp.conjugate(d)
        n, d = sp.expand(n * dc), sp.expand(d * dc)
    n = sp.expand(n)
    return sp.re(n) / d, sp.im(n) / d


def _tidy(expr: sp.Expr) -> sp.Expr:
    """A condition ``expr = 0`` in a readable form: expanded over monomial
    denominators (Song and Wang's ``m_1 q_1/a_1 - m_2 q_2/a_2``), else multiplied
    by the positive non-monomial part of the denominator."""
    n, d = sp.fraction(sp.together(sp.expand(expr)))
    _, factors = sp.factor_list(d)
    rest = sp.Mul(*[f**k for f, k in factors if not (f.is_Symbol or f.is_Number)])
    if rest == 1:
        return sp.expand(expr)
    return sp.expand(sp.cancel(n / (d / rest)))


def force_balance(scene: Scene, model: BalanceModel | None = None) -> ForceBalance:
    """Derive the shaking-force balance conditions (see the module docstring)."""
    model = model or BalanceModel(scene)
    links = model.links
    e = {link: sp.Symbol(f"e_{tag(link)}") for link in links}
    pos = {P: {} for P in model.ground_pins}
    loops = []
    done: set = set()
    while len(done) < len(links):
        for link in links:
            if link in done:
                continue
            pins = model.link_pins(link)
            known = [P for P in pins if P in pos]
            if known:
                break
        else:
            raise SceneError([f"links '{l}': not connected to the ground" for l in links if l not in done])
        P0 = known[0]
        zu = _add(pos[P0], {link: -model.local_point(link, P0)})
        for Q in pins:
            zq = _nonzero(_add(zu, {link: model.local_point(link, Q)}))
            if Q in pos:
                loop = _nonzero(_add(zq, pos[Q], -1))
                if loop:
                    loops.append(loop)
            else:
                pos[Q] = zq
        done.add(link)

    centre: dict = {}
    for link in links:
        m, a, p, q, k = model.link_symbols(link)
        u, _ = model.uv(link)
        centre = _add(centre, {j: m * c for j, c in pos[u].items()})
        centre = _add(centre, {link: m * (p + sp.I * q)})
    centre = _nonzero(centre)

    dependent = _choose_dependent(model, loops)
    independent = tuple(l for l in links if l not in dependent)
    L = len(loops)
    if L:
        Ld = sp.Matrix(L, L, lambda r, c: loops[r].get(dependent[c], 0))
        sd = sp.Matrix([centre.get(d, 0) for d in dependent])
        lam = Ld.T.LUsolve(sd)  # centre_dep . Ld^-1
    coefficients = {}
    conditions = []
    for k in independent:
        g = centre.get(k, 0)
        if L:
            g -= sum(lam[r] * loops[r].get(k, 0) for r in range(L))
        a = model.link_symbols(k)[1]
        g = sp.expand(g / a)
        coefficients[k] = g
        re, im = re_im(g)
        conditions.append(ForceCondition(f"Re_{tag(k)}", k, "real", _tidy(re)))
        conditions.append(ForceCondition(f"Im_{tag(k)}", k, "imag", _tidy(im)))
    return ForceBalance(model, e, tuple(loops), centre, independent, tuple(dependent),
                        coefficients, tuple(conditions))


def _choose_dependent(model: BalanceModel, loops: list) -> tuple:
    """Links whose vectors the loops eliminate: floating links first, each
    kept only if it raises the rank (checked at random parameter values)."""
    if not loops:
        return ()
    rng = random.Random(12345)
    syms = set()
    for lp in loops:
        for c in lp.values():
            syms |= c.free_symbols
    val = {s: rng.uniform(0.5, 2.0) for s in syms}
    floating = [l for l in model.links if not any(model.pins[P].ground for P in model.link_pins(l))]
    order = floating + [l for l in model.links if l not in floating]
    chosen: list = []
    for link in order:
        trial = chosen + [link]
        M = np.array([[complex(sp.sympify(lp.get(j, 0)).subs(val)) for j in trial] for lp in loops])
        if np.linalg.matrix_rank(M) == len(trial):
            chosen = trial
        if len(chosen) == len(loops):
            return tuple(chosen)
    raise SceneError([f"balancing: the {len(loops)} loop equations do not determine "
                      f"{len(loops)} link directions (a degenerate mechanism)"])
