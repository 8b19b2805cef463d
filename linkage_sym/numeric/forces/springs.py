"""Springs and dampers as loads (the contract's ``springs``; ``docs/scene-format.md``).

A spring between two links pulls its two points, ``P0`` on ``links[0]`` and
``P1`` on ``links[1]``, toward each other with the tension
``T = k (L - L0) + c dL/dt`` (``L = |P1 - P0|``, ``dL/dt`` the rate of the
distance from the points' velocities): the force ``T u`` on ``links[0]`` at
``P0`` and ``-T u`` on ``links[1]`` at ``P1``, ``u`` the unit vector from
``P0`` to ``P1``.  A spring at an ``R`` joint puts the torque
``tau = -k (theta - theta0) - c omega`` on the joint's ``links[1]`` and
``-tau`` on its ``links[0]`` (``theta`` the relative rotation from the
assembly configuration, ``omega`` its rate).  An end on the ground loads the
frame: its part goes into the ground's wrench, which collects what the
moving links put on the frame.

Every force method reads the springs through :func:`add_spring_wrenches`
(called by :func:`~linkage_sym.numeric.forces.loads.applied_wrenches`): a
spring is a known load at each step, like the scene's loads.

Examples
--------
>>> import linkage_sym
>>> from linkage_sym.model import Spring
>>> import dataclasses
>>> scene = linkage_sym.load_example("crank_rocker")
>>> k = Spring("k", 100.0, links=("ground", "rocker"), at=((0.1, 0.05), (0.07, 0.02)),
...            free_length=0.03)
>>> scene = dataclasses.replace(scene, springs=(k,),
...                             effects=dataclasses.replace(scene.effects, springs=True))
>>> res = linkage_sym.analyze(scene)
>>> rec = res.forces.springs["k"]
>>> list(rec), bool(abs(rec["force"][0] - 100.0 * (rec["length"][0] - 0.03)) < 1e-12)
(['length', 'force'], True)
"""

from __future__ import annotations

import numpy as np

from linkage_sym.model import Scene

__all__ = ["add_spring_wrenches", "needs_rates", "record_keys", "spring_values"]


def record_keys(spring) -> tuple[str, str]:
    """The keys of a spring's result record: ``("length", "force")`` between two links,
    ``("angle", "torque")`` at a joint."""
    return ("angle", "torque") if spring.joint is not None else ("length", "force")


def needs_rates(scene: Scene) -> bool:
    """Whether a scene's acting springs need velocities (a damper among them)."""
    return any(k.damping != 0.0 for k in scene.active_springs)


def _ends(spring, S):
    """A link spring's two points and their velocities' difference (``None`` without damping)."""
    a, b = spring.links
    (p0, p1), (sa, sb) = spring.at, (S[a], S[b])
    x0, y0 = sa.point(p0)
    x1, y1 = sb.point(p1)
    rel = None
    if spring.damping != 0.0:
        u0, v0 = sa.point_velocity(p0)
        u1, v1 = sb.point_velocity(p1)
        rel = (u1 - u0, v1 - v0)
    return (x0, y0), (x1, y1), rel


def spring_values(scene: Scene, S) -> dict:
    """Each acting spring's ``(length, tension)`` or ``(angle, torque)`` over the steps of ``S``.

    Parameters
    ----------
    scene : Scene
    S : dict of LinkState
        Solved link states (velocities read only for springs with damping).

    Returns
    -------
    dict of str to (ndarray, ndarray)
        By spring name: a link spring's length ``L`` (m) and tension (N,
        pulling its points together when positive); a joint spring's angle
        ``theta`` (rad, relative rotation from the assembly configuration) and
        the torque (N·m) on its joint's ``links[1]``.
    """
    out = {}
    for k in scene.active_springs:
        if k.joint is not None:
            j = scene.joint(k.joint)
            s0, s1 = S[j.links[0]], S[j.links[1]]
            theta = np.asarray(s1.th - s0.th, dtype=float)
            torque = -k.stiffness * (theta - k.free_angle)
            if k.damping != 0.0:
                torque = torque - k.damping * (s1.w - s0.w)
            out[k.name] = (theta, np.asarray(torque, dtype=float))
            continue
        (x0, y0), (x1, y1), rel = _ends(k, S)
        dx, dy = x1 - x0, y1 - y0
        L = np.asarray(np.hypot(dx, dy), dtype=float)
        tension = k.stiffness * (L - k.free_length)
        if rel is not None:
            tension = tension + k.damping * (dx * rel[0] + dy * rel[1]) / L
        out[k.name] = (L, np.asarray(tension, dtype=float))
    return out


def add_spring_wrenches(scene: Scene, S, W, values: dict | None = None) -> None:
    """Add every acting spring's forces and couples to the wrenches ``W`` (ground included).

    ``values``: :func:`spring_values` of the same states, when already computed.
    """
    values = spring_values(scene, S) if values is None else values
    for k in scene.active_springs:
        value, effort = values[k.name]
        if k.joint is not None:
            a, b = scene.joint(k.joint).links
            W[b].add_couple(effort)
            W[a].add_couple(-effort)
            continue
        (x0, y0), (x1, y1), _ = _ends(k, S)
        fx, fy = effort * (x1 - x0) / value, effort * (y1 - y0) / value
        a, b = k.links
        W[a].add_force(fx, fy, x0, y0)
        W[b].add_force(-fx, -fy, x1, y1)
