"""Explicit positions of input links, gears and dyads, derived with SymPy.

The part of :class:`~linkage_sym.symbolic.mechanism.MechanismEquations` (a
mixin it inherits) that solves a group's loop equations in closed form, in
solving order: an input link's angle from its driver, a gear's from its mesh,
a dyad's two coordinates from the intersection of its two loci -- two circles
(``RRR``, Heron's half-chord), a circle and a line (``RRP``), a circle about a
slide (``RPR``) or two lines (``PRP``, ``RPP``) -- with its assembly-mode
sign ``sigma_<i>``.  Each position is written twice: as one expression
(:attr:`closed_forms`) and as a reader follows it, through named intermediate
quantities (:attr:`position_steps`, :attr:`intermediates`).

Examples
--------
>>> from linkage_sym.examples import load_example
>>> from linkage_sym.symbolic.mechanism import derive
>>> eqs = derive(load_example("crank_rocker"))
>>> [str(s) for s, _ in eqs.closed_forms]
['theta_crank', 'theta_coupler', 'theta_rocker']
>>> [str(s) for s, _ in eqs.intermediates][:3]
['x_B', 'y_B', 'dx_2']
"""

from __future__ import annotations

import sympy as sp

from linkage_sym.structure.parameters import ident
from linkage_sym.symbolic.tangent import coordinate_size, tangent_sqrt
from linkage_sym.symbolic.vectors import cross, dot

__all__ = ["ClosedForms", "other_link"]


def other_link(joint, link):
    """The link of ``joint`` that is not ``link``."""
    a, b = joint.links
    return b if a == link else a


def _size(*values):
    """The size of the coordinates a locus intersection is computed from (the numeric
    solver's ``coordinate_size``): the largest magnitude, for the rounding test of
    :func:`~linkage_sym.symbolic.tangent.tangent_sqrt`."""
    return coordinate_size(*values)


