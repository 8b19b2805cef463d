"""Independent checks of a kinetostatic result, written without the solver's code.

Every function here reads an :class:`~linkage_sym.numeric.results.result.Analysis`
(kinematics and forces as arrays) and the scene, and rebuilds a physical
identity from the scene-format conventions alone:

* :func:`link_residuals`: each link's force and moment balance under its
  reported joint reactions, driver efforts, weight, loads and d'Alembert
  terms;
* :func:`power_residual`: driver power against the rate of change of kinetic
  energy minus the power of gravity, loads and springs (the springs' forces
  and power from :mod:`tests.support.spring_checks`), plus the power the joints' friction
  dissipates (contract part two);
* :func:`momentum_frame`: ``-sum m a_G`` and ``-dH_O/dt`` (the shaking force
  and moment when inertia is the only effect);
* :func:`mesh_residuals`: each gear mesh's force on the line of action: at the
  pressure angle from the common tangent of the pitch circles, pressing the
  teeth into each gear's body (the ring's outwards).

Each returns a residual and the scale it should be compared with (the sum of
the magnitudes of the terms), so tests assert ``|residual| <= tol * scale``.
"""

from __future__ import annotations

import numpy as np

from tests.support.spring_checks import spring_power, spring_terms

GROUND = "ground"


def _cross(r, f):
    return r[..., 0] * f[..., 1] - r[..., 1] * f[..., 0]


def _rotation(a, link):
    return 0.0 if link == GROUND else a.links[link].rotation


def _axis(a, joint, angle):
    """Global unit vector of a slide direction fixed on ``joint.links[0]``."""
    th = _rotation(a, joint.links[0]) + angle
    return np.stack(np.broadcast_arrays(np.cos(th), np.sin(th)), axis=-1)


def load_factor(ld, a) -> np.ndarray | float:
    """A load's factor at the steps of ``a`` (loads over the cycle, an extension of the
    format), written out here: the driver's value brought into the table's first period,
    the bracketing table interval found, the factor interpolated on it; zero outside an
    ``active`` range (brought into the period after its start)."""
    if ld.driver is None:
        return 1.0
    x = np.asarray(a.drivers[ld.driver]["q"], float)
    f = np.ones_like(x)
    if ld.table is not None:
        q = list(ld.table.q)
        s = list(ld.table.scale)
        if ld.period is not None:
            x = q[0] + (x - q[0]) - ld.period * np.floor((x - q[0]) / ld.period)
            q, s = q + [q[0] + ld.period], s + [s[0]]
        f = np.empty_like(x)
        for i, v in enumerate(x):
            k = max(j for j in range(len(q) - 1) if q[j] <= v) if v < q[-1] else len(q) - 2
            f[i] = s[k] + (s[k + 1] - s[k]) * (v - q[k]) / (q[k + 1] - q[k])
    if ld.active is not None:
        lo, hi = ld.active
        y = np.asarray(a.drivers[ld.driver]["q"], float)
        if ld.period is not None:
            y = lo + (y - lo) - ld.period * np.floor((y - lo) / ld.period)
        # ends included: a step on an end, up to rounding (1e-12 of the range's scale), is in
        end = 1e-12 * max(abs(lo), abs(hi), 1.0)
        f = f * ((y >= lo - end) & (y <= hi + end) | (ld.period is not None)
                 & (y >= lo + ld.period - end))
    return f


def applied(scene, a, inertia=None, gravity=None, loads=None):
    """Per link: list of (force (N,2), point (N,2)) and list of couples (N,)."""
    eff = scene.effects
    inertia = eff.inertia if inertia is None else inertia
    gravity = eff.gravity if gravity is None else gravity
    loads = eff.loads if loads is None else loads
    out = {}
    for link in scene.links:
        lk = a.links[link.name]
        forces, couples = [], []
        if link.mass > 0:
            if inertia:
                forces.append((-link.mass * lk.com_acceleration, lk.com))
            if gravity:
                forces.append((link.mass * np.broadcast_to(gravity, lk.com.shape), lk.com))
        if inertia and link.inertia > 0:
            couples.append(-link.inertia * lk.alpha)
        out[link.name] = (forces, couples)
    if loads:
        for ld in scene.loads:
            lk = a.links[ld.link]
            forces, couples = out[ld.link]
            k = np.reshape(load_factor(ld, a), (-1, 1))
            if ld.force is not None:
                p = lk.point(ld.at)
                forces.append((k * np.broadcast_to(np.asarray(ld.force, float), p.shape), p))
            if ld.torque:
                couples.append(k[:, 0] * np.full(a.n_steps, ld.torque))
    for name, (forces, couples) in spring_terms(scene, a).items():  # the acting springs
        out[name][0].extend(forces)
        out[name][1].extend(couples)
    return out


