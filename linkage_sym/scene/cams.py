"""Reading cam contacts (``cam`` joints), an extension of the scene format.

A cam contact keeps a follower element on link ``links[1]`` (a knife-edge
point, a roller, or a flat face) in contact with the profile of the cam
``links[0]``; see the extension "cam contacts" of ``docs/scene-format.md``.
:func:`read_cam_fields` reads the ``profile`` and ``follower`` fields with the
checks and wording of :class:`~linkage_sym.scene.fields.FieldReader` and checks
the profile (closed, not crossing itself, convex where the follower needs it)
and that the follower touches it in the assembly configuration, naming each
bad field with the reason and, for a follower off the profile, by how much.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from linkage_sym.model.scene import CamSpec, Point
from linkage_sym.numeric.kinematics.cam_profile import CamProfile, self_intersection
from linkage_sym.scene.fields import FieldReader, did_you_mean, show_value

CAM_KEYS = ("profile", "follower")
"""The keys only a ``cam`` joint has."""

PROFILE_FORMS = ("circle", "polar", "points")
FOLLOWER_KINDS = ("roller", "knife", "flat")

CONTACT_TOLERANCE = 1e-6
"""Relative tolerance (to the profile's size) of the follower's contact in the assembly
configuration, and of a polar profile's closing sample: a micrometre on a metre."""

MIN_SAMPLES = 4
"""Fewest samples of a polar profile or points of a spline profile."""

CHECK_SAMPLES = 1024
"""Samples of the profile on which closure, crossing and convexity are checked."""


def read_cam_fields(
    reader: FieldReader, entry: Mapping[str, Any], path: str, at: Point | None
) -> CamSpec | None:
    """The :class:`CamSpec` of a ``cam`` joint, or ``None`` with every problem reported.

    ``at`` is the joint's point: the follower's element point in the assembly
    configuration (roller centre, knife point, or a point of the flat face).
    """
    before = len(reader.problems)
    follower = _follower(reader, entry, path)
    profile = _profile(reader, entry, path, follower)
    if len(reader.problems) != before or profile is None or follower is None:
        return None
    (kind, data, pitch), (fkind, radius, face) = profile, follower
    if pitch and fkind != "roller":
        reader.add(f"{path}.profile.pitch", f"a pitch curve is a roller's: not allowed with a "
                   f"{fkind} follower")
        return None
    curve = CamProfile(kind, data)
    if not _curve_ok(reader, f"{path}.profile.{kind}", curve, fkind):
        return None
    spec = CamSpec(kind, data, fkind, radius, face, pitch)
    if at is not None:
        touching(reader, path, curve, spec, at)
    return None if len(reader.problems) != before else spec


def _follower(reader, entry, path):
    field = f"{path}.follower"
    if "follower" not in entry:
        reader.missing(field, "a cam contact gives its follower: roller, knife or flat")
        return None
    f = entry["follower"]
    if not reader.object(f, field):
        return None
    reader.keys(f, field, ("kind", "radius", "face_deg"))
    kind = f.get("kind")
    if "kind" not in f:
        reader.missing(f"{field}.kind", "one of 'roller', 'knife', 'flat'")
        return None
    if kind not in FOLLOWER_KINDS:
        reader.add(f"{field}.kind", f"must be one of 'roller', 'knife', 'flat', got {show_value(kind)}"
                   f"{did_you_mean(str(kind), FOLLOWER_KINDS)}")
        return None
    radius, face = 0.0, None
    if kind == "roller":
        radius = reader.number(f, "radius", field, why="a roller gives its radius (m)")
        if radius is not None and radius <= 0:
            reader.add(f"{field}.radius", f"a roller's radius must be > 0, got {radius:g}")
            radius = None
    elif "radius" in f:
        reader.add(f"{field}.radius", f"not allowed on a {kind} follower (only a roller has a radius)")
    if kind == "flat":
        deg = reader.number(f, "face_deg", field, why="a flat face gives its direction (degrees)",
                            limit=1e6, limit_why="an angle must be within +-1e6 degrees")
        face = None if deg is None else math.radians(deg)
    elif "face_deg" in f:
        reader.add(f"{field}.face_deg", f"not allowed on a {kind} follower (only a flat face has one)")
    if radius is None or (kind == "flat" and face is None):
        return None
    return kind, radius, face


def _profile(reader, entry, path, follower):
    field = f"{path}.profile"
    if "profile" not in entry:
        reader.missing(field, "a cam contact gives the cam's profile: circle, polar or points")
        return None
    p = entry["profile"]
    if not reader.object(p, field):
        return None
    reader.keys(p, field, (*PROFILE_FORMS, "pitch"))
    forms = [k for k in PROFILE_FORMS if k in p]
    if len(forms) != 1:
        got = "none" if not forms else " and ".join(forms)
        reader.add(field, f"must give exactly one of 'circle', 'polar', 'points', got {got}")
        return None
    pitch = reader.boolean(p, "pitch", field, default=False)
    form = forms[0]
    sub = f"{field}.{form}"
    body = p[form]
    if form != "points" and not reader.object(body, sub):
        return None
    if form == "circle":
        reader.keys(body, sub, ("centre", "radius"))
        centre = reader.point(body, "centre", sub)
        R = reader.number(body, "radius", sub, why="the circle's radius (m)")
        if R is not None and R <= 0:
            reader.add(f"{sub}.radius", f"a circle's radius must be > 0, got {R:g}")
            R = None
        data = None if centre is None or R is None else (centre, R)
    elif form == "polar":
        reader.keys(body, sub, ("centre", "phi_deg", "r"))
        centre = reader.point(body, "centre", sub)
        phi = reader.numbers(body, "phi_deg", sub, min_length=MIN_SAMPLES, angle=True)
        r = reader.numbers(body, "r", sub, min_length=MIN_SAMPLES)
        data = None
        if phi is not None and r is not None:
            data = _polar(reader, sub, centre, phi, r)
    else:
        values = reader.array(p, "points", field)
        data = None
        if values is not None:
            data = _points(reader, sub, values)
    if pitch is None or data is None:
        return None
    return form, data, pitch


def _polar(reader, sub, centre, phi, r):
    ok = True
    if len(phi) != len(r):
        reader.add(f"{sub}.r", f"must have as many samples as phi_deg ({len(phi)}), got {len(r)}")
        return None
    for i, v in enumerate(r):
        if v <= 0:
            reader.add(f"{sub}.r[{i}]", f"a radius of the profile must be > 0, got {v:g}")
            ok = False
    for i in range(1, len(phi)):
        if phi[i] <= phi[i - 1]:
            reader.add(f"{sub}.phi_deg[{i}]", f"must increase: {phi[i]:g} after {phi[i - 1]:g}")
            ok = False
    if not ok or centre is None:
        return None
    span = phi[-1] - phi[0]
    size = max(r)
    if span > 360.0 + 1e-9:
        reader.add(f"{sub}.phi_deg", f"spans {span:g} degrees: a closed profile's samples span at "
                   "most one turn (360, the last then repeating the first)")
        return None
    if span >= 360.0 - 1e-9 and abs(r[-1] - r[0]) > CONTACT_TOLERANCE * size:
        reader.add(f"{sub}.r", f"the profile is not closed: r = {r[-1]:g} at {phi[-1]:g} deg but "
                   f"{r[0]:g} at {phi[0]:g} deg, one turn before (they differ by "
                   f"{abs(r[-1] - r[0]):.3g} m)")
        return None
    return centre, tuple(math.radians(v) for v in phi), tuple(r)


def _points(reader, sub, values):
    pts = []
    for i, v in enumerate(values):
        if not isinstance(v, (list, tuple)) or len(v) != 2:
            reader.add(f"{sub}[{i}]", f"must be an array of 2 finite numbers [x, y], got {show_value(v)}")
            continue
        x = reader.point({"p": v}, "p", f"{sub}[{i}]")
        if x is not None:
            pts.append(x)
    if len(pts) != len(values):
        return None
    if len(pts) >= 2 and math.dist(pts[0], pts[-1]) == 0.0:
        pts = pts[:-1]  # the closing point repeats the first
    if len(pts) < MIN_SAMPLES:
        reader.add(sub, f"must have at least {MIN_SAMPLES} distinct points, got {len(pts)}")
        return None
    for i in range(1, len(pts)):
        if math.dist(pts[i], pts[i - 1]) == 0.0:
            reader.add(f"{sub}[{i}]", f"repeats the point before it, {list(pts[i])}")
            return None
    return (tuple(pts),)


def _curve_ok(reader, field, curve: CamProfile, fkind: str) -> bool:
    """The sampled profile: no crossing, a positive polar radius, convex for a flat face."""
    u, (x, y), _, _, kappa = curve.samples(CHECK_SAMPLES)
    if curve.kind == "polar":
        rr = curve._r(np.mod(u - curve._phi0, 2 * math.pi))
        if np.min(rr) <= 0:
            k = int(np.argmin(rr))
            reader.add(f"{field}.r", f"the spline through the samples reaches r = {rr[k]:.3g} <= 0 at "
                       f"phi = {math.degrees(u[k]):.4g} deg: sample more densely there")
            return False
    cross = self_intersection(x, y)
    if cross is not None:
        i, j = cross
        reader.add(field, f"the profile crosses itself (near u = {math.degrees(u[i]):.4g} and "
                   f"{math.degrees(u[j]):.4g} deg of its parameter, at [{x[i]:.6g}, {y[i]:.6g}])")
        return False
    if fkind == "flat" and np.min(kappa) <= 0:
        k = int(np.argmin(kappa))
        reader.add(field, f"a flat-faced follower needs a convex profile, but it is "
                   f"{'straight' if kappa[k] == 0 else 'concave'} at [{x[k]:.6g}, {y[k]:.6g}] "
                   f"(curvature {kappa[k]:.4g} 1/m): a flat face cannot follow it there")
        return False
    return True


def touching(reader, path, curve: CamProfile, spec: CamSpec, at: Point) -> None:
    """Report a follower that does not touch the profile in the assembly configuration."""
    u, (x, y), _, _, _ = curve.samples(CHECK_SAMPLES)
    size = max(np.ptp(x), np.ptp(y))
    tol = CONTACT_TOLERANCE * size
    if spec.follower == "flat":
        mx, my = -math.sin(spec.face), math.cos(spec.face)
        f = mx * at[0] + my * at[1]
        hi, lo = (
            float(mx * c[0][0] + my * c[1][0])
            for c in (curve.evaluate(curve.support(d * mx, d * my), 0)[0] for d in (1.0, -1.0))
        )
        gap = min(abs(f - hi), abs(f - lo))
        if gap > tol:
            where = "crosses the profile" if lo < f < hi else "misses the profile"
            reader.add(f"{path}.at", f"the flat face through [{at[0]:g}, {at[1]:g}] at "
                       f"{math.degrees(spec.face):g} deg {where}: it is {gap:.6g} m from touching "
                       f"it (tolerance {tol:.2g} m, {CONTACT_TOLERANCE:g} of the profile's size)")
        return
    uu = curve.nearest(at[0], at[1])
    (cx, cy), _, (nx, ny), _ = curve.frame(uu)
    dx, dy = at[0] - float(cx[0]), at[1] - float(cy[0])
    signed = dx * float(nx[0]) + dy * float(ny[0])  # > 0 outside
    rho = spec.radius if spec.follower == "roller" and not spec.pitch else 0.0
    off = signed - rho
    if abs(off) > tol:
        if spec.follower == "knife":
            what = f"the knife point [{at[0]:g}, {at[1]:g}] is {abs(signed):.6g} m " \
                   f"{'outside' if signed > 0 else 'inside'} the profile"
        elif spec.pitch:
            what = f"the roller's centre [{at[0]:g}, {at[1]:g}] is {abs(signed):.6g} m " \
                   f"{'outside' if signed > 0 else 'inside'} the pitch curve"
        else:
            what = (f"the roller (centre [{at[0]:g}, {at[1]:g}], radius {rho:g}) is {abs(off):.6g} m "
                    f"{'off' if off > 0 else 'into'} the profile (its centre is {signed:.6g} m from it)")
        reader.add(f"{path}.at", f"the follower does not touch the cam's profile in the assembly "
                   f"configuration: {what} (tolerance {tol:.2g} m, {CONTACT_TOLERANCE:g} of the "
                   "profile's size)")