class ClosedForms:
    """The closed-form positions of :class:`~linkage_sym.symbolic.mechanism.MechanismEquations`.

    A mixin: it reads the geometry (``pos``, ``rel``, ``dist_arg``, ``slide_unit``,
    ``theta0``, ``sym``) and the symbols (``th``, ``slide``, ``q_of``) of the class
    that inherits it, and appends to its ``closed_forms``, ``position_steps``,
    ``intermediates`` and ``sigmas`` (and ``two_slides``: each dyad of two slides, with the
    cross product of its slides' directions, the denominator of its closed form).
    """

    def _copied(self, b, J):
        """Closed form of ``b``'s angle copied through ``P`` joint ``J``."""
        k = other_link(J, b)
        return self.theta(k) - self.theta0(k) + self.theta0(b)

    def _define(self, symbol, expr, readable=None):
        """``symbol = expr`` (closed forms); ``readable``: the same in intermediates."""
        self.closed_forms.append((symbol, expr))
        self.position_steps.append((symbol, expr if readable is None else readable))

    def _named(self, name: str, expr, meaning: str):
        """An intermediate symbol for ``expr`` (``expr`` itself if it is a symbol or number)."""
        expr = sp.sympify(expr)
        if expr.is_Atom or (-expr).is_Atom:
            return expr
        taken = {str(t) for t, _ in self.intermediates} | set(self._syms) | {
            str(t) for t in (*self.th.values(), *self.slide.values(), *self.q)}
        while name in taken:
            name += "'"
        sym = sp.Symbol(name, real=True)
        self.intermediates.append((sym, meaning))
        self.position_steps.append((sym, expr))
        return sym

    def _named_point(self, joint: str, P):
        return (self._named(f"x_{ident(joint)}", P[0], f"x-coordinate of joint {joint}"),
                self._named(f"y_{ident(joint)}", P[1], f"y-coordinate of joint {joint}"))

    def _input_closed_form(self, g, d):
        J = self.scene.joint(d.joint)
        (b,) = g.links
        q = self.q_of[J.name]
        if d.kind == "P":
            self._define(self.th[b], self._copied(b, J))
            self._define(self.slide[J.name], q)
            return
        # theta_b + delta - (theta_a - theta0_a) - q = 0, solved for the unknown angle
        eq = self._driver_eq(d)
        coeff = eq.coeff(self.th[b])
        self._define(self.th[b], sp.expand(self.th[b] - eq / coeff))

    def _gear_closed_form(self, g, J):
        """A gear on its pivot: its angle from the mesh equation, linear in it."""
        (b,) = g.links
        eq = sp.expand(self._mesh_eq(J))
        coeff = eq.coeff(self.th[b])
        self._define(self.th[b], sp.expand(self.th[b] - eq / coeff))

    def _line(self, J, b, Y):
        """Line locus ``Y = Q + t u`` of point ``Y`` of ``b`` (rotation known) through
        ``P`` joint ``J`` with a known link; ``s_J = sign * t``."""
        k = other_link(J, b)
        Qv = self.pos(k, J.name) + self.rel(b, J.name, Y)
        sign = 1 if b == J.links[1] else -1
        return (Qv.x, Qv.y), self.slide_unit(J.name), sign

    def _dyad_closed_form(self, gi, g):
        """Define a dyad's two coordinates from its loci; its assembly-mode sign (or None).

        ``gi`` is the group's index in the solving order (``sigma_<gi + 1>``),
        ``g`` the group, whose joints are its outer joint of ``links[0]``, its
        inner joint and its outer joint of ``links[1]``.
        """
        scene = self.scene
        t = g.dyad_type
        b0, b1 = g.links
        e0, ji, e1 = (scene.joint(n) for n in g.joints)
        sigma = None
        if t in ("RRR", "RRP", "RPR"):
            sigma = sp.Symbol(f"sigma_{gi + 1}", real=True)
            self.sigmas.append(sigma)
        if t == "RRR":
            self._rrr(gi + 1, sigma, (b0, b1), (e0, ji, e1))
        elif t == "RRP":
            self._rrp(gi + 1, sigma, (b0, b1), (e0, ji, e1))
        elif t == "RPR":
            self._rpr(gi + 1, sigma, (b0, b1), (e0, ji, e1))
        elif t == "PRP":
            self._define(self.th[b0], self._copied(b0, e0))
            self._define(self.th[b1], self._copied(b1, e1))
            den = self._two_lines((e0, b0, ji.name), (e1, b1, ji.name))
            self.two_slides.append((gi, (e0.name, e1.name), ji.name, den))
        elif t == "RPP":
            self._define(self.th[b1], self._copied(b1, e1))
            self._define(self.th[b0], self._copied(b0, ji))
            den = self._two_lines((ji, b1, ji.name), (e1, b1, ji.name))
            self.two_slides.append((gi, (ji.name, e1.name), ji.name, den))
        else:  # pragma: no cover - the structure refuses other types
            raise ValueError(t)
        return sigma

    def _rrr(self, g, sigma, links, joints):
        """Two circles: the inner joint ``R`` at distances ``r0``, ``r1`` from the outer
        joints (group number ``g`` in the names)."""
        (b0, b1), (e0, ji, e1) = links, joints
        k0, k1 = other_link(e0, b0), other_link(e1, b1)
        C0, C1 = self.pos(k0, e0.name), self.pos(k1, e1.name)
        C0, C1 = (C0.x, C0.y), (C1.x, C1.y)
        r0, d0 = self.dist_arg(b0, e0.name, ji.name)
        r1, d1 = self.dist_arg(b1, e1.name, ji.name)
        ex, ey = C1[0] - C0[0], C1[1] - C0[1]
        d = sp.sqrt(ex**2 + ey**2)
        # Heron form of the half-chord: accurate near the dead centres
        # (a tangency a few ulps off is a tangency in the generated code: tangent_sqrt)
        size = _size(r0, r1, *C0, *C1)
        h = tangent_sqrt(size, r0 + r1 - d, d + r0 - r1, d - r0 + r1, r0 + r1 + d) / (2 * d)
        a = (d**2 + r0**2 - r1**2) / (2 * d)
        Yx = C0[0] + (a * ex - sigma * h * ey) / d
        Yy = C0[1] + (a * ey + sigma * h * ex) / d
        # the same, as a reader follows it: named intermediates
        o0, o1, i = e0.name, e1.name, ji.name
        P0, P1 = self._named_point(o0, C0), self._named_point(o1, C1)
        nx = self._named(f"dx_{g}", P1[0] - P0[0], f"x-distance from joint {o0} to joint {o1}")
        ny = self._named(f"dy_{g}", P1[1] - P0[1], f"y-distance from joint {o0} to joint {o1}")
        nd = self._named(f"d_{g}", sp.sqrt(nx**2 + ny**2), f"distance between joints {o0} and {o1}")
        na = self._named(f"a_{g}", (nd**2 + r0**2 - r1**2) / (2 * nd),
                         f"projection of {o0}{i} on the line {o0}{o1}")
        nh = self._named(
            f"h_{g}",
            tangent_sqrt(size, r0 + r1 - nd, nd + r0 - r1, nd - r0 + r1, r0 + r1 + nd) / (2 * nd),
            f"half-chord: distance of joint {i} from the line {o0}{o1} (Heron's form)")
        Y = self._named_point(i, (P0[0] + (na * nx - sigma * nh * ny) / nd,
                                  P0[1] + (na * ny + sigma * nh * nx) / nd))
        self._define(self.th[b0], sp.atan2(Yy - C0[1], Yx - C0[0]) - d0,
                     sp.atan2(Y[1] - P0[1], Y[0] - P0[0]) - d0)
        self._define(self.th[b1], sp.atan2(Yy - C1[1], Yx - C1[0]) - d1,
                     sp.atan2(Y[1] - P1[1], Y[0] - P1[0]) - d1)

    def _rrp(self, g, sigma, links, joints):
        """A circle and a line: ``links[1]``'s angle copied through its ``P`` joint, the
        inner joint on the circle about ``links[0]``'s outer joint and on the line."""
        (b0, b1), (e0, ji, e1) = links, joints
        k0 = other_link(e0, b0)
        self._define(self.th[b1], self._copied(b1, e1))
        (Qx, Qy), (ux, uy), sign = self._line(e1, b1, ji.name)
        C = self.pos(k0, e0.name)
        C = (C.x, C.y)
        r0, d0 = self.dist_arg(b0, e0.name, ji.name)
        w = (C[0] - Qx, C[1] - Qy)
        delta = -uy * w[0] + ux * w[1]  # distance of the centre from the line
        size = _size(r0, *C, Qx, Qy)
        tt = dot(w, (ux, uy)) + sigma * tangent_sqrt(size, r0 - delta, r0 + delta)
        Yx, Yy = Qx + tt * ux, Qy + tt * uy
        o0, o1, i = e0.name, e1.name, ji.name
        P0 = self._named_point(o0, C)
        Q = (self._named(f"xQ_{g}", Qx, f"x of the point of {i}'s line through {o1}"),
             self._named(f"yQ_{g}", Qy, f"y of the point of {i}'s line through {o1}"))
        ndel = self._named(f"delta_{g}", -uy * (P0[0] - Q[0]) + ux * (P0[1] - Q[1]),
                           f"distance of joint {o0} from the line of {i}")
        nt = self._named(
            f"t_{g}",
            ux * (P0[0] - Q[0]) + uy * (P0[1] - Q[1])
            + sigma * tangent_sqrt(size, r0 - ndel, r0 + ndel),
            f"position of joint {i} along its line")
        Y = self._named_point(i, (Q[0] + nt * ux, Q[1] + nt * uy))
        self._define(self.th[b0], sp.atan2(Yy - C[1], Yx - C[0]) - d0,
                     sp.atan2(Y[1] - P0[1], Y[0] - P0[0]) - d0)
        self._define(self.slide[e1.name], sign * tt, sign * nt)

    def _rpr(self, g, sigma, links, joints):
        """A slide through the inner ``P`` joint: both angles from the direction of the
        slide through the two outer joints, then the slide."""
        (b0, b1), (e0, ji, e1) = links, joints
        k0, k1 = other_link(e0, b0), other_link(e1, b1)
        E0, E1 = self.pos(k0, e0.name), self.pos(k1, e1.name)
        D = (E1.x - E0.x, E1.y - E0.y)
        carrier = ji.links[0]
        gam = self.sym(self.table.gamma(ji.name))
        phi = sp.Dummy("phi")
        th_c = {b: phi - gam + self.theta0(b) - self.theta0(carrier) for b in (b0, b1)}
        K = (self.rel(b0, e0.name, ji.name) + self.rel(b1, ji.name, e1.name))
        K = K.xreplace({self.th[b]: th_c[b] for b in (b0, b1)}).rotate(-phi)
        Kx, Ky = K.x, K.y
        assert phi not in (Kx + Ky).free_symbols
        D2 = D[0] ** 2 + D[1] ** 2
        dd = sp.sqrt(D2)
        size = _size(Ky, E0.x, E0.y, E1.x, E1.y)
        w = tangent_sqrt(size, dd - Ky, dd + Ky)
        ex = (sigma * w * D[0] + Ky * D[1]) / D2
        ey = (sigma * w * D[1] - Ky * D[0]) / D2
        ang = sp.atan2(ey, ex) - gam  # angle of the carrier's x-axis
        # the same with named intermediates
        o0, o1, i = e0.name, e1.name, ji.name
        P0, P1 = self._named_point(o0, (E0.x, E0.y)), self._named_point(o1, (E1.x, E1.y))
        nx = self._named(f"dx_{g}", P1[0] - P0[0], f"x-distance from joint {o0} to joint {o1}")
        ny = self._named(f"dy_{g}", P1[1] - P0[1], f"y-distance from joint {o0} to joint {o1}")
        nd = self._named(f"d_{g}", sp.sqrt(nx**2 + ny**2), f"distance between joints {o0} and {o1}")
        nk = self._named(f"k_{g}", Ky, f"offset of joint {o1} from the slide of {i} through {o0}")
        nc = self._named(f"c_{g}", Kx, f"offset along the slide of {i} (link geometry)")
        nw = self._named(f"w_{g}", tangent_sqrt(size, nd - nk, nd + nk),
                         f"distance from {o0} to the foot of {o1} on the slide of {i}")
        ncos = self._named(f"cphi_{g}", (sigma * nw * nx + nk * ny) / nd**2,
                           f"cosine of the slide direction of {i}")
        nsin = self._named(f"sphi_{g}", (sigma * nw * ny - nk * nx) / nd**2,
                           f"sine of the slide direction of {i}")
        ang_r = sp.atan2(nsin, ncos) - gam
        for b in (b0, b1):
            self._define(self.th[b], ang + self.theta0(b) - self.theta0(carrier),
                         ang_r + self.theta0(b) - self.theta0(carrier))
        ss = 1 if b1 == ji.links[1] else -1
        self._define(self.slide[ji.name], ss * (sigma * w - Kx), ss * (sigma * nw - nc))

    def _two_lines(self, first, second):
        """The slides of two lines' intersection; returns their denominator, the cross
        product of the lines' directions (zero where they are parallel)."""
        (Q0, u0, s0), (Q1, u1, s1) = self._line(*first), self._line(*second)
        den = cross(u0, u1)
        dQ = (Q1[0] - Q0[0], Q1[1] - Q0[1])
        self._define(self.slide[first[0].name], s0 * cross(dQ, u1) / den)
        self._define(self.slide[second[0].name], s1 * cross(dQ, u0) / den)
        return den

    def nested_closed_forms(self) -> dict:
        """Each closed-form coordinate in terms of drivers, parameters and the
        coordinates of Newton groups only."""
        out: dict = {}
        for s, e in self.closed_forms:
            out[s] = e.xreplace(out)
        return out
