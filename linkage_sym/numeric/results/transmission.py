"""Transmission angles of the RRR dyads over a sweep.

The *transmission angle* of a dyad ``RRR`` (external joints ``E1``, ``E2``,
inner joint ``J``) is the angle between its two links at their common joint:
between the vectors ``J -> E1`` and ``J -> E2``, in radians, 0..pi
(``atan2(|u x v|, u . v)``, accurate at 0 and pi where ``acos`` is not).  As
a measure of how well the dyad transmits motion only its distance from a
straight line counts, ``min(gamma, pi - gamma)``; the four-bar design chapter
of the textbook (*Design of four-bar mechanisms*, Sources [2] of the README)
asks for a minimum transmission angle.

This is an extension of the scene format's result
(``steps[i].transmission_angles``, keyed by the inner joint; see
``docs/scene-format.md``).  NumPy only.
"""

from __future__ import annotations

import numpy as np

from linkage_sym.model import Scene
from linkage_sym.structure.groups import Decomposition, decompose


def rrr_dyads(scene: Scene, decomposition: Decomposition | None = None) -> list:
    """``(inner joint, external joint 1, external joint 2)`` of every RRR dyad, in solving order.

    Examples
    --------
    >>> import linkage_sym
    >>> rrr_dyads(linkage_sym.load_example("watt_sixbar"))
    [('C', 'B', 'G'), ('E', 'D', 'F')]
    """
    dec = decomposition if decomposition is not None else decompose(scene)
    return [(g.internal[0], g.external[0], g.external[1]) for g in dec.groups
            if g.kind == "dyad" and g.dyad_type == "RRR"]


def transmission_angles(scene: Scene, analysis, decomposition: Decomposition | None = None) -> dict:
    """The transmission angle of every RRR dyad at every step, by inner joint.

    Parameters
    ----------
    scene : Scene
    analysis : Analysis
        Its joints' positions are read (NaN where a step has none).
    decomposition : Decomposition, optional
        The scene's, if already at hand.

    Returns
    -------
    dict of str to ndarray, shape (N,)
        Radians, 0..pi; NaN at steps without positions.  Empty for a scene
        without RRR dyads.

    Examples
    --------
    >>> import linkage_sym
    >>> scene = linkage_sym.load_example("crank_rocker")
    >>> g = transmission_angles(scene, linkage_sym.analyze(scene))
    >>> list(g), round(float(np.degrees(g["C"][0])), 6)
    (['C'], 56.107236)
    """
    out = {}
    for inner, e1, e2 in rrr_dyads(scene, decomposition):
        J = analysis.joints[inner].position
        u = analysis.joints[e1].position - J
        v = analysis.joints[e2].position - J
        out[inner] = np.arctan2(np.abs(u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0]),
                                u[:, 0] * v[:, 0] + u[:, 1] * v[:, 1])
    return out
