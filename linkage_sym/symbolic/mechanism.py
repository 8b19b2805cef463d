"""SymPy derivation of a mechanism's loop, rate and force equations.

:func:`derive` turns a scene's topology (its dimensions kept as symbols named
after the scene, or as numbers) into :class:`MechanismEquations`:

* **coordinates** ``x``: the angle ``theta_<link>`` of every moving link's
  x-axis (its joint ``u`` toward ``v``, see
  :mod:`linkage_sym.structure.parameters`) and the slide ``s_<J>`` of every
  ``P`` joint (0 in the assembly configuration); drivers ``q_<J>``;
* **loop equations** (kinematics textbook chapter, eq. 3-8): one closed vector loop per joint
  that closes a loop, in complex form, and their projections on the axes
  (eq. 3-9); ``P`` joints add ``theta_b - theta_a = const`` and drivers their
  own equations.  Every link is placed from the ground along a spanning
  tree that follows the solving order, so the loops of a group involve only
  that group's coordinates and those solved before it;
* **positions**: the explicit closed form of every input link and dyad, with
  its assembly-mode sign ``sigma_<i>``; class-III and other groups keep their
  loop equations for a numeric root;
* **rates** (eqs. 3-28, 3-29): ``A xd = B qd`` and
  ``A xdd = B qdd - (d/dx (A xd - B qd)) xd``, with ``A`` and ``B``
  the jacobians of the equations (never solved symbolically);
* **points**: joint and centre-of-mass positions, velocities and
  accelerations (jacobians again);
* **forces**: each group's equilibrium as ``A_g F_g = b_g - C_g F_later``
  (jacobians of the link equations with respect to the group's reactions
  and efforts, and to those of the groups solved after it), and the frame
  force and moment as linear forms in the reactions.

Conventions are those of the scene format: ``R_<J>x, R_<J>y`` is the force
``links[0]`` exerts on ``links[1]`` at an ``R`` joint; a ``P`` joint carries
``N_<J>`` along the slide normal (the axis turned by +90 degrees) at its
reference point and the couple ``M_<J>``; ``tau_<J>``/``f_<J>`` is a driver's
effort on ``links[1]``.

Size: about 700 lines, one class -- :class:`MechanismEquations` derives a
whole mechanism (loops, closed forms, rates, forces, frame loads) from one
set of symbols and caches; split, its parts would hand the same dozen caches
to each other.

Examples
--------
>>> from linkage_sym.examples import load_example
>>> eqs = derive(load_example("crank_rocker"))
>>> eqs.x
[theta_crank, theta_coupler, theta_rocker]
>>> eqs.loops[0][1].complex()
l_AB*exp(I*theta_crank) + l_BC*exp(I*theta_coupler) + l_CD*exp(I*theta_rocker) + x_A - x_D + I*y_A - I*y_D
"""

from __future__ import annotations

from dataclasses import dataclass, field

import sympy as sp

from linkage_sym.errors import refuse_symbolic_unsupported
from linkage_sym.model import GROUND, Scene
from linkage_sym.structure import Decomposition, Group, decompose
from linkage_sym.structure.parameters import ParameterTable, ident
from linkage_sym.symbolic.tangent import coordinate_size, tangent_sqrt
from linkage_sym.symbolic.vectors import Vec, cross, dot

HALF_PI = sp.pi / 2


def _size(*values):
    """The size of the coordinates a locus intersection is computed from (the numeric
    solver's ``coordinate_size``): the largest magnitude, for the rounding test of
    :func:`~linkage_sym.symbolic.tangent.tangent_sqrt`."""
    return coordinate_size(*values)


def _other(joint, link):
    a, b = joint.links
    return b if a == link else a


@dataclass
class GroupEquations:
    """One group of the solving order, with its equations.

    Attributes
    ----------
    group : Group
        The structural group.
    x : list of Symbol
        The group's coordinates (its links' angles, then its slides).
    rows : slice
        The group's rows in :attr:`MechanismEquations.Phi`.
    sigma : Symbol or None
        Assembly-mode sign of the group's closed form.
    closed : bool
        Whether the positions have an explicit closed form (input links, dyads).
    forces : list of Symbol
        The group's reactions and efforts, ``F_g``.
    """

    index: int
    group: Group
    x: list
    rows: slice
    sigma: sp.Symbol | None = None
    closed: bool = True
    forces: list = field(default_factory=list)
    force_rows: list = field(default_factory=list)


