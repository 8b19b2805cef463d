"""A mechanism's force equations, derived with SymPy.

The part of :class:`~linkage_sym.symbolic.mechanism.MechanismEquations` (a
mixin it inherits) that writes each moving link's equilibrium (d'Alembert:
forces and moment about its frame origin, with the joint reactions, the
drivers' efforts, gravity, inertia and the scene's loads), then each group's
block ``A_g F_g = b_g - C_g F_later`` (solved from the last group back) and
the frame force and moment, what the links put on the ground about the origin.

Conventions are those of the scene format: ``R_<J>x, R_<J>y`` is the force
``links[0]`` exerts on ``links[1]`` at an ``R`` joint; a ``P`` joint carries
``N_<J>`` along the slide normal at its reference point and the couple
``M_<J>``; a gear mesh ``Fn_<J>`` along its line of action; ``tau_<J>``/``f_<J>``
is a driver's effort on ``links[1]``.

Examples
--------
>>> from linkage_sym.examples import load_example
>>> from linkage_sym.symbolic.mechanism import derive
>>> eqs = derive(load_example("crank_rocker"), forces=True)
>>> eqs.groups[0].forces
[R_Ax, R_Ay, tau_A]
>>> [len(block[0].tolist()) for block in eqs.force_blocks]
[3, 6]
"""

from __future__ import annotations

import sympy as sp

from linkage_sym.model import GROUND
from linkage_sym.structure.parameters import ident
from linkage_sym.symbolic.friction import friction_laws, friction_loads, on_frame
from linkage_sym.symbolic.springs import spring_loads
from linkage_sym.symbolic.vectors import Vec

__all__ = ["ForceEquations"]


def _add(acc, link, f=None, lever=None, couple=0):
    """Add force ``f`` at ``lever`` (from ``link``'s origin) and ``couple`` to ``link``'s row
    ``[Fx, Fy, Mz]`` of ``acc`` (nothing for the ground)."""
    if link == GROUND:
        return
    row = acc[link]
    if f is not None:
        row[0] += f[0]
        row[1] += f[1]
        row[2] += lever.x * f[1] - lever.y * f[0]
    row[2] += couple