def link_residuals(scene, a):
    """Force and moment residual of every moving link, with their scales (the joints'
    friction, where the result has it, among the joint forces).

    Returns ``{link: (res_force (N,2), res_moment (N,), scale_force (N,), scale_moment (N,))}``;
    moments about the global origin.
    """
    f = a.forces
    drivers = {d.joint: d for d in scene.drivers}
    terms = {l.name: ([], []) for l in scene.links}  # (force, point) and couples
    for j in scene.joints:
        p = a.joints[j.name].position
        R = f.reactions[j.name]
        m = f.reaction_moments[j.name]
        on1 = [(R, p)]
        c1 = [m]
        mu = None if f.friction is None else f.friction.get(j.name)
        if mu is not None:  # contract part two: the friction links[0] exerts on links[1]
            if j.type == "R":
                c1.append(mu)
            else:
                on1.append((mu[:, None] * _axis(a, j, j.axis), p))
        if j.name in drivers:
            e = f.driving[j.name]
            if j.type == "R":
                c1.append(e)
            else:
                on1.append((e[:, None] * _axis(a, j, j.axis), p))
        for link, s in ((j.links[1], 1.0), (j.links[0], -1.0)):
            if link == GROUND:
                continue
            forces, couples = terms[link]
            forces += [(s * F, P) for F, P in on1]
            couples += [s * c for c in c1]
    ext = applied(scene, a)
    out = {}
    for link in scene.links:
        forces, couples = terms[link.name]
        ef, ec = ext[link.name]
        forces = forces + ef
        couples = couples + ec
        N = a.n_steps
        rf = np.zeros((N, 2))
        rm = np.zeros(N)
        sf = np.zeros(N)
        sm = np.zeros(N)
        for F, P in forces:
            rf = rf + F
            mom = _cross(P, F)
            rm = rm + mom
            sf = sf + np.hypot(F[:, 0], F[:, 1])
            # rounding is relative to |P| |F|, not to |P x F| (which vanishes where the
            # force passes through the origin while its rounding does not)
            sm = sm + np.hypot(P[..., 0], P[..., 1]) * np.hypot(F[:, 0], F[:, 1])
        for c in couples:
            rm = rm + c
            sm = sm + np.abs(c)
        out[link.name] = (rf, rm, sf, sm)
    return out


def kinetic_energy_rate(scene, a):
    """``dT/dt = sum m a_G . v_G + I alpha omega`` (only links with mass or inertia)."""
    out = np.zeros(a.n_steps)
    terms = []
    for link in scene.links:
        lk = a.links[link.name]
        if link.mass > 0:
            terms.append(link.mass * np.sum(lk.com_acceleration * lk.com_velocity, axis=1))
        if link.inertia > 0:
            terms.append(link.inertia * lk.alpha * lk.omega)
    for t in terms:
        out = out + t
    return out, terms


def power_residual(scene, a):
    """``sum effort qd - (dT/dt - P_gravity - P_loads - P_springs)`` and its scale at each step.

    The scale is what rounding is relative to: for each power term ``F . v`` the
    product of the magnitudes ``|F| |v|`` (not ``|F . v|``, which vanishes where
    the two are perpendicular, e.g. at a dead centre, while their rounding does
    not), and for a driver's ``effort x qd`` the largest reaction at the step
    times the mechanism's size (for a torque) times ``|qd|`` (the effort is computed
    from those reactions).
    """
    L = scene.characteristic_length() or 1.0
    rs = reaction_scale(scene, a.forces)
    terms = []
    drive = np.zeros(a.n_steps)
    for d in scene.drivers:
        qd = a.drivers[d.joint]["qd"]
        p = a.forces.driving[d.joint] * qd
        drive = drive + p
        arm = L if d.kind == "R" else 1.0  # a torque's reactions act at lever arms up to L
        terms.append(np.abs(p) + rs * arm * np.abs(qd))

    def mag(v):
        return np.hypot(v[:, 0], v[:, 1])

    rhs = np.zeros(a.n_steps)
    if scene.effects.inertia:
        dT, _ = kinetic_energy_rate(scene, a)
        rhs = rhs + dT
        for link in scene.links:
            lk = a.links[link.name]
            if link.mass > 0:
                terms.append(link.mass * mag(lk.com_acceleration) * mag(lk.com_velocity))
            if link.inertia > 0:
                terms.append(np.abs(link.inertia * lk.alpha * lk.omega))
    g = scene.effects.gravity
    if g:
        for link in scene.links:
            if link.mass > 0:
                v = a.links[link.name].com_velocity
                rhs = rhs - link.mass * (v @ np.asarray(g, float))
                terms.append(link.mass * mag(v) * np.hypot(*g))
    if scene.effects.loads:
        for ld in scene.loads:
            lk = a.links[ld.link]
            k = load_factor(ld, a)
            if ld.force is not None:
                v = lk.point_velocity(ld.at)
                rhs = rhs - k * (v @ np.asarray(ld.force, float))
                terms.append(np.abs(k) * mag(v) * np.hypot(*ld.force))
            if ld.torque:
                p = k * ld.torque * lk.omega
                rhs = rhs - p
                terms.append(np.abs(p))
    springs, spring_scale = spring_power(scene, a)  # -dV/dt less the dampers' loss
    rhs = rhs - springs
    terms.append(spring_scale)
    if a.forces.friction_power is not None:  # contract part two: what the friction dissipates
        rhs = rhs + a.forces.friction_power
        terms.append(np.abs(a.forces.friction_power))
    scale = np.zeros(a.n_steps)
    for t in terms:
        scale = scale + t
    return drive - rhs, scale


