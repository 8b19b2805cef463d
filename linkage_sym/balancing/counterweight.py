"""Counterweights as data, and a scene with them merged into its links (plain Python, no SymPy).

A *counterweight* is a point mass fixed on a moving link, placed in the
link's frame of :func:`~linkage_sym.structure.parameters.link_frames`
(origin at the link's first joint ``u`` in scene order, x-axis toward its
second joint ``v``).  :func:`with_counterweights` writes the scene that
carries them: the force solver, the module series and the plots then see an
ordinary scene.  Both the derived force balance
(:mod:`~.force_counterweights`) and the optimiser (:mod:`~.search`) return
:class:`Counterweight` objects.

Examples
--------
>>> from linkage_sym.examples import load_example
>>> s = with_counterweights(load_example("crank_rocker"), [Counterweight("crank", 0.2, (-0.012, 0))])
>>> [round(v, 9) for v in s["links"][0]["com"]], round(s["links"][0]["mass"], 9)
([0.0, 0.0], 0.4)
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

from linkage_sym.model import Link, Scene
from linkage_sym.scene import dump_scene, load_scene
from linkage_sym.structure.parameters import link_frames

__all__ = ["Counterweight", "as_scene", "check_counterweights", "with_counterweights"]


@dataclass(frozen=True)
class Counterweight:
    """A point mass fixed on a moving link.

    Parameters
    ----------
    link : str
        Name of the moving link that carries it.
    mass : float
        Mass in kg, ``>= 0``.
    at : tuple of float
        Position in the link's frame of
        :func:`~linkage_sym.structure.parameters.link_frames` (origin at the
        link's first joint ``u`` in scene order, x-axis toward its second
        joint ``v``), in metres.

    Examples
    --------
    >>> Counterweight("crank", 0.1, (-0.01, 0))
    Counterweight(link='crank', mass=0.1, at=(-0.01, 0.0))
    >>> Counterweight("crank", -1.0, (0, 0))
    Traceback (most recent call last):
      ...
    ValueError: counterweight on crank: mass must be finite and >= 0, not -1.0
    """

    link: str
    mass: float
    at: tuple[float, float]

    def __post_init__(self):
        mass = float(self.mass)
        if not (math.isfinite(mass) and mass >= 0.0):
            raise ValueError(f"counterweight on {self.link}: mass must be finite and >= 0, not {self.mass!r}")
        at = tuple(float(c) for c in self.at)
        if len(at) != 2 or not all(math.isfinite(c) for c in at):
            raise ValueError(f"counterweight on {self.link}: at must be two finite numbers, not {self.at!r}")
        object.__setattr__(self, "mass", mass)
        object.__setattr__(self, "at", at)


def as_scene(scene) -> Scene:
    """``scene`` itself if it is a :class:`~linkage_sym.model.Scene`, else loaded (mapping or path)."""
    return scene if isinstance(scene, Scene) else load_scene(scene)


def check_counterweights(scene: Scene, counterweights) -> list[Counterweight]:
    """The counterweights as a list, each a :class:`Counterweight` on a moving link of ``scene``.

    Raises
    ------
    TypeError
        For an item that is not a :class:`Counterweight`.
    ValueError
        For a counterweight on a link the scene does not have (or on the ground).
    """
    cws = list(counterweights)
    names = set(scene.link_names)
    for cw in cws:
        if not isinstance(cw, Counterweight):
            raise TypeError(f"expected Counterweight, got {type(cw).__name__}")
        if cw.link not in names:
            raise ValueError(
                f"counterweight on {cw.link!r}: no such moving link (links: {', '.join(scene.link_names)})"
            )
    return cws


def _global_point(frame, w) -> tuple[float, float]:
    """Assembly-configuration (global) position of the link-frame point ``w``."""
    c, s = math.cos(frame.theta0), math.sin(frame.theta0)
    return (frame.origin[0] + c * w[0] - s * w[1], frame.origin[1] + s * w[0] + c * w[1])


def with_counterweights(scene, counterweights, name=None) -> dict:
    """A scene with counterweights merged into their links.

    Parameters
    ----------
    scene : Scene or mapping or path
        The scene (anything :func:`~linkage_sym.scene.load_scene` takes).
    counterweights : iterable of Counterweight
        Several on one link are all merged.
    name : str, optional
        Name of the new scene; default ``"<name> with counterweights"``.

    Returns
    -------
    dict
        The new scene in the file layout (:func:`~linkage_sym.scene.dump_scene`),
        which loads back with :func:`~linkage_sym.scene.load_scene`.  Each
        link that carries counterweights gets the total mass, the combined
        centre of mass (global coordinates of the assembly configuration)
        and the moment of inertia about that new centre of mass by the
        parallel-axis theorem (a counterweight is a point: it adds no inertia
        about its own centre).  A link whose total mass stays zero is left as
        it is.
    """
    scene = as_scene(scene)
    cws = check_counterweights(scene, counterweights)
    frames = link_frames(scene)
    links = []
    for link in scene.links:
        mine = [cw for cw in cws if cw.link == link.name and cw.mass > 0]
        total = link.mass + sum(cw.mass for cw in mine)
        if not mine or total <= 0.0:
            links.append(link)
            continue
        pts = [(cw.mass, _global_point(frames[link.name], cw.at)) for cw in mine]
        if link.mass > 0:
            pts_all = [(link.mass, tuple(link.com))] + pts
        else:
            pts_all = pts
        cx = math.fsum(m * p[0] for m, p in pts_all) / total
        cy = math.fsum(m * p[1] for m, p in pts_all) / total
        inertia = math.fsum([link.inertia] + [m * ((p[0] - cx) ** 2 + (p[1] - cy) ** 2) for m, p in pts_all])
        links.append(Link(link.name, total, (cx, cy), inertia))
    new = dataclasses.replace(
        scene, links=tuple(links), name=f"{scene.name} with counterweights" if name is None else name
    )
    return dump_scene(new)
