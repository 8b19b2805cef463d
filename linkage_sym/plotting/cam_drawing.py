"""A cam contact drawn with its mechanism (Matplotlib only): the cam's profile (and pitch
curve) on the cam, the roller or flat face of the follower; and the points of a link at a
step, which the drawings place by.
"""

from __future__ import annotations

import math

import numpy as np
from matplotlib.colors import to_rgb, to_rgba
from matplotlib.patches import Circle, Polygon

from linkage_sym.numeric.kinematics.cam_profile import CamProfile
from linkage_sym.model import GROUND

__all__ = ["PROFILE_SAMPLES", "cam_outline", "draw_cam", "face_span", "points_on_link"]

PROFILE_SAMPLES = 721
"""Points of a drawn cam profile (a polygon; its chords stray from the curve by about
``R (pi / 720)^2 / 2``, 1e-5 of the radius ``R``)."""


def points_on_link(analysis, link, step, local) -> np.ndarray:
    """Global positions (M, 2) at ``step`` (``None``: assembly) of points (M, 2) of ``link``."""
    local = np.asarray(local, dtype=float)
    if step is None or link == GROUND:
        return local
    lk = analysis.links[link]
    th = float(lk.rotation[step])
    c, s = math.cos(th), math.sin(th)
    return np.asarray(lk.origin[step], dtype=float) + local @ np.array([[c, s], [-s, c]])


def cam_outline(joint):
    """The drawn curves of a ``cam`` joint, in the cam's frame (m).

    Returns
    -------
    working : ndarray, shape (PROFILE_SAMPLES, 2)
        The working profile: the given curve, or for a pitch curve (a roller's
        ``"pitch": true``) the curve a roller's radius inside it.
    pitch : ndarray or None
        The pitch curve when the scene gives one.
    """
    spec = joint.cam
    curve = CamProfile(spec.profile, spec.data)
    u = np.linspace(0.0, 2.0 * math.pi, PROFILE_SAMPLES)
    (x, y), _, (nx, ny), _ = curve.frame(u)
    given = np.stack([x, y], axis=-1)
    if not spec.pitch:
        return given, None
    return given - spec.radius * np.stack([nx, ny], axis=-1), given


def face_span(analysis, joint, unit_u) -> tuple[float, float]:
    """Where a flat face must reach along itself (from ``at``): the contact's travel on it."""
    lk = analysis.links.get(joint.links[1]) if analysis is not None else None
    contact = analysis.joints.get(joint.name) if analysis is not None else None
    s = [0.0]
    if lk is not None and contact is not None:
        pos = np.asarray(contact.position, dtype=float)
        rot = np.asarray(lk.rotation, dtype=float)
        good = np.all(np.isfinite(pos), axis=-1) & np.isfinite(rot)
        if good.any():
            d = pos[good] - np.asarray(lk.origin, dtype=float)[good]
            c, sn = np.cos(rot[good]), np.sin(rot[good])
            local = np.stack([c * d[:, 0] + sn * d[:, 1], -sn * d[:, 0] + c * d[:, 1]], axis=-1)
            t = (local - np.asarray(joint.at, dtype=float)) @ unit_u
            s += [float(t.min()), float(t.max())]
    return min(s), max(s)


def draw_cam(scene, analysis, joint, step, ax, unit_scale, alpha, base_z, colors) -> list:
    """Draw cam ``joint``'s profile on its cam and its follower's element at ``step``."""
    cam, follower = joint.links
    spec = joint.cam
    working, pitch = cam_outline(joint)
    col = colors.get(cam, "0.3")
    out = []
    bold = alpha >= 1.0  # a faded snapshot gets the outline only
    ring = points_on_link(analysis, cam, step, working) * unit_scale
    edge = Polygon(ring, closed=True, fill=bold, facecolor=(*to_rgb(col), 0.3),
                   edgecolor=to_rgba(col, alpha), lw=1.8 if bold else 1.2, zorder=base_z - 0.1,
                   gid=f"cam profile {joint.name}")
    ax.add_patch(edge)
    out.append(edge)
    if pitch is not None and bold:
        pc = points_on_link(analysis, cam, step, pitch) * unit_scale
        (line,) = ax.plot(pc[:, 0], pc[:, 1], color=col, lw=0.8, ls=(0, (4, 3)), alpha=alpha,
                          zorder=base_z - 0.1, gid=f"cam pitch curve {joint.name}")
        out.append(line)
    fcol = colors.get(follower, "0.3")
    at = points_on_link(analysis, follower, step, np.asarray([joint.at]))[0] * unit_scale
    if spec.follower == "roller":
        roller = Circle(tuple(at), spec.radius * unit_scale, facecolor="white", edgecolor=fcol,
                        lw=1.8, alpha=alpha, zorder=base_z + 1, gid=f"cam follower {joint.name}")
        ax.add_patch(roller)
        out.append(roller)
    elif spec.follower == "flat":
        u = np.array([math.cos(spec.face), math.sin(spec.face)])
        L = scene.characteristic_length() or 1.0
        lo, hi = face_span(analysis, joint, u)
        ends = np.asarray(joint.at, dtype=float) + np.outer([lo - 0.08 * L, hi + 0.08 * L], u)
        ends = points_on_link(analysis, follower, step, ends) * unit_scale
        (face,) = ax.plot(ends[:, 0], ends[:, 1], color="0.15", lw=2.2, alpha=alpha,
                          solid_capstyle="butt", zorder=base_z + 1,
                          gid=f"cam follower {joint.name}")
        out.append(face)
    return out
