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

One class, :class:`MechanismEquations`, derives a whole mechanism from one
set of symbols and caches; this module holds its symbols, geometry, loop
equations, rates and points, and it inherits its closed forms from
:class:`~linkage_sym.symbolic.closed_forms.ClosedForms` and its force
equations from :class:`~linkage_sym.symbolic.forces.ForceEquations`.

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
from linkage_sym.symbolic.closed_forms import ClosedForms, other_link
from linkage_sym.symbolic.forces import ForceEquations
from linkage_sym.symbolic.vectors import Vec

HALF_PI = sp.pi / 2


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


class MechanismEquations(ClosedForms, ForceEquations):
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

    def __init__(self, scene: Scene, symbolic=True, forces=None, decomposition=None,
                 friction=False):
        outs = set(scene.outputs)
        want = bool(outs & {"reactions", "driving", "frame"}) if forces is None else forces
        # cams not derived yet; joint friction only where asked (derive(): its terms and laws
        # written out; the compiled runtime: its laws solved at run time, codegen.friction)
        refuse_symbolic_unsupported(scene, friction_derived=friction)
        self.with_friction = friction
        self.friction_laws: list = []
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
        self.two_slides: list = []  # (group, slide joints, joint, cross product of the slides)
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

    @property
    def substituted(self) -> list[str]:
        """The names of the parameters put in as the scene's numbers (not kept symbolic)."""
        return [n for n, s in self._syms.items() if not isinstance(s, sp.Symbol)]

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
        base = self.pos(other_link(J, link), J.name)
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

    Where the scene's joint friction acts, the force equations carry it, and
    ``friction_laws`` its laws (:mod:`linkage_sym.symbolic.friction`).
    """
    return MechanismEquations(scene, symbolic, forces, friction=True)