class ForceEquations:
    """The force equations of :class:`~linkage_sym.symbolic.mechanism.MechanismEquations`.

    A mixin: it reads the geometry (``off``, ``pos``, ``origin``, ``frame_vec``,
    ``slide_unit``, ``pitch_point``, ``line_of_action``, ``sym``), the points'
    accelerations (``com_kin``) and the groups of the class that inherits it, and
    sets ``F``, ``E``, ``force_intermediates``, ``friction_laws`` (joint friction, where
    ``with_friction``: :mod:`linkage_sym.symbolic.friction`), ``spring_efforts`` (the
    acting springs: :mod:`linkage_sym.symbolic.springs`; ``spring_steps``: their named
    quantities, a spring's length among them), ``link_equations``,
    ``force_blocks``, ``readable_force_blocks``, ``all_forces``, ``frame`` and
    ``readable_frame``.
    """

    def _forces(self):
        self._force_unknowns()
        acc = {n: [sp.Integer(0)] * 3 for n in self.scene.link_names}
        self.force_intermediates = []
        self._joint_loads(acc)
        # joint friction (contract part two), where derive() asks for it: see symbolic.friction
        self.friction_laws = friction_laws(self) if self.with_friction else []
        friction_loads(self, self.friction_laws,
                       lambda link, f=None, lever=None, couple=0: _add(acc, link, f, lever, couple))
        self._driver_loads(acc)
        self._body_loads(acc)
        # the scene's springs and dampers (contract part two), known loads: see symbolic.springs
        ground = [sp.Integer(0)] * 3

        def on_ground(fx, fy, mz):
            for i, v in enumerate((fx, fy, mz)):
                ground[i] += v

        self.spring_efforts, self.spring_steps = spring_loads(
            self, lambda link, f=None, lever=None, couple=0: _add(acc, link, f, lever, couple),
            on_ground)
        self.force_intermediates += self.spring_steps
        named: dict = {}  # each in the coordinates, rates and parameters alone
        for sym, e, _ in self.force_intermediates:
            named[sym] = e.xreplace(named)
        self.link_equations = {n: [e.xreplace(named) for e in row] for n, row in acc.items()}
        self._group_blocks(acc, named)
        # the frame with the springs' efforts named (a reader's form), and substituted
        self.readable_frame = [e + g for e, g in zip(self._frame_loads(), ground)]
        self.frame = [e.xreplace(named) for e in self.readable_frame]

    def _force_unknowns(self):
        """The joints' reactions ``F`` and the drivers' efforts ``E``, as symbols."""
        scene = self.scene
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

    def _at_point(self, J, link):
        """Lever of ``P`` joint ``J``'s reference point on ``link``."""
        lever = self.off(link, J.name)
        if link == J.links[0]:
            lever = lever + Vec.of(self.slide[J.name], self.theta(link) + self.sym(self.table.gamma(J.name)))
        return lever

    def _joint_loads(self, acc):
        """Each joint's reaction on its two links."""
        for j in self.scene.joints:
            a, b = j.links
            if j.type == "R":
                F = self.F[j.name]
                _add(acc, b, F, self.off(b, j.name) if b != GROUND else None)
                _add(acc, a, (-F[0], -F[1]), self.off(a, j.name) if a != GROUND else None)
            elif j.type == "G":
                (Fn,) = self.F[j.name]
                ux, uy = self.line_of_action(j)
                P = self.pitch_point(j)
                for link, sgn in ((b, 1), (a, -1)):
                    if link != GROUND:
                        _add(acc, link, (sgn * Fn * ux, sgn * Fn * uy), P - self.origin(link))
            else:
                N, M = self.F[j.name]
                ux, uy = self.slide_unit(j.name)
                F = (-uy * N, ux * N)
                if b != GROUND:
                    _add(acc, b, F, self._at_point(j, b), M)
                if a != GROUND:
                    _add(acc, a, (-F[0], -F[1]), self._at_point(j, a), -M)

    def _driver_loads(self, acc):
        """Each driver's effort on its two links."""
        scene = self.scene
        for d in scene.drivers:
            j = scene.joint(d.joint)
            a, b = j.links
            e = self.E[d.joint]
            if d.kind == "R":
                _add(acc, b, couple=e)
                _add(acc, a, couple=-e)
            else:
                ux, uy = self.slide_unit(j.name)
                if b != GROUND:
                    _add(acc, b, (e * ux, e * uy), self._at_point(j, b))
                if a != GROUND:
                    _add(acc, a, (-e * ux, -e * uy), self._at_point(j, a))

    def _body_loads(self, acc):
        """Gravity, inertia (the centres of mass's accelerations named in
        ``force_intermediates``) and the scene's loads."""
        scene = self.scene
        eff = scene.effects
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
                _add(acc, n, (m * self.sym(g[0]), m * self.sym(g[1])), lever)
            if eff.inertia:
                if has_mass:
                    # named in the equations (a reader's form), substituted below
                    _, _, (ax, ay) = self.com_kin[n]
                    sx, sy = (sp.Symbol(f"aG{c}_{ident(n)}", real=True) for c in "xy")
                    self.force_intermediates += [
                        (sx, ax, f"acceleration of the centre of mass of link {n}, x"),
                        (sy, ay, f"acceleration of the centre of mass of link {n}, y"),
                    ]
                    _add(acc, n, (-m * sx, -m * sy), lever)
                if link.inertia > 0:
                    _add(acc, n, couple=-I * self.xdd[self.x.index(self.th[n])])
        if eff.loads:
            for i, ld in enumerate(scene.loads):
                names = self.table.load(i)
                if "force" in names:
                    fx, fy = (self.sym(s) for s in names["force"])
                    px, py = (self.sym(s) for s in names["at"])
                    _add(acc, ld.link, (fx, fy), self.frame_vec(ld.link, px, py))
                if "torque" in names:
                    _add(acc, ld.link, couple=self.sym(names["torque"]))

    def _group_blocks(self, acc, named):
        """Group blocks, solved from the last group back (``readable_force_blocks``: the
        same with the centres of mass's accelerations named)."""
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

    def _frame_loads(self):
        """Frame force and moment ``[fx, fy, mz]`` (what the links put on the ground, about
        the origin)."""
        fx = fy = mz = sp.Integer(0)
        for j in self.scene.joints:
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
            law = next((x for x in self.friction_laws if x.joint == j.name), None)
            if law is not None:  # the joint's friction, as its reaction, on links[1]
                gx, gy, gc = on_frame(law, self.slide_unit(j.name) if j.type == "P" else None)
                F, c = (F[0] + gx, F[1] + gy), c + gc
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
        return [fx, fy, mz]
