"""Fixed and moving centrodes: the paths of a link's instant centre with the ground.

The centre ``P`` of a link and the ground traces the *fixed centrode* on the
ground and the *moving centrode* on the link; in the motion the moving one
rolls on the fixed one without slipping (the textbook chapter *Kinematic analysis of planar mechanisms*,
README Sources [4], section 3-2, Fig. 3-6).  Here the moving centrode is written in the
link's frame, which is the global frame of the assembly configuration (see
:mod:`linkage_sym.model.scene`): its points are where the centre sits in
the drawing of the assembly configuration.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from linkage_sym.model import GROUND

__all__ = ["Centrode", "centrodes", "floating_links"]


@dataclass
class Centrode:
    """The centrodes of one link relative to the ground.

    Attributes
    ----------
    link : str
    fixed : ndarray, shape (N, 2)
        The instant centre in global coordinates (m) at every step; NaN where
        it is at infinity, undefined or not computed.
    moving : ndarray, shape (N, 2)
        The same points in the link's frame (its assembly-configuration
        coordinates).
    """

    link: str
    fixed: np.ndarray
    moving: np.ndarray

    def moving_at(self, analysis, step: int) -> np.ndarray:
        """The moving centrode carried by the link to its position at ``step`` (N, 2).

        Parameters
        ----------
        analysis : Analysis
            Where the link is (any analysis of the scene: a sweep, or one step).
        step : int

        Examples
        --------
        >>> import numpy as np, linkage_sym
        >>> from linkage_sym.centres import instant_centres
        >>> scene = linkage_sym.load_example("slider_crank_offset")
        >>> res = linkage_sym.analyze(scene)
        >>> c = centrodes(scene, res, instant_centres(scene, res))["connecting_rod"]
        >>> bool(np.allclose(c.moving_at(res, 0)[0], c.fixed[0], rtol=0, atol=1e-15))
        True
        """
        lk = analysis.links[self.link]
        th = float(lk.rotation[step])
        c, s = np.cos(th), np.sin(th)
        x, y = self.moving[:, 0], self.moving[:, 1]
        return np.asarray(lk.origin[step]) + np.stack([c * x - s * y, s * x + c * y], axis=-1)


def floating_links(scene) -> tuple:
    """The links that share no joint with the ground (couplers), in scene order.

    Examples
    --------
    >>> import linkage_sym
    >>> floating_links(linkage_sym.load_example("shaper"))
    ('block', 'connecting_link')
    """
    grounded = {x for j in scene.joints if GROUND in j.links for x in j.links}
    return tuple(n for n in scene.link_names if n not in grounded)


def centrodes(scene, analysis, centres, links=None) -> dict:
    """Fixed and moving centrodes of links relative to the ground over the sweep.

    Parameters
    ----------
    scene : Scene
    analysis : Analysis
    centres : InstantCentres
        The sweep's centres (:func:`linkage_sym.centres.instant_centres`).
    links : sequence of str, optional
        Default: :func:`floating_links` (a link pivoted on the ground has a
        point for each centrode, a link sliding on it has none).

    Returns
    -------
    dict of str to Centrode

    Examples
    --------
    The moving centrode rolls on the fixed one: at every step the two touch
    at the instant centre.

    >>> import numpy as np, linkage_sym
    >>> from linkage_sym.centres import instant_centres
    >>> scene = linkage_sym.load_example("crank_rocker")
    >>> res = linkage_sym.analyze(scene)
    >>> c = centrodes(scene, res, instant_centres(scene, res))["coupler"]
    >>> bool(np.allclose(c.moving_at(res, 40)[40], c.fixed[40], rtol=0, atol=1e-15))
    True
    """
    if links is None:
        links = floating_links(scene)
    out = {}
    for name in links:
        P = np.asarray(centres.position[:, centres.index(GROUND, name)], dtype=float)
        lk = analysis.links[name]
        th = np.asarray(lk.rotation, dtype=float)
        r = P - np.asarray(lk.origin, dtype=float)
        c, s = np.cos(th), np.sin(th)
        local = np.stack([c * r[:, 0] + s * r[:, 1], -s * r[:, 0] + c * r[:, 1]], axis=-1)
        out[name] = Centrode(name, P, local)
    return out
