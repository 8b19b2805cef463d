"""Springs and dampers in the derived force equations (the contract's ``springs``).

Where a scene's springs act (``effects.springs``), :func:`linkage_sym.symbolic.derive`
writes each one into its links' equilibrium as a known load, a function of the
coordinates and their rates (as :mod:`linkage_sym.numeric.forces.springs` computes it
from solved states):

* between two links: the tension ``T_<k> = k_<k> (L_<k> - L0_<k>) + c_<k> dL/dt`` (the
  damper's term, and its parameter ``c_<k>``, where the scene's spring has damping) with
  ``L_<k> = |P1 - P0|`` (named, as a dyad's distance ``d``, from the components ``dx_<k>,
  dy_<k>`` of ``P1 - P0``) the distance between the spring's end ``P0`` (the point
  ``(xi_<k>_0, eta_<k>_0)`` of ``links[0]``'s frame; the ground's: global) and ``P1``, and
  ``dL/dt = (P1 - P0) . (V1 - V0) / L`` from the points' velocities; ``T u`` on
  ``links[0]`` at ``P0`` and ``-T u`` on ``links[1]`` at ``P1`` (``u`` from ``P0`` to ``P1``);
* at an ``R`` joint: the torque ``tau_<k> = -k_<k> (theta - theta_f_<k>) - c_<k> omega``
  on the joint's ``links[1]`` (``-tau`` on ``links[0]``), with ``theta`` the relative
  rotation from the assembly configuration, ``(theta_b - theta0_b) - (theta_a -
  theta0_a)`` in the link angles, and ``omega = omega_b - omega_a``.  The angle counts
  whole turns: the coordinates are continuous from the assembly configuration (the
  runtime's angles are, as the rotations it reports).

A spring's end on the ground pulls on the frame: its part enters the frame force and
moment.  Stiffness, damping, free length or angle and the ends' points are parameters
(:meth:`~linkage_sym.structure.parameters.ParameterTable.spring`), so a design sweep
varies them.

Examples
--------
>>> from linkage_sym.examples import load_example
>>> from linkage_sym.symbolic import derive
>>> eqs = derive(load_example("crank_rocker_spring"))
>>> [(name, s, kind) for name, s, _, kind, _ in eqs.spring_efforts]
[('k1', T_k1, 'tension'), ('k2', tau_k2, 'torque')]
>>> eqs.spring_efforts[1][2]  # at D: the ground (links[1]) turning relative to the rocker
-k_k2*(theta0_rocker - theta_f_k2 - theta_rocker)
"""

from __future__ import annotations

import sympy as sp

from linkage_sym.model import GROUND
from linkage_sym.structure.parameters import ident
from linkage_sym.symbolic.vectors import Vec

__all__ = ["spring_loads"]


def _end(eqs, link, xi, eta):
    """A spring's end: the point ``(xi, eta)`` of ``link``'s frame (the ground's: global)."""
    if link == GROUND:
        return Vec.xy(xi, eta)
    return eqs.origin(link) + eqs.frame_vec(link, xi, eta)


def _velocity(eqs, P: Vec):
    """The velocity of the point ``P`` (a function of the coordinates)."""
    M = sp.Matrix([P.x, P.y])
    V = M.jacobian(eqs.x) * sp.Matrix(eqs.xd)
    return V[0], V[1]


def spring_loads(eqs, add, frame) -> tuple[list, list]:
    """Add every acting spring's forces and couples through ``add(link, f, lever, couple)``
    and what it puts on the ground through ``frame(fx, fy, mz)`` (about the origin).

    The forces are written with named quantities, as a dyad's distance ``d`` is: a spring
    between two links has the components ``dx_<k>, dy_<k>`` from its end ``P0`` to ``P1``,
    its length ``L_<k> = sqrt(dx_<k>**2 + dy_<k>**2)`` and its tension ``T_<k>`` in them.

    Returns
    -------
    efforts : list of (str, Symbol, Expr, str, Expr)
        Each spring's name and effort: its symbol (``T_<k>``, ``tau_<k>``), its
        expression, its kind (``"tension"``, ``"torque"``) and its length or angle, in the
        coordinates, rates and parameters alone.
    steps : list of (Symbol, Expr, str)
        The named quantities in the order a reader defines them, each with its expression
        (in the names before it) and its meaning.
    """
    scene = eqs.scene
    out, steps = [], []
    for k in scene.active_springs:
        names = eqs.table.spring(k.name)
        n = ident(k.name)
        # the damper's term only where the scene's spring has one (its rates are then solved)
        stiff, damp = eqs.sym(names["k"]), eqs.sym(names["c"]) or sp.Integer(0)
        if k.joint is not None:
            a, b = scene.joint(k.joint).links
            theta = (eqs.theta(b) - eqs.theta0(b)) - (eqs.theta(a) - eqs.theta0(a))
            rate = sum((eqs.xd[eqs.x.index(eqs.th[m])] * s for m, s in ((b, 1), (a, -1))
                        if m != GROUND), sp.Integer(0)) if damp != 0 else 0
            effort = -stiff * (theta - eqs.sym(names["theta_f"])) - damp * rate
            sym = sp.Symbol(f"tau_{n}", real=True)
            add(b, couple=sym)
            add(a, couple=-sym)
            if GROUND in (a, b):
                frame(0, 0, -sym if a == GROUND else sym)
            out.append((k.name, sym, effort, "torque", theta))
            steps.append((sym, effort, f"torque of spring {k.name}"))
            continue
        sym, f, P0, P1, ends = _tension(eqs, k, names, stiff, damp, out, steps)
        a, b = k.links
        add(a, f, eqs.frame_vec(a, *ends[0]) if a != GROUND else None)
        add(b, (-f[0], -f[1]), eqs.frame_vec(b, *ends[1]) if b != GROUND else None)
        for link, P, s in ((a, P0, 1), (b, P1, -1)):
            if link == GROUND:
                frame(s * f[0], s * f[1], s * (P.x * f[1] - P.y * f[0]))
    return out, steps


def _tension(eqs, k, names, stiff, damp, out, steps):
    """The tension of the spring ``k`` between two links, its named quantities appended to
    ``steps`` and its effort to ``out``; ``(T, its force on links[0], P0, P1, the ends'
    parameters)``."""
    n = ident(k.name)
    a, b = k.links
    ends = [tuple(eqs.sym(s) for s in names["ends"][i]) for i in (0, 1)]
    P0, P1 = (_end(eqs, link, *e) for link, e in zip((a, b), ends))
    d = P1 - P0
    dx, dy, L = (sp.Symbol(f"{c}_{n}", real=True) for c in ("dx", "dy", "L"))
    length = sp.sqrt(dx ** 2 + dy ** 2)
    effort = stiff * (L - eqs.sym(names["L0"]))
    if damp != 0:
        (u0, v0), (u1, v1) = _velocity(eqs, P0), _velocity(eqs, P1)
        effort += damp * (dx * (u1 - u0) + dy * (v1 - v0)) / L
    sym = sp.Symbol(f"T_{n}", real=True)
    steps += [(dx, d.x, f"x-distance from the end 0 of spring {k.name} to its end 1"),
              (dy, d.y, f"y-distance from the end 0 of spring {k.name} to its end 1"),
              (L, length, f"length of spring {k.name}"),
              (sym, effort, f"tension of spring {k.name}")]
    named = {dx: d.x, dy: d.y}
    named[L] = length.xreplace(named)
    out.append((k.name, sym, effort.xreplace(named), "tension", named[L]))
    return sym, (sym * dx / L, sym * dy / L), P0, P1, ends