class MechanismEquations:
    """Everything :func:`derive` derives for one scene (see the module docstring).

    Attributes
    ----------
    x, xd, xdd : list of Symbol
        Coordinates, their rates (``omega_<link>``, ``sdot_<J>``) and
        accelerations (``alpha_<link>``, ``sddot_<J>``).
    q, qd, qdd : list of Symbol
        Driver coordinates ``q_<J>`` and their rates, in scene order.
    loops : list of (str, Vec)
        The closed vector loop of every joint that closes a loop (``= 0``).
    meshes : list of (str, Expr)
        Each gear mesh's rolling-without-slip equation (``= 0``, a length).
    Phi : Matrix
        All position equations, group by group.
    row_is_length : list of bool
        Whether each row of ``Phi`` has the dimension of a length (loop
        projections, slide drivers) rather than of an angle.
    A, B : Matrix
        ``A = dPhi/dx``, ``B = -dPhi/dq``: ``A xd = B qd``.
    acc_rhs : Matrix
        Right-hand side of ``A xdd = acc_rhs``.
    closed_forms : list of (Symbol, Expr)
        Explicit positions, in solving order; an expression may use the
        coordinates defined before it.
    position_steps : list of (Symbol, Expr)
        The same positions as a reader follows them: each dyad's named
        intermediate quantities (its outer joints' coordinates, the distance
        between them, the projection and half-chord of the inner joint, the
        inner joint's coordinates) defined once, then its angles in terms of
        them.  Equal to :attr:`closed_forms` once the intermediates are
        substituted (tested); printed by :mod:`linkage_sym.symbolic.latex`.
    intermediates : list of (Symbol, str)
        Each intermediate symbol of :attr:`position_steps` with its meaning.
    """

    def __init__(self, scene: Scene, symbolic=True, forces=None, decomposition=None):
        refuse_symbolic_unsupported(scene)  # cams not derived yet: refused by name, never wrong
        self.scene = scene
        self.decomposition: Decomposition = decomposition or decompose(scene)
        self.table = ParameterTable(scene)
        self.symbolic = symbolic
        self._syms: dict[str, sp.Expr] = {}
        self.th = {n: sp.Symbol(f"theta_{ident(n)}", real=True) for n in scene.link_names}
        self.slide = {
            j.name: sp.Symbol(f"s_{ident(j.name)}", real=True) for j in scene.joints if j.type == "P"
        }
        # a gear mesh's flank: the sign of its tangential force (+1 or -1), an input
        # like an assembly-mode sign (chosen by the runtime so that the tooth load presses)
        self.flank = {
            j.name: sp.Symbol(f"kappa_{ident(j.name)}", real=True) for j in scene.meshes
        }
        self.flanks = list(self.flank.values())
        self.q = [sp.Symbol(f"q_{ident(d.joint)}", real=True) for d in scene.drivers]
        self.qd = [sp.Symbol(f"qdot_{ident(d.joint)}", real=True) for d in scene.drivers]
        self.qdd = [sp.Symbol(f"qddot_{ident(d.joint)}", real=True) for d in scene.drivers]
        self.q_of = {d.joint: s for d, s in zip(scene.drivers, self.q)}
        self.anchor: dict[str, str] = {}
        self.groups: list[GroupEquations] = []
        self.loops: list = []
        self.meshes: list = []  # (mesh name, rolling-without-slip row = 0)
        self.closed_forms: list = []
        self.position_steps: list = []
        self.intermediates: list = []
        self.sigmas: list = []
        self.row_is_length: list[bool] = []
        rows = []
        for gi, g in enumerate(self.decomposition.groups):
            rows += self._group(gi, g, len(rows))
        self.Phi = sp.Matrix(rows)
        self.x = [s for ge in self.groups for s in ge.x]
        self.xd = [_rate(s, 1) for s in self.x]
        self.xdd = [_rate(s, 2) for s in self.x]
        self.A = self.Phi.jacobian(self.x)
        self.B = -self.Phi.jacobian(self.q)
        xd, qd = sp.Matrix(self.xd), sp.Matrix(self.qd)
        V = self.A * xd - self.B * qd  # dPhi/dt
        self.acc_rhs = self.B * sp.Matrix(self.qdd) - V.jacobian(self.x) * xd - V.jacobian(self.q) * qd
        self._points()
        outs = set(scene.outputs)
        want = bool(outs & {"reactions", "driving", "frame"}) if forces is None else forces
        self.has_forces = want
        if want:
            self._forces()

    # -- parameters ------------------------------------------------------------
    def sym(self, name):
        """The symbol of parameter ``name`` (a number when it is not kept symbolic)."""
        if name is None:
            return None
        got = self._syms.get(name)
        if got is None:
            p = self.table.params[name]
            s = self.symbolic
            keep = s if isinstance(s, bool) else (name in s or p.kind in s)
            got = sp.Symbol(name, real=True) if keep else sp.Float(p.value)
            self._syms[name] = got
        return got

    @property
    def parameters(self) -> list:
        """The parameters kept symbolic, in registration order."""
        return [s for s in self._syms.values() if isinstance(s, sp.Symbol)]

    def parameter_values(self) -> dict:
        """``{symbol: value}`` of the symbolic parameters (the scene's numbers)."""
        return {
            self._syms[n]: p.value
            for n, p in self.table.params.items()
            if isinstance(self._syms.get(n), sp.Symbol)
        }

    # -- geometry ----------------------------------------------------------------
    def theta(self, link):
        return sp.Integer(0) if link == GROUND else self.th[link]

    def theta0(self, link):
        return sp.Integer(0) if link == GROUND else self.sym(self.table.theta0(link))

    def off(self, link, point) -> Vec:
        """Vector from ``link``'s frame origin to its joint ``point``."""
        pl = self.table.point(link, point)
        if pl is None:
            return Vec()
        l, b = pl
        th = self.theta(link)
        return Vec.of(self.sym(l), th if b is None else th + self.sym(b))

    def frame_vec(self, link, px, py) -> Vec:
        """The vector with components ``(px, py)`` in ``link``'s frame."""
        th = self.theta(link)
        return Vec(polar=((px, th), (py, th + HALF_PI)))

    def rel(self, link, P, Q) -> Vec:
        """Vector from point ``P`` to point ``Q`` of ``link`` (joint names)."""
        if link == GROUND:
            return self.pos(GROUND, Q) - self.pos(GROUND, P)
        return self.off(link, Q) - self.off(link, P)

    def dist_arg(self, link, P, Q):
        """``(r, delta)`` with ``Q - P = r e^{i(theta_link + delta)}`` on ``link``."""
        tp, tq = self.table.point(link, P), self.table.point(link, Q)

        def polar(t):
            return self.sym(t[0]), (sp.Integer(0) if t[1] is None else self.sym(t[1]))

        if tp is None:
            return polar(tq)
        if tq is None:
            l, b = polar(tp)
            return l, b + sp.pi
        (lp, bp), (lq, bq) = polar(tp), polar(tq)
        cx = lq * sp.cos(bq) - lp * sp.cos(bp)
        cy = lq * sp.sin(bq) - lp * sp.sin(bp)
        return sp.sqrt(cx**2 + cy**2), sp.atan2(cy, cx)

    def slide_unit(self, jname) -> tuple:
        j = self.scene.joint(jname)
        phi = self.theta(j.links[0]) + self.sym(self.table.gamma(jname))
        return sp.cos(phi), sp.sin(phi)

    def pos(self, link, point) -> Vec:
        """Position of the point ``point`` (a joint name) of ``link``, along the tree."""
        if link == GROUND:
            return Vec.xy(*(self.sym(n) for n in self.table.ground_point(point)))
        J = self.anchor[link]
        return self.anchor_pos(link) + self.rel(link, J, point)

    def anchor_pos(self, link) -> Vec:
        J = self.scene.joint(self.anchor[link])
        base = self.pos(_other(J, link), J.name)
        if J.type == "R":
            return base
        u = Vec.of(self.slide[J.name], self.theta(J.links[0]) + self.sym(self.table.gamma(J.name)))
        return base + u if link == J.links[1] else base - u

    def origin(self, link) -> Vec:
        """Position of ``link``'s frame origin ``u``."""
        return self.pos(link, self.table.frames[link].u)

    # -- equations of one group ------------------------------------------------
    def _angle_eq(self, J):
        a, b = J.links
        return (self.theta(b) - self.theta(a)) - (self.theta0(b) - self.theta0(a))

    def _copied(self, b, J):
        """Closed form of ``b``'s angle copied through ``P`` joint ``J``."""
        k = _other(J, b)
        return self.theta(k) - self.theta0(k) + self.theta0(b)

    def _driver_eq(self, d):
        J = self.scene.joint(d.joint)
        if d.kind == "P":
            return self.slide[J.name] - self.q_of[J.name]
        a, b = J.links
        fr = self.table.frames.get(b)
        if fr is not None and fr.u == J.name and fr.v == d.toward:
            delta = sp.Integer(0)
        else:
            delta = self.sym(self.table.delta(J.name, d.toward))
        return self.theta(b) + delta - (self.theta(a) - self.theta0(a)) - self.q_of[J.name]

    def _group(self, gi, g: Group, row0):
        scene = self.scene
        joints = [scene.joint(n) for n in g.joints]
        drivers = [d for d in scene.drivers if d.joint in g.drivers]
        # anchors: each link placed from a link already placed, in the group's joint order
        placed = set(self.anchor) | {GROUND}
        pending = list(g.links)
        used = set()
        while pending:
            for J in joints:
                if J.name in used or J.type == "G":  # a mesh places no link
                    continue
                a, b = J.links
                if (a in placed) != (b in placed) and (a in pending or b in pending):
                    new = b if a in placed else a
                    self.anchor[new] = J.name
                    placed.add(new)
                    pending.remove(new)
                    used.add(J.name)
                    break
            else:  # pragma: no cover - a group is always connected to known links
                raise ValueError(f"group {g.links} is not connected to solved links")
        rows = []
        for J in joints:
            if J.name in used:
                continue
            a, b = J.links
            if J.type == "G":
                self.meshes.append((J.name, self._mesh_eq(J)))
                rows.append(self.meshes[-1][1])
                continue
            if J.type == "R":
                loop = self.pos(a, J.name) - self.pos(b, J.name)
            else:
                s = self.slide[J.name]
                u = Vec.of(s, self.theta(a) + self.sym(self.table.gamma(J.name)))
                loop = self.pos(b, J.name) - self.pos(a, J.name) - u
            self.loops.append((J.name, loop))
            rows += [loop.x, loop.y]
        angles = [self._angle_eq(J) for J in joints if J.type == "P"]
        # which rows are lengths (loop projections, slide drivers) rather than angles
        self.row_is_length += [True] * len(rows) + [False] * len(angles)
        self.row_is_length += [d.kind == "P" for d in drivers]
        rows += angles + [self._driver_eq(d) for d in drivers]
        x = [self.th[n] for n in g.links] + [self.slide[J.name] for J in joints if J.type == "P"]
        ge = GroupEquations(gi, g, x, slice(row0, row0 + len(rows)))
        if g.kind == "input":
            self._input_closed_form(g, drivers[0])
        elif g.kind == "gear" and len(g.links) == 1:
            self._gear_closed_form(g, next(J for J in joints if J.type == "G"))
        elif g.kind == "dyad":
            ge.sigma = self._dyad_closed_form(gi, g)
        else:
            ge.closed = False
        self.groups.append(ge)
        return rows

    def _mesh_eq(self, J):
        """Rolling without slip (a length): ``ra (da - dc) +- rb (db - dc)`` with ``d`` the
        rotations from the assembly configuration (plus for an external mesh)."""
        a, b = J.links
        ra, rb, _, _ = (self.sym(n) for n in self.table.mesh(J.name))
        c = J.carrier

        def turned(link):
            return self.theta(link) - self.theta0(link) - (self.theta(c) - self.theta0(c))

        return ra * turned(a) + (-rb if J.internal else rb) * turned(b)

    def pitch_point(self, J) -> Vec:
        """Position of mesh ``J``'s pitch point (a point of its carrier)."""
        return self.pos(J.carrier, J.name)

    def line_of_action(self, J):
        """Unit line of action ``(ux, uy)`` of the force of gear ``a`` on gear ``b``:
        ``kappa cos(phi) t + rho sin(phi) e``, ``e`` the line of centres ``a -> b``, ``t``
        it turned by +90 degrees, ``rho`` +1 external and -1 internal, ``kappa`` the flank."""
        _, _, phi, eps = (self.sym(n) for n in self.table.mesh(J.name))
        ang = self.theta(J.carrier) + eps
        ex, ey = sp.cos(ang), sp.sin(ang)
        k, rho = self.flank[J.name], (-1 if J.internal else 1)
        return (-k * sp.cos(phi) * ey + rho * sp.sin(phi) * ex,
                k * sp.cos(phi) * ex + rho * sp.sin(phi) * ey)

    # -- closed forms -------------------------------------------------------------
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
        k = _other(J, b)
        Qv = self.pos(k, J.name) + self.rel(b, J.name, Y)
        sign = 1 if b == J.links[1] else -1
        return (Qv.x, Qv.y), self.slide_unit(J.name), sign

    def _dyad_closed_form(self, gi, g):
        scene = self.scene
        t = g.dyad_type
        b0, b1 = g.links
        e0, ji, e1 = (scene.joint(n) for n in g.joints)
        k0, k1 = _other(e0, b0), _other(e1, b1)
        sigma = None
        if t in ("RRR", "RRP", "RPR"):
            sigma = sp.Symbol(f"sigma_{gi + 1}", real=True)
            self.sigmas.append(sigma)
        if t == "RRR":
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
            g, o0, o1, i = gi + 1, e0.name, e1.name, ji.name
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
        elif t == "RRP":
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
            g, o0, o1, i = gi + 1, e0.name, e1.name, ji.name
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
        elif t == "RPR":
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
            g, o0, o1, i = gi + 1, e0.name, e1.name, ji.name
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
        elif t == "PRP":
            self._define(self.th[b0], self._copied(b0, e0))
            self._define(self.th[b1], self._copied(b1, e1))
            self._two_lines((e0, b0, ji.name), (e1, b1, ji.name))
        elif t == "RPP":
            self._define(self.th[b1], self._copied(b1, e1))
            self._define(self.th[b0], self._copied(b0, ji))
            self._two_lines((ji, b1, ji.name), (e1, b1, ji.name))
        else:  # pragma: no cover - the structure refuses other types
            raise ValueError(t)
        return sigma

    def _two_lines(self, first, second):
        (Q0, u0, s0), (Q1, u1, s1) = self._line(*first), self._line(*second)
        den = cross(u0, u1)
        dQ = (Q1[0] - Q0[0], Q1[1] - Q0[1])
        self._define(self.slide[first[0].name], s0 * cross(dQ, u1) / den)
        self._define(self.slide[second[0].name], s1 * cross(dQ, u0) / den)

    def nested_closed_forms(self) -> dict:
        """Each closed-form coordinate in terms of drivers, parameters and the
        coordinates of Newton groups only."""
        out: dict = {}
        for s, e in self.closed_forms:
            out[s] = e.xreplace(out)
        return out

    # -- points --------------------------------------------------------------------
    def _kin(self, v: Vec):
        """Position, velocity and acceleration of a point given as a Vec."""
        P = sp.Matrix([v.x, v.y])
        J = P.jacobian(self.x)
        xd, xdd = sp.Matrix(self.xd), sp.Matrix(self.xdd)
        V = J * xd
        Acc = J * xdd + V.jacobian(self.x) * xd
        return list(P), list(V), list(Acc)

    def com_vec(self, link) -> Vec:
        p, q = (self.sym(n) for n in self.table.com(link))
        return self.origin(link) + self.frame_vec(link, p, q)

    def _points(self):
        scene = self.scene
        # a mesh's point is its pitch point, on its carrier
        self.joint_kin = {
            j.name: self._kin(self.pitch_point(j) if j.type == "G" else self.pos(j.links[1], j.name))
            for j in scene.joints
        }
        self.origin_kin = {n: self._kin(self.origin(n)) for n in scene.link_names}
        self.com_kin = {
            link.name: self._kin(self.com_vec(link.name)) for link in scene.links if link.com is not None
        }

    # -- forces --------------------------------------------------------------------
    def _forces(self):
        scene = self.scene
        eff = scene.effects
        self.F = {}
        for j in scene.joints:
            n = ident(j.name)
            if j.type == "R":
                self.F[j.name] = (sp.Symbol(f"R_{n}x", real=True), sp.Symbol(f"R_{n}y", real=True))
            elif j.type == "G":  # the tooth load along the line of action
                self.F[j.name] = (sp.Symbol(f"Fn_{n}", real=True),)
            else:
                self.F[j.name] = (sp.Symbol(f"N_{n}", real=True), sp.Symbol(f"M_{n}", real=True))
        self.E = {
            d.joint: sp.Symbol(f"{'tau' if d.kind == 'R' else 'f'}_{ident(d.joint)}", real=True)
            for d in scene.drivers
        }
        acc = {n: [sp.Integer(0)] * 3 for n in scene.link_names}
        self.force_intermediates = []

        def add(link, f=None, lever=None, couple=0):
            if link == GROUND:
                return
            row = acc[link]
            if f is not None:
                row[0] += f[0]
                row[1] += f[1]
                row[2] += lever.x * f[1] - lever.y * f[0]
            row[2] += couple

        def at_point(J, link):
            """Lever of ``P`` joint ``J``'s reference point on ``link``."""
            lever = self.off(link, J.name)
            if link == J.links[0]:
                lever = lever + Vec.of(self.slide[J.name], self.theta(link) + self.sym(self.table.gamma(J.name)))
            return lever

        for j in scene.joints:
            a, b = j.links
            if j.type == "R":
                F = self.F[j.name]
                add(b, F, self.off(b, j.name) if b != GROUND else None)
                add(a, (-F[0], -F[1]), self.off(a, j.name) if a != GROUND else None)
            elif j.type == "G":
                (Fn,) = self.F[j.name]
                ux, uy = self.line_of_action(j)
                P = self.pitch_point(j)
                for link, sgn in ((b, 1), (a, -1)):
                    if link != GROUND:
                        add(link, (sgn * Fn * ux, sgn * Fn * uy), P - self.origin(link))
            else:
                N, M = self.F[j.name]
                ux, uy = self.slide_unit(j.name)
                F = (-uy * N, ux * N)
                if b != GROUND:
                    add(b, F, at_point(j, b), M)
                if a != GROUND:
                    add(a, (-F[0], -F[1]), at_point(j, a), -M)
        for d in scene.drivers:
            j = scene.joint(d.joint)
            a, b = j.links
            e = self.E[d.joint]
            if d.kind == "R":
                add(b, couple=e)
                add(a, couple=-e)
            else:
                ux, uy = self.slide_unit(j.name)
                if b != GROUND:
                    add(b, (e * ux, e * uy), at_point(j, b))
                if a != GROUND:
                    add(a, (-e * ux, -e * uy), at_point(j, a))
        g = self.table.gravity() if eff.gravity else None
        for link in scene.links:
            n = link.name
            has_mass = link.mass > 0
            if link.com is None or not (has_mass or link.inertia > 0):
                continue
            m, I = (self.sym(s) for s in self.table.mass(n))
            p, q = (self.sym(s) for s in self.table.com(n))
            lever = self.frame_vec(n, p, q)
            if has_mass and g is not None:
                add(n, (m * self.sym(g[0]), m * self.sym(g[1])), lever)
            if eff.inertia:
                if has_mass:
                    # named in the equations (a reader's form), substituted below
                    _, _, (ax, ay) = self.com_kin[n]
                    sx, sy = (sp.Symbol(f"aG{c}_{ident(n)}", real=True) for c in "xy")
                    self.force_intermediates += [
                        (sx, ax, f"acceleration of the centre of mass of link {n}, x"),
                        (sy, ay, f"acceleration of the centre of mass of link {n}, y"),
                    ]
                    add(n, (-m * sx, -m * sy), lever)
                if link.inertia > 0:
                    add(n, couple=-I * self.xdd[self.x.index(self.th[n])])
        if eff.loads:
            for i, ld in enumerate(scene.loads):
                names = self.table.load(i)
                if "force" in names:
                    fx, fy = (self.sym(s) for s in names["force"])
                    px, py = (self.sym(s) for s in names["at"])
                    add(ld.link, (fx, fy), self.frame_vec(ld.link, px, py))
                if "torque" in names:
                    add(ld.link, couple=self.sym(names["torque"]))
        named = {sym: e for sym, e, _ in self.force_intermediates}
        self.link_equations = {n: [e.xreplace(named) for e in row] for n, row in acc.items()}
        # group blocks, solved from the last group back (``readable_force_blocks``: the
        # same with the centres of mass's accelerations named)
        order = []
        for ge in self.groups:
            g = ge.group
            ge.forces = [s for n in g.joints for s in self.F[n]] + [self.E[n] for n in g.drivers]
            ge.force_rows = [e for n in g.links for e in self.link_equations[n]]
            order.append(ge)
        later: list = []
        zero = {s: 0 for ge in self.groups for s in ge.forces}
        self.force_blocks = []
        self.readable_force_blocks = []
        for ge in reversed(order):
            eqs = sp.Matrix([e for n in ge.group.links for e in acc[n]])
            Ag = eqs.jacobian(ge.forces)
            Cg = eqs.jacobian(later) if later else sp.zeros(len(ge.force_rows), 0)
            bg = -eqs.xreplace(zero)
            self.readable_force_blocks.insert(0, (Ag, bg, Cg, list(later)))
            self.force_blocks.insert(0, (Ag.xreplace(named), bg.xreplace(named), Cg.xreplace(named),
                                         list(later)))
            later = list(ge.forces) + later
        self.all_forces = later
        # frame force and moment (what the links put on the ground, about the origin)
        fx = fy = mz = sp.Integer(0)
        for j in scene.joints:
            if GROUND not in j.links:
                continue
            s = 1 if j.links[1] == GROUND else -1
            if j.type == "G":
                (Fn,) = self.F[j.name]
                ux, uy = self.line_of_action(j)
                P = self.pitch_point(j)
                fx += s * Fn * ux
                fy += s * Fn * uy
                mz += s * Fn * (P.x * uy - P.y * ux)
                continue
            P = self.pos(j.links[1], j.name)
            if j.type == "R":
                F, c = self.F[j.name], sp.Integer(0)
            else:
                N, M = self.F[j.name]
                ux, uy = self.slide_unit(j.name)
                F, c = (-uy * N, ux * N), M
            if j.name in self.E:
                e = self.E[j.name]
                if j.type == "R":
                    c = c + e
                else:
                    ux, uy = self.slide_unit(j.name)
                    F = (F[0] + e * ux, F[1] + e * uy)
            fx += s * F[0]
            fy += s * F[1]
            mz += s * (P.x * F[1] - P.y * F[0] + c)
        self.frame = [fx, fy, mz]


def _rate(sym, order):
    name = sym.name
    if name.startswith("theta_"):
        return sp.Symbol(("omega_" if order == 1 else "alpha_") + name[6:], real=True)
    return sp.Symbol(("sdot_" if order == 1 else "sddot_") + name[2:], real=True)


def derive(scene: Scene, symbolic=True, forces=None) -> MechanismEquations:
    """Derive a scene's equations with SymPy (see the module docstring).

    Parameters
    ----------
    scene : Scene
    symbolic : bool or collection of str
        Which parameters stay symbols: all (``True``), none (``False``: the
        scene's numbers from the start), or those named or of the kinds given
        (``"length"``, ``"angle"``, ``"coordinate"``, ``"mass"``,
        ``"inertia"``, ``"gravity"``, ``"load"``).
    forces : bool, optional
        Derive the force equations (default: when the scene asks for forces).
    """
    return MechanismEquations(scene, symbolic, forces)
