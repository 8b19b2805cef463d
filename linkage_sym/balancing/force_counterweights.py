"""Counterweights that satisfy the derived shaking-force balance conditions.

A counterweight of mass ``mu`` at ``w`` (link frame) on link ``j`` turns the
link's ``(m, m p, m q)`` into ``(m + mu, m p + mu w_x, m q + mu w_y)``; the
force conditions (:mod:`~.force`) are linear in these, so the counterweights'
*first moments* come from one linear solve.  On a link turning about a fixed
pivot only the first moment about the pivot matters (the link's mass centre
moves on a circle about it), so the mass is free: it is set by the distance
``radius`` from the pivot (default: the link's length ``a``), opposite
where the balance needs it.  A floating link needs its counterweight mass
given (``masses``), and then its first moment about ``u`` is solved for.

Examples
--------
>>> from linkage_sym.examples import load_example
>>> cws = force_balancing_counterweights(load_example("crank_rocker"))
>>> [(c.link, round(c.mass, 4)) for c in cws]
[('crank', 0.3712), ('rocker', 0.3854)]
"""

from __future__ import annotations

import math

import numpy as np
import sympy as sp

from linkage_sym.balancing.conditions import Balance, derive_balance
from linkage_sym.balancing.counterweight import Counterweight
from linkage_sym.errors import BalanceError
from linkage_sym.model import Scene


def pivot_of(balance: Balance, link: str):
    """The fixed pin ``link`` turns about, or ``None`` for a floating link."""
    m = balance.model
    return next((P for P in m.link_pins(link) if m.pins[P].ground), None)


def force_balancing_counterweights(scene: Scene, balance: Balance | None = None, links=None,
                                   radius=None, masses=None, tol: float = 1e-10) -> list:
    """Counterweights that make the shaking force of ``scene`` vanish.

    With ``links`` omitted, the links turning about fixed pivots are tried
    first; when they cannot balance the force alone (a six-bar whose ground
    carries two pivots), the floating links are added one by one in scene
    order, each with a counterweight as heavy as the link itself (or the
    mean link mass for a massless link) unless ``masses`` says otherwise.
    See :func:`solve_counterweights` for the parameters.
    """
    balance = balance or derive_balance(scene)
    if links is not None:
        return solve_counterweights(scene, balance, links, radius, masses, tol)
    model = balance.model
    pivoted = [l for l in model.links if pivot_of(balance, l)]
    floating = [l for l in model.links if l not in pivoted]
    masses = dict(masses or {})
    mean = sum(scene.link(l).mass for l in model.links) / len(model.links)
    for l in floating:
        masses.setdefault(l, scene.link(l).mass or mean)
    for n in range(len(floating) + 1):
        try:
            return solve_counterweights(scene, balance, pivoted + floating[:n], radius, masses, tol)
        except BalanceError:
            if n == len(floating):
                raise


def solve_counterweights(scene: Scene, balance: Balance, links, radius=None, masses=None,
                         tol: float = 1e-10) -> list:
    """Counterweights that make the shaking force of ``scene`` vanish.

    Parameters
    ----------
    scene : Scene
    balance : Balance, optional
        :func:`~.conditions.derive_balance` of the scene (derived if omitted).
    links : list of str, optional
        Links that get a counterweight; default: every link turning about a
        fixed pivot.
    radius : dict, optional
        ``{link: distance of the counterweight from the pivot}`` (m); default
        the link's length.
    masses : dict, optional
        ``{link: counterweight mass}`` for floating links (required for them).
    tol : float
        Largest residual of the conditions, relative to the largest term.

    Raises
    ------
    BalanceError
        When the conditions cannot all hold with counterweights on ``links``
        (the message names the links), or a floating link has no mass given.
    """
    model = balance.model
    values = model.values()
    links = list(links)
    radius, masses = dict(radius or {}), dict(masses or {})
    missing = [l for l in links if pivot_of(balance, l) is None and l not in masses]
    if missing:
        raise BalanceError(f"links {', '.join(missing)} are floating; give their counterweight masses")

    unknown, rep, anchor = _counterweight_symbols(balance, links, masses, values)
    numeric = model.substitution()
    eqs = []
    for c in balance.force.conditions:
        e = c.expr.xreplace(rep)
        e = e.xreplace({s: numeric[s] for s in e.free_symbols if s in numeric})
        eqs.append(sp.expand(e))
    xs = [s for pair in unknown.values() for s in pair]
    A, b = sp.linear_eq_to_matrix(eqs, xs)
    A = np.array(A.tolist(), dtype=float)
    b = np.array(b.tolist(), dtype=float).ravel()
    sol, *_ = np.linalg.lstsq(A, b, rcond=None)
    scale = max(np.abs(A).max() * np.abs(sol).max(), np.abs(b).max(), 1e-300)
    res = np.abs(A @ sol - b).max()
    if res > tol * scale:
        raise BalanceError(
            f"the force balance conditions cannot all hold with counterweights "
            f"on {', '.join(links)} only (residual {res:.3g}, relative {res / scale:.2g}); "
            "add floating links with their counterweight masses")
    out = []
    for i, link in enumerate(links):
        S = sol[2 * i : 2 * i + 2]
        gx, gy = anchor[link]
        norm = math.hypot(*S)
        if pivot_of(balance, link) is not None:
            r = radius.get(link, values[model.link_symbols(link)[1].name])
            if norm <= tol * scale:
                continue
            mu = norm / r
        else:
            mu = masses[link]
        out.append(Counterweight(link, mu, (gx + S[0] / mu, gy + S[1] / mu)))
    return out


def _counterweight_symbols(balance: Balance, links, masses: dict, values: dict) -> tuple:
    """``(unknown, rep, anchor)``: each link's unknown first moment ``(S_x, S_y)`` of its
    counterweight, the substitution of its mass and centre of mass with the counterweight
    added, and its pivot in the link frame (the origin for a floating link)."""
    model = balance.model
    unknown = {}
    rep = {}
    anchor = {}
    for link in links:
        m, a, p, q, k = model.link_symbols(link)
        sx, sy = sp.symbols(f"S_{link}_x S_{link}_y", real=True)
        unknown[link] = (sx, sy)
        P = pivot_of(balance, link)
        g = model.local_point(link, P) if P is not None else sp.Integer(0)
        gx = float(sp.re(g).xreplace({s: values[s.name] for s in g.free_symbols}))
        gy = float(sp.im(g).xreplace({s: values[s.name] for s in g.free_symbols}))
        anchor[link] = (gx, gy)
        mu = masses.get(link, 1.0)  # any mass on a pivoted link: it drops out
        mv, pv, qv = values[m.name], values[p.name], values[q.name]
        m_new = mv + mu
        rep[m] = m_new
        rep[p] = (mv * pv + mu * gx + sx) / m_new
        rep[q] = (mv * qv + mu * gy + sy) / m_new
    return unknown, rep, anchor