def momentum_frame(scene, a):
    """``(-sum m a_G, -dH_O/dt)`` with scales (sum of term magnitudes)."""
    F = np.zeros((a.n_steps, 2))
    M = np.zeros(a.n_steps)
    sF = np.zeros(a.n_steps)
    sM = np.zeros(a.n_steps)
    for link in scene.links:
        lk = a.links[link.name]
        if link.mass > 0:
            ma = link.mass * lk.com_acceleration
            F = F - ma
            sF = sF + np.hypot(ma[:, 0], ma[:, 1])
            h = _cross(lk.com, ma)
            M = M - h
            sM = sM + np.abs(h)
        if link.inertia > 0:
            M = M - link.inertia * lk.alpha
            sM = sM + np.abs(link.inertia * lk.alpha)
    return F, M, sF, sM


def max_rel(diff, scale):
    """Largest ``|diff| / scale`` over finite steps (scale floored by 1e-300)."""
    d = np.abs(np.asarray(diff, float))
    if d.ndim == 2:
        d = np.hypot(d[:, 0], d[:, 1])
    return float(np.nanmax(d / np.maximum(scale, 1e-300)))


def reaction_scale(scene, forces):
    """Per step: the largest joint reaction or effort (couples and torques divided by ``L``).

    ``L`` is the scene's characteristic length, so every entry is a force.
    """
    L = scene.characteristic_length()
    s = 0.0
    for name, R in forces.reactions.items():
        s = np.fmax(s, np.hypot(np.hypot(R[:, 0], R[:, 1]), forces.reaction_moments[name] / L))
    for d in scene.drivers:
        e = np.abs(forces.driving[d.joint])
        s = np.fmax(s, e / L if d.kind == "R" else e)
    return s



def mesh_residuals(scene, a):
    """Per gear mesh: how far its reported force is from the line of action, with a scale.

    Written from the format alone: the gears' centres are the positions of the
    R joints they turn on (each gear's joint with the carrier, or coaxial with
    it), the pitch point is the mesh joint's position; the force ``R`` that
    ``links[0]`` exerts on ``links[1]`` has a tangential part ``R . t`` and a
    radial part ``R . n`` with ``n`` the unit vector from the pitch point into
    gear ``links[1]``'s body (towards its centre; away from it for the ring,
    the larger gear of an internal mesh).  On the line of action
    ``R . n = tan(phi) |R . t|``, with ``R . n >= 0``.

    Returns ``{mesh: (residual (N,), scale (N,), radial (N,))}``.
    """
    out = {}
    for j in scene.joints:
        if j.type != "G":
            continue
        R = a.forces.reactions[j.name]
        P = a.joints[j.name].position
        pivot_b = a.joints[j.pivots[1]].position
        n = pivot_b - P
        n = n / np.hypot(n[:, 0], n[:, 1])[:, None]
        ring_b = j.internal and j.radii[1] > j.radii[0]
        if ring_b:
            n = -n
        t = np.stack([-n[:, 1], n[:, 0]], axis=-1)
        rn = np.sum(R * n, axis=1)
        rt = np.sum(R * t, axis=1)
        out[j.name] = (rn - np.tan(j.pressure_angle) * np.abs(rt), np.hypot(R[:, 0], R[:, 1]), rn)
    return out


def dyad_and_global_checked(scene, plan, tol):
    """``plan``'s dyad-routine and global runs, checked: every reaction of one within ``tol``
    of the other (relative to :func:`reaction_scale`), and in both each link's equilibrium
    (:func:`link_residuals`) and the power balance (:func:`power_residual`) within ``tol``.
    Returns the two analyses ``(dyad, global)``."""
    a, g = plan.run(), plan.run(method="global")
    scale = reaction_scale(scene, g.forces)
    for j in a.forces.reactions:
        assert max_rel(a.forces.reactions[j] - g.forces.reactions[j], scale) <= tol, j
    for res in (a, g):
        for link, (rf, rm, sf, sm) in link_residuals(scene, res).items():
            assert max_rel(rf, sf) <= tol and max_rel(rm, sm) <= tol, link
        r, s = power_residual(scene, res)
        assert max_rel(r, s) <= tol
    return a, g
