"""Springs and dampers, written from the scene format alone (no solver code).

For the checks of :mod:`tests.support.force_checks`: each acting spring's
forces on its links (:func:`spring_terms`) and its power
(:func:`spring_power`), from an analysis's kinematics
(:class:`~linkage_sym.numeric.results.result.LinkKinematics` of the result,
not the solver's link states) and the contract's rules:

* between two links: ``L = |P1 - P0|``, ``P0 = at[0]`` on ``links[0]`` and
  ``P1 = at[1]`` on ``links[1]`` carried by their links; the potential energy
  ``V = k (L - L0)^2 / 2``; the tension ``k (L - L0) + c dL/dt`` pulls the two
  points together;
* at an ``R`` joint: ``theta`` the rotation of ``links[1]`` less that of
  ``links[0]``, ``V = k (theta - theta0)^2 / 2``; the torque on ``links[1]`` is
  ``-k (theta - theta0) - c dtheta/dt``.

The power the springs deliver to the mechanism is ``-dV/dt`` minus what the
dampers dissipate, ``c (dL/dt)^2`` or ``c (dtheta/dt)^2``; ``dV/dt`` is
differentiated here by the chain rule from ``V``'s own variables (the two
points' positions, the two rotations), not from the tension.
"""

from __future__ import annotations

import numpy as np

GROUND = "ground"


def _point(a, link, local, N, rates=True):
    """A point fixed on ``link`` (its assembly position ``local``) and its velocity, (N, 2)
    (zeros without ``rates``: a run without velocities, for a spring without damping)."""
    if link == GROUND:
        p = np.broadcast_to(np.asarray(local, float), (N, 2))
        return p, np.zeros((N, 2))
    lk = a.links[link]
    return lk.point(local), lk.point_velocity(local) if rates else np.zeros((N, 2))


def _angle(a, link, N):
    if link == GROUND:
        return np.zeros(N), np.zeros(N)
    lk = a.links[link]
    return lk.rotation, lk.omega


def springs_of(scene):
    """The springs that act (``effects.springs``), read off the scene's fields."""
    return scene.springs if scene.effects.springs else ()


def energy(scene, a):
    """Per acting spring: ``(V, dV/dt, dissipated)`` arrays (N,), and the scale of its power."""
    N = a.n_steps
    out = {}
    for k in springs_of(scene):
        if k.joint is not None:
            j = scene.joint(k.joint)
            t0, w0 = _angle(a, j.links[0], N)
            t1, w1 = _angle(a, j.links[1], N)
            x = (t1 - t0) - np.radians(k.free_angle_deg)
            rate = w1 - w0
            V = 0.5 * k.stiffness * x * x
            dV = k.stiffness * x * rate  # dV/dtheta * dtheta/dt
        else:
            p0, v0 = _point(a, k.links[0], k.at[0], N)
            p1, v1 = _point(a, k.links[1], k.at[1], N)
            d = p1 - p0
            L = np.sqrt(d[:, 0] ** 2 + d[:, 1] ** 2)
            x = L - k.free_length
            V = 0.5 * k.stiffness * x * x
            # grad V with respect to P1 is k x d / L (and minus that for P0)
            gx, gy = k.stiffness * x * d[:, 0] / L, k.stiffness * x * d[:, 1] / L
            dV = gx * (v1[:, 0] - v0[:, 0]) + gy * (v1[:, 1] - v0[:, 1])
            rate = ((v1 - v0) * d).sum(axis=1) / L
        out[k.name] = (V, dV, k.damping * rate * rate,
                       np.abs(dV) + k.damping * rate * rate)
    return out


def spring_terms(scene, a):
    """Per moving link: the acting springs' ``[(force (N,2), point (N,2)), ...]`` and couples."""
    N = a.n_steps
    terms = {link.name: ([], []) for link in scene.links}
    for k in springs_of(scene):
        if k.joint is not None:
            j = scene.joint(k.joint)
            t0, w0 = _angle(a, j.links[0], N)
            t1, w1 = _angle(a, j.links[1], N)
            tau = -k.stiffness * ((t1 - t0) - np.radians(k.free_angle_deg))
            if k.damping:
                tau = tau - k.damping * (w1 - w0)
            for link, s in ((j.links[1], 1.0), (j.links[0], -1.0)):
                if link != GROUND:
                    terms[link][1].append(s * tau)
            continue
        p0, v0 = _point(a, k.links[0], k.at[0], N, rates=k.damping != 0)
        p1, v1 = _point(a, k.links[1], k.at[1], N, rates=k.damping != 0)
        d = p1 - p0
        L = np.hypot(d[:, 0], d[:, 1])
        u = d / L[:, None]
        T = k.stiffness * (L - k.free_length) + k.damping * ((v1 - v0) * u).sum(axis=1)
        for link, s, p in ((k.links[0], 1.0, p0), (k.links[1], -1.0, p1)):
            if link != GROUND:
                terms[link][0].append((s * T[:, None] * u, p))
    return terms


def spring_power(scene, a):
    """The power the acting springs deliver, ``sum(-dV/dt - dissipated)``, and its scale."""
    power = np.zeros(a.n_steps)
    scale = np.zeros(a.n_steps)
    for _, dV, lost, s in energy(scene, a).values():
        power = power - dV - lost
        scale = scale + s
    return power, scale


def class3_with_springs():
    """The shipped class-III six-bar (73 steps) with five springs: two between links of its
    triad and across it, one to the ground, two at joints, most of them damped."""
    import linkage_sym
    from linkage_sym.examples import example_dict

    d = example_dict("sixbar_class3")
    d["drivers"][0]["steps"] = 73
    d["springs"] = [
        {"name": "inside", "links": ["link_BC", "rocker_FG"], "at": [[0.10, 0.09], [0.26, -0.04]],
         "stiffness": 800.0, "free_length": 0.15, "damping": 3.0},
        {"name": "across", "links": ["crank", "lever"], "at": [[0.0, 0.04], [0.2, 0.06]],
         "stiffness": 300.0, "damping": 1.0},
        {"name": "anchor", "links": ["lever", "ground"], "at": [[0.25, 0.03], [0.3, 0.2]],
         "stiffness": 500.0, "free_length": 0.1},
        {"name": "torsion", "joint": "D", "stiffness": 2.0, "free_angle_deg": 15.0,
         "damping": 0.02},
        {"name": "pivot", "joint": "E", "stiffness": 1.0, "damping": 0.01},
    ]
    return linkage_sym.load_scene(d)
