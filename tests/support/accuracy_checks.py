"""Measured errors of a step against the 50-digit reference (``mp_reference``), in the
scales the accuracy estimate speaks of (``linkage_sym.numeric.results.accuracy``).

* position: joint, traced-point and centre-of-mass coordinates over the mechanism's
  size ``L``; link rotations in radians;
* velocity: every point's velocity over the step's largest point speed ``V`` (links'
  ``omega * L`` counted among the speeds), ``omega`` errors times ``L / V``;
* acceleration: likewise with accelerations;
* forces: reactions, reaction moments over ``L``, efforts (torques over ``L``), frame
  force, frame moment over ``L * R`` (``R``: the largest joint distance from the origin
  over ``L``, at least 1) -- each over the step's largest reaction or effort ``F``.

A scale that is 0 (no motion) gives ``None``.
"""

from __future__ import annotations

import math

import mpmath as mp


def _d(a, b):
    return float(abs(mp.mpf(float(a)) - b))


def _dv(a, b):
    return math.hypot(_d(a[0], b[0]), _d(a[1], b[1]))


def measured(scene, res, i, ref):
    """``{"position", "velocity", "acceleration", "forces"}`` errors at step ``i``."""
    L = scene.characteristic_length()
    out = {}
    pos = []
    for n, r in ref["joints"].items():
        pos.append(_dv(res.joints[n].position[i], r["position"]) / L)
    for n, r in ref["points"].items():
        pos.append(_dv(res.points[n].position[i], r["position"]) / L)
    for n, r in ref["links"].items():
        lk = res.links[n]
        rot = r["rotation"]
        rot = rot + 2 * mp.pi * mp.nint((mp.mpf(float(lk.rotation[i])) - rot) / (2 * mp.pi))
        pos.append(_d(lk.rotation[i], rot))
        if "com" in r:
            pos.append(_dv(lk.com[i], r["com"]) / L)
    out["position"] = max(pos)
    for stage, key, rot in (("velocity", "velocity", "omega"), ("acceleration", "acceleration", "alpha")):
        if stage not in res.stages or res.status[i] != "ok":
            continue
        pairs, ang = [], []
        for grp in ("joints", "points"):
            for n, r in ref[grp].items():
                k = getattr(res.joints[n] if grp == "joints" else res.points[n], key)[i]
                pairs.append((k, r[key]))
        for n, r in ref["links"].items():
            lk = res.links[n]
            ang.append((getattr(lk, rot)[i], r[rot]))
            if "com" in r:
                pairs.append((getattr(lk, "com_" + key)[i], r["com_" + key]))
        scale = max([float(mp.hypot(*b)) for _, b in pairs] + [float(abs(b)) * L for _, b in ang])
        if scale == 0:
            out[stage] = None
            continue
        out[stage] = max([_dv(a, b) / scale for a, b in pairs] + [_d(a, b) * L / scale for a, b in ang])
    if "reactions" in ref and res.forces is not None:
        f = res.forces
        F = max([float(mp.hypot(*r)) for r in ref["reactions"].values()]
                + [float(abs(m)) / L for m in ref["reaction_moments"].values()]
                + [float(abs(e)) / (L if scene.joint(n).type == "R" else 1)
                   for n, e in ref["driving"].items()])
        if F == 0:
            out["forces"] = None
            return out
        R = max([1.0] + [math.hypot(*j.at) / L for j in scene.joints])
        errs = [_dv(f.reactions[n][i], r) / F for n, r in ref["reactions"].items()]
        errs += [_d(f.reaction_moments[n][i], m) / (L * F) for n, m in ref["reaction_moments"].items()]
        errs += [_d(f.driving[n][i], e) / F / (L if scene.joint(n).type == "R" else 1)
                 for n, e in ref["driving"].items()]
        fx, fy, mz = ref["frame"]
        errs += [_dv(f.frame_force[i], (fx, fy)) / F, _d(f.frame_moment[i], mz) / (L * R * F)]
        out["forces"] = max(errs)
    return out
